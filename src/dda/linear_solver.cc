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
#include "part_team.h"
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



  /**
   * Block D-ILU preconditioned CG with Eisenstat's trick. Large systems are
   * renumbered as P subdomains and their separator (each in the original
   * order; internal::level_parts()): the subdomains do not couple, so their
   * parts of the pivot computation and of every sweep run at once (two threads,
   * or one MPI rank each: internal::PartTeam), and the separator is
   * eliminated last by every process. The operations and their order are
   * the same for one and two threads, and on P ranks those of the serial
   * solver with the same P subdomains.
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
    /// The renumbered pairs (i < j).
    std::vector<std::pair<int, int>> new_pairs;
    /// Subdomain d = [first[d], first[d + 1]) for d < P; the separator =
    /// [first[P], n) = [end1, n).
    int              n = 0, end1 = 0, P = 1, n_sep = 0;
    std::vector<int> first;
    std::vector<int> row_start;
    /// The rows this process stores, [a0, a1) and [b0, n) (every row, or on
    /// a rank its subdomain and the separator), and their pairs [pa0, pa1)
    /// and [pb0, row_start[n]): a row's values are at row_slot(), a pair's
    /// at pair_slot().
    int a0 = 0, a1 = 0, b0 = 0, pa0 = 0, pa1 = 0, pb0 = 0;
    /// The stored rows' blocks, renumbered.
    std::vector<Dense> diag_store, off_store;
    /// The blocks the sweeps read (the stored ones or the caller's matrix)
    /// and the pairs.
    const Dense               *D = nullptr, *O = nullptr;
    const std::pair<int, int> *PR = nullptr;
    /// Pivots P_i, their inverses and K_ii - 2 P_i (stored rows).
    std::vector<Dense> pivot, inverse_pivot, diag_shift;
    /// Each subdomain's contributions to the separator's pivots (P slices
    /// of n_sep blocks).
    std::vector<Dense> pivot_update;
    Eigen::VectorXd    f, x, r, z, p, q, t, y;
    /// Each subdomain's contributions to a vector on the separator and its
    /// partial sum (P slices of dofs n_sep + 1 values).
    Eigen::VectorXd     exchange;
    std::vector<double> partial, flags;

    int
    row_slot(const int i) const
    {
      return i < a1 ? i - a0 : (a1 - a0) + (i - b0);
    }
    int
    pair_slot(const int k) const
    {
      return k < pa1 ? k - pa0 : (pa1 - pa0) + (k - pb0);
    }
    /// The stored blocks of row @p i's pairs: its k-th pair is at
    /// row_pairs(i)[k - row_start[i]].
    const Dense *
    row_pairs(const int i) const
    {
      return O
             + (i < a1 ? row_start[i] - pa0
                       : (pa1 - pa0) + (row_start[i] - pb0));
    }
    const Dense &
    Kdiag(const int i) const
    {
      return D[row_slot(i)];
    }
    int
    col(const int k) const
    {
      return PR[k].second;
    }
    Dense &
    piv(const int i)
    {
      return pivot[row_slot(i)];
    }
    const Dense &
    piv(const int i) const
    {
      return pivot[row_slot(i)];
    }
    Dense &
    ipiv(const int i)
    {
      return inverse_pivot[row_slot(i)];
    }
    const Dense &
    ipiv(const int i) const
    {
      return inverse_pivot[row_slot(i)];
    }
    Dense &
    dshift(const int i)
    {
      return diag_shift[row_slot(i)];
    }
    const Dense &
    dshift(const int i) const
    {
      return diag_shift[row_slot(i)];
    }

    /// Rows [begin, end) of subdomain @p part (< P) or the separator (P).
    std::pair<int, int>
    rows(const int part) const
    {
      return part < P ? std::make_pair(first[part], first[part + 1])
                      : std::make_pair(end1, n);
    }

    /// Slice @p d of the exchange buffer (dofs n_sep separator values,
    /// then the partial sum).
    double *
    slice(const int d)
    {
      return exchange.data() + static_cast<std::size_t>(d) * (dofs * n_sep + 1);
    }

    /// Add the subdomains' separator contributions in exchange to @p v on
    /// the separator, in the order of the subdomains, and return the sum
    /// of their partial sums.
    double
    add_slices(Eigen::VectorXd &v)
    {
      double sum = 0.;
      for (int d = 0; d < P; ++d)
        {
          const double *s = slice(d);
          for (int k = 0; k < dofs * n_sep; ++k)
            v[dofs * end1 + k] += s[k];
          sum += s[dofs * n_sep];
        }
      return sum;
    }

    /// The sum of partial over the subdomains, in their order.
    double
    sum_partial() const
    {
      double sum = 0.;
      for (const double v : partial)
        sum += v;
      return sum;
    }

    /// The pattern of @p K in @p parts subdomains (1: the natural order),
    /// this process computing subdomain @p own (-1: all of them).
    void
    new_pattern(const Matrix &K, const int parts, const int own)
    {
      n                                             = K.n_blocks();
      renumbered                                    = parts > 1 && n >= 1;
      P                                             = renumbered ? parts : 1;
      const std::vector<std::pair<int, int>> *pairs = &K.pairs;
      first.assign(P + 1, 0);
      first[P] = end1 = n;
      if (renumbered)
        {
          const std::vector<int> part = internal::level_parts(n, K.pairs, P);
          // The sweeps of different subdomains run at once: no pair may
          // couple two of them.
          for (const auto &pr : K.pairs)
            if (part[pr.first] != part[pr.second] && part[pr.first] != P
                && part[pr.second] != P)
              throw std::logic_error(
                "block D-ILU: blocks " + std::to_string(pr.first) + " and "
                + std::to_string(pr.second)
                + " couple two subdomains (no separator between them)");
          order.clear();
          for (int which = 0; which <= P; ++which)
            {
              first[which] = static_cast<int>(order.size());
              for (int i = 0; i < n; ++i)
                if (part[i] == which)
                  order.push_back(i);
            }
          end1 = first[P];
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
          new_pairs.clear();
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
          pairs = &new_pairs;
        }
      n_sep = n - end1;
      row_start.assign(n + 1, 0);
      for (const auto &pr : *pairs)
        ++row_start[pr.first + 1];
      for (int i = 0; i < n; ++i)
        row_start[i + 1] += row_start[i];
      const bool all         = !renumbered || own < 0;
      a0                     = all ? 0 : first[own];
      a1                     = all ? n : first[own + 1];
      b0                     = all ? n : end1;
      pa0                    = row_start[a0];
      pa1                    = row_start[a1];
      pb0                    = row_start[b0];
      const int rows_stored  = (a1 - a0) + (n - b0);
      const int pairs_stored = (pa1 - pa0) + (row_start[n] - pb0);
      if (renumbered)
        {
          diag_store.resize(rows_stored);
          off_store.resize(pairs_stored);
        }
      else
        {
          std::vector<Dense>().swap(diag_store);
          std::vector<Dense>().swap(off_store);
          std::vector<std::pair<int, int>>().swap(new_pairs);
        }
      pivot.resize(rows_stored);
      inverse_pivot.resize(rows_stored);
      diag_shift.resize(rows_stored);
      pivot_update.resize(static_cast<std::size_t>(P) * n_sep);
      for (auto &v : {&f, &x, &r, &z, &p, &q, &t, &y})
        v->resize(dofs * n);
      exchange.resize(static_cast<Eigen::Index>(P) * (dofs * n_sep + 1));
      partial.assign(P, 0.);
      flags.assign(P, 0.);
    }

    /// Point the sweeps at the values of @p K: copied into the stored
    /// rows when renumbered.
    void
    gather(const Matrix &K)
    {
      if (!renumbered)
        {
          D  = K.diag.data();
          O  = K.off.data();
          PR = K.pairs.data();
          return;
        }
      D  = diag_store.data();
      O  = off_store.data();
      PR = new_pairs.data();
      for (const auto &[begin, end] :
           {std::make_pair(a0, a1), std::make_pair(b0, n)})
        for (int i = begin; i < end; ++i)
          {
            diag_store[row_slot(i)] = K.diag[order[i]];
            for (int k = row_start[i]; k < row_start[i + 1]; ++k)
              if (pair_transposed[k])
                off_store[pair_slot(k)] = K.off[pair_source[k]].transpose();
              else
                off_store[pair_slot(k)] = K.off[pair_source[k]];
          }
    }

    /// Run f(d) for the subdomains this process computes (at once on a
    /// team of two threads; the natural order is one subdomain).
    template <typename F>
    void
    run(internal::PartTeam &team, F &&f)
    {
      if (P == 1)
        f(0);
      else
        team.run(f);
    }

    /// Pivot of row @p i (its P_i accumulated), then its updates of later
    /// pivots; those of the separator go to @p separator_update when given.
    bool
    eliminate(const int i, Dense *separator_update)
    {
      if (!invert_spd(piv(i), ipiv(i)))
        {
          // Modified pivot not positive definite: fall back to the
          // diagonal block (symmetric Gauss-Seidel there); M stays SPD.
          piv(i) = Kdiag(i);
          if (!invert_spd(piv(i), ipiv(i)))
            return false;
        }
      dshift(i)        = Kdiag(i) - 2. * piv(i);
      const int    ks  = row_start[i];
      const Dense *row = row_pairs(i);
      for (int k = ks; k < row_start[i + 1]; ++k)
        {
          const Dense &A      = row[k - ks];
          const Dense  PiA    = ipiv(i).lazyProduct(A);
          const int    j      = col(k);
          Dense       &target = (separator_update != nullptr && j >= end1)
                                  ? separator_update[j - end1]
                                  : piv(j);
          target.noalias() -= A.transpose().lazyProduct(PiA);
        }
      return true;
    }

    /// Pivots P_i = K_ii - sum_{j<i} K_ij P_j^-1 K_ji.
    bool
    setup(const Matrix &K_in, internal::PartTeam &team)
    {
      gather(K_in);
      auto part = [&](const int d) {
        const auto [begin, end] = rows(d);
        Dense *update
          = pivot_update.data() + static_cast<std::size_t>(d) * n_sep;
        for (int s = 0; s < n_sep; ++s)
          update[s].setZero();
        for (int i = begin; i < end; ++i)
          piv(i) = Kdiag(i);
        flags[d] = 1.;
        for (int i = begin; i < end && flags[d] == 1.; ++i)
          flags[d] = eliminate(i, update) ? 1. : 0.;
      };
      run(team, part);
      if (P > 1)
        {
          team.share(flags.data(), 1);
          if (n_sep > 0)
            team.share(pivot_update.data()->data(),
                       static_cast<std::size_t>(dofs * dofs) * n_sep);
        }
      for (const double ok : flags)
        if (ok != 1.)
          return false;
      for (int i = end1; i < n; ++i)
        {
          piv(i) = Kdiag(i);
          for (int d = 0; d < P; ++d)
            piv(i)
              += pivot_update[static_cast<std::size_t>(d) * n_sep + (i - end1)];
        }
      for (int i = end1; i < n; ++i)
        if (!eliminate(i, nullptr))
          return false;
      return true;
    }

    /// Rows [begin, end) of the solve of (P + U) out = v, U the strict
    /// upper block triangle (descending; the rows above end must be done).
    void
    backward_solve_rows(const int              begin,
                        const int              end,
                        const Eigen::VectorXd &v,
                        Eigen::VectorXd       &out) const
    {
      for (int i = end - 1; i >= begin; --i)
        {
          Vector       acc = v.template segment<dofs>(dofs * i);
          const int    ks  = row_start[i];
          const Dense *row = row_pairs(i);
          // Descending, as backward_rows.
          for (int k = row_start[i + 1] - 1; k >= ks; --k)
            acc.noalias()
              -= row[k - ks] * out.template segment<dofs>(dofs * col(k));
          out.template segment<dofs>(dofs * i).noalias() = ipiv(i) * acc;
        }
    }

    /// Rows [begin, end) of the solve of (P + L) s = w in place; updates of
    /// the separator go to @p separator_update when given.
    void
    forward_solve_rows(const int        begin,
                       const int        end,
                       Eigen::VectorXd &w,
                       double          *separator_update) const
    {
      for (int i = begin; i < end; ++i)
        {
          const Vector s = ipiv(i) * w.template segment<dofs>(dofs * i);
          w.template segment<dofs>(dofs * i) = s;
          const int    ks                    = row_start[i];
          const Dense *row                   = row_pairs(i);
          for (int k = ks; k < row_start[i + 1]; ++k)
            {
              const Dense &A      = row[k - ks];
              const int    j      = col(k);
              double      *target = (separator_update != nullptr && j >= end1)
                                      ? separator_update + dofs * (j - end1)
                                      : w.data() + dofs * j;
              for (int c = 0; c < dofs; ++c)
                target[c] -= A.col(c).dot(s);
            }
        }
    }

    /// Solve (P + L) s = w in place on every row this process holds.
    void
    forward_solve(Eigen::VectorXd &w, internal::PartTeam &team)
    {
      run(team, [&](const int d) {
        double *s = slice(d);
        std::fill(s, s + dofs * n_sep + 1, 0.);
        const auto [begin, end] = rows(d);
        forward_solve_rows(begin, end, w, s);
      });
      if (P > 1)
        team.share(exchange.data(), dofs * n_sep + 1);
      add_slices(w);
      forward_solve_rows(end1, n, w, nullptr);
    }

    /// Rows [begin, end): out = P in; returns their part of in.out.
    double
    times_pivot_rows(const int              begin,
                     const int              end,
                     const Eigen::VectorXd &in,
                     Eigen::VectorXd       &out) const
    {
      double sum = 0.;
      for (int i = begin; i < end; ++i)
        {
          out.template segment<dofs>(dofs * i).noalias()
            = piv(i) * in.template segment<dofs>(dofs * i);
          sum += in.template segment<dofs>(dofs * i).dot(
            out.template segment<dofs>(dofs * i));
        }
      return sum;
    }

    /// out = P in on every row this process holds; returns in.out.
    double
    times_pivot(const Eigen::VectorXd &in,
                Eigen::VectorXd       &out,
                internal::PartTeam    &team)
    {
      run(team, [&](const int d) {
        const auto [begin, end] = rows(d);
        partial[d]              = times_pivot_rows(begin, end, in, out);
      });
      if (P > 1)
        team.share(partial.data(), 1);
      return sum_partial() + times_pivot_rows(end1, n, in, out);
    }

    /// Rows [begin, end) of the backward sweep of the Eisenstat operator
    /// with p = z + beta p fused in: t = (P + U)^-1 p.
    void
    backward_rows(const int begin, const int end, const double beta)
    {
      for (int i = end - 1; i >= begin; --i)
        {
          auto pi    = p.template segment<dofs>(dofs * i);
          pi         = z.template segment<dofs>(dofs * i) + beta * pi;
          Vector acc = pi;
          // The row's blocks in descending order: the sweep then reads the
          // off-diagonal blocks as one descending stream, which the hardware
          // prefetcher follows (ascending within each row, it read them 3x
          // slower than the forward sweep: benchmarks/dda-scaling, section 14).
          const int    ks  = row_start[i];
          const Dense *row = row_pairs(i);
          for (int k = row_start[i + 1] - 1; k >= ks; --k)
            acc.noalias()
              -= row[k - ks] * t.template segment<dofs>(dofs * PR[k].second);
          t.template segment<dofs>(dofs * i).noalias() = ipiv(i) * acc;
        }
    }

    /// Rows [begin, end) of the forward sweep: q = t + (P + L)^-1 (p +
    /// (D - 2P) t); q must hold the updates from earlier rows. Updates of
    /// the separator go to @p separator_update when given. Returns the
    /// rows' part of p.q.
    double
    forward_rows(const int begin, const int end, double *separator_update)
    {
      double pq = 0.;
      for (int i = begin; i < end; ++i)
        {
          const auto ti   = t.template segment<dofs>(dofs * i);
          auto       qi   = q.template segment<dofs>(dofs * i);
          Vector     w    = qi + p.template segment<dofs>(dofs * i);
          const int  slot = row_slot(i);
          w.noalias() += diag_shift[slot] * ti;
          const Vector si = inverse_pivot[slot] * w;
          qi              = si + ti;
          pq += p.template segment<dofs>(dofs * i).dot(qi);
          const int    ks  = row_start[i];
          const Dense *row = row_pairs(i);
          for (int k = ks; k < row_start[i + 1]; ++k)
            {
              const Dense &A      = row[k - ks];
              const int    j      = PR[k].second;
              double      *target = (separator_update != nullptr && j >= end1)
                                      ? separator_update + dofs * (j - end1)
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
          zi.noalias() = piv(i) * ri;
          rz += ri.dot(zi);
        }
      return rz;
    }

    /// Rows [begin, end): y = (P + U) x, and w = f - y - (D - 2P) x.
    void
    start_rows(const int begin, const int end, Eigen::VectorXd &w)
    {
      for (int i = begin; i < end; ++i)
        {
          auto yi          = y.template segment<dofs>(dofs * i);
          yi.noalias()     = piv(i) * x.template segment<dofs>(dofs * i);
          const int    ks  = row_start[i];
          const Dense *row = row_pairs(i);
          for (int k = ks; k < row_start[i + 1]; ++k)
            yi.noalias()
              += row[k - ks] * x.template segment<dofs>(dofs * col(k));
          auto wi = w.template segment<dofs>(dofs * i);
          wi      = f.template segment<dofs>(dofs * i) - yi;
          wi.noalias() -= dshift(i) * x.template segment<dofs>(dofs * i);
        }
    }

    /// PCG on K with M = (P + L) P^-1 (P + U) is CG on
    /// A^ = (P + L)^-1 K (P + U)^-1 (unknown y = (P + U) x) preconditioned
    /// by multiplication with P. With K = (P + L) + (P + U) + (D - 2 P):
    /// A^ v = t + (P + L)^-1 (v + (D - 2 P) t), t = (P + U)^-1 v. Every
    /// process keeps the rows of its subdomains and the separator; the
    /// solution comes back whole on each.
    bool
    cg(const Eigen::VectorXd &f_in,
       Eigen::VectorXd       &x_out,
       internal::PartTeam    &team,
       const double           tolerance,
       const int              max_iterations,
       int                   &iterations)
    {
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
      // Right-hand side norm f^T M^-1 f for the stopping test.
      r = f;
      forward_solve(r, team);
      const double bnorm = times_pivot(r, z, team);
      if (!(bnorm > 0.))
        {
          x_out.setZero();
          return std::isfinite(bnorm);
        }
      // y0 = (P + U) x0, r^0 = (P + L)^-1 (f - K x0)
      //                      = (P + L)^-1 (f - y0 - (D - 2P) x0) - x0.
      run(team, [&](const int d) {
        const auto [begin, end] = rows(d);
        start_rows(begin, end, r);
      });
      start_rows(end1, n, r);
      forward_solve(r, team);
      r -= x;
      double rz = times_pivot(r, z, team);
      p.setZero();
      double       beta = 0.;
      const double tol2 = tolerance * tolerance * bnorm;
      // One pass per sweep, with the vector updates fused into them.
      // Separator rows first (backward), then the subdomains (backward
      // and forward, at once), then the separator (forward), then the
      // vector updates.
      while (rz > tol2)
        {
          if (iterations >= max_iterations)
            return false;
          ++iterations;
          backward_rows(end1, n, beta);
          run(team, [&](const int d) {
            const auto [begin, end] = rows(d);
            q.segment(dofs * begin, dofs * (end - begin)).setZero();
            double *s = slice(d);
            std::fill(s, s + dofs * n_sep, 0.);
            backward_rows(begin, end, beta);
            s[dofs * n_sep] = forward_rows(begin, end, s);
          });
          if (P > 1)
            team.share(exchange.data(), dofs * n_sep + 1);
          q.segment(dofs * end1, dofs * n_sep).setZero();
          const double pq = add_slices(q) + forward_rows(end1, n, nullptr);
          if (!(pq > 0.))
            return false;
          const double alpha = rz / pq;
          run(team, [&](const int d) {
            const auto [begin, end] = rows(d);
            partial[d]              = update_rows(begin, end, alpha);
          });
          if (P > 1)
            team.share(partial.data(), 1);
          const double rz_new = sum_partial() + update_rows(end1, n, alpha);
          beta                = rz_new / rz;
          rz                  = rz_new;
          if (!std::isfinite(rz))
            return false;
        }
      // x = (P + U)^-1 y: the separator, then each subdomain.
      backward_solve_rows(end1, n, y, x);
      run(team, [&](const int d) {
        const auto [begin, end] = rows(d);
        backward_solve_rows(begin, end, y, x);
      });
      if (P > 1)
        team.share_rows(x.data(), first, dofs);
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
    if (ranks)
      return ranks->n_parts();
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
    const auto p = options.distributed_preconditioner;
    if (current == SolverType::distributed && ranks)
      return "CG + block D-ILU on " + std::to_string(n_ranks())
             + " MPI ranks (a subdomain each, a separator of "
             + std::to_string(separator_size())
             + " blocks eliminated last by every rank; geometry, contacts "
               "and assembly replicated)";
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
    // The Trilinos path is written for 2D blocks (6 unknowns); automatic
    // distributes only 2D runs (3D has no MPI driver).
    constexpr bool can_distribute = dofs == 6;
    if (current == SolverType::automatic)
      current = K.n_blocks() <= options.automatic_limit ? SolverType::direct
                : world_ranks() > 1 && can_distribute ? SolverType::distributed
                                                      : SolverType::iterative;
    if (current == SolverType::distributed
        && options.distributed_preconditioner
             == DistributedPreconditioner::dilu)
      {
        // The block D-ILU with one subdomain per rank (every dofs).
        if (!ranks)
          ranks = std::make_unique<internal::RankTeam>(MPI_COMM_WORLD);
        if (!dilu)
          dilu = std::make_unique<Dilu>();
        int own = 0;
        while (!ranks->computes(own))
          ++own;
        dilu->new_pattern(K, ranks->n_parts(), own);
      }
    else if (current == SolverType::distributed)
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
        const int n = K.n_blocks();
        dilu->new_pattern(K,
                          n >= options.subdomain_limit && n >= 3 ? 2 : 1,
                          -1);
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

    if (current == SolverType::distributed && ranks)
      {
        // The replicated inputs must agree bit for bit (otherwise the
        // ranks have diverged and their open-close decisions would differ).
        if (!ranks->same_everywhere(f))
          throw std::runtime_error(
            "distributed DDA: the ranks hold different load vectors (their "
            "replicated states have diverged)");
        if (x.size() != f.size() || !x.allFinite())
          x = Eigen::VectorXd::Zero(f.size());
        if (!same_matrix || !factorised)
          {
            factorised = dilu->setup(K, *ranks);
            if (!factorised)
              return false;
          }
        return dilu->cg(f,
                        x,
                        *ranks,
                        tolerance > 0. ? tolerance : options.tolerance,
                        iteration_limit(K.n_blocks()),
                        iterations);
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
        internal::PairTeam threads(pair_of_run(), dilu->P);
        factorised = dilu->setup(K, threads);
        if (!factorised)
          return false;
      }
    internal::PairTeam threads(pair_of_run(), dilu->P);
    const bool         ok = dilu->cg(f,
                             x,
                             threads,
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
