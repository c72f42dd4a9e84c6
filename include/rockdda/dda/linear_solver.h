/**
 * @file
 * The linear system of 2D DDA: a symmetric sparse matrix of 6x6 blocks
 * with a pattern fixed within a step, and its direct (sparse LDL^T) and
 * iterative (block-Jacobi or block D-ILU preconditioned CG) solvers.
 */
#ifndef ROCKDDA_DDA_LINEAR_SOLVER_H
#define ROCKDDA_DDA_LINEAR_SOLVER_H

#include <rockdda/dda/block_system.h>

#include <Eigen/Core>

#include <functional>
#include <memory>
#include <utility>
#include <vector>

namespace rockdda::dda
{
  /**
   * Symmetric matrix of n x n blocks of size 6: every diagonal block and
   * the upper block K_ij (i < j) of each coupled pair are stored. The
   * pattern is set once per step; values are filled in place.
   */
  class BlockSparseMatrix
  {
  public:
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
    std::vector<Matrix6> diag;
    /// Upper off-diagonal blocks K_ij, one per pair.
    std::vector<Matrix6> off;
    /// The pairs (i < j) of the off-diagonal blocks.
    std::vector<std::pair<int, int>> pairs;
  };

  /// Which linear solver to use.
  enum class SolverType
  {
    /// Direct for up to automatic_limit blocks, iterative above (measured
    /// faster from about 60 blocks, benchmarks/dda-scaling).
    automatic,
    /// Sparse LDL^T (Eigen SimplicialLDLT, AMD ordering), pattern analysed
    /// once per step, factorised per open-close iteration.
    direct,
    /// Block-Jacobi preconditioned conjugate gradients, warm-started.
    iterative
  };

  /// Preconditioner of the iterative solver.
  enum class Preconditioner
  {
    /// Inverse 6x6 diagonal blocks.
    block_jacobi,
    /// Block diagonal-ILU M = (P + L) P^-1 (P + L)^T, with L the strict
    /// lower block triangle of K and P_i = K_ii - sum_{j<i} K_ij P_j^-1
    /// K_ji (no fill-in), applied with Eisenstat's trick so that a CG
    /// iteration costs about one mat-vec (Eisenstat 1981; Saad 2003,
    /// Sec. 10.3).
    block_dilu
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
  };

  namespace internal
  {
    class TaskTeam;
    class ThreadPair;
  } // namespace internal

  /**
   * Solves K x = f for the block matrix. new_pattern() is called when the
   * pattern changes (each step); solve() may be called many times.
   */
  class LinearSolver
  {
  public:
    explicit LinearSolver(const SolverOptions &options = SolverOptions());
    ~LinearSolver();

    /// Analyse the pattern of @p matrix (symbolic factorisation, or the
    /// subdomain ordering of the D-ILU).
    void
    new_pattern(const BlockSparseMatrix &matrix);

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
    solve(const BlockSparseMatrix &matrix,
          const Eigen::VectorXd   &f,
          Eigen::VectorXd         &x,
          const bool               same_matrix = false,
          const double             tolerance   = 0.);

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

    /// Threads of the run (SolverOptions::threads resolved).
    unsigned int
    n_threads() const;

    /// Blocks in the separator of the D-ILU subdomain ordering (0: the
    /// natural order is used).
    int
    separator_size() const;

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
    jacobi_cg(const BlockSparseMatrix &K,
              const Eigen::VectorXd   &f,
              Eigen::VectorXd         &x);
    /// The run's threads (made on first use).
    internal::TaskTeam &
    team_of_run() const;
    /// The D-ILU's pair of threads (made on first use).
    internal::ThreadPair &
    pair_of_run();
    /// Iteration limit for @p n blocks.
    int
    iteration_limit(const int n) const;

    SolverOptions                               options;
    SolverType                                  current    = SolverType::direct;
    int                                         iterations = 0;
    bool                                        factorised = false;
    std::unique_ptr<Direct>                     direct;
    std::unique_ptr<Dilu>                       dilu;
    mutable std::unique_ptr<internal::TaskTeam> team;
    std::unique_ptr<internal::ThreadPair>       pair;
    /// Inverse diagonal blocks (block-Jacobi).
    std::vector<Matrix6> inverse_diag;
    Eigen::VectorXd      r, z, p, q;
  };
} // namespace rockdda::dda

#endif
