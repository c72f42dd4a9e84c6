/**
 * @file
 * The "Ground motion" parameter section: where an acceleration history comes
 * from and how it is processed before an analysis uses it.
 */
#ifndef ROCKDDA_SEISMIC_GROUND_MOTION_H
#define ROCKDDA_SEISMIC_GROUND_MOTION_H

#include <rockdda/seismic/attenuation.h>
#include <rockdda/seismic/processing.h>
#include <rockdda/seismic/record.h>

#include <string>
#include <vector>

namespace dealii
{
  class ParameterHandler;
}

namespace rockdda::seismic
{
  /**
   * A processed input motion, read from the "Ground motion" section: a record
   * file (SLAMMER one column with a given dt, time/acceleration columns, or
   * PEER AT2; in g, m/s^2 or cm/s^2) or a harmonic A sin(2 pi f t);
   * resampled, baseline-corrected and filtered as its "Processing"
   * subsection says; then scaled to a target PGA, by a factor or to the
   * BJF97 PGA of the "Attenuation" subsection's scenario; with the chosen
   * polarity. An optional vertical record (same units, format and time
   * step keys) gets the same processing and scaling factor, times
   * "Vertical scale"; it is positive upward and not inverted by the
   * polarity (used by the dda analysis).
   */
  struct GroundMotionInput
  {
    /// Which polarities to analyse.
    enum class Polarity
    {
      normal,
      inverted,
      both
    };

    /// Declare the section (once; later calls do nothing).
    static void
    declare_parameters(dealii::ParameterHandler &prm);

    /// Read the section and load and scale the record (normal polarity).
    /// Throws InputError naming @p prm_file, the key or the record line.
    void
    parse_parameters(dealii::ParameterHandler &prm,
                     const std::string        &prm_file);

    /**
     * The sign of the horizontal records for an analysis that runs one
     * simulation per parameter file (both DDA engines): +1 normal, -1
     * inverted. Polarity 'both' throws InputError naming @p prm_file, the
     * key and @p analysis.
     */
    double
    single_polarity_sign(const std::string &prm_file,
                         const std::string &analysis) const;

    /// The processed and scaled record in normal polarity (g).
    Record record;
    /// The record as read (converted to g), before processing and scaling.
    Record raw_record;
    /// The processing applied (resampling, baseline, filters).
    ProcessingOptions processing;
    /// What processing did (padding kept before the record, description).
    ProcessingReport processing_report;
    /// Scaling = BJF97: the scenario and its PGA (g); pga 0 otherwise.
    Bjf97Scenario scenario;
    double        attenuation_pga = 0.;
    /// Factor the processed record was multiplied by (1 if not scaled).
    double scale_factor = 1.;
    /// Warnings about the input (units, BJF97 range), also appended to the
    /// description.
    std::vector<std::string> warnings;
    /// Requested polarity.
    Polarity polarity = Polarity::normal;
    /// Vertical ground acceleration (g, positive upward), processed and
    /// scaled like the record (times vertical_scale); empty if no
    /// "Vertical record file" is given.
    Record vertical_record;
    /// Second horizontal ground acceleration (g), at 90 deg clockwise
    /// from the record's direction, processed and scaled like the record
    /// (normal polarity); empty if no "Transverse record file" is given.
    Record transverse_record;
    /// Multiplier of the vertical record after the common scaling (-).
    double vertical_scale = 1.;
    /// Harmonic source: amplitude (g) and angular frequency (rad/s); 0 for
    /// a record file.
    double harmonic_amplitude = 0., harmonic_omega = 0.;
    /// One line describing the input, for the log.
    std::string description;
  };
} // namespace rockdda::seismic

#endif
