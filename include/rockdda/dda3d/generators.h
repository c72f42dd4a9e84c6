/**
 * @file
 * Generators of polyhedral 3D DDA blocks: boxes, prisms (extruded
 * polygons), tetrahedra and tetrahedral wedges, and convex blocks cut by
 * half-spaces (e.g. a block cut from a slab by joints given as dip / dip
 * direction).
 */
#ifndef ROCKDDA_DDA3D_GENERATORS_H
#define ROCKDDA_DDA3D_GENERATORS_H

#include <rockdda/dda3d/polyhedron.h>
#include <rockdda/geometry/polygon.h>

#include <vector>

namespace rockdda::dda3d
{
  /// An axis-aligned box with corners @p lo and @p hi (m); 8 vertices, 6
  /// quadrilateral faces.
  Polyhedron
  make_box(const Point &lo, const Point &hi);

  /**
   * A prism: the simple polygon @p base (m, convex or not; either
   * orientation) in the plane z = @p z0 extruded to z = @p z1 > z0. Two
   * polygon faces and one quadrilateral per edge.
   */
  Polyhedron
  make_prism(const geometry::Polygon &base, const double z0, const double z1);

  /// The tetrahedron with vertices @p a, @p b, @p c, @p d (m), faces
  /// oriented outward whatever the order of the vertices.
  Polyhedron
  make_tetrahedron(const Point &a,
                   const Point &b,
                   const Point &c,
                   const Point &d);

  /**
   * A half-space n . x <= offset: @p normal points out of the kept side.
   */
  struct HalfSpace
  {
    Point  normal = Point::UnitZ();
    double offset = 0.;
  };

  /// The half-space below (against the normal of) the plane through
  /// @p point with dip @p dip_deg and dip direction @p dip_direction_deg
  /// (x east, y north, z up; the plane's upward normal as
  /// analytical::plane_normal(), thesis Eq. 4.1); @p above keeps the other
  /// side.
  HalfSpace
  half_space_from_dip(const double dip_deg,
                      const double dip_direction_deg,
                      const Point &point,
                      const bool   above = false);

  /**
   * The convex polyhedron @p convex clipped by each half-space in turn
   * (polygon clipping of every face and a cap face on each cutting plane;
   * vertices closer than 1e-9 x the block size are merged). Throws
   * InputError if nothing is left. Use it with make_box() for a block cut
   * from a slab, or for a tetrahedral wedge (two joint planes, the slope
   * face and the top face, see make_tetrahedral_wedge()).
   */
  Polyhedron
  clip_convex(const Polyhedron &convex, const std::vector<HalfSpace> &cuts);

  /**
   * The Hoek-Bray tetrahedral wedge: the block above two joint planes
   * (dip, dip direction; through the crest point @p crest) and below the
   * slope face and the horizontal top surface, both through @p crest. The
   * wedge is found by clipping a box of edge 4 @p size about the crest, so
   * it must lie within it. Throws InputError if the planes leave no
   * block.
   */
  Polyhedron
  make_tetrahedral_wedge(const double joint1_dip_deg,
                         const double joint1_dip_direction_deg,
                         const double joint2_dip_deg,
                         const double joint2_dip_direction_deg,
                         const double slope_dip_deg,
                         const double slope_dip_direction_deg,
                         const double height,
                         const Point &crest = Point::Zero());
} // namespace rockdda::dda3d

#endif
