/**
 * @file
 * Time functions for heat boundary conditions: a sum of sinusoids, a
 * time series read from a CSV file, or a constant (deal.II-free).
 */
#ifndef ROCKDDA_THERMAL_BOUNDARY_DATA_H
#define ROCKDDA_THERMAL_BOUNDARY_DATA_H

#include <string>
#include <vector>

namespace rockdda::thermal
{
  /// One harmonic: amplitude sin(2 pi t / period + phase).
  struct Sinusoid
  {
    double amplitude = 0.; ///< K (or W/m^2 for a flux)
    double period    = 1.; ///< s
    double phase     = 0.; ///< rad
  };

  /**
   * Parse "A1, P1, phi1; A2, P2, phi2; ..." (amplitude, period in s, phase
   * in rad). Throws InputError naming @p where for a malformed entry or a
   * period <= 0.
   */
  std::vector<Sinusoid>
  parse_sinusoids(const std::string &text, const std::string &where);

  /// mean + sum of the sinusoids at time @p t (s).
  double
  evaluate(const std::vector<Sinusoid> &terms,
           const double                 mean,
           const double                 t);

  /**
   * A piecewise-linear time series (time in s, strictly increasing), e.g. a
   * measured air temperature record.
   */
  struct TimeSeries
  {
    std::vector<double> time;
    std::vector<double> value;
    std::string         file;

    /// Linear interpolation; throws std::runtime_error outside the record.
    double
    operator()(const double t) const;
  };

  /**
   * Read a time series: two columns (time, value) separated by commas or
   * blanks; '#' comments and blank lines are skipped, and the first data
   * line may be a header of names. Time is multiplied by @p time_unit (s per
   * unit, e.g. 86400 for days). A missing file, a non-numeric value, a wrong
   * number of columns or a time that does not increase throws InputError
   * giving the file and the line.
   */
  TimeSeries
  read_time_series(const std::string &file_name, const double time_unit = 1.);
} // namespace rockdda::thermal

#endif
