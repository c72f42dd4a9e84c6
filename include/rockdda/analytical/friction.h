/**
 * @file
 * Friction coefficient laws shared by the sliding-block analyses.
 */
#ifndef ROCKDDA_ANALYTICAL_FRICTION_H
#define ROCKDDA_ANALYTICAL_FRICTION_H

#include <algorithm>
#include <cmath>

namespace rockdda::analytical
{
  /**
   * The steady-state velocity-dependent friction coefficient (Dieterich
   * 1979; Ruina 1983; thesis Eq. 2.3 and Sec. 4.7.3, 4.8):
   *   mu(V) = mu0 + (A - B) ln(max(|V|, V_min) / V0),  clamped to >= 0,
   * with @p mu0 the coefficient at the reference slip rate @p v0 (m/s, > 0),
   * @p a_minus_b = A - B (-; < 0 velocity weakening), @p v_min the velocity
   * floor (m/s, > 0; the logarithm diverges at rest) and @p v the slip rate
   * (m/s, either sign). The one law of the analytical sliding solutions
   * (FrictionLaw) and of both DDA engines' contacts
   * (dda::friction_coefficient()).
   */
  inline double
  steady_state_friction(const double mu0,
                        const double a_minus_b,
                        const double v0,
                        const double v_min,
                        const double v)
  {
    const double speed = std::max(std::abs(v), v_min);
    return std::max(0., mu0 + a_minus_b * std::log(speed / v0));
  }

  /**
   * Friction coefficient of an interface as a function of slip rate.
   *
   * - Coulomb: mu = tan(phi), constant.
   * - Steady-state rate dependence (Dieterich 1979; Ruina 1983; thesis
   *   Eq. 2.3): mu(V) = mu0 + (A - B) ln(V / V0).
   *
   * The logarithm diverges at V = 0, so the law is evaluated at
   * max(|V|, v_cutoff): below the cutoff velocity (and at rest, for the
   * stick test) the friction is mu(v_cutoff). The result is clipped at 0 from
   * below, so extreme weakening never yields negative friction.
   */
  struct FrictionLaw
  {
    /// Which law.
    enum class Type
    {
      coulomb,
      steady_state
    };
    Type type = Type::coulomb;
    /// Reference friction coefficient mu0 (= tan(phi) for Coulomb) (-).
    double mu0 = 0.6;
    /// Steady-state velocity dependence A - B (-); < 0 is velocity weakening.
    double a_minus_b = 0.;
    /// Reference slip rate V0 (m/s), > 0.
    double v0 = 1e-6;
    /// Velocity below which mu is held at mu(v_cutoff) (m/s), > 0.
    double v_cutoff = 1e-6;

    /// A Coulomb law with friction angle @p phi_deg (degrees).
    static FrictionLaw
    coulomb_deg(const double phi_deg);

    /// Friction coefficient at slip rate @p v (m/s); v may be negative.
    double
    coefficient(const double v) const;

    /// Friction coefficient at rest (static check).
    double
    static_coefficient() const
    {
      return coefficient(0.);
    }
  };
} // namespace rockdda::analytical

#endif
