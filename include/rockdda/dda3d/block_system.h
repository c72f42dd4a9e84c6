/**
 * @file
 * Plain data of a 3D DDA block system (issue 17): materials, polyhedral
 * blocks with their 12 unknowns, fixed, load and measurement points and the
 * body acceleration. SI units (m, kg/m^3, Pa, N, s).
 */
#ifndef ROCKDDA_DDA3D_BLOCK_SYSTEM_H
#define ROCKDDA_DDA3D_BLOCK_SYSTEM_H

#include <rockdda/dda/contact_mechanics.h>
#include <rockdda/dda3d/polyhedron.h>

#include <Eigen/Core>

#include <string>
#include <vector>

namespace rockdda::dda3d
{
  /**
   * The 12 unknowns of a block (thesis Eq. 2.4, Shi 2001):
   * (u0, v0, w0, r1, r2, r3, eps_x, eps_y, eps_z, gamma_xy, gamma_yz,
   * gamma_zx): translation of the centroid (m), rotations (rad) about the
   * z-, x- and y-axis (right-handed, so the rotation vector is
   * (r2, r3, r1)), normal strains and engineering shear strains (-).
   */
  using Vector12 = Eigen::Matrix<double, 12, 1>;
  /// A 12x12 block submatrix.
  using Matrix12 = Eigen::Matrix<double, 12, 12>;
  /// Stress or strain in Voigt order (xx, yy, zz, xy, yz, zx); strains with
  /// engineering shear (gamma = 2 eps).
  using Vector6 = Eigen::Matrix<double, 6, 1>;

  /// Isotropic elastic block material.
  struct Material
  {
    /// Density (kg/m^3), > 0.
    double density = 2700.;
    /// Young's modulus (Pa), > 0.
    double young = 1e10;
    /// Poisson's ratio (-), in [0, 0.5).
    double poisson = 0.25;
    /// The user's id from the block file; -1 = none.
    int id = -1;
  };

  /// One block: a closed polyhedron with its state.
  struct Block
  {
    /// Identifier from the input (used in messages).
    int id = 0;
    /// Current geometry (m).
    Polyhedron polyhedron;
    /// Index into BlockSystem::materials.
    int material = -1;
    /// Index into BlockSystem::joints: the joint material of the block's
    /// faces (a contact uses the one of the block that owns its face or
    /// second edge).
    int joint = 0;
    /// Velocity of the 12 unknowns (m/s, rad/s, 1/s).
    Vector12 velocity = Vector12::Zero();
    /// Accumulated stress (Pa, tension positive), Voigt order.
    Vector6 stress = Vector6::Zero();
    /// Accumulated strain (-), Voigt order, engineering shear.
    Vector6 strain = Vector6::Zero();
    /// Centroid at t = 0 (m).
    Point initial_centroid = Point::Zero();
  };

  /// A material point of a block held to its initial position by a stiff
  /// spring (penalty).
  struct FixedPoint
  {
    int   block  = 0;
    Point point  = Point::Zero();
    Point anchor = Point::Zero();
  };

  /// A constant point force (N) on a block.
  struct LoadPoint
  {
    int   block = 0;
    Point point = Point::Zero();
    Point force = Point::Zero();
  };

  /// A material point whose motion is reported.
  struct MeasurementPoint
  {
    int   block   = 0;
    Point point   = Point::Zero();
    Point initial = Point::Zero();
  };

  /// The whole scene.
  struct BlockSystem
  {
    std::vector<Material> materials;
    /// Joint (contact) materials, shared with the 2D engine: friction,
    /// cohesion and tensile strength (Pa, over a contact's area), joint
    /// stiffness (Pa/m). Needed only by scenes with contacts.
    std::vector<dda::JointMaterial> joints;
    std::vector<Block>              blocks;
    std::vector<FixedPoint>         fixed_points;
    std::vector<LoadPoint>          load_points;
    std::vector<MeasurementPoint>   measurement_points;
    /// Constant body acceleration (m/s^2), default (0, 0, -9.80665).
    Point gravity = Point(0., 0., -9.80665);
  };

  /**
   * Check a scene and prepare it (initial centroids, anchors of the fixed
   * points, initial positions of measurement points). Throws InputError
   * naming the block (and face) for a defective polyhedron
   * (polyhedron_defect()), a missing material, a density, Young's modulus
   * or Poisson's ratio out of range, and a fixed, load or measurement
   * point outside its block. Overlapping blocks at t = 0 are checked
   * separately (check_overlaps(); the Engine does it on construction).
   */
  void
  validate_and_prepare(BlockSystem &system);

  /// How deep two polyhedra overlap (overlap_depth()).
  struct OverlapDepth
  {
    /// Penetration depth (m); <= 0 if they are apart or only touch.
    double depth = 0.;
    /// A point in or near the overlap (m).
    Point point = Point::Zero();
    /// For convex blocks the axis of least overlap (unit).
    Point axis = Point::Zero();
  };

  /**
   * The overlap of two polyhedra. Both convex (every vertex within 1e-9 of
   * the size on the inner side of every face): the separating-axis test
   * over the face normals of both and the cross products of an edge of
   * each, exact: the depth is the least overlap of the projections.
   * Otherwise a lower bound: the depth of the deepest vertex (or centroid)
   * of one inside the other, measured to the nearest face plane; two
   * non-convex blocks whose edges cross with no vertex inside the other are
   * not detected.
   */
  OverlapDepth
  overlap_depth(const Polyhedron &a, const Polyhedron &b);

  /**
   * Throw InputError naming both blocks (ids), the depth and a point of the
   * overlap (plus @p origin, m) if two blocks of @p system overlap by more
   * than @p overlap_fraction times the smaller block's size (touching and
   * round-off are allowed). Pairs come from the broad phase on the
   * bounding boxes, so the check is O(N) for blocks of similar size.
   */
  void
  check_overlaps(const BlockSystem &system,
                 const double       overlap_fraction = 1e-6,
                 const Point       &origin           = Point::Zero());
} // namespace rockdda::dda3d

#endif
