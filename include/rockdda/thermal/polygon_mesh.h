/**
 * @file
 * Coarse quadrilateral meshes of block polygons (no deal.II): a structured
 * grid for a single convex quadrilateral, otherwise ear-clipping
 * triangulation with every triangle split into three quadrilaterals.
 */
#ifndef ROCKDDA_THERMAL_POLYGON_MESH_H
#define ROCKDDA_THERMAL_POLYGON_MESH_H

#include <rockdda/thermal/heat_solver.h>

#include <array>
#include <string>
#include <vector>

namespace rockdda::thermal
{
  /// A coarse mesh: vertices and counter-clockwise quadrilaterals.
  struct CoarseMesh
  {
    std::vector<Point2>                      vertices;
    std::vector<std::array<unsigned int, 4>> quads; ///< counter-clockwise
    std::vector<unsigned int>                quad_block;
  };

  /**
   * Mesh @p blocks. With @p merge_blocks, vertices shared by blocks are
   * merged (one conforming domain); otherwise each block keeps its own
   * vertices (the blocks are disconnected). A single convex quadrilateral is
   * meshed as a structured grid with cells of about @p cell_size; other
   * polygons by ear clipping (the caller refines to @p cell_size). Throws
   * InputError for a degenerate or self-intersecting polygon or a tag count
   * that differs from the vertex count.
   */
  CoarseMesh
  mesh_blocks(const std::vector<Block> &blocks,
              const double              cell_size,
              const bool                merge_blocks);

  /// Distance from @p p to the segment [@p a, @p b], m.
  double
  distance_to_segment(const Point2 &p, const Point2 &a, const Point2 &b);

  /// Signed area of a polygon (positive if counter-clockwise), m^2.
  double
  signed_area(const std::vector<Point2> &polygon);
} // namespace rockdda::thermal

#endif
