/**
 * @file
 * Peak ground acceleration of an earthquake scenario by the attenuation
 * relation of Boore, Joyner & Fumal (1997), and scaling a record to it.
 */
#ifndef ROCKDDA_SEISMIC_ATTENUATION_H
#define ROCKDDA_SEISMIC_ATTENUATION_H

#include <string>
#include <vector>

namespace rockdda::seismic
{
  /// Fault mechanism of a BJF97 scenario (it sets the coefficient b1).
  enum class FaultMechanism
  {
    strike_slip,
    reverse,
    unspecified
  };

  /// An earthquake scenario for BJF97.
  struct Bjf97Scenario
  {
    /// Moment magnitude (-); the relation is fitted for 4 <= M <= 8.
    double magnitude = 6.;
    /// Joyner-Boore distance Rjb (km): to the surface projection of the
    /// rupture; fitted for Rjb <= 80 km.
    double distance_km = 10.;
    /// Average shear-wave velocity of the top 30 m (m/s), > 0.
    double         vs30      = 360.;
    FaultMechanism mechanism = FaultMechanism::unspecified;
    /// Number of standard deviations of ln Y above the median (0: median).
    double n_sigma = 0.;
  };

  /// Standard deviation of ln PGA in BJF97 (-).
  constexpr double bjf97_sigma_ln_pga = 0.495;

  /**
   * PGA (g) of the horizontal component for @p scenario:
   * ln Y = b1 + b2 (M - 6) + b3 (M - 6)^2 + b5 ln r + bV ln(Vs30 / VA)
   *        + n_sigma sigma_lnY,  r = sqrt(Rjb^2 + h^2),
   * with the coefficients of Boore, Joyner & Fumal (1997) for PGA. Throws
   * std::invalid_argument for a non-finite value, Rjb < 0 or Vs30 <= 0.
   */
  double
  bjf97_pga(const Bjf97Scenario &scenario);

  /**
   * Warnings for a scenario outside the data BJF97 was fitted to (M outside
   * 4-8, Rjb > 80 km), each naming the quantity, its value and the range.
   */
  std::vector<std::string>
  bjf97_warnings(const Bjf97Scenario &scenario);
} // namespace rockdda::seismic

#endif
