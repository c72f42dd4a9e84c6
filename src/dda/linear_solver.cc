/**
 * @file
 * Block sparse matrix and its direct and iterative solvers.
 */
#include <rockdda/dda/linear_solver.h>

#include <Eigen/Cholesky>
#include <Eigen/SparseCholesky>
#include <Eigen/SparseCore>

#include <algorithm>
#include <cmath>

namespace rockdda::dda
{
  namespace
  {
    /// Inverse of a symmetric positive definite 6x6 matrix by Cholesky
    /// (fixed-size loops; Eigen's LLT::solve takes a generic path here).
    /// Returns false if a pivot is not positive.
    bool
    invert_spd(const Matrix6 &A, Matrix6 &inverse)
    {
      double L[6][6] = {};
      for (int j = 0; j < 6; ++j)
        {
          double d = A(j, j);
          for (int k = 0; k < j; ++k)
            d -= L[j][k] * L[j][k];
          if (!(d > 0.))
            return false;
          L[j][j] = std::sqrt(d);
          for (int i = j + 1; i < 6; ++i)
            {
              double v = A(i, j);
              for (int k = 0; k < j; ++k)
                v -= L[i][k] * L[j][k];
              L[i][j] = v / L[j][j];
            }
        }
      // W = L^-1 (lower triangular), inverse = W^T W.
      double W[6][6] = {};
      for (int c = 0; c < 6; ++c)
        {
          W[c][c] = 1. / L[c][c];
          for (int i = c + 1; i < 6; ++i)
            {
              double v = 0.;
              for (int k = c; k < i; ++k)
                v -= L[i][k] * W[k][c];
              W[i][c] = v / L[i][i];
            }
        }
      for (int a = 0; a < 6; ++a)
        for (int b = a; b < 6; ++b)
          {
            double v = 0.;
            for (int k = b; k < 6; ++k)
              v += W[k][a] * W[k][b];
            inverse(a, b) = inverse(b, a) = v;
          }
      return true;
    }
  } // namespace



  void
  BlockSparseMatrix::reinit(const int                               n,
                            const std::vector<std::pair<int, int>> &p)
  {
    diag.assign(n, Matrix6::Zero());
    pairs = p;
    off.assign(pairs.size(), Matrix6::Zero());
  }



  void
  BlockSparseMatrix::set_zero()
  {
    for (auto &m : diag)
      m.setZero();
    for (auto &m : off)
      m.setZero();
  }



  void
  BlockSparseMatrix::vmult(const Eigen::VectorXd &x, Eigen::VectorXd &y) const
  {
    y.resize(x.size());
    const int n = n_blocks();
    for (int i = 0; i < n; ++i)
      y.segment<6>(6 * i).noalias() = diag[i] * x.segment<6>(6 * i);
    for (std::size_t k = 0; k < pairs.size(); ++k)
      {
        const int      i = pairs[k].first, j = pairs[k].second;
        const Matrix6 &A  = off[k];
        const auto     xi = x.segment<6>(6 * i);
        y.segment<6>(6 * i).noalias() += A * x.segment<6>(6 * j);
        // y_j += A^T x_i, column by column (vectorises, unlike the lazy
        // transposed product).
        for (int c = 0; c < 6; ++c)
          y[6 * j + c] += A.col(c).dot(xi);
      }
  }



  /// The direct solver: a lower-triangular CSC copy of the matrix whose
  /// values are gathered from the block storage through a fixed map, and
  /// its sparse LDL^T factorisation (Eigen SimplicialLDLT, AMD ordering).
  /// The symbolic analysis is kept while the block pattern is unchanged.
  /// (CHOLMOD's supernodal LL^T was measured 1.3-3x slower at 1,000
  /// blocks with the reference BLAS of this machine and is not used.)
  struct LinearSolver::Direct
  {
    using Sparse = Eigen::SparseMatrix<double, Eigen::ColMajor, int>;
    Sparse                                                               matrix;
    Eigen::SimplicialLDLT<Sparse, Eigen::Lower, Eigen::AMDOrdering<int>> ldlt;
    /// For each stored value: block kind (0 diag, 1 off), index, entry.
    std::vector<int>  source_block, source_entry;
    std::vector<char> source_kind;
    /// The pattern analysed last.
    std::vector<std::pair<int, int>> analysed_pairs;
    int                              analysed_blocks = -1;

    /// True if the factorisation has only positive pivots.
    bool
    positive_definite() const
    {
      if (ldlt.info() != Eigen::Success)
        return false;
      return !(ldlt.vectorD().array() <= 0.).any();
    }

    void
    analyse(const BlockSparseMatrix &K)
    {
      const int n = K.n_blocks();
      if (n == analysed_blocks && K.pairs == analysed_pairs)
        return;
      analysed_blocks = n;
      analysed_pairs  = K.pairs;
      // Column block c: the diagonal block's lower part, then the
      // transposed upper blocks K_cj (j > c) as rows of block j.
      std::vector<std::vector<std::pair<int, int>>> below(n);
      for (std::size_t k = 0; k < K.pairs.size(); ++k)
        below[K.pairs[k].first].emplace_back(K.pairs[k].second,
                                             static_cast<int>(k));
      for (auto &b : below)
        std::sort(b.begin(), b.end());
      matrix.resize(6 * n, 6 * n);
      std::size_t nnz = 21 * static_cast<std::size_t>(n) + 36 * K.pairs.size();
      matrix.resizeNonZeros(nnz);
      source_block.resize(nnz);
      source_entry.resize(nnz);
      source_kind.resize(nnz);
      int *outer = matrix.outerIndexPtr();
      int *inner = matrix.innerIndexPtr();
      int  pos   = 0;
      for (int c = 0; c < n; ++c)
        for (int a = 0; a < 6; ++a)
          {
            outer[6 * c + a] = pos;
            for (int b = a; b < 6; ++b)
              {
                inner[pos]        = 6 * c + b;
                source_kind[pos]  = 0;
                source_block[pos] = c;
                source_entry[pos] = b + 6 * a; // (b, a) column-major
                ++pos;
              }
            for (const auto &[j, k] : below[c])
              for (int b = 0; b < 6; ++b)
                {
                  // entry (6j + b, 6c + a) = K_cj(a, b)
                  inner[pos]        = 6 * j + b;
                  source_kind[pos]  = 1;
                  source_block[pos] = k;
                  source_entry[pos] = a + 6 * b;
                  ++pos;
                }
          }
      outer[6 * n] = pos;
      gather(K);
      ldlt.analyzePattern(matrix);
    }

    void
    gather(const BlockSparseMatrix &K)
    {
      double    *v = matrix.valuePtr();
      const auto n = source_kind.size();
      for (std::size_t p = 0; p < n; ++p)
        v[p] = source_kind[p] == 0
                 ? K.diag[source_block[p]].data()[source_entry[p]]
                 : K.off[source_block[p]].data()[source_entry[p]];
    }
  };



  LinearSolver::LinearSolver(const SolverOptions &options)
      : options(options)
  {}



  LinearSolver::~LinearSolver() = default;



  void
  LinearSolver::new_pattern(const BlockSparseMatrix &K)
  {
    factorised = false;
    current    = options.type;
    if (current == SolverType::automatic)
      current = K.n_blocks() <= options.automatic_limit ? SolverType::direct
                                                        : SolverType::iterative;
    if (current == SolverType::direct)
      {
        if (!direct)
          direct = std::make_unique<Direct>();
        direct->analyse(K);
      }
  }



  bool
  LinearSolver::solve(const BlockSparseMatrix &K,
                      const Eigen::VectorXd   &f,
                      Eigen::VectorXd         &x,
                      const bool               same_matrix)
  {
    iterations = 0;
    if (current == SolverType::direct)
      {
        if (!same_matrix || !factorised)
          {
            factorised = false;
            direct->gather(K);
            direct->ldlt.factorize(direct->matrix);
            if (!direct->positive_definite())
              return false;
            factorised = true;
          }
        x = direct->ldlt.solve(f);
        return x.allFinite();
      }

    if (!same_matrix || !factorised)
      {
        factorised = setup_preconditioner(K);
        if (!factorised)
          return false;
      }
    if (x.size() != f.size() || !x.allFinite())
      x = Eigen::VectorXd::Zero(f.size());
    return options.preconditioner == Preconditioner::block_dilu
             ? dilu_cg(K, f, x)
             : jacobi_cg(K, f, x);
  }



  int
  LinearSolver::iteration_limit(const int n) const
  {
    return options.max_iterations > 0 ? options.max_iterations
                                      : std::min(20000, 60 * n + 100);
  }



  bool
  LinearSolver::setup_preconditioner(const BlockSparseMatrix &K)
  {
    const int n = K.n_blocks();
    inverse_diag.resize(n);
    if (options.preconditioner == Preconditioner::block_jacobi)
      {
        for (int i = 0; i < n; ++i)
          if (!invert_spd(K.diag[i], inverse_diag[i]))
            return false;
        return true;
      }
    // Rows of the upper block triangle.
    row_start.assign(n + 1, 0);
    for (const auto &pr : K.pairs)
      ++row_start[pr.first + 1];
    for (int i = 0; i < n; ++i)
      row_start[i + 1] += row_start[i];
    // Pivots P_i = K_ii - sum_{j<i} K_ij P_j^-1 K_ji, accumulated forward.
    pivot.assign(K.diag.begin(), K.diag.end());
    diag_shift.resize(n);
    for (int i = 0; i < n; ++i)
      {
        if (!invert_spd(pivot[i], inverse_diag[i]))
          {
            // Modified pivot not positive definite: fall back to the
            // diagonal block (symmetric Gauss-Seidel there); M stays SPD.
            pivot[i] = K.diag[i];
            if (!invert_spd(pivot[i], inverse_diag[i]))
              return false;
          }
        diag_shift[i] = K.diag[i] - 2. * pivot[i];
        for (int k = row_start[i]; k < row_start[i + 1]; ++k)
          {
            const Matrix6 &A   = K.off[k];
            const Matrix6  PiA = inverse_diag[i].lazyProduct(A);
            pivot[K.pairs[k].second].noalias()
              -= A.transpose().lazyProduct(PiA);
          }
      }
    return true;
  }



  bool
  LinearSolver::jacobi_cg(const BlockSparseMatrix &K,
                          const Eigen::VectorXd   &f,
                          Eigen::VectorXd         &x)
  {
    const int n       = K.n_blocks();
    auto precondition = [&](const Eigen::VectorXd &in, Eigen::VectorXd &out) {
      out.resize(in.size());
      for (int i = 0; i < n; ++i)
        out.segment<6>(6 * i).noalias()
          = inverse_diag[i] * in.segment<6>(6 * i);
    };
    precondition(f, z);
    const double bnorm = f.dot(z);
    if (!(bnorm > 0.))
      {
        x.setZero();
        return std::isfinite(bnorm);
      }
    K.vmult(x, q);
    r = f - q;
    precondition(r, z);
    p                   = z;
    double       rz     = r.dot(z);
    const double tol2   = options.tolerance * options.tolerance * bnorm;
    const int    max_it = iteration_limit(n);
    while (rz > tol2)
      {
        if (iterations >= max_it)
          return false;
        ++iterations;
        K.vmult(p, q);
        const double pq = p.dot(q);
        if (!(pq > 0.))
          return false;
        const double alpha = rz / pq;
        x += alpha * p;
        r -= alpha * q;
        precondition(r, z);
        const double rz_new = r.dot(z);
        p                   = z + (rz_new / rz) * p;
        rz                  = rz_new;
        if (!std::isfinite(rz))
          return false;
      }
    return x.allFinite();
  }



  void
  LinearSolver::backward_sweep(const BlockSparseMatrix &K,
                               const Eigen::VectorXd   &v,
                               Eigen::VectorXd         &out) const
  {
    const int n = K.n_blocks();
    out.resize(v.size());
    for (int i = n - 1; i >= 0; --i)
      {
        Vector6 acc = v.segment<6>(6 * i);
        for (int k = row_start[i]; k < row_start[i + 1]; ++k)
          acc.noalias() -= K.off[k] * out.segment<6>(6 * K.pairs[k].second);
        out.segment<6>(6 * i).noalias() = inverse_diag[i] * acc;
      }
  }



  void
  LinearSolver::forward_sweep(const BlockSparseMatrix &K,
                              Eigen::VectorXd         &w) const
  {
    const int n = K.n_blocks();
    for (int i = 0; i < n; ++i)
      {
        const Vector6 s     = inverse_diag[i] * w.segment<6>(6 * i);
        w.segment<6>(6 * i) = s;
        for (int k = row_start[i]; k < row_start[i + 1]; ++k)
          {
            const Matrix6 &A = K.off[k];
            const int      j = K.pairs[k].second;
            for (int c = 0; c < 6; ++c)
              w[6 * j + c] -= A.col(c).dot(s);
          }
      }
  }



  bool
  LinearSolver::dilu_cg(const BlockSparseMatrix &K,
                        const Eigen::VectorXd   &f,
                        Eigen::VectorXd         &x)
  {
    // PCG on K with M = (P + L) P^-1 (P + U) is CG on
    // A^ = (P + L)^-1 K (P + U)^-1 (unknown y = (P + U) x) preconditioned
    // by multiplication with P. With K = (P + L) + (P + U) + (D - 2 P):
    // A^ v = t + (P + L)^-1 (v + (D - 2 P) t), t = (P + U)^-1 v.
    const int n      = K.n_blocks();
    auto times_pivot = [&](const Eigen::VectorXd &in, Eigen::VectorXd &out) {
      out.resize(in.size());
      for (int i = 0; i < n; ++i)
        out.segment<6>(6 * i).noalias() = pivot[i] * in.segment<6>(6 * i);
    };
    // Right-hand side norm r^T M^-1 r for the stopping test.
    r = f;
    forward_sweep(K, r);
    times_pivot(r, z);
    const double bnorm = r.dot(z);
    if (!(bnorm > 0.))
      {
        x.setZero();
        return std::isfinite(bnorm);
      }
    // y0 = (P + U) x0, r^0 = (P + L)^-1 (f - K x0).
    Eigen::VectorXd &y = t_y;
    times_pivot(x, y);
    for (std::size_t k = 0; k < K.pairs.size(); ++k)
      y.segment<6>(6 * K.pairs[k].first).noalias()
        += K.off[k] * x.segment<6>(6 * K.pairs[k].second);
    K.vmult(x, q);
    r = f - q;
    forward_sweep(K, r);
    times_pivot(r, z);
    p = Eigen::VectorXd::Zero(f.size());
    q.resize(f.size());
    t.resize(f.size());
    double       rz     = r.dot(z);
    double       beta   = 0.;
    const double tol2   = options.tolerance * options.tolerance * bnorm;
    const int    max_it = iteration_limit(n);
    // One pass per sweep, with the vector updates fused into them:
    // p = z + beta p in the backward sweep, q = A^ p and p.q in the forward
    // sweep, then y, r, z and r.z in one loop.
    while (rz > tol2)
      {
        if (iterations >= max_it)
          return false;
        ++iterations;
        for (int i = n - 1; i >= 0; --i)
          {
            auto pi     = p.segment<6>(6 * i);
            pi          = z.segment<6>(6 * i) + beta * pi;
            Vector6 acc = pi;
            for (int k = row_start[i]; k < row_start[i + 1]; ++k)
              acc.noalias() -= K.off[k] * t.segment<6>(6 * K.pairs[k].second);
            t.segment<6>(6 * i).noalias() = inverse_diag[i] * acc;
          }
        q.setZero();
        double pq = 0.;
        for (int i = 0; i < n; ++i)
          {
            const auto ti = t.segment<6>(6 * i);
            auto       qi = q.segment<6>(6 * i);
            Vector6    w  = qi + p.segment<6>(6 * i);
            w.noalias() += diag_shift[i] * ti;
            const Vector6 si = inverse_diag[i] * w;
            qi               = si + ti;
            pq += p.segment<6>(6 * i).dot(qi);
            for (int k = row_start[i]; k < row_start[i + 1]; ++k)
              {
                const Matrix6 &A = K.off[k];
                const int      j = K.pairs[k].second;
                for (int c = 0; c < 6; ++c)
                  q[6 * j + c] -= A.col(c).dot(si);
              }
          }
        if (!(pq > 0.))
          return false;
        const double alpha  = rz / pq;
        double       rz_new = 0.;
        for (int i = 0; i < n; ++i)
          {
            y.segment<6>(6 * i) += alpha * p.segment<6>(6 * i);
            auto ri = r.segment<6>(6 * i);
            ri -= alpha * q.segment<6>(6 * i);
            auto zi      = z.segment<6>(6 * i);
            zi.noalias() = pivot[i] * ri;
            rz_new += ri.dot(zi);
          }
        beta = rz_new / rz;
        rz   = rz_new;
        if (!std::isfinite(rz))
          return false;
      }
    backward_sweep(K, y, x);
    return x.allFinite();
  }
} // namespace rockdda::dda
