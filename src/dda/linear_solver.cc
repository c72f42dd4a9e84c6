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
    const int n = K.n_blocks();
    iterations  = 0;
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

    // Block-Jacobi preconditioned CG.
    if (!same_matrix || !factorised)
      {
        factorised = false;
        inverse_diag.resize(n);
        for (int i = 0; i < n; ++i)
          {
            Eigen::LLT<Matrix6> llt(K.diag[i]);
            if (llt.info() != Eigen::Success)
              return false;
            inverse_diag[i] = llt.solve(Matrix6::Identity());
          }
        factorised = true;
      }
    auto precondition = [&](const Eigen::VectorXd &in, Eigen::VectorXd &out) {
      out.resize(in.size());
      for (int i = 0; i < n; ++i)
        out.segment<6>(6 * i).noalias()
          = inverse_diag[i] * in.segment<6>(6 * i);
    };
    if (x.size() != f.size() || !x.allFinite())
      x = Eigen::VectorXd::Zero(f.size());
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
    const int    max_it = options.max_iterations > 0
                            ? options.max_iterations
                            : std::min(20000, 60 * n + 100);
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
} // namespace rockdda::dda
