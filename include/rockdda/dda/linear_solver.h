/**
 * @file
 * The linear system of DDA: a symmetric sparse matrix of dofs x dofs
 * blocks (6 in 2D, 12 in 3D) with a pattern fixed within a step, and its
 * direct (block sparse Cholesky) and iterative (block-Jacobi or block D-ILU
 * preconditioned CG) solvers, written once over the block size.
 */
#ifndef ROCKDDA_DDA_LINEAR_SOLVER_H
#define ROCKDDA_DDA_LINEAR_SOLVER_H

#include <rockdda/dda/block_system.h>

#include <Eigen/Core>

#include <functional>
#include <memory>
#include <string>
#include <utility>
#include <vector>

namespace rockdda::dda
{
  /**
   * Symmetric matrix of n x n blocks of size @p dofs (the unknowns of one
   * block: 6 in 2D, 12 in 3D): every diagonal block and the upper block
   * K_ij (i < j) of each coupled pair are stored. The pattern is set once
   * per step; values are filled in place.
   */
  template <int dofs>
  class BlockSparseMatrixOf
  {
  public:
    /// One dofs x dofs block.
    using Dense = Eigen::Matrix<double, dofs, dofs>;

    /// Set the pattern: @p n blocks and the coupled pairs (i < j, unique).
    void
    reinit(const int n, const std::vector<std::pair<int, int>> &pairs);

    /// Set every stored value to zero.
    void
    set_zero();

    /// Number of blocks.
    int
    n_blocks() const
    {
      return static_cast<int>(diag.size());
    }

    /// y = K x.
    void
    vmult(const Eigen::VectorXd &x, Eigen::VectorXd &y) const;

    /// Diagonal blocks.
    std::vector<Dense> diag;
    /// Upper off-diagonal blocks K_ij, one per pair.
    std::vector<Dense> off;
    /// The pairs (i < j) of the off-diagonal blocks.
    std::vector<std::pair<int, int>> pairs;
  };

  /// The 2D engine's matrix: blocks of 6 unknowns.
  using BlockSparseMatrix = BlockSparseMatrixOf<6>;

  /// Which linear solver to use.
  enum class SolverType
  {
    /// Direct for up to automatic_limit blocks, iterative above (measured
    /// faster from about 60 blocks, benchmarks/dda-scaling).
    automatic,
    /// Sparse Cholesky on the dofs x dofs blocks (AMD ordering of the block
    /// graph), pattern analysed when it changes, factorised per open-close
    /// iteration.
    direct,
    /// Block-Jacobi preconditioned conjugate gradients, warm-started.
    iterative,
    /// CG whose block rows are distributed over the ranks of
    /// MPI_COMM_WORLD, preconditioned by
    /// SolverOptions::distributed_preconditioner: the block D-ILU with one
    /// subdomain per rank, or on a Trilinos matrix (a space-filling-curve
    /// partition of the blocks); the solution is gathered on every rank
    /// (doc/theory/dda-mpi.md). Automatic picks it instead of iterative
    /// when a 2D run has more than one rank. Needs MPI to be initialised.
    /// The Trilinos preconditioners are 2D only (6 unknowns per block):
    /// with 12 (3D) new_pattern() throws.
    distributed
  };

  /// Preconditioner of the iterative solver.
  enum class Preconditioner
  {
    /// Inverse diagonal blocks.
    block_jacobi,
    /// Block diagonal-ILU M = (P + L) P^-1 (P + L)^T, with L the strict
    /// lower block triangle of K and P_i = K_ii - sum_{j<i} K_ij P_j^-1
    /// K_ji (no fill-in), applied with Eisenstat's trick so that a CG
    /// iteration costs about one mat-vec (Eisenstat 1981; Saad 2003,
    /// Sec. 10.3).
    block_dilu
  };

  /// Preconditioner of the distributed solver.
  enum class DistributedPreconditioner
  {
    /// The block D-ILU of the iterative solver with one subdomain per rank
    /// and a separator eliminated last by every rank (CG on the replicated
    /// block matrix, its sweeps split over the ranks; any block size).
    dilu,
    /// ML smoothed-aggregation algebraic multigrid, the six unknowns of a
    /// block aggregated together.
    amg,
    /// Ifpack ILU(0) on each rank's rows (additive Schwarz, no overlap).
    ilu,
    /// Ifpack block-Jacobi with the 6x6 blocks of the (2D) blocks.
    block_jacobi
  };

  /// Options of the linear solver.
  struct SolverOptions
  {
    SolverType     type           = SolverType::automatic;
    Preconditioner preconditioner = Preconditioner::block_dilu;
    /// Relative tolerance of CG on the preconditioned residual norm, for
    /// every solve (benchmarks/dda-scaling: 1e-8 keeps block positions
    /// within ~1e-11 m of the direct solver).
    double tolerance = 1e-8;
    /// CG iteration limit (0: 10 * number of unknowns, at most 20000).
    int max_iterations = 0;
    /// Automatic choice: direct up to this many blocks.
    int automatic_limit = 60;
    /// Threads of the run: contact detection, kinematics and state checks
    /// in chunks on a TBB task arena, and the two subdomains of the D-ILU
    /// sweeps on a spinning pair of threads (internal::ThreadPair; two if
    /// this is >= 2); 0 = one per core. The result does not depend on it.
    int threads = 0;
    /// From this many blocks on, the D-ILU orders the blocks as two
    /// subdomains and their separator (last), so that the two subdomains
    /// are swept in parallel.
    int subdomain_limit = 300;
    /// Preconditioner of the distributed solver (the D-ILU over the ranks:
    /// the fastest on the brick walls, doc/theory/dda-mpi.md).
    DistributedPreconditioner distributed_preconditioner
      = DistributedPreconditioner::dilu;
  };

  namespace internal
  {
    class TaskTeam;
    class ThreadPair;
    class DistributedSolver;
    class RankTeam;
  } // namespace internal

  /**
   * Solves K x = f for the block matrix of blocks of @p dofs unknowns.
   * new_pattern() is called when the pattern changes (each step); solve()
   * may be called many times. Explicitly instantiated for 6 (2D) and 12
   * (3D).
   */
  template <int dofs>
  class LinearSolverOf
  {
  public:
    /// The matrix it solves.
    using Matrix = BlockSparseMatrixOf<dofs>;

    explicit LinearSolverOf(const SolverOptions &options = SolverOptions());
    ~LinearSolverOf();

    /// Analyse the pattern of @p matrix (symbolic factorisation, or the
    /// subdomain ordering of the D-ILU, or the distributed pattern). The
    /// distributed solver partitions the blocks by the initial centroids
    /// of @p blocks (the 2D scene's blocks, one per block row) when their
    /// number changes; the other solvers do not use them.
    void
    new_pattern(const Matrix             &matrix,
                const std::vector<Block> *blocks = nullptr);

    /**
     * Solve K x = f; @p x holds the starting guess on entry (iterative).
     * With @p same_matrix the matrix is known to equal the one of the
     * previous call (only f changed), and its factorisation (direct) or
     * preconditioner (iterative) is reused. Returns false if the matrix is
     * not positive definite, CG did not converge, or the result is not
     * finite. A @p tolerance > 0 replaces SolverOptions::tolerance for this
     * solve (CG).
     */
    bool
    solve(const Matrix          &matrix,
          const Eigen::VectorXd &f,
          Eigen::VectorXd       &x,
          const bool             same_matrix = false,
          const double           tolerance   = 0.);

    /// The solver used for the current pattern (never automatic).
    SolverType
    type() const
    {
      return current;
    }

    /// CG iterations of the last solve (0 for direct).
    int
    last_iterations() const
    {
      return iterations;
    }

    /// MPI ranks the distributed solver runs on (1 for the others).
    int
    n_ranks() const;

    /// Threads of the run (SolverOptions::threads resolved; 0 = the cores
    /// shared by the ranks of this machine).
    unsigned int
    n_threads() const;

    /// Blocks in the separator of the D-ILU subdomain ordering (0: the
    /// natural order is used).
    int
    separator_size() const;

    /// The log's description of the solver of the current pattern, e.g.
    /// "CG + block D-ILU, two subdomains and a separator of 12 blocks, 2
    /// thread(s) for its sweeps".
    std::string
    description() const;

    /**
     * Run @p f(lo, hi) over the chunks of [0, n) of @p grain items on the
     * run's threads (ChunkRunner). The chunks must write disjoint data;
     * results are then the same on any number of threads.
     */
    void
    for_chunks(const std::size_t                                    n,
               const std::size_t                                    grain,
               const std::function<void(std::size_t, std::size_t)> &f);

  private:
    struct Direct;
    struct Dilu;
    /// Block-Jacobi preconditioned CG.
    bool
    jacobi_cg(const Matrix &K, const Eigen::VectorXd &f, Eigen::VectorXd &x);
    /// The run's threads (made on first use).
    internal::TaskTeam &
    team_of_run() const;
    /// The D-ILU's pair of threads (made on first use).
    internal::ThreadPair &
    pair_of_run();
    /// Iteration limit for @p n blocks.
    int
    iteration_limit(const int n) const;

    SolverOptions options;
    /// MPI ranks on this machine (1 without MPI): they share its cores.
    int                                          machine_ranks = 1;
    SolverType                                   current = SolverType::direct;
    int                                          iterations = 0;
    bool                                         factorised = false;
    std::unique_ptr<Direct>                      direct;
    std::unique_ptr<Dilu>                        dilu;
    std::unique_ptr<internal::DistributedSolver> distributed;
    /// The ranks of the D-ILU over MPI (DistributedPreconditioner::dilu).
    std::unique_ptr<internal::RankTeam>         ranks;
    mutable std::unique_ptr<internal::TaskTeam> team;
    std::unique_ptr<internal::ThreadPair>       pair;
    /// Inverse diagonal blocks (block-Jacobi).
    std::vector<typename Matrix::Dense> inverse_diag;
    Eigen::VectorXd                     r, z, p, q;
  };

  /// The 2D engine's solver: blocks of 6 unknowns.
  using LinearSolver = LinearSolverOf<6>;

  extern template class BlockSparseMatrixOf<6>;
  extern template class BlockSparseMatrixOf<12>;
  extern template class LinearSolverOf<6>;
  extern template class LinearSolverOf<12>;
} // namespace rockdda::dda

#endif
