/**
 * @file
 * Ground-motion intensity measures of a record: peaks, Arias intensity,
 * significant duration, and the integrated velocity and displacement.
 */
#ifndef ROCKDDA_SEISMIC_INTENSITY_H
#define ROCKDDA_SEISMIC_INTENSITY_H

#include <rockdda/seismic/record.h>

#include <vector>

namespace rockdda::seismic
{
  /// Ground velocity (m/s) and displacement (m) at the samples of a record.
  struct IntegratedMotion
  {
    std::vector<double> velocity, displacement;
  };

  /**
   * Integrate the acceleration (g, x 9.80665 m/s^2) twice from rest with the
   * trapezoidal rule (exact for the piecewise-linear record; the
   * displacement is exact for piecewise-linear velocity).
   */
  IntegratedMotion
  integrate(const Record &record);

  /// Intensity measures of one record.
  struct IntensityMeasures
  {
    /// Peak |a| (g), |v| (m/s), |d| (m).
    double pga = 0., pgv = 0., pgd = 0.;
    /// Arias intensity pi/(2g) int a^2 dt (m/s) (Arias 1970).
    double arias = 0.;
    /// Times (s) at which 5 % and 95 % of the Arias intensity is reached
    /// (linear within a step) and D5-95 = t95 - t5 (Trifunac & Brady 1975).
    double t5 = 0., t95 = 0., d5_95 = 0.;
    /// Drift: velocity (m/s) and displacement (m) at the last sample.
    double final_velocity = 0., final_displacement = 0.;
  };

  /// The intensity measures of @p record.
  IntensityMeasures
  intensity_measures(const Record &record);
} // namespace rockdda::seismic

#endif
