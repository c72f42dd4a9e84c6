/**
 * @file
 * Pseudo-static yield accelerations of a block on a plane or a wedge, and
 * their inversion for the friction angle.
 */
#ifndef ROCKDDA_ANALYTICAL_YIELD_H
#define ROCKDDA_ANALYTICAL_YIELD_H

#include <rockdda/analytical/sliding3d.h>

namespace rockdda::analytical
{
  /**
   * Pseudo-static horizontal yield acceleration (g) of a block on a plane
   * dipping @p dip_deg with friction angle @p phi_deg, optional cohesion
   * @p cohesion (Pa) over contact area @p area (m^2) for block weight
   * @p weight (N), for a horizontal inertial load pointing down the dip
   * (Goodman & Seed 1966):
   * ky = (cA/W + cos(a) tan(phi) - sin(a)) / (cos(a) + sin(a) tan(phi));
   * c = 0 gives tan(phi - a). For 19 deg, 41 deg: 0.404 g. A negative value
   * means the block is unstable under gravity alone. Throws InputError for a
   * dip outside [0, 90], phi outside [0, 90), c < 0, A <= 0 or W <= 0.
   */
  double
  plane_yield_acceleration(const double dip_deg,
                           const double phi_deg,
                           const double cohesion = 0.,
                           const double area     = 1.,
                           const double weight   = 1.);

  /**
   * Horizontal yield acceleration (g) of a wedge resting on the
   * intersection line of @p p1 and @p p2 for a horizontal inertial load
   * along the azimuth @p azimuth_deg (clockwise from north): the smallest
   * k >= 0 for which the resultant k h - z (g) no longer holds the block,
   * found with the static equations and mode selection used by slide_3d()
   * (wedge or single-face sliding, lift-off), by a scan in steps of 0.01 g
   * followed by bisection to @p tolerance (g). Static friction coefficients
   * are used. Returns 0 if the wedge is unstable under gravity and +infinity
   * if no load up to 10 g makes it slide.
   */
  double
  wedge_yield_acceleration(const SlidingPlane &p1,
                           const SlidingPlane &p2,
                           const double        azimuth_deg,
                           const double        tolerance = 1e-10);

  /**
   * The friction angle (deg) that makes the horizontal acceleration @p k_g
   * (g, down-dip) critical for a block on a plane: a + atan(k) for c = 0,
   * bisection on plane_yield_acceleration() with cohesion. Throws InputError
   * if no angle in [0, 90) deg does.
   */
  double
  critical_friction_angle_plane(const double dip_deg,
                                const double k_g,
                                const double cohesion = 0.,
                                const double area     = 1.,
                                const double weight   = 1.);

  /**
   * The friction angle (deg, the same on both planes, Coulomb) that makes
   * the horizontal acceleration @p k_g (g) along @p azimuth_deg critical for
   * a wedge: the smallest angle that holds the wedge at rest under k h - z,
   * by bisection on the static test of slide_3d(). Throws InputError if no
   * angle below 90 deg holds it (e.g. the load lifts the wedge off).
   */
  double
  critical_friction_angle_wedge(const double dip1,
                                const double dipdir1,
                                const double dip2,
                                const double dipdir2,
                                const double azimuth_deg,
                                const double k_g);
} // namespace rockdda::analytical

#endif
