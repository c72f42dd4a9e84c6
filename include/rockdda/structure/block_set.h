/**
 * @file
 * Plain data of rock structure: tagged line segments (the input of block
 * cutting) and the cut blocks (its output, the input of the DDA engine).
 */
#ifndef ROCKDDA_STRUCTURE_BLOCK_SET_H
#define ROCKDDA_STRUCTURE_BLOCK_SET_H

#include <rockdda/geometry/polygon.h>

#include <string>
#include <vector>

namespace rockdda::structure
{
  using geometry::Point;
  using geometry::Polygon;

  /// Where a discontinuity (and so a block edge) comes from.
  enum class EdgeKind : int
  {
    boundary   = 0, ///< the outer domain boundary
    bedding    = 1, ///< a bedding plane (layer boundary)
    joint      = 2, ///< a joint of set EdgeTag::set
    excavation = 3, ///< the outline of excavation EdgeTag::set
    split      = 4  ///< a fictitious cut added to split a face with a hole
  };

  /// Name of an edge kind ("boundary", "bedding", ...).
  std::string
  to_string(const EdgeKind kind);

  /**
   * The tag of an edge: its kind and, for joints and excavations, the index
   * (from 0) of the joint set or excavation; 0 otherwise.
   */
  struct EdgeTag
  {
    EdgeKind kind = EdgeKind::joint;
    int      set  = 0;

    bool
    operator==(const EdgeTag &o) const
    {
      return kind == o.kind && set == o.set;
    }
    bool
    operator!=(const EdgeTag &o) const
    {
      return !(*this == o);
    }
  };

  /// A straight trace (m) with the tag it gives to the block edges on it.
  struct TaggedSegment
  {
    Point   a, b;
    EdgeTag tag;
  };

  /**
   * One block: a simple polygon with counter-clockwise vertices; edge i runs
   * from vertex i to vertex i+1 (mod n) and carries edge_tags[i];
   * vertex_ids[i] indexes BlockSet::vertices, so neighbours share vertices
   * (and their double coordinates are bit-identical).
   */
  struct Block
  {
    Polygon                  polygon;
    std::vector<EdgeTag>     edge_tags;
    std::vector<std::size_t> vertex_ids;
  };

  /**
   * The result of block cutting: the blocks, every vertex once, and an area
   * budget: domain_area = sum of block areas + excavated_area +
   * dropped_area (up to rounding of the double conversion).
   */
  struct BlockSet
  {
    std::vector<Block> blocks;
    std::vector<Point> vertices;

    double domain_area    = 0.; ///< m^2
    double excavated_area = 0.; ///< faces inside excavations, m^2
    double dropped_area   = 0.; ///< slivers that could not be merged, m^2

    unsigned int n_segments_in       = 0; ///< segments given to the cutter
    unsigned int n_dangling_edges    = 0; ///< arrangement edges removed
    unsigned int n_holes_split       = 0; ///< holes removed by split cuts
    unsigned int n_slivers_merged    = 0;
    unsigned int n_slivers_dropped   = 0;
    unsigned int n_slivers_remaining = 0; ///< still below a threshold
    /// Slivers found by the area, width and angle tests (merged, dropped
    /// or remaining; one sliver may fail several tests).
    unsigned int n_slivers_by_area = 0, n_slivers_by_width = 0,
                 n_slivers_by_angle = 0;
    /// Faces that collapse when rounded to double (area below rounding).
    unsigned int n_degenerate_dropped = 0;

    /// Sum of the block areas (m^2).
    double
    total_block_area() const;
  };
} // namespace rockdda::structure

#endif
