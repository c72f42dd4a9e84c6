/**
 * @file
 * Exact block cutting: traces, domain boundary and excavation outlines into
 * a CGAL arrangement (exact kernel), then blocks with tagged edges.
 */
#ifndef ROCKDDA_STRUCTURE_BLOCK_CUTTER_H
#define ROCKDDA_STRUCTURE_BLOCK_CUTTER_H

#include <rockdda/structure/block_set.h>

#include <vector>

namespace rockdda::structure
{
  /**
   * Options of block cutting. A block is a sliver if its area is below
   * sliver_area, its smallest width (Polygon::min_width) is below
   * sliver_width or its smallest interior angle is below sliver_angle.
   */
  struct CutOptions
  {
    double sliver_area   = 0.;   ///< m^2; 0 disables the area test
    double sliver_width  = 0.;   ///< m; 0 disables the width test
    double sliver_angle  = 0.;   ///< rad; 0 disables the angle test
    bool   merge_slivers = true; ///< merge (true) or only report (false)
    /**
     * Remove every vertex at which a block's boundary goes straight on
     * (true), or only those with two edges in the arrangement, keeping
     * T-junction vertices so that neighbours are conforming (false).
     */
    bool remove_all_collinear = true;
  };

  /**
   * Cut the @p domain (a simple polygon, either orientation) by @p segments,
   * removing the @p excavations (simple polygons inside the domain).
   *
   * Rules (see doc/block-file-format.md):
   * - Everything is inserted at once into a CGAL Arrangement_2 with exact
   *   constructions; segment parts outside the domain are discarded.
   * - Edges with the same face on both sides (dangling trees and bridges)
   *   are removed: they do not separate blocks.
   * - A face containing a hole (a floating block or an excavation not
   *   touched by any joint) is split by vertical "split" cuts: down from the
   *   hole's lowest-leftmost vertex and up from its highest-rightmost vertex
   *   to the nearest edge, repeated until no face has a hole.
   * - An edge on several inputs gets one tag, by priority boundary >
   *   excavation > bedding > joint (lowest set) > split.
   * - Slivers: each sliver face is merged into the neighbour across its
   *   longest shared edge (the shared edges are removed); a sliver with no
   *   block neighbour is dropped (dropped_area). Merging runs once; blocks
   *   still below a threshold are counted in n_slivers_remaining.
   * - Coordinates are rounded to double once per arrangement vertex.
   *
   * Throws InputError for a degenerate or self-intersecting domain or an
   * excavation not inside the domain.
   */
  BlockSet
  cut_blocks(const Polygon                    &domain,
             const std::vector<Polygon>       &excavations,
             const std::vector<TaggedSegment> &segments,
             const CutOptions                 &options = CutOptions());
} // namespace rockdda::structure

#endif
