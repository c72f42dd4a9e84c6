/**
 * @file
 * Plain data of a 2D DDA block system: blocks, materials, joints, fixed,
 * load and measurement points, body acceleration and seismic input. All
 * quantities are SI per unit thickness (m, kg/m^3, Pa, N/m, s).
 */
#ifndef ROCKDDA_DDA_BLOCK_SYSTEM_H
#define ROCKDDA_DDA_BLOCK_SYSTEM_H

#include <rockdda/dda/contact_mechanics.h>
#include <rockdda/geometry/polygon.h>
#include <rockdda/seismic/record.h>

#include <Eigen/Core>

#include <string>
#include <vector>

namespace rockdda::dda
{
  /// The 6 unknowns of a block (u0, v0, r0, eps_x, eps_y, gamma_xy).
  using Vector6 = Eigen::Matrix<double, 6, 1>;
  /// A 6x6 block submatrix.
  using Matrix6 = Eigen::Matrix<double, 6, 6>;

  /// Elastic block material.
  struct BlockMaterial
  {
    /// Density (kg/m^3), > 0.
    double density = 2700.;
    /// Young's modulus (Pa), > 0.
    double young = 1e10;
    /// Poisson's ratio (-), in [0, 0.5).
    double poisson = 0.25;
    /// Plane strain (true) or plane stress (false).
    bool plane_strain = false;
    /// The user's material id from the block file (written as the blocks'
    /// `material` in the VTU output); -1 = none (a scene built in code: the
    /// outputs use the index into BlockSystem::materials).
    int id = -1;
  };

  /// One block: a simple polygon with its state.
  struct Block
  {
    /// Identifier from the input (used in messages).
    int id = 0;
    /// Current geometry (m), counter-clockwise.
    geometry::Polygon polygon;
    /// Index into BlockSystem::materials; -1 = none (rejected by validate).
    int material = -1;
    /// Index into BlockSystem::joints (joint material of the block's faces).
    int joint = 0;
    /// Per-edge joint materials (indices into BlockSystem::joints): edge k
    /// runs from vertex k to vertex k+1. Empty: every edge uses @p joint.
    /// A contact on a tagged edge uses that edge's joint material (e.g. one
    /// per joint set of a cut rock mass, doc/block-file-format-dda.md).
    std::vector<int> edge_joints;
    /// Velocity of the 6 unknowns (m/s, rad/s, 1/s).
    Vector6 velocity = Vector6::Zero();
    /// Accumulated stress (sigma_x, sigma_y, tau_xy) (Pa), tension positive.
    Eigen::Vector3d stress = Eigen::Vector3d::Zero();
    /// Accumulated strain (eps_x, eps_y, gamma_xy) (-).
    Eigen::Vector3d strain = Eigen::Vector3d::Zero();
    /// Eigenstrain (eps_x, eps_y, gamma_xy) in the scene's frame (-): the
    /// in-plane strain the block would take if it were free, e.g. thermal
    /// expansion (thermal_eigenstrain()). Set by the caller between steps
    /// (DdaSystem::set_eigenstrains); the stress is C (strain - eigenstrain)
    /// and the next step loads the block by the change, an initial-strain
    /// load A C (eigenstrain - applied_eigenstrain) on its strain terms.
    Eigen::Vector3d eigenstrain = Eigen::Vector3d::Zero();
    /// The eigenstrain already in the block's stress (-).
    Eigen::Vector3d applied_eigenstrain = Eigen::Vector3d::Zero();
    /// Centroid at t = 0 (m); displacement = centroid now - this.
    geometry::Point initial_centroid = geometry::Point::Zero();
    /// Cumulative rotation (rad).
    double rotation = 0.;
  };

  /// A point of a block held to a target position by a stiff spring.
  struct FixedPoint
  {
    /// Block index.
    int block = 0;
    /// Current position of the material point (m).
    geometry::Point point = geometry::Point::Zero();
    /// Position at t = 0 (m); the target is this plus the prescribed
    /// displacement (ground displacement in displacement mode).
    geometry::Point anchor = geometry::Point::Zero();
    /// Whether the seismic displacement moves this point's target.
    bool moves_with_ground = true;
  };

  /// A constant point force on a block (N per m thickness).
  struct LoadPoint
  {
    int             block = 0;
    geometry::Point point = geometry::Point::Zero();
    geometry::Point force = geometry::Point::Zero();
  };

  /// A material point of a block whose motion and stress are reported.
  struct MeasurementPoint
  {
    int             block   = 0;
    geometry::Point point   = geometry::Point::Zero();
    geometry::Point initial = geometry::Point::Zero();
  };

  /**
   * Seismic input. The record is the horizontal ground acceleration (g,
   * positive towards +x); the optional vertical record the vertical one
   * (g, positive upward). Inertial mode: every block is loaded by -a(t) g
   * along each direction (the system is analysed in the frame of the
   * ground and the fixed points stay put), so an upward ground
   * acceleration a_v raises the effective gravity to g (1 + a_v).
   * Displacement mode: the fixed points follow the ground displacement,
   * the exact double integral of each piecewise-linear record from rest
   * (Kamai & Hatzor 2008).
   */
  struct SeismicInput
  {
    enum class Mode
    {
      none,
      inertial,
      displacement
    };
    Mode            mode = Mode::none;
    seismic::Record record;
    /// Vertical ground acceleration (g, positive along @p vertical), on its
    /// own time step from t = 0; empty: no vertical motion.
    seismic::Record vertical_record;
    /// Unit direction of the ground motion in the scene's plane (default
    /// +x); a rotated scene rotates it with the blocks.
    geometry::Point direction = geometry::Point(1., 0.);
    /// Unit upward direction of the vertical record (default +y); a
    /// rotated scene rotates it with the blocks.
    geometry::Point vertical = geometry::Point(0., 1.);
    /// Gravitational acceleration used to convert g to m/s^2.
    double g = 9.80665;
  };

  /// The whole scene: plain data handed to DdaSystem.
  struct BlockSystem
  {
    std::vector<BlockMaterial>    materials;
    std::vector<JointMaterial>    joints;
    std::vector<Block>            blocks;
    std::vector<FixedPoint>       fixed_points;
    std::vector<LoadPoint>        load_points;
    std::vector<MeasurementPoint> measurement_points;
    /// Constant body acceleration (m/s^2), e.g. (0, -9.80665).
    geometry::Point gravity = geometry::Point(0., -9.80665);
    SeismicInput    seismic;
    /// The coordinates above are relative to this point (m): a scene's
    /// global position is origin + local. DdaSystem moves its scene to a
    /// local origin (the lower-left corner of the blocks' bounding box) so that
    /// round- off does not depend on where the scene sits (e.g. UTM
    /// coordinates); outputs add the origin back.
    geometry::Point origin = geometry::Point::Zero();
  };

  /**
   * The eigenstrain that the next step applies to @p b: the change from
   * Block::applied_eigenstrain to Block::eigenstrain, multiplicative in the
   * normal components, (1 + e) / (1 + a) - 1, so that a free block's sides
   * are 1 + e times their length at zero eigenstrain whatever the path of
   * e. (The difference e - a, applied step by step to the current
   * geometry, shortened them by half the sum of the squared increments in
   * every cycle of expansion and contraction: Block 1's top tilted by
   * 7.5e-9 m per year at 24 steps per year, 3.8e-9 at 48.) The shear
   * component is the difference.
   */
  inline Eigen::Vector3d
  eigenstrain_step(const Block &b)
  {
    return Eigen::Vector3d(
      (1. + b.eigenstrain[0]) / (1. + b.applied_eigenstrain[0]) - 1.,
      (1. + b.eigenstrain[1]) / (1. + b.applied_eigenstrain[1]) - 1.,
      b.eigenstrain[2] - b.applied_eigenstrain[2]);
  }

  /**
   * Check a scene and prepare it: clockwise polygons are reversed (a
   * warning per block is appended to @p warnings), initial centroids are
   * set. Throws InputError naming the block id for fewer than 3 vertices,
   * zero area, a self-intersecting polygon, a missing or invalid material,
   * zero density, blocks overlapping at t = 0 (by more than
   * @p overlap_fraction of the smaller block's size), and fixed, load and
   * measurement points outside their block.
   */
  void
  validate_and_prepare(BlockSystem              &system,
                       std::vector<std::string> &warnings,
                       const double              overlap_fraction);

  /**
   * Check @p block (in @p system's coordinates) before it joins @p system
   * between steps, as validate_and_prepare() checks a block at t = 0:
   * reversed if clockwise (with a warning), initial centroid set; throws
   * InputError naming it for bad vertices, area or materials, or if it
   * overlaps a block of @p system as that block is now by more than
   * @p overlap_fraction of the smaller block's size.
   */
  void
  validate_added_block(const BlockSystem        &system,
                       Block                    &block,
                       std::vector<std::string> &warnings,
                       const double              overlap_fraction);

  /**
   * The ground displacement and velocity of a seismic record, integrated
   * exactly for a piecewise-linear acceleration from rest at t = 0.
   */
  class GroundMotionIntegral
  {
  public:
    GroundMotionIntegral() = default;
    /// Integrate @p record (g) with @p g (m/s^2). The record starts at
    /// time @p start (s): the ground is at rest before it (a seismic
    /// episode of a run that has been going on; DdaSystem::
    /// set_seismic_input()).
    GroundMotionIntegral(const seismic::Record &record,
                         const double           g,
                         const double           start = 0.);
    /// Acceleration (m/s^2) at t; 0 outside the record.
    double
    acceleration(const double t) const;
    /// Displacement (m) at t; after the record the ground moves on at the
    /// final velocity.
    double
    displacement(const double t) const;
    /// Largest |ground velocity| (m/s) of the record.
    double
    peak_velocity() const;
    /// Ground velocity (m/s) and displacement (m) at the end of the record
    /// (the integration drift of an uncorrected record).
    double
    final_velocity() const
    {
      return v.empty() ? 0. : v.back();
    }
    double
    final_displacement() const
    {
      return u.empty() ? 0. : u.back();
    }

  private:
    double              dt = 0., t0 = 0.;
    std::vector<double> a, v, u;
  };

} // namespace rockdda::dda

#endif
