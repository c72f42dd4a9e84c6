/**
 * @file
 * The analysis types of the 3D DDA subsystem as the driver sees them.
 */
#ifndef ROCKDDA_DDA3D_ANALYSES_H
#define ROCKDDA_DDA3D_ANALYSES_H

#include <rockdda/dda3d/engine.h>
#include <rockdda/io/analysis.h>

#include <functional>
#include <memory>
#include <string>
#include <vector>

namespace dealii
{
  class ParameterHandler;
}

namespace rockdda::dda3d
{
  /// The analyses of this subsystem ("dda3d"), for io::all_analyses().
  std::vector<std::unique_ptr<io::Analysis>>
  make_analyses();

  /**
   * The seismic input of a 3D DDA run as the engine takes it: the ground
   * acceleration a_g(t) (m/s^2) for the loading mode and the ground
   * displacement u_g(t) (m, from rest at t = 0) for the displacement mode
   * (one of them set), and a line for the log.
   */
  struct SeismicInput3d
  {
    enum class Mode
    {
      none,
      loading,
      displacement
    };
    Mode                         mode = Mode::none;
    std::function<Point(double)> acceleration, displacement;
    std::string                  description;
  };

  /**
   * Read the seismic keys of the "DDA 3d" section (and the "Ground motion"
   * section if the source is a record or a harmonic): the three ground
   * acceleration components (g) from expressions of t or from the record
   * (horizontal along the azimuth), the transverse record (90 deg
   * clockwise) and the vertical record (upward), processed and scaled as
   * "Ground motion" says. The loading mode evaluates the expressions at
   * the time asked; the displacement mode integrates the records exactly
   * (piecewise linear, dda::GroundMotionIntegral) and the expressions
   * sampled at @p time_step / 20. Throws InputError naming @p prm_file and
   * the key.
   */
  SeismicInput3d
  parse_seismic_input(dealii::ParameterHandler &prm,
                      const std::string        &prm_file,
                      const double              end_time,
                      const double              time_step,
                      const double              g);
} // namespace rockdda::dda3d

#endif
