/**
 * @file
 * Acceleration records: reading (SLAMMER one column, time/acceleration
 * columns, PEER NGA AT2; g, m/s^2 or cm/s^2), scaling and polarity.
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

  /// The unit of the acceleration values in a record file.
  enum class AccelerationUnit
  {
    g,
    metre_per_second2,
    centimetre_per_second2
  };

  /// Factor that converts a value in @p unit to g (g = 9.80665 m/s^2).
  double
  factor_to_g(const AccelerationUnit unit);

  /// The unit as written in parameter files: "g", "m/s^2" or "cm/s^2".
  std::string
  unit_name(const AccelerationUnit unit);

  /// The layout of a record file.
  enum class RecordFormat
  {
    /// PEER AT2 if the name ends in .AT2 or the first line names PEER;
    /// otherwise one column or columns by the first data line.
    automatic,
    /// One acceleration value per line (SLAMMER); dt given separately.
    one_column,
    /// Time (s) in the first column and acceleration in another; commas,
    /// semicolons or blanks between values; one header line allowed.
    columns,
    /// PEER NGA strong-motion record: four header lines (the third states
    /// the units, the fourth NPTS and DT), then the samples.
    peer_at2
  };

  /// How to read a record file.
  struct RecordFileOptions
  {
    RecordFormat     format = RecordFormat::automatic;
    AccelerationUnit unit   = AccelerationUnit::g;
    /// Sampling interval (s) of a one-column file.
    double dt = 0.;
    /// 1-based column of the acceleration in a columns file (>= 2).
    unsigned int column = 2;
  };

  /**
   * Read a record file in any of the formats of RecordFormat and convert it
   * to g. Throws InputError naming the file and the line for a malformed or
   * non-finite value (NaN, inf), a wrong AT2 header, an AT2 unit that
   * contradicts @p options.unit, a sample count that differs from NPTS, a
   * non-uniform time column, fewer than 2 samples, or dt <= 0.
   */
  Record
  read_record(const std::string &file_name, const RecordFileOptions &options);

  /**
   * The sampling interval (s) that the SLAMMER library's index records.csv
   * beside @p file_name (a header with the columns 'file' and 'dt_s') lists
   * for that file, and the index's line in @p line; 0 if there is no index
   * or it does not list the file. Throws InputError naming the index and
   * line for a dt_s that is not a number > 0.
   */
  double
  listed_time_step(const std::string &file_name, unsigned int &line);

  /**
   * Check that the peak of @p record (in g, read from @p file_name in
   * @p unit) is plausible: above 5 g no earthquake has been recorded (the
   * largest are about 4 g), so that is an InputError naming the file, the
   * key @p unit_key and the PGA in the other units. Returns a warning (empty
   * if none) for a peak below 1e-3 g, which is plausible only for a weak
   * motion or a record in g read as cm/s^2.
   */
  std::string
  check_units_plausible(const Record          &record,
                        const AccelerationUnit unit,
                        const std::string     &file_name,
                        const std::string     &unit_key);

  /// Multiply every sample by @p factor.
  void
  scale(Record &record, const double factor);

  /// Scale linearly so that max |a| equals @p target_pga (g).
  void
  scale_to_pga(Record &record, const double target_pga);
} // namespace rockdda::seismic

#endif
