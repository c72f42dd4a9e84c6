/**
 * @file
 * Sparse Cholesky factorisation of a symmetric positive definite block
 * matrix in its own dofs x dofs blocks (internal to the DDA linear solver).
 */
#ifndef ROCKDDA_DDA_BLOCK_CHOLESKY_H
#define ROCKDDA_DDA_BLOCK_CHOLESKY_H

#include <rockdda/dda/linear_solver.h>

#include <Eigen/Core>

#include <utility>
#include <vector>

namespace rockdda::dda::internal
{
  /**
   * K = P^T L L^T P for a BlockSparseMatrixOf<dofs>, computed on the
   * blocks themselves: the minimum-degree ordering P (Eigen's AMD) and the
   * fill-in of L come from the block graph (the pairs), once per pattern;
   * the numeric factorisation is right-looking with dense dofs x dofs
   * operations (a Cholesky factor per diagonal block, kept as its inverse
   * so that the column below it and the solves are dense products, and
   * the Schur updates into precomputed targets). Compared with a scalar sparse
   * LDL^T on the same matrix this does the same arithmetic without an index per
   * entry, and needs no copy of the matrix into compressed storage (George &
   * Liu 1981, Computer Solution of Large Sparse Positive Definite Systems, ch.
   * 5 and 7; Davis 2006, Direct Methods for Sparse Linear Systems, ch. 4).
   */
  template <int dofs>
  class BlockCholeskyOf
  {
  public:
    using Matrix = BlockSparseMatrixOf<dofs>;
    using Dense  = typename Matrix::Dense;
    using Vector = Eigen::Matrix<double, dofs, 1>;

    /// Ordering and fill-in for the pattern of @p K (n blocks, pairs);
    /// nothing is done when the pattern equals the last one analysed.
    void
    analyse(const Matrix &K);

    /// Numeric factorisation of @p K (pattern as analysed). Returns false
    /// if K is not positive definite (a pivot block is not) or not finite.
    bool
    factorize(const Matrix &K);

    /// x = K^-1 f with the last factorisation.
    void
    solve(const Eigen::VectorXd &f, Eigen::VectorXd &x) const;

  private:
    int n = -1;
    /// The pattern analysed last.
    std::vector<std::pair<int, int>> pairs;
    /// new_of[old block] and old_of[new block].
    std::vector<int> new_of, old_of;
    /// Column k of L: factor[start[k]] is the inverse of its diagonal
    /// factor (lower),
    /// factor[start[k] + 1 ..< start[k + 1]] the blocks of rows
    /// row[start[k] + 1 ..] (ascending, > k).
    std::vector<int>   start, row;
    std::vector<Dense> factor;
    /// Where K's blocks go: the diagonal of old block b at
    /// factor[start[new_of[b]]]; pair p at factor[pair_target[p]],
    /// transposed if pair_transposed[p].
    std::vector<int>  pair_target;
    std::vector<char> pair_transposed;
    /// Schur updates of column k, for its off blocks a <= b (positions in
    /// the column): factor[update[u]] -= L_b L_a^T, in the order of
    /// update_start[k] ..< update_start[k + 1].
    std::vector<int> update_start, update;
    /// Work vector in the new ordering.
    mutable Eigen::VectorXd y;
  };
} // namespace rockdda::dda::internal

#endif
