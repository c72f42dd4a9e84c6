/**
 * @file
 * The "Ground motion" parameter section: where an acceleration history comes
 * from and how it is processed before an analysis uses it.
 */
#ifndef ROCKDDA_SEISMIC_GROUND_MOTION_H
#define ROCKDDA_SEISMIC_GROUND_MOTION_H

#include <rockdda/seismic/record.h>

#include <string>

namespace dealii
{
  class ParameterHandler;
}

namespace rockdda::seismic
{
  /**
   * A processed input motion, read from the "Ground motion" section: a record
   * file (one column in g with a given dt, or time/acceleration columns) or a
   * harmonic A sin(2 pi f t), scaled to a target PGA or by a factor, with the
   * chosen polarity.
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

    /// The processed record in normal polarity (g).
    Record record;
    /// Requested polarity.
    Polarity polarity = Polarity::normal;
    /// Harmonic source: amplitude (g) and angular frequency (rad/s); 0 for
    /// a record file.
    double harmonic_amplitude = 0., harmonic_omega = 0.;
    /// One line describing the input, for the log.
    std::string description;
  };
} // namespace rockdda::seismic

#endif
