#include <rockdda/analytical/yield.h>
#include <rockdda/io/error.h>

#include <cmath>
#include <limits>
#include <string>

namespace rockdda::analytical
{
  namespace
  {
    constexpr double degree = M_PI / 180.;
    /// Largest load tried by wedge_yield_acceleration() (g).
    constexpr double max_load = 10.;
    /// Scan step of wedge_yield_acceleration() (g).
    constexpr double scan_step = 0.01;
    /// Largest friction angle tried by the inversions (deg).
    constexpr double max_phi = 90. - 1e-9;

    void
    check_plane_inputs(const double dip_deg,
                       const double cohesion,
                       const double area,
                       const double weight)
    {
      if (!(dip_deg >= 0. && dip_deg <= 90.))
        throw InputError("plane dip = " + std::to_string(dip_deg)
                         + " deg is outside the valid range [0, 90] deg");
      if (!(cohesion >= 0. && std::isfinite(cohesion)))
        throw InputError("cohesion = " + std::to_string(cohesion)
                         + " Pa must be >= 0");
      if (!(area > 0. && std::isfinite(area)))
        throw InputError("contact area = " + std::to_string(area)
                         + " m^2 must be > 0");
      if (!(weight > 0. && std::isfinite(weight)))
        throw InputError("block weight = " + std::to_string(weight)
                         + " N must be > 0");
    }

    /// Horizontal unit vector along @p azimuth_deg (clockwise from north).
    Eigen::Vector3d
    horizontal(const double azimuth_deg)
    {
      return Eigen::Vector3d(std::sin(azimuth_deg * degree),
                             std::cos(azimuth_deg * degree),
                             0.);
    }

    /// Bisection for the switch of a predicate between lo (false) and hi
    /// (true), down to @p tolerance or machine precision.
    template <typename Predicate>
    double
    bisect(double lo, double hi, const double tolerance, const Predicate &p)
    {
      while (hi - lo > tolerance)
        {
          const double mid = 0.5 * (lo + hi);
          if (mid <= lo || mid >= hi)
            break;
          (p(mid) ? hi : lo) = mid;
        }
      return 0.5 * (lo + hi);
    }
  } // namespace



  double
  plane_yield_acceleration(const double dip_deg,
                           const double phi_deg,
                           const double cohesion,
                           const double area,
                           const double weight)
  {
    check_plane_inputs(dip_deg, cohesion, area, weight);
    if (!(phi_deg >= 0. && phi_deg < 90.))
      throw InputError("friction angle = " + std::to_string(phi_deg)
                       + " deg is outside the valid range [0, 90) deg");
    const double a = dip_deg * degree, t = std::tan(phi_deg * degree);
    return (cohesion * area / weight + std::cos(a) * t - std::sin(a))
           / (std::cos(a) + std::sin(a) * t);
  }



  double
  wedge_yield_acceleration(const SlidingPlane &p1,
                           const SlidingPlane &p2,
                           const double        azimuth_deg,
                           const double        tolerance)
  {
    Sliding3dOptions options;
    options.wedge  = true;
    options.plane1 = p1;
    options.plane2 = p2;
    validate(options);
    if (!std::isfinite(azimuth_deg))
      throw InputError("load azimuth must be finite");
    if (!(tolerance > 0.))
      throw InputError("yield tolerance = " + std::to_string(tolerance)
                       + " g must be > 0");
    const Eigen::Vector3d h = horizontal(azimuth_deg);
    const Eigen::Vector3d z(0., 0., 1.);
    auto slides = [&](const double k) { return !is_stuck(options, k * h - z); };
    if (slides(0.))
      return 0.;
    // Scan for the first load that slides, then bisect.
    const unsigned int n = static_cast<unsigned int>(max_load / scan_step);
    for (unsigned int i = 1; i <= n; ++i)
      if (slides(i * scan_step))
        return bisect((i - 1) * scan_step, i * scan_step, tolerance, slides);
    return std::numeric_limits<double>::infinity();
  }



  double
  critical_friction_angle_plane(const double dip_deg,
                                const double k_g,
                                const double cohesion,
                                const double area,
                                const double weight)
  {
    check_plane_inputs(dip_deg, cohesion, area, weight);
    if (!std::isfinite(k_g))
      throw InputError("yield acceleration must be finite");
    if (cohesion == 0.)
      {
        const double phi = dip_deg + std::atan(k_g) / degree;
        if (!(phi >= 0. && phi < 90.))
          throw InputError("no friction angle in [0, 90) deg makes k = "
                           + std::to_string(k_g)
                           + " g critical on a plane"
                             " dipping "
                           + std::to_string(dip_deg) + " deg");
        return phi;
      }
    auto excess = [&](const double phi) {
      return plane_yield_acceleration(dip_deg, phi, cohesion, area, weight)
             - k_g;
    };
    const double f0 = excess(0.), f1 = excess(max_phi);
    if ((f0 > 0. && f1 > 0.) || (f0 < 0. && f1 < 0.))
      throw InputError("no friction angle in [0, 90) deg makes k = "
                       + std::to_string(k_g)
                       + " g critical for the given cohesion");
    const bool increasing = f1 >= f0;
    return bisect(0., max_phi, 0., [&](const double phi) {
      return (excess(phi) >= 0.) == increasing;
    });
  }



  double
  critical_friction_angle_wedge(const double dip1,
                                const double dipdir1,
                                const double dip2,
                                const double dipdir2,
                                const double azimuth_deg,
                                const double k_g)
  {
    if (!std::isfinite(k_g) || !std::isfinite(azimuth_deg))
      throw InputError("load and azimuth must be finite");
    Sliding3dOptions options;
    options.wedge                    = true;
    options.plane1.dip_deg           = dip1;
    options.plane1.dip_direction_deg = dipdir1;
    options.plane2.dip_deg           = dip2;
    options.plane2.dip_direction_deg = dipdir2;
    validate(options);
    const Eigen::Vector3d r
      = k_g * horizontal(azimuth_deg) - Eigen::Vector3d(0., 0., 1.);
    auto holds = [&](const double phi) {
      Sliding3dOptions o = options;
      o.plane1.friction  = FrictionLaw::coulomb_deg(phi);
      o.plane2.friction  = o.plane1.friction;
      return is_stuck(o, r);
    };
    if (holds(0.))
      return 0.;
    if (!holds(max_phi))
      throw InputError(
        "no friction angle in [0, 90) deg holds the wedge at k = "
        + std::to_string(k_g) + " g (azimuth " + std::to_string(azimuth_deg)
        + " deg)");
    return bisect(0., max_phi, 0., holds);
  }
} // namespace rockdda::analytical
