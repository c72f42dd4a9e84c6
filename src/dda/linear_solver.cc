/**
 * @file
 * Block sparse matrix and its direct and iterative solvers, over the
 * number of unknowns per block (explicitly instantiated for 6 and 12).
 */
#include <rockdda/dda/linear_solver.h>

#include <deal.II/base/mpi.h>

#include <Eigen/Cholesky>
#include <Eigen/SparseCore>

#include "block_cholesky.h"
#include "distributed_solver.h"
#include "task_team.h"
#include "thread_pair.h"
#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <thread>

namespace rockdda::dda
{
  namespace
  {
    /// Ranks of MPI_COMM_WORLD (1 without MPI).
    int
    world_ranks()
    {
      return dealii::Utilities::MPI::job_supports_mpi() ? static_cast<int>(
               dealii::Utilities::MPI::n_mpi_processes(MPI_COMM_WORLD))
                                                        : 1;
    }

    /// Ranks of MPI_COMM_WORLD on this machine (1 without MPI).
    int
    ranks_on_this_machine()
    {
      if (world_ranks() == 1)
        return 1;
      MPI_Comm node;
      MPI_Comm_split_type(
        MPI_COMM_WORLD, MPI_COMM_TYPE_SHARED, 0, MPI_INFO_NULL, &node);
      int n = 1;
      MPI_Comm_size(node, &n);
      MPI_Comm_free(&node);
      return n;
    }

    /// Inverse of a symmetric positive definite m x m matrix by Cholesky
    /// (fixed-size loops; Eigen's LLT::solve takes a generic path here).
    /// Returns false if a pivot is not positive.
    template <int m>
    bool
    invert_spd(const Eigen::Matrix<double, m, m> &A,
               Eigen::Matrix<double, m, m>       &inverse)
    {
      double L[m][m] = {};
      for (int j = 0; j < m; ++j)
        {
          double d = A(j, j);
          for (int k = 0; k < j; ++k)
            d -= L[j][k] * L[j][k];
          if (!(d > 0.))
            return false;
          L[j][j] = std::sqrt(d);
          for (int i = j + 1; i < m; ++i)
            {
              double v = A(i, j);
              for (int k = 0; k < j; ++k)
                v -= L[i][k] * L[j][k];
              L[i][j] = v / L[j][j];
            }
        }
      // W = L^-1 (lower triangular), inverse = W^T W.
      double W[m][m] = {};
      for (int c = 0; c < m; ++c)
        {
          W[c][c] = 1. / L[c][c];
          for (int i = c + 1; i < m; ++i)
            {
              double v = 0.;
              for (int k = c; k < i; ++k)
                v -= L[i][k] * W[k][c];
              W[i][c] = v / L[i][i];
            }
        }
      for (int a = 0; a < m; ++a)
        for (int b = a; b < m; ++b)
          {
            double v = 0.;
            for (int k = b; k < m; ++k)
              v += W[k][a] * W[k][b];
            inverse(a, b) = inverse(b, a) = v;
          }
      return true;
    }
  } // namespace



  template <int dofs>
  void
  BlockSparseMatrixOf<dofs>::reinit(const int                               n,
                                    const std::vector<std::pair<int, int>> &p)
  {
    diag.assign(n, Dense::Zero());
    pairs = p;
    off.assign(pairs.size(), Dense::Zero());
  }



  template <int dofs>
  void
  BlockSparseMatrixOf<dofs>::set_zero()
  {
    for (auto &m : diag)
      m.setZero();
    for (auto &m : off)
      m.setZero();
  }



  template <int dofs>
  void
  BlockSparseMatrixOf<dofs>::vmult(const Eigen::VectorXd &x,
                                   Eigen::VectorXd       &y) const
  {
    y.resize(x.size());
    const int n = n_blocks();
    for (int i = 0; i < n; ++i)
      y.template segment<dofs>(dofs * i).noalias()
        = diag[i] * x.template segment<dofs>(dofs * i);
    for (std::size_t k = 0; k < pairs.size(); ++k)
      {
        const int    i = pairs[k].first, j = pairs[k].second;
        const Dense &A  = off[k];
        const auto   xi = x.template segment<dofs>(dofs * i);
        y.template segment<dofs>(dofs * i).noalias()
          += A * x.template segment<dofs>(dofs * j);
        // y_j += A^T x_i, column by column (vectorises, unlike the lazy
        // transposed product).
        for (int c = 0; c < dofs; ++c)
          y[dofs * j + c] += A.col(c).dot(xi);
      }
  }



  /// The direct solver: the block sparse Cholesky factorisation of the
  /// matrix (internal::BlockCholeskyOf, minimum-degree ordering of the
  /// blocks), its ordering and fill-in kept while the block pattern is
  /// unchanged. It replaced a scalar sparse LDL^T (Eigen SimplicialLDLT)
  /// that spent most of its time in index work (doc/theory/dda.md, "Linear
  /// solvers"; benchmarks/dda-scaling README).
  template <int dofs>
  struct LinearSolverOf<dofs>::Direct
  {
    internal::BlockCholeskyOf<dofs> cholesky;
  };



  namespace
  {
    /**
     * Two subdomains and a separator of the block graph (the pairs): BFS
     * level structure from a pseudo-peripheral block of each connected
     * component (levels numbered on across components), split at the level
     * that best balances the blocks below and above it. Edges join equal
     * or neighbouring levels only, so that level separates the blocks
     * below it (part 0) from those above (part 1); it is part 2 (George &
     * Liu 1981, Computer Solution of Large Sparse Positive Definite
     * Systems, ch. 4 and 8).
     */
    std::vector<int>
    two_subdomains(const int n, const std::vector<std::pair<int, int>> &pairs)
    {
      std::vector<int> start(n + 1, 0), adjacent(2 * pairs.size());
      for (const auto &pr : pairs)
        {
          ++start[pr.first + 1];
          ++start[pr.second + 1];
        }
      for (int i = 0; i < n; ++i)
        start[i + 1] += start[i];
      std::vector<int> fill(start.begin(), start.end() - 1);
      for (const auto &pr : pairs)
        {
          adjacent[fill[pr.first]++]  = pr.second;
          adjacent[fill[pr.second]++] = pr.first;
        }
      std::vector<int> level(n, -1), probe(n, -1), queue;
      queue.reserve(n);
      const auto bfs = [&](const int root, std::vector<int> &depth, int base) {
        queue.clear();
        queue.push_back(root);
        depth[root] = base;
        for (std::size_t h = 0; h < queue.size(); ++h)
          {
            const int u = queue[h];
            for (int a = start[u]; a < start[u + 1]; ++a)
              if (depth[adjacent[a]] < 0)
                {
                  depth[adjacent[a]] = depth[u] + 1;
                  queue.push_back(adjacent[a]);
                }
          }
        return depth[queue.back()];
      };
      int n_levels = 0;
      for (int s = 0; s < n; ++s)
        if (level[s] < 0)
          {
            bfs(s, probe, 0);
            n_levels = bfs(queue.back(), level, n_levels) + 1;
          }
      std::vector<int> count(n_levels, 0);
      for (int i = 0; i < n; ++i)
        ++count[level[i]];
      int split = 0, best = n + 1;
      for (int l = 0, b = 0; l < n_levels; b += count[l], ++l)
        {
          const int imbalance = std::abs(b - (n - b - count[l]));
          if (imbalance < best)
            {
              best  = imbalance;
              split = l;
            }
        }
      std::vector<int> part(n);
      for (int i = 0; i < n; ++i)
        part[i] = level[i] < split ? 0 : level[i] > split ? 1 : 2;
      return part;
    }
  } // namespace



  /**
   * Block D-ILU preconditioned CG with Eisenstat's trick. Large systems are
   * renumbered as subdomain 0, subdomain 1, separator (each in the
   * original order): the two subdomains do not couple, so their parts of
   * the pivot computation and of both sweeps run in parallel, and the
   * separator is eliminated last. The operations and their order are the
   * same for one and two threads.
   */
  template <int dofs>
  struct LinearSolverOf<dofs>::Dilu
  {
    using Dense  = typename Matrix::Dense;
    using Vector = Eigen::Matrix<double, dofs, 1>;

    /// Renumbered (new -> old), or the natural order.
    bool             renumbered = false;
    std::vector<int> order;
    /// Source pair of each renumbered pair, and whether it is transposed.
    std::vector<int>  pair_source;
    std::vector<char> pair_transposed;
    Matrix            renumbered_matrix;
    /// Subdomain 0 = [0, end0), subdomain 1 = [end0, end1), separator =
    /// [end1, n).
    int n = 0, end0 = 0, end1 = 0;
    /// The matrix the sweeps use (renumbered_matrix or the caller's).
    const Matrix    *M = nullptr;
    std::vector<int> row_start;
    /// Pivots P_i, their inverses and K_ii - 2 P_i.
    std::vector<Dense> pivot, inverse_pivot, diag_shift;
    /// Contributions of each subdomain to the separator's pivots.
    std::vector<Dense> pivot_update[2];
    Eigen::VectorXd    f, x, r, z, p, q, t, y;
    /// Contributions of each subdomain to q on the separator.
    Eigen::VectorXd q_update[2];
    double          partial[2] = {0., 0.};

    /// Rows [begin, end) of subdomain @p part (0, 1) or the separator (2).
    std::pair<int, int>
    rows(const int part) const
    {
      return part == 0   ? std::make_pair(0, end0)
             : part == 1 ? std::make_pair(end0, end1)
                         : std::make_pair(end1, n);
    }

    void
    new_pattern(const Matrix &K, const int subdomain_limit)
    {
      n          = K.n_blocks();
      renumbered = n >= subdomain_limit && n >= 3;
      const std::vector<std::pair<int, int>> *pairs = &K.pairs;
      end0 = end1 = n;
      if (renumbered)
        {
          const std::vector<int> part = two_subdomains(n, K.pairs);
          order.clear();
          for (int which = 0; which < 3; ++which)
            for (int i = 0; i < n; ++i)
              if (part[i] == which)
                order.push_back(i);
          end0 = static_cast<int>(std::count(part.begin(), part.end(), 0));
          end1
            = end0 + static_cast<int>(std::count(part.begin(), part.end(), 1));
          std::vector<int> position(n);
          for (int i = 0; i < n; ++i)
            position[order[i]] = i;
          std::vector<std::pair<std::pair<int, int>, int>> renumbered_pairs;
          renumbered_pairs.reserve(K.pairs.size());
          for (std::size_t k = 0; k < K.pairs.size(); ++k)
            {
              const int a = position[K.pairs[k].first];
              const int b = position[K.pairs[k].second];
              // Source index, negative (-k - 1) when K_ab is transposed.
              renumbered_pairs.push_back(
                a < b ? std::make_pair(std::make_pair(a, b), int(k))
                      : std::make_pair(std::make_pair(b, a), -int(k) - 1));
            }
          std::sort(renumbered_pairs.begin(), renumbered_pairs.end());
          std::vector<std::pair<int, int>> new_pairs;
          new_pairs.reserve(renumbered_pairs.size());
          pair_source.resize(renumbered_pairs.size());
          pair_transposed.resize(renumbered_pairs.size());
          for (std::size_t k = 0; k < renumbered_pairs.size(); ++k)
            {
              new_pairs.push_back(renumbered_pairs[k].first);
              const int s        = renumbered_pairs[k].second;
              pair_transposed[k] = s < 0;
              pair_source[k]     = s < 0 ? -s - 1 : s;
            }
          renumbered_matrix.reinit(n, new_pairs);
          pairs = &renumbered_matrix.pairs;
        }
      row_start.assign(n + 1, 0);
      for (const auto &pr : *pairs)
        ++row_start[pr.first + 1];
      for (int i = 0; i < n; ++i)
        row_start[i + 1] += row_start[i];
      pivot.resize(n);
      inverse_pivot.resize(n);
      diag_shift.resize(n);
      for (auto &u : pivot_update)
        u.resize(n - end1);
      for (auto &v : {&f, &x, &r, &z, &p, &q, &t, &y})
        v->resize(dofs * n);
      for (auto &u : q_update)
        u.resize(dofs * (n - end1));
    }

    /// Copy the values of @p K into the renumbered matrix.
    void
    gather(const Matrix &K)
    {
      if (!renumbered)
        {
          M = &K;
          return;
        }
      M = &renumbered_matrix;
      for (int i = 0; i < n; ++i)
        renumbered_matrix.diag[i] = K.diag[order[i]];
      for (std::size_t k = 0; k < pair_source.size(); ++k)
        if (pair_transposed[k])
          renumbered_matrix.off[k] = K.off[pair_source[k]].transpose();
        else
          renumbered_matrix.off[k] = K.off[pair_source[k]];
    }

    /// Run f(0), f(1): on two threads when renumbered.
    template <typename F>
    void
    run(internal::ThreadPair &team, F &&f)
    {
      if (renumbered)
        team.run(f);
      else
        {
          f(0);
          f(1);
        }
    }

    /// Pivot of row @p i (its P_i accumulated), then its updates of later
    /// pivots; those of the separator go to @p separator_update when given.
    bool
    eliminate(const int i, std::vector<Dense> *separator_update)
    {
      const Matrix &K = *M;
      if (!invert_spd(pivot[i], inverse_pivot[i]))
        {
          // Modified pivot not positive definite: fall back to the
          // diagonal block (symmetric Gauss-Seidel there); M stays SPD.
          pivot[i] = K.diag[i];
          if (!invert_spd(pivot[i], inverse_pivot[i]))
            return false;
        }
      diag_shift[i] = K.diag[i] - 2. * pivot[i];
      for (int k = row_start[i]; k < row_start[i + 1]; ++k)
        {
          const Dense &A      = K.off[k];
          const Dense  PiA    = inverse_pivot[i].lazyProduct(A);
          const int    j      = K.pairs[k].second;
          Dense       &target = (separator_update != nullptr && j >= end1)
                                  ? (*separator_update)[j - end1]
                                  : pivot[j];
          target.noalias() -= A.transpose().lazyProduct(PiA);
        }
      return true;
    }

    /// Pivots P_i = K_ii - sum_{j<i} K_ij P_j^-1 K_ji.
    bool
    setup(const Matrix &K_in, internal::ThreadPair &team)
    {
      gather(K_in);
      const Matrix &K     = *M;
      bool          ok[2] = {true, true};
      auto          part  = [&](const int d) {
        const auto [begin, end] = rows(d);
        for (auto &u : pivot_update[d])
          u.setZero();
        for (int i = begin; i < end; ++i)
          pivot[i] = K.diag[i];
        for (int i = begin; i < end && ok[d]; ++i)
          ok[d] = eliminate(i, &pivot_update[d]);
      };
      run(team, part);
      if (!ok[0] || !ok[1])
        return false;
      for (int i = end1; i < n; ++i)
        pivot[i]
          = K.diag[i] + pivot_update[0][i - end1] + pivot_update[1][i - end1];
      for (int i = end1; i < n; ++i)
        if (!eliminate(i, nullptr))
          return false;
      return true;
    }

    /// Solve (P + U) out = v, U the strict upper block triangle.
    void
    backward_sweep(const Eigen::VectorXd &v, Eigen::VectorXd &out) const
    {
      const Matrix &K = *M;
      for (int i = n - 1; i >= 0; --i)
        {
          Vector acc = v.template segment<dofs>(dofs * i);
          // Descending, as backward_rows.
          for (int k = row_start[i + 1] - 1; k >= row_start[i]; --k)
            acc.noalias()
              -= K.off[k]
                 * out.template segment<dofs>(dofs * K.pairs[k].second);
          out.template segment<dofs>(dofs * i).noalias()
            = inverse_pivot[i] * acc;
        }
    }

    /// Solve (P + L) s = w in place.
    void
    forward_sweep(Eigen::VectorXd &w) const
    {
      const Matrix &K = *M;
      for (int i = 0; i < n; ++i)
        {
          const Vector s
            = inverse_pivot[i] * w.template segment<dofs>(dofs * i);
          w.template segment<dofs>(dofs * i) = s;
          for (int k = row_start[i]; k < row_start[i + 1]; ++k)
            {
              const Dense &A = K.off[k];
              const int    j = K.pairs[k].second;
              for (int c = 0; c < dofs; ++c)
                w[dofs * j + c] -= A.col(c).dot(s);
            }
        }
    }

    /// Rows [begin, end) of the backward sweep of the Eisenstat operator
    /// with p = z + beta p fused in: t = (P + U)^-1 p.
    void
    backward_rows(const int begin, const int end, const double beta)
    {
      const Matrix &K = *M;
      for (int i = end - 1; i >= begin; --i)
        {
          auto pi    = p.template segment<dofs>(dofs * i);
          pi         = z.template segment<dofs>(dofs * i) + beta * pi;
          Vector acc = pi;
          // The row's blocks in descending order: the sweep then reads the
          // off-diagonal blocks as one descending stream, which the hardware
          // prefetcher follows (ascending within each row, it read them 3x
          // slower than the forward sweep: benchmarks/dda-scaling, section 14).
          for (int k = row_start[i + 1] - 1; k >= row_start[i]; --k)
            acc.noalias()
              -= K.off[k] * t.template segment<dofs>(dofs * K.pairs[k].second);
          t.template segment<dofs>(dofs * i).noalias() = inverse_pivot[i] * acc;
        }
    }

    /// Rows [begin, end) of the forward sweep: q = t + (P + L)^-1 (p +
    /// (D - 2P) t); q must hold the updates from earlier rows. Updates of
    /// the separator go to @p separator_update when given. Returns the
    /// rows' part of p.q.
    double
    forward_rows(const int        begin,
                 const int        end,
                 Eigen::VectorXd *separator_update)
    {
      const Matrix &K  = *M;
      double        pq = 0.;
      for (int i = begin; i < end; ++i)
        {
          const auto ti = t.template segment<dofs>(dofs * i);
          auto       qi = q.template segment<dofs>(dofs * i);
          Vector     w  = qi + p.template segment<dofs>(dofs * i);
          w.noalias() += diag_shift[i] * ti;
          const Vector si = inverse_pivot[i] * w;
          qi              = si + ti;
          pq += p.template segment<dofs>(dofs * i).dot(qi);
          for (int k = row_start[i]; k < row_start[i + 1]; ++k)
            {
              const Dense &A      = K.off[k];
              const int    j      = K.pairs[k].second;
              double      *target = (separator_update != nullptr && j >= end1)
                                      ? separator_update->data() + dofs * (j - end1)
                                      : q.data() + dofs * j;
              for (int c = 0; c < dofs; ++c)
                target[c] -= A.col(c).dot(si);
            }
        }
      return pq;
    }

    /// Rows [begin, end): y += alpha p, r -= alpha q, z = P r; returns
    /// their part of r.z.
    double
    update_rows(const int begin, const int end, const double alpha)
    {
      double rz = 0.;
      for (int i = begin; i < end; ++i)
        {
          y.template segment<dofs>(dofs * i)
            += alpha * p.template segment<dofs>(dofs * i);
          auto ri = r.template segment<dofs>(dofs * i);
          ri -= alpha * q.template segment<dofs>(dofs * i);
          auto zi      = z.template segment<dofs>(dofs * i);
          zi.noalias() = pivot[i] * ri;
          rz += ri.dot(zi);
        }
      return rz;
    }

    /// PCG on K with M = (P + L) P^-1 (P + U) is CG on
    /// A^ = (P + L)^-1 K (P + U)^-1 (unknown y = (P + U) x) preconditioned
    /// by multiplication with P. With K = (P + L) + (P + U) + (D - 2 P):
    /// A^ v = t + (P + L)^-1 (v + (D - 2 P) t), t = (P + U)^-1 v.
    bool
    cg(const Eigen::VectorXd &f_in,
       Eigen::VectorXd       &x_out,
       internal::ThreadPair  &team,
       const double           tolerance,
       const int              max_iterations,
       int                   &iterations)
    {
      const Matrix &K = *M;
      if (renumbered)
        for (int i = 0; i < n; ++i)
          {
            f.template segment<dofs>(dofs * i)
              = f_in.template segment<dofs>(dofs * order[i]);
            x.template segment<dofs>(dofs * i)
              = x_out.template segment<dofs>(dofs * order[i]);
          }
      else
        {
          f = f_in;
          x = x_out;
        }
      auto times_pivot = [&](const Eigen::VectorXd &in, Eigen::VectorXd &out) {
        for (int i = 0; i < n; ++i)
          out.template segment<dofs>(dofs * i).noalias()
            = pivot[i] * in.template segment<dofs>(dofs * i);
      };
      // Right-hand side norm r^T M^-1 r for the stopping test.
      r = f;
      forward_sweep(r);
      times_pivot(r, z);
      const double bnorm = r.dot(z);
      if (!(bnorm > 0.))
        {
          x_out.setZero();
          return std::isfinite(bnorm);
        }
      // y0 = (P + U) x0, r^0 = (P + L)^-1 (f - K x0).
      times_pivot(x, y);
      for (std::size_t k = 0; k < K.pairs.size(); ++k)
        y.template segment<dofs>(dofs * K.pairs[k].first).noalias()
          += K.off[k] * x.template segment<dofs>(dofs * K.pairs[k].second);
      K.vmult(x, q);
      r = f - q;
      forward_sweep(r);
      times_pivot(r, z);
      p.setZero();
      double       rz   = r.dot(z);
      double       beta = 0.;
      const double tol2 = tolerance * tolerance * bnorm;
      // One pass per sweep, with the vector updates fused into them.
      // Separator rows first (backward), then both subdomains (backward
      // and forward, in parallel), then the separator (forward), then the
      // vector updates (in parallel).
      while (rz > tol2)
        {
          if (iterations >= max_iterations)
            return false;
          ++iterations;
          backward_rows(end1, n, beta);
          auto sweeps = [&](const int d) {
            const auto [begin, end] = rows(d);
            q.segment(dofs * begin, dofs * (end - begin)).setZero();
            q_update[d].setZero();
            backward_rows(begin, end, beta);
            partial[d] = forward_rows(begin, end, &q_update[d]);
          };
          run(team, sweeps);
          q.segment(dofs * end1, dofs * (n - end1)) = q_update[0] + q_update[1];
          const double pq
            = (partial[0] + partial[1]) + forward_rows(end1, n, nullptr);
          if (!(pq > 0.))
            return false;
          const double alpha   = rz / pq;
          auto         updates = [&](const int d) {
            const auto [begin, end] = rows(d);
            partial[d]              = update_rows(begin, end, alpha);
            if (d == 0)
              partial[d] += update_rows(end1, n, alpha);
          };
          run(team, updates);
          const double rz_new = partial[0] + partial[1];
          beta                = rz_new / rz;
          rz                  = rz_new;
          if (!std::isfinite(rz))
            return false;
        }
      backward_sweep(y, x);
      if (renumbered)
        for (int i = 0; i < n; ++i)
          x_out.template segment<dofs>(dofs * order[i])
            = x.template segment<dofs>(dofs * i);
      else
        x_out = x;
      return x_out.allFinite();
    }
  };



  template <int dofs>
  LinearSolverOf<dofs>::LinearSolverOf(const SolverOptions &options)
      : options(options)
      , machine_ranks(ranks_on_this_machine())
  {}



  template <int dofs>
  LinearSolverOf<dofs>::~LinearSolverOf() = default;



  template <int dofs>
  int
  LinearSolverOf<dofs>::n_ranks() const
  {
    return distributed ? distributed->n_ranks() : 1;
  }



  template <int dofs>
  unsigned int
  LinearSolverOf<dofs>::n_threads() const
  {
    return team_of_run().n_threads();
  }



  template <int dofs>
  int
  LinearSolverOf<dofs>::separator_size() const
  {
    return dilu && dilu->renumbered ? dilu->n - dilu->end1 : 0;
  }



  template <int dofs>
  std::string
  LinearSolverOf<dofs>::description() const
  {
    const auto  p = options.distributed_preconditioner;
    std::string text
      = current == SolverType::direct ? "sparse LDL^T (direct)"
        : current == SolverType::distributed
          ? std::string("CG (Trilinos) + ")
              + (p == DistributedPreconditioner::amg   ? "ML AMG"
                 : p == DistributedPreconditioner::ilu ? "Ifpack ILU(0)"
                                                       : "Ifpack block-Jacobi")
              + " on " + std::to_string(n_ranks())
              + " MPI ranks (blocks partitioned along a Hilbert curve; "
                "geometry, contacts and assembly replicated)"
        : options.preconditioner == Preconditioner::block_jacobi
          ? "CG + block-Jacobi"
          : "CG + block D-ILU";
    if (separator_size() > 0)
      text += ", two subdomains and a separator of "
              + std::to_string(separator_size()) + " blocks, "
              + std::to_string(std::min(2u, n_threads()))
              + " thread(s) for its sweeps";
    return text;
  }



  template <int dofs>
  internal::TaskTeam &
  LinearSolverOf<dofs>::team_of_run() const
  {
    if (!team)
      {
        // 0: one per core, the cores shared by the ranks on this machine.
        int threads = std::max(options.threads, 0);
        if (threads == 0 && world_ranks() > 1)
          threads
            = std::max(1,
                       static_cast<int>(std::thread::hardware_concurrency())
                         / machine_ranks);
        team = std::make_unique<internal::TaskTeam>(
          static_cast<unsigned int>(threads));
      }
    return *team;
  }



  template <int dofs>
  internal::ThreadPair &
  LinearSolverOf<dofs>::pair_of_run()
  {
    // A worker thread only where the sweeps use it (the subdomain order).
    if (!pair)
      pair = std::make_unique<internal::ThreadPair>(n_threads() >= 2 && dilu
                                                    && dilu->renumbered);
    return *pair;
  }



  template <int dofs>
  void
  LinearSolverOf<dofs>::for_chunks(
    const std::size_t                                    n,
    const std::size_t                                    grain,
    const std::function<void(std::size_t, std::size_t)> &f)
  {
    team_of_run().for_chunks(n, grain, f);
  }



  template <int dofs>
  void
  LinearSolverOf<dofs>::new_pattern(const Matrix             &K,
                                    const std::vector<Block> *blocks)
  {
    factorised = false;
    current    = options.type;
    // The distributed solver is written for 2D blocks (6 unknowns).
    constexpr bool can_distribute = dofs == 6;
    if (current == SolverType::automatic)
      current = K.n_blocks() <= options.automatic_limit ? SolverType::direct
                : world_ranks() > 1 && can_distribute ? SolverType::distributed
                                                      : SolverType::iterative;
    if (current == SolverType::distributed)
      {
        if constexpr (!can_distribute)
          throw std::invalid_argument(
            "LinearSolver: the distributed solver is 2D only (6 unknowns "
            "per block, not "
            + std::to_string(dofs) + ")");
        else
          {
            if (!distributed)
              distributed = std::make_unique<internal::DistributedSolver>(
                options.distributed_preconditioner);
            std::vector<geometry::Point> centroids(K.n_blocks(),
                                                   geometry::Point::Zero());
            if (blocks != nullptr)
              for (int b = 0; b < K.n_blocks(); ++b)
                centroids[b] = (*blocks)[b].initial_centroid;
            distributed->new_pattern(K, centroids);
          }
      }
    else if (current == SolverType::direct)
      {
        if (!direct)
          direct = std::make_unique<Direct>();
        direct->cholesky.analyse(K);
      }
    else if (options.preconditioner == Preconditioner::block_dilu)
      {
        if (!dilu)
          dilu = std::make_unique<Dilu>();
        dilu->new_pattern(K, options.subdomain_limit);
      }
  }



  template <int dofs>
  bool
  LinearSolverOf<dofs>::solve(const Matrix          &K,
                              const Eigen::VectorXd &f,
                              Eigen::VectorXd       &x,
                              const bool             same_matrix,
                              const double           tolerance)
  {
    iterations = 0;
    if (current == SolverType::direct)
      {
        if (!same_matrix || !factorised)
          {
            factorised = false;
            if (!direct->cholesky.factorize(K))
              return false;
            factorised = true;
          }
        direct->cholesky.solve(f, x);
        return x.allFinite();
      }

    if constexpr (dofs == 6)
      if (current == SolverType::distributed)
        return distributed->solve(K,
                                  f,
                                  x,
                                  same_matrix,
                                  tolerance > 0. ? tolerance
                                                 : options.tolerance,
                                  iteration_limit(K.n_blocks()),
                                  iterations);
    if (x.size() != f.size() || !x.allFinite())
      x = Eigen::VectorXd::Zero(f.size());
    if (options.preconditioner == Preconditioner::block_jacobi)
      {
        if (!same_matrix || !factorised)
          {
            const int n = K.n_blocks();
            inverse_diag.resize(n);
            factorised = true;
            for (int i = 0; i < n && factorised; ++i)
              factorised = invert_spd(K.diag[i], inverse_diag[i]);
            if (!factorised)
              return false;
          }
        return jacobi_cg(K, f, x);
      }
    if (!same_matrix || !factorised)
      {
        factorised = dilu->setup(K, pair_of_run());
        if (!factorised)
          return false;
      }
    const bool ok = dilu->cg(f,
                             x,
                             pair_of_run(),
                             tolerance > 0. ? tolerance : options.tolerance,
                             iteration_limit(K.n_blocks()),
                             iterations);
    // Between solves the engine's other phases run on TBB: the pair's
    // worker sleeps instead of spinning on a core they need.
    pair_of_run().rest();
    return ok;
  }



  template <int dofs>
  int
  LinearSolverOf<dofs>::iteration_limit(const int n) const
  {
    return options.max_iterations > 0 ? options.max_iterations
                                      : std::min(20000, 60 * n + 100);
  }



  template <int dofs>
  bool
  LinearSolverOf<dofs>::jacobi_cg(const Matrix          &K,
                                  const Eigen::VectorXd &f,
                                  Eigen::VectorXd       &x)
  {
    const int n       = K.n_blocks();
    auto precondition = [&](const Eigen::VectorXd &in, Eigen::VectorXd &out) {
      out.resize(in.size());
      for (int i = 0; i < n; ++i)
        out.template segment<dofs>(dofs * i).noalias()
          = inverse_diag[i] * in.template segment<dofs>(dofs * i);
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



  template class BlockSparseMatrixOf<6>;
  template class BlockSparseMatrixOf<12>;
  template class LinearSolverOf<6>;
  template class LinearSolverOf<12>;
} // namespace rockdda::dda
