/**
 * @file
 * The distributed DDA linear solver (distributed_solver.h).
 */
#include "distributed_solver.h"

#include <rockdda/dda/block_partition.h>

#include <deal.II/base/index_set.h>
#include <deal.II/base/mpi.h>
#include <deal.II/lac/solver_cg.h>
#include <deal.II/lac/solver_control.h>
#include <deal.II/lac/trilinos_precondition.h>
#include <deal.II/lac/trilinos_sparse_matrix.h>
#include <deal.II/lac/trilinos_sparsity_pattern.h>
#include <deal.II/lac/trilinos_vector.h>

#include "part_team.h"
#include <Epetra_CrsMatrix.h>
#include <Epetra_Map.h>
#include <Epetra_SerialComm.h>
#include <Epetra_Vector.h>
#include <Ifpack.h>
#include <Ifpack_ILU.h>
#include <Ifpack_Preconditioner.h>
#include <Teuchos_ParameterList.hpp>
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <stdexcept>
#include <string>

namespace rockdda::dda::internal
{



  struct DistributedSolver::Impl
  {
    using size_type = dealii::types::global_dof_index;

    /// One 6x6 block of a block row: the column block (new numbering), the
    /// stored off-diagonal block it comes from (-1: the diagonal block),
    /// and whether it is the transpose of the stored one.
    struct Entry
    {
      int  column;
      int  pair;
      bool transposed;
    };

    MPI_Comm                  comm = MPI_COMM_WORLD;
    int                       rank = 0, size = 1;
    DistributedPreconditioner kind;
    BlockPartition            partition;
    int                       partitioned_blocks = -1;
    /// The block count and coupled pairs of the current pattern.
    int                              pattern_blocks = -1;
    std::vector<std::pair<int, int>> pattern_pairs;
    /// This rank's rows (contiguous in the new numbering).
    dealii::IndexSet owned;
    int              begin = 0, end = 0;
    /// Block rows of the owned blocks.
    std::vector<std::vector<Entry>>        rows;
    dealii::TrilinosWrappers::SparseMatrix matrix;
    dealii::TrilinosWrappers::MPI::Vector  rhs, solution;
    bool                                   ready              = false;
    bool                                   built_this_pattern = false;
    /// Rows per rank for the gather of the solution.
    std::vector<int>       counts, displacements;
    std::vector<double>    gathered;
    std::vector<size_type> columns;
    std::vector<double>    values;

    /// Where each stored value of the Epetra matrix comes from, in the
    /// order of its rows' storage: the 6x6 block (-1 - block for a
    /// diagonal block, else the pair) and the entry (r + 6 c; transposed
    /// blocks give c + 6 r).
    std::vector<int> source_block, source_entry;

    /// Map the storage of the Epetra matrix (local rows, then the
    /// entries of each row in Epetra's order) to the block entries.
    void
    map_storage()
    {
      const Epetra_CrsMatrix &E = matrix.trilinos_matrix();
      source_block.clear();
      source_entry.clear();
      source_block.reserve(E.NumMyNonzeros());
      source_entry.reserve(E.NumMyNonzeros());
      for (int l = 0; l < end - begin; ++l)
        {
          const int   block = partition.order[begin + l];
          const auto &row   = rows[l];
          for (int r = 0; r < 6; ++r)
            {
              int     n       = 0;
              double *v       = nullptr;
              int    *indices = nullptr;
              const_cast<Epetra_CrsMatrix &>(E).ExtractMyRowView(6 * l + r,
                                                                 n,
                                                                 v,
                                                                 indices);
              for (int e = 0; e < n; ++e)
                {
                  const auto g
                    = static_cast<long long>(E.ColMap().GID64(indices[e]));
                  const int  column = static_cast<int>(g / 6);
                  const int  c      = static_cast<int>(g % 6);
                  const auto it
                    = std::lower_bound(row.begin(),
                                       row.end(),
                                       column,
                                       [](const Entry &a, const int col) {
                                         return a.column < col;
                                       });
                  source_block.push_back(it->pair < 0 ? -1 - block : it->pair);
                  source_entry.push_back(it->transposed ? c + 6 * r
                                                        : r + 6 * c);
                }
            }
        }
    }

    /// Copy the owned block rows of @p K into the matrix, in storage
    /// order (no search, no communication: every entry is owned).
    void
    set_values(const BlockSparseMatrix &K)
    {
      auto       &E = const_cast<Epetra_CrsMatrix &>(matrix.trilinos_matrix());
      std::size_t k = 0;
      for (int row = 0; row < E.NumMyRows(); ++row)
        {
          double   *v = E[row];
          const int n = E.NumMyEntries(row);
          for (int e = 0; e < n; ++e, ++k)
            {
              const int b = source_block[k];
              v[e]        = b < 0 ? K.diag[-1 - b].data()[source_entry[k]]
                                  : K.off[b].data()[source_entry[k]];
            }
        }
    }

    /// The Ifpack preconditioner (all but amg): made and initialised
    /// (its symbolic part) once per pattern, computed per matrix.
    std::unique_ptr<Ifpack_Preconditioner>                     ifpack;
    std::unique_ptr<dealii::TrilinosWrappers::PreconditionAMG> amg;

    /**
     * ILU(0) on each rank's diagonal block (additive Schwarz without
     * overlap), on a serial Epetra matrix of exactly that block. Ifpack's
     * AdditiveSchwarz would wrap the rank's rows in an Ifpack_LocalFilter,
     * a row matrix for which Ifpack_ILU::Initialize allocates the longest
     * row's length for every row: a fixed base touching every bottom brick
     * has rows of 6 x (bottom bricks) entries, so that rank's factors grew
     * as N^1.5 on a square wall (23 GB on one rank at 10^5 blocks,
     * benchmarks/dda-scaling section 18).
     */
    struct LocalIlu
    {
      Epetra_SerialComm                 comm;
      std::unique_ptr<Epetra_Map>       map;
      std::unique_ptr<Epetra_CrsMatrix> matrix;
      std::unique_ptr<Ifpack_ILU>       ilu;
      /// For each stored entry of the distributed matrix (row by row, in
      /// its storage order): its offset in the row of the local matrix, or
      /// -1 for a column of another rank.
      std::vector<int> target;

      /// Set up the pattern of the diagonal block of @p E (rows and
      /// columns [first, first + n) in global numbering) and ILU's graph.
      void
      initialize(const Epetra_CrsMatrix &E, const long long first)
      {
        const int n = E.NumMyRows();
        ilu.reset();
        matrix.reset();
        map = std::make_unique<Epetra_Map>(n, 0, comm);
        std::vector<int>              length(n, 0);
        std::vector<std::vector<int>> local(n);
        for (int row = 0; row < n; ++row)
          {
            int     m = 0;
            double *v = nullptr;
            int    *c = nullptr;
            const_cast<Epetra_CrsMatrix &>(E).ExtractMyRowView(row, m, v, c);
            for (int e = 0; e < m; ++e)
              {
                const long long g = E.ColMap().GID64(c[e]) - first;
                if (g >= 0 && g < n)
                  local[row].push_back(static_cast<int>(g));
              }
            length[row] = static_cast<int>(local[row].size());
          }
        matrix
          = std::make_unique<Epetra_CrsMatrix>(Copy, *map, length.data(), true);
        for (int row = 0; row < n; ++row)
          {
            const std::vector<double> zero(local[row].size(), 0.);
            if (matrix->InsertGlobalValues(
                  row, length[row], zero.data(), local[row].data())
                < 0)
              throw std::runtime_error("local ILU: pattern insertion failed");
          }
        if (matrix->FillComplete() != 0 || matrix->OptimizeStorage() != 0)
          throw std::runtime_error("local ILU: FillComplete failed");
        // Where each entry of E goes in the local matrix, whose column map
        // on one process is its row map (every column is a row of it), so
        // that its local column indices are the global ones, sorted.
        if (!matrix->ColMap().SameAs(*map))
          throw std::runtime_error("local ILU: unexpected column map");
        target.clear();
        target.reserve(E.NumMyNonzeros());
        for (int row = 0; row < n; ++row)
          {
            int     m = 0, ml = 0;
            double *v = nullptr, *vl = nullptr;
            int    *c = nullptr, *cl = nullptr;
            const_cast<Epetra_CrsMatrix &>(E).ExtractMyRowView(row, m, v, c);
            matrix->ExtractMyRowView(row, ml, vl, cl);
            for (int e = 0; e < m; ++e)
              {
                const long long g = E.ColMap().GID64(c[e]) - first;
                int             t = -1;
                if (g >= 0 && g < n)
                  {
                    const int *at = std::lower_bound(cl, cl + ml, int(g));
                    if (at == cl + ml || *at != g)
                      throw std::runtime_error("local ILU: entry not found");
                    t = static_cast<int>(at - cl);
                  }
                target.push_back(t);
              }
          }
        ilu = std::make_unique<Ifpack_ILU>(matrix.get());
        Teuchos::ParameterList list;
        list.set("fact: level-of-fill", 0);
        list.set("fact: absolute threshold", 0.);
        list.set("fact: relative threshold", 1.);
        if (ilu->SetParameters(list) != 0 || ilu->Initialize() != 0)
          throw std::runtime_error("Ifpack ILU set-up failed");
      }

      /// Copy the diagonal block's values from @p E and factor it.
      void
      compute(const Epetra_CrsMatrix &E)
      {
        std::size_t k = 0;
        for (int row = 0; row < E.NumMyRows(); ++row)
          {
            const double *src = E[row];
            double       *dst = (*matrix)[row];
            const int     m   = E.NumMyEntries(row);
            for (int e = 0; e < m; ++e, ++k)
              if (target[k] >= 0)
                dst[target[k]] = src[e];
          }
        if (ilu->Compute() != 0)
          throw std::runtime_error("Ifpack ILU Compute failed");
      }
    };
    LocalIlu local_ilu;

    /// The local ILU as a preconditioner of deal.II's CG.
    struct LocalIluOperator
    {
      const LocalIlu &p;
      void
      vmult(dealii::TrilinosWrappers::MPI::Vector       &dst,
            const dealii::TrilinosWrappers::MPI::Vector &src) const
      {
        const Epetra_Vector x(View, *p.map, const_cast<double *>(src.begin()));
        Epetra_Vector       y(View, *p.map, dst.begin());
        const int           ierr = p.ilu->ApplyInverse(x, y);
        if (ierr != 0)
          throw std::runtime_error("Ifpack ApplyInverse failed ("
                                   + std::to_string(ierr) + ")");
      }
    };

    /// Applies the Ifpack preconditioner to deal.II's Trilinos vectors.
    struct IfpackOperator
    {
      const Ifpack_Preconditioner &p;
      void
      vmult(dealii::TrilinosWrappers::MPI::Vector       &dst,
            const dealii::TrilinosWrappers::MPI::Vector &src) const
      {
        const int ierr
          = p.ApplyInverse(src.trilinos_vector(), dst.trilinos_vector());
        if (ierr != 0)
          throw std::runtime_error("Ifpack ApplyInverse failed ("
                                   + std::to_string(ierr) + ")");
      }
    };

    /// A new pattern: the Ifpack preconditioner of the new matrix, its
    /// symbolic set-up done.
    void
    new_preconditioner()
    {
      amg.reset();
      ifpack.reset();
      if (kind == DistributedPreconditioner::amg)
        return;
      if (kind == DistributedPreconditioner::ilu)
        {
          local_ilu.initialize(matrix.trilinos_matrix(), 6LL * begin);
          return;
        }
      // Block Jacobi on the 6 x 6 blocks of the blocks.
      const std::string      type = "block relaxation";
      Teuchos::ParameterList list;
      list.set("relaxation: type", std::string("Jacobi"));
      list.set("relaxation: sweeps", 1);
      list.set("relaxation: damping factor", 1.);
      list.set("relaxation: zero starting solution", true);
      list.set("partitioner: type", std::string("linear"));
      list.set("partitioner: local parts", std::max(1, end - begin));
      Ifpack factory;
      // Overlap 0: each rank preconditions its own rows (additive Schwarz).
      ifpack.reset(factory.Create(
        type, const_cast<Epetra_CrsMatrix *>(&matrix.trilinos_matrix()), 0));
      if (!ifpack || ifpack->SetParameters(list) != 0
          || ifpack->Initialize() != 0)
        throw std::runtime_error("Ifpack '" + type + "' set-up failed");
    }

    /// The preconditioner of the current matrix values.
    void
    make_preconditioner()
    {
      using namespace dealii::TrilinosWrappers;
      if (kind == DistributedPreconditioner::ilu)
        {
          local_ilu.compute(matrix.trilinos_matrix());
          return;
        }
      if (kind != DistributedPreconditioner::amg)
        {
          if (ifpack->Compute() != 0)
            throw std::runtime_error("Ifpack Compute failed");
          return;
        }
      // ML's smoothed aggregation with the six kinds of unknowns of a block
      // as the near null space (one constant mode each), so that a block's
      // unknowns are aggregated together.
      PreconditionAMG::AdditionalData data;
      data.elliptic              = true;
      data.higher_order_elements = false;
      data.smoother_sweeps       = 2;
      data.aggregation_threshold = 1e-4;
      const unsigned int n_local = 6 * (end - begin);
      data.constant_modes.assign(6, std::vector<bool>(n_local, false));
      for (unsigned int i = 0; i < n_local; ++i)
        data.constant_modes[i % 6][i] = true;
      amg = std::make_unique<PreconditionAMG>();
      amg->initialize(matrix, data);
    }
  };



  DistributedSolver::DistributedSolver(
    const DistributedPreconditioner preconditioner)
      : impl(std::make_unique<Impl>())
  {
    impl->kind = preconditioner;
    impl->rank
      = static_cast<int>(dealii::Utilities::MPI::this_mpi_process(impl->comm));
    impl->size
      = static_cast<int>(dealii::Utilities::MPI::n_mpi_processes(impl->comm));
  }



  DistributedSolver::~DistributedSolver() = default;



  int
  DistributedSolver::n_ranks() const
  {
    return impl->size;
  }



  int
  DistributedSolver::n_owned_blocks() const
  {
    return impl->end - impl->begin;
  }



  void
  DistributedSolver::new_pattern(const BlockSparseMatrix            &K,
                                 const std::vector<geometry::Point> &centroids)
  {
    Impl     &d = *impl;
    const int n = K.n_blocks();
    if (n != d.partitioned_blocks)
      {
        if (static_cast<int>(centroids.size()) != n)
          throw std::invalid_argument(
            "DistributedSolver: " + std::to_string(centroids.size())
            + " centroids for " + std::to_string(n) + " blocks");
        d.partition          = partition_blocks(centroids, d.size);
        d.partitioned_blocks = n;
        // Within each part, blocks coupled to many others (a fixed base
        // under a whole wall) are numbered last: ILU(0) then eliminates
        // their long rows against the short rows of their neighbours,
        // instead of updating every neighbour's row with the long one.
        {
          std::vector<int> degree(n, 0);
          for (const auto &pr : K.pairs)
            {
              ++degree[pr.first];
              ++degree[pr.second];
            }
          auto &order = d.partition.order;
          for (int r = 0; r < d.size; ++r)
            std::stable_partition(order.begin() + d.partition.first[r],
                                  order.begin() + d.partition.first[r + 1],
                                  [&](const int b) { return degree[b] <= 16; });
          for (int p = 0; p < n; ++p)
            d.partition.position[order[p]] = p;
        }
        d.begin = d.partition.first[d.rank];
        d.end   = d.partition.first[d.rank + 1];
        d.owned = dealii::IndexSet(6 * static_cast<Impl::size_type>(n));
        d.owned.add_range(6 * static_cast<Impl::size_type>(d.begin),
                          6 * static_cast<Impl::size_type>(d.end));
        d.owned.compress();
        d.rhs.reinit(d.owned, d.comm);
        d.solution.reinit(d.owned, d.comm);
        d.counts.resize(d.size);
        d.displacements.resize(d.size);
        for (int r = 0; r < d.size; ++r)
          {
            d.displacements[r] = 6 * d.partition.first[r];
            d.counts[r] = 6 * (d.partition.first[r + 1] - d.partition.first[r]);
          }
        d.gathered.resize(6 * static_cast<std::size_t>(n));
      }
    // The same coupled pairs in the same order as the last pattern (a rock
    // mass whose contacts change state but not neighbours, most steps):
    // the Epetra pattern, the map into it and ILU's symbolic factorization
    // stay; only the values are refreshed by the next solve. Rebuilding
    // them every step cost 40 % of a 10^5-block step (page faults of the
    // fresh matrices, index searches).
    if (n == d.pattern_blocks && K.pairs == d.pattern_pairs)
      {
        d.ready = false;
        return;
      }
    d.pattern_blocks = n;
    d.pattern_pairs  = K.pairs;
    d.rows.assign(d.end - d.begin, {});
    for (int l = 0; l < d.end - d.begin; ++l)
      d.rows[l].push_back({d.begin + l, -1, false});
    const auto &position = d.partition.position;
    for (std::size_t k = 0; k < K.pairs.size(); ++k)
      {
        const int pi = position[K.pairs[k].first];
        const int pj = position[K.pairs[k].second];
        if (pi >= d.begin && pi < d.end)
          d.rows[pi - d.begin].push_back({pj, static_cast<int>(k), false});
        if (pj >= d.begin && pj < d.end)
          d.rows[pj - d.begin].push_back({pi, static_cast<int>(k), true});
      }
    dealii::TrilinosWrappers::SparsityPattern pattern(d.owned, d.owned, d.comm);
    std::vector<Impl::size_type>              cols;
    for (int l = 0; l < d.end - d.begin; ++l)
      {
        auto &row = d.rows[l];
        std::sort(row.begin(), row.end(), [](const auto &a, const auto &b) {
          return a.column < b.column;
        });
        cols.clear();
        for (const auto &e : row)
          for (int c = 0; c < 6; ++c)
            cols.push_back(6 * static_cast<Impl::size_type>(e.column) + c);
        for (int r = 0; r < 6; ++r)
          pattern.add_entries(6 * static_cast<Impl::size_type>(d.begin + l) + r,
                              cols.begin(),
                              cols.end(),
                              true);
      }
    pattern.compress();
    d.matrix.reinit(pattern);
    d.map_storage();
    d.new_preconditioner();
    d.ready = false;
  }



  bool
  DistributedSolver::solve(const BlockSparseMatrix &K,
                           const Eigen::VectorXd   &f,
                           Eigen::VectorXd         &x,
                           const bool               same_matrix,
                           const double             tolerance,
                           const int                max_iterations,
                           int                     &iterations)
  {
    Impl &d    = *impl;
    iterations = 0;
    // The replicated inputs must agree bit for bit (otherwise the ranks
    // have diverged and their open-close decisions would differ).
    if (!same_on_every_rank(f, d.comm))
      throw std::runtime_error(
        "distributed DDA: the ranks hold different load vectors (their "
        "replicated states have diverged)");
    if (x.size() != f.size() || !x.allFinite())
      x = Eigen::VectorXd::Zero(f.size());

    int ok = 1;
    if (!same_matrix || !d.ready)
      {
        try
          {
            d.set_values(K);
            d.make_preconditioner();
          }
        catch (const std::exception &)
          {
            ok = 0;
          }
        d.ready = dealii::Utilities::MPI::min(ok, d.comm) == 1;
        if (!d.ready)
          return false;
      }
    const auto &order = d.partition.order;
    double     *b     = d.rhs.begin();
    double     *u     = d.solution.begin();
    for (int p = d.begin; p < d.end; ++p)
      for (int c = 0; c < 6; ++c)
        {
          b[6 * (p - d.begin) + c] = f[6 * order[p] + c];
          u[6 * (p - d.begin) + c] = x[6 * order[p] + c];
        }
    const double fnorm = d.rhs.l2_norm();
    if (!(fnorm > 0.))
      {
        x.setZero();
        return std::isfinite(fnorm);
      }
    dealii::SolverControl control(max_iterations,
                                  tolerance * fnorm,
                                  false,
                                  false);
    dealii::SolverCG<dealii::TrilinosWrappers::MPI::Vector> cg(control);
    try
      {
        if (d.amg)
          cg.solve(d.matrix, d.solution, d.rhs, *d.amg);
        else if (d.kind == DistributedPreconditioner::ilu)
          cg.solve(d.matrix,
                   d.solution,
                   d.rhs,
                   Impl::LocalIluOperator{d.local_ilu});
        else
          cg.solve(d.matrix,
                   d.solution,
                   d.rhs,
                   Impl::IfpackOperator{*d.ifpack});
      }
    catch (const std::exception &)
      {
        // Not converged, or broken down (a matrix that is not positive
        // definite): the same on every rank (CG's scalars are global).
        ok = 0;
      }
    iterations = static_cast<int>(control.last_step());
    ok         = dealii::Utilities::MPI::min(ok, d.comm);
    if (ok == 0)
      return false;
    MPI_Allgatherv(d.solution.begin(),
                   6 * (d.end - d.begin),
                   MPI_DOUBLE,
                   d.gathered.data(),
                   d.counts.data(),
                   d.displacements.data(),
                   MPI_DOUBLE,
                   d.comm);
    const int n = static_cast<int>(order.size());
    for (int p = 0; p < n; ++p)
      x.segment<6>(6 * order[p])
        = Eigen::Map<const Vector6>(d.gathered.data() + 6 * p);
    return x.allFinite();
  }
} // namespace rockdda::dda::internal
