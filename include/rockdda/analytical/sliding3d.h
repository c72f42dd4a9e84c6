/**
 * @file
 * Rigid-block sliding in 3D on one plane or on two planes (wedge), after
 * Bakun-Mazor's thesis, Chapter 4.2 (Eqs. 4.1-4.14), with contact-mode
 * detection (Goodman & Shi 1985) and proper stick/slip. See
 * doc/theory/sliding3d.md.
 */
#ifndef ROCKDDA_ANALYTICAL_SLIDING3D_H
#define ROCKDDA_ANALYTICAL_SLIDING3D_H

#include <rockdda/analytical/friction.h>

#include <Eigen/Core>

#include <array>
#include <functional>
#include <vector>

namespace rockdda::analytical
{
  /// A planar discontinuity a block slides on: orientation and friction.
  struct SlidingPlane
  {
    /// Dip (degrees), in [0, 90].
    double dip_deg = 0.;
    /// Dip direction (degrees clockwise from north), in [0, 360].
    double dip_direction_deg = 0.;
    /// Friction law of the interface.
    FrictionLaw friction;
  };

  /**
   * Which contacts carry the block.
   * - rest: stuck (on whatever planes touch);
   * - plane1 / plane2: single-face sliding;
   * - wedge: double-face sliding along the intersection line;
   * - lifted_off: free flight.
   */
  enum class SlidingMode
  {
    rest,
    plane1,
    plane2,
    wedge,
    lifted_off
  };

  /// Name of a mode ("rest", "plane1", "plane2", "wedge", "lifted_off").
  const char *
  to_string(const SlidingMode mode);

  /// Input of slide_3d().
  struct Sliding3dOptions
  {
    /// false: single plane (plane1 only); true: wedge on plane1 and plane2.
    bool wedge = false;
    /// The sliding plane(s).
    SlidingPlane plane1, plane2;
    /// Time step (s), > 0.
    double time_step = 1e-3;
    /// Duration of the analysis (s), > 0.
    double duration = 1.;
    /// Output interval (s); 0 = every step.
    double output_interval = 0.;
    /// Gravitational acceleration (m/s^2), converts the resultant from g.
    double g = 9.80665;
  };

  /// Output of slide_3d(). Vectors are in x east, y north, z up.
  struct Sliding3dResult
  {
    /// Output times (s), starting with 0.
    std::vector<double> time;
    /// Block displacement at the output times (m).
    std::vector<Eigen::Vector3d> displacement;
    /// Block velocity at the output times (m/s).
    std::vector<Eigen::Vector3d> velocity;
    /// Contact mode at the end of the step ending at each output time.
    std::vector<SlidingMode> mode;
    /// Displacement at the end of the analysis (m).
    Eigen::Vector3d final_displacement = Eigen::Vector3d::Zero();
    /// Mode at the end of the analysis.
    SlidingMode final_mode = SlidingMode::rest;
    /// Number of changes of the per-step mode over all steps.
    unsigned int n_mode_changes = 0;
    /// Largest speed reached (m/s).
    double max_speed = 0;
    /// Number of time steps taken.
    unsigned long n_steps = 0;
  };

  /**
   * Integrate the motion of a rigid block (unit mass) resting at t = 0 on
   * plane 1 (single plane) or on the intersection line of planes 1 and 2
   * (wedge), under the resultant acceleration @p resultant_g (in g, gravity
   * included, e.g. [0, 0, -1]; multiplied by options.g). Eqs. 4.1-4.14 of the
   * thesis with the corrected wedge normal forces, stick/slip with in-step
   * stop detection, and contact-mode detection (single face, wedge, lift-off,
   * inelastic re-contact). Throws InputError on invalid options.
   */
  Sliding3dResult
  slide_3d(const std::function<Eigen::Vector3d(double)> &resultant_g,
           const Sliding3dOptions                       &options);

  /// Unit normal of a plane (Eq. 4.1): x east, y north, z up; dip direction
  /// clockwise from north; the normal points up (n_z = cos(dip) >= 0).
  Eigen::Vector3d
  plane_normal(const double dip_deg, const double dip_direction_deg);

  /**
   * Check the options; throws InputError naming the quantity and its valid
   * range for: dip outside [0, 90] deg, dip direction outside [0, 360] deg,
   * friction angle >= 90 deg (mu0 not finite or < 0), parallel or nearly
   * parallel wedge planes (|n1 x n2| < 1e-6), time step <= 0, duration <= 0,
   * output interval < 0, g <= 0.
   */
  void
  validate(const Sliding3dOptions &options);

  /// Check one plane; @p name ("plane 1") is used in the message.
  void
  validate(const SlidingPlane &plane, const char *name);

  /**
   * Driving and normal forces (per unit mass, i.e. accelerations) of one
   * contact mode for a given resultant: the static equations shared by
   * slide_3d() and the yield-acceleration functions.
   */
  struct ContactForces
  {
    /// Kinematic mode: plane1, plane2, wedge or lifted_off.
    SlidingMode mode = SlidingMode::lifted_off;
    /// Driving force m: the part of the resultant the contacts leave free,
    /// Eq. 4.2 (plane) or Eq. 4.7 (wedge); the resultant itself in flight.
    Eigen::Vector3d driving = Eigen::Vector3d::Zero();
    /// Normal reactions N_i >= 0 on plane 1 and plane 2 (per unit mass).
    std::array<double, 2> normal = {{0., 0.}};
  };

  /**
   * Geometry of the contact planes and the mode analysis of a resultant. The
   * block lies on the +n side of each plane, and the intersection line of a
   * wedge passes through the origin (the initial block position).
   */
  class ContactGeometry
  {
  public:
    /// From the planes of @p options (validates them).
    explicit ContactGeometry(const Sliding3dOptions &options);

    /// 1 (single plane) or 2 (wedge).
    unsigned int
    n_planes() const
    {
      return n_planes_;
    }

    /// Upward unit normal of plane @p i (0 or 1).
    const Eigen::Vector3d &
    normal(const unsigned int i) const
    {
      return normals[i];
    }

    /// Unit intersection direction n1 x n2 / |n1 x n2| (wedge only).
    const Eigen::Vector3d &
    intersection() const
    {
      return unit_intersection;
    }

    /**
     * Kinematic mode for a resultant @p r on the planes that touch the block
     * (Goodman & Shi 1985): write r = a n1 + b n2 + c I (wedge); the wedge
     * slides on both planes if a <= 0 and b <= 0, on plane 1 alone if b > 0
     * and r.n1 <= 0, on plane 2 alone if a > 0 and r.n2 <= 0, and lifts off
     * otherwise. With one touching plane: contact if r.n <= 0.
     */
    SlidingMode
    select_mode(const Eigen::Vector3d     &r,
                const std::array<bool, 2> &touching) const;

    /// Driving and normal forces of @p r in @p mode (normal forces clipped at
    /// 0, for a mode held over a step while r changes).
    ContactForces
    forces(const Eigen::Vector3d &r, const SlidingMode mode) const;

    /// Project @p x onto the directions the block may move in @p mode
    /// (the plane, the intersection line, or everything in flight).
    Eigen::Vector3d
    tangential(const Eigen::Vector3d &x, const SlidingMode mode) const;

    /// Whether plane @p i carries the block in @p mode.
    static bool
    is_active(const SlidingMode mode, const unsigned int i);

  private:
    unsigned int                   n_planes_;
    std::array<Eigen::Vector3d, 2> normals;
    Eigen::Vector3d                unit_intersection;
    /// |n1 x n2| (sine of the angle between the normals).
    double sin_normals = 1.;
  };

  /**
   * Static stick test at rest (Eq. 4.4 / 4.10 with the corrected normal
   * forces): true if |m| <= mu1 N1 + mu2 N2 and the mode is not lift-off.
   */
  bool
  holds_at_rest(const ContactForces &forces,
                const double         mu1,
                const double         mu2);

  /**
   * Whether a block at rest on all planes of @p options (static friction
   * coefficients) stays at rest under the resultant @p resultant_g (g).
   */
  bool
  is_stuck(const Sliding3dOptions &options, const Eigen::Vector3d &resultant_g);
} // namespace rockdda::analytical

#endif
