/**
 * @file
 * Internal to the DDA: the distributed linear solver of 2D DDA over MPI
 * (doc/theory/dda-mpi.md). The blocks are partitioned over the ranks of
 * MPI_COMM_WORLD by a space-filling curve (block_partition.h); each rank
 * writes the rows of its blocks into a Trilinos (Epetra) matrix, which is
 * solved by CG with a preconditioner from Trilinos (ML's algebraic
 * multigrid, Ifpack's ILU(0) or 6x6 block-Jacobi). The solution is then
 * gathered on every rank, so that the open-close iteration that follows
 * takes the same decisions everywhere.
 */
#ifndef ROCKDDA_DDA_DISTRIBUTED_SOLVER_H
#define ROCKDDA_DDA_DISTRIBUTED_SOLVER_H

#include <rockdda/dda/linear_solver.h>

#include <Eigen/Core>

#include <memory>
#include <vector>

namespace rockdda::dda::internal
{
  /**
   * CG on a Trilinos matrix distributed by blocks over MPI_COMM_WORLD, for
   * the block matrix of LinearSolver (SolverType::distributed). Every rank
   * holds the whole BlockSparseMatrix and right-hand side (the geometry is
   * replicated) and copies only the rows of the blocks it owns; the
   * solution comes back whole on every rank.
   */
  class DistributedSolver
  {
  public:
    explicit DistributedSolver(const DistributedPreconditioner preconditioner);
    ~DistributedSolver();

    /**
     * Set up the distributed pattern of @p K. The partition is made from
     * @p centroids (m, one per block) when the number of blocks changes
     * (first call, a block added), and kept otherwise.
     */
    void
    new_pattern(const BlockSparseMatrix            &K,
                const std::vector<geometry::Point> &centroids);

    /**
     * Solve K x = f to ||f - K x||_2 <= @p tolerance ||f||_2, from the
     * guess @p x (the same on every rank). With @p same_matrix the matrix
     * and preconditioner of the last call are reused. Returns false on
     * every rank if CG did not converge within @p max_iterations or the
     * preconditioner failed on any rank. Throws std::runtime_error if the
     * ranks hold different right-hand sides (their replicated states have
     * diverged).
     */
    bool
    solve(const BlockSparseMatrix &K,
          const Eigen::VectorXd   &f,
          Eigen::VectorXd         &x,
          const bool               same_matrix,
          const double             tolerance,
          const int                max_iterations,
          int                     &iterations);

    /// Number of ranks, and the blocks owned by this rank.
    int
    n_ranks() const;
    int
    n_owned_blocks() const;

  private:
    struct Impl;
    std::unique_ptr<Impl> impl;
  };
} // namespace rockdda::dda::internal

#endif
