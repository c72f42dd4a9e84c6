/**
 * @file
 * Geometric partition of the blocks of a 2D DDA scene over MPI ranks: the
 * blocks ordered along a Hilbert space-filling curve through their
 * centroids, cut into contiguous pieces of equal block counts
 * (doc/theory/dda-mpi.md).
 */
#ifndef ROCKDDA_DDA_BLOCK_PARTITION_H
#define ROCKDDA_DDA_BLOCK_PARTITION_H

#include <rockdda/geometry/polygon.h>

#include <cstdint>
#include <vector>

namespace rockdda::dda
{
  /**
   * A partition of n blocks into parts (ranks) by a space-filling curve.
   * The blocks are renumbered along the curve, so that the blocks of part
   * r are the contiguous range [first[r], first[r + 1]) of the new
   * numbering; a distributed vector of 6 unknowns per block then owns a
   * contiguous range of rows on every rank.
   */
  struct BlockPartition
  {
    /// Block (scene index) at each position of the new numbering.
    std::vector<int> order;
    /// Position in the new numbering of each block (inverse of order).
    std::vector<int> position;
    /// Start of each part in the new numbering; first.back() = n.
    std::vector<int> first;

    /// Number of parts.
    int
    n_parts() const
    {
      return static_cast<int>(first.size()) - 1;
    }
    /// The part that owns block @p b (scene index).
    int
    owner(const int b) const;
  };

  /**
   * Index of the cell (@p x, @p y) of a 2^@p bits x 2^@p bits grid along
   * the Hilbert curve of that order (0 <= x, y < 2^bits, 1 <= bits <= 31).
   */
  std::uint64_t
  hilbert_index(std::uint32_t x, std::uint32_t y, const int bits);

  /**
   * Partition the blocks at @p centroids (m) into @p n_parts (>= 1)
   * pieces: sorted by the Hilbert index of their centroid on a 2^16 grid
   * over the bounding box (ties by block index, so the result depends on
   * the centroids alone), then cut into pieces whose sizes differ by at
   * most one block. Deterministic: every rank computes the same partition
   * from the same centroids.
   */
  BlockPartition
  partition_blocks(const std::vector<geometry::Point> &centroids,
                   const int                           n_parts);
} // namespace rockdda::dda

#endif
