/**
 * @file
 * Generators of polyhedral 3D DDA blocks: boxes, prisms (extruded
 * polygons), tetrahedra and tetrahedral wedges, and convex blocks cut by
 * half-spaces (e.g. a block cut from a slab by joints given as dip / dip
 * direction).
 */
#ifndef ROCKDDA_DDA3D_GENERATORS_H
#define ROCKDDA_DDA3D_GENERATORS_H

#include <rockdda/dda/contact_mechanics.h>
#include <rockdda/dda3d/block_system.h>
#include <rockdda/dda3d/polyhedron.h>
#include <rockdda/geometry/polygon.h>

#include <array>
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
   * The planes of a Hoek-Bray wedge: two joints and the slope face, each
   * as dip and dip direction (degrees).
   */
  struct WedgePlanes
  {
    double joint1_dip_deg = 0., joint1_dip_direction_deg = 0.;
    double joint2_dip_deg = 0., joint2_dip_direction_deg = 0.;
    double slope_dip_deg = 0., slope_dip_direction_deg = 0.;
  };

  /**
   * The Hoek-Bray tetrahedral wedge: the block above two joint planes
   * (dip, dip direction; through the crest point @p crest) and below the
   * slope face and the horizontal top surface, both through @p crest. The
   * wedge is found by clipping a box of edge 4 @p size about the crest, so
   * it must lie within it. Throws InputError if the planes leave no
   * block.
   */
  Polyhedron
  make_tetrahedral_wedge(const WedgePlanes &planes,
                         const double       height,
                         const Point       &crest = Point::Zero());

  /**
   * A tetrahedral wedge (make_tetrahedral_wedge()) with the V-shaped trough
   * it rests in: the two joint planes through the wedge's toe bound two
   * convex trough blocks below them, split by the plane through the joints'
   * line of intersection that bisects them ((n1 - n2) . (x - toe) = 0, n1,
   * n2 the joints' upward normals). The trough fills the wedge's bounding
   * box widened by @p margin (m, > 0) on every side (and 2 @p margin
   * below), so that the wedge stays on it for a slide of up to @p margin
   * in any direction. The wedge touches trough block 1 (2) on joint 1 (2)
   * only.
   */
  struct WedgeInTrough
  {
    Polyhedron wedge;
    /// Trough blocks below joint 1 and joint 2.
    std::array<Polyhedron, 2> trough;
    /// The wedge's lowest vertex, where the joints' line daylights (m).
    Point toe = Point::Zero();
  };

  /// The wedge and trough of WedgeInTrough (arguments as
  /// make_tetrahedral_wedge(), @p margin as documented there).
  WedgeInTrough
  make_wedge_in_trough(const WedgePlanes &planes,
                       const double       height,
                       const double       margin,
                       const Point       &crest = Point::Zero());

  /**
   * The scene of @p w: trough blocks (ids 1, 2) clamped by a fixed point at
   * every vertex, the wedge (id 3) with a measurement point at its
   * centroid; all of material @p material, every face of joint @p joint.
   * Gravity is the default.
   */
  BlockSystem
  wedge_in_trough_scene(const WedgeInTrough      &w,
                        const Material           &material,
                        const dda::JointMaterial &joint);
} // namespace rockdda::dda3d

#endif
