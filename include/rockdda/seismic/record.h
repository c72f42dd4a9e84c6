/**
 * @file
 * Acceleration records: reading, scaling and polarity.
 */
#ifndef ROCKDDA_SEISMIC_RECORD_H
#define ROCKDDA_SEISMIC_RECORD_H

#include <string>
#include <vector>

namespace rockdda::seismic
{
  /**
   * A uniformly sampled acceleration time history of one component, in units
   * of g. Sample i is at time i*dt. Plain data: solvers take it as it is.
   */
  struct Record
  {
    /// Name for reports (usually the file name).
    std::string name;
    /// Sampling interval (s), > 0.
    double dt = 0.;
    /// Samples (g).
    std::vector<double> acceleration;

    /// Time of the last sample (s).
    double
    duration() const;
    /// Largest |a| (g).
    double
    peak() const;
    /// Linear interpolation at time t (s); 0 before the start and after the
    /// end (the ground is at rest outside the record).
    double
    at(const double t) const;
  };

  /**
   * Read a record file. Two layouts are accepted:
   * - one value per line (acceleration), with @p dt (s) given by the caller;
   * - two columns per line: time (s) and acceleration; the time step is taken
   *   from the file and must be uniform (relative deviation < 1e-6).
   * Blank lines and lines starting with '#' are skipped. Values are multiplied
   * by @p to_g to convert them to g (1 for a file in g, 1/9.80665 for m/s^2).
   * Throws InputError naming the file and line for a malformed number, a
   * missing file, an empty record, a non-uniform time column, or dt <= 0.
   */
  Record
  read_record(const std::string &file_name,
              const double       dt,
              const double       to_g = 1.);

  /// Multiply every sample by @p factor.
  void
  scale(Record &record, const double factor);

  /// Scale linearly so that max |a| equals @p target_pga (g).
  void
  scale_to_pga(Record &record, const double target_pga);
} // namespace rockdda::seismic

#endif
