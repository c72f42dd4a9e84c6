#include <rockdda/io/error.h>
#include <rockdda/io/parameters.h>
#include <rockdda/seismic/ground_motion.h>

#include <cmath>
#include <sstream>

namespace rockdda::seismic
{
  using dealii::Patterns::Bool;
  using dealii::Patterns::Double;
  using dealii::Patterns::Selection;

  void
  GroundMotionInput::declare_parameters(dealii::ParameterHandler &prm)
  {
    if (prm.subsection_path_exists({"Ground motion"}))
      return;
    prm.enter_subsection("Ground motion");
    io::declare(prm,
                "Source",
                "file",
                Selection("file|harmonic"),
                "-",
                "'file': an acceleration record file; 'harmonic': "
                "A sin(2 pi f t) with the amplitude and frequency below.");
    io::declare(prm,
                "Record file",
                "",
                dealii::Patterns::Anything(),
                "-",
                "Record file: one acceleration value per line (then 'Time "
                "step' gives dt), or two columns time (s) and acceleration. "
                "Relative to this parameter file; $VAR is expanded "
                "(e.g. $ROCKDDA_SHARED_DATA). Lines starting with # are "
                "skipped.");
    io::declare(prm,
                "Time step",
                "0.01",
                io::DoubleInterval::positive(),
                "s",
                "Sampling interval of a one-column record file, or of the "
                "harmonic input. Must be > 0.");
    io::declare(prm,
                "Units",
                "g",
                Selection("g|m/s^2"),
                "-",
                "Units of the acceleration values in the record file.");
    io::declare(prm,
                "Scaling",
                "none",
                Selection("none|target PGA|factor"),
                "-",
                "'target PGA': scale linearly so max |a| equals 'Target PGA'; "
                "'factor': multiply by 'Scale factor'.");
    io::declare(prm,
                "Target PGA",
                "0.2",
                io::DoubleInterval::positive(),
                "g",
                "Peak ground acceleration after scaling (Scaling = target "
                "PGA). Must be > 0.");
    io::declare(prm,
                "Scale factor",
                "1",
                Double(),
                "-",
                "Multiplier of the record (Scaling = factor).");
    io::declare(prm,
                "Polarity",
                "normal",
                Selection("normal|inverted|both"),
                "-",
                "'inverted' multiplies the record by -1; 'both' analyses "
                "both polarities (where the analysis supports it).");
    io::declare(prm,
                "Harmonic amplitude",
                "0.5",
                Double(0.),
                "g",
                "Amplitude A of the harmonic input.");
    io::declare(prm,
                "Harmonic frequency",
                "1",
                io::DoubleInterval::positive(),
                "Hz",
                "Frequency f of the harmonic input. Must be > 0.");
    io::declare(prm,
                "Duration",
                "10",
                io::DoubleInterval::positive(),
                "s",
                "Length of the harmonic input. Must be > 0.");
    prm.leave_subsection();
  }



  void
  GroundMotionInput::parse_parameters(dealii::ParameterHandler &prm,
                                      const std::string        &prm_file)
  {
    prm.enter_subsection("Ground motion");
    const std::string source = prm.get("Source");
    const double      dt     = prm.get_double("Time step");
    io::require(dt > 0., prm_file, "Ground motion/Time step", dt, "dt > 0 s");
    std::ostringstream d;
    if (source == "harmonic")
      {
        const double a = prm.get_double("Harmonic amplitude");
        const double f = prm.get_double("Harmonic frequency");
        const double T = prm.get_double("Duration");
        io::require(
          f > 0., prm_file, "Ground motion/Harmonic frequency", f, "f > 0 Hz");
        io::require(
          T > 0., prm_file, "Ground motion/Duration", T, "duration > 0 s");
        io::require(T / dt < 1e9,
                    prm_file,
                    "Ground motion/Time step",
                    dt,
                    "at most 1e9 samples (Duration/Time step)");
        harmonic_amplitude = a;
        harmonic_omega     = 2. * M_PI * f;
        record.name        = "harmonic";
        record.dt          = dt;
        const auto n       = static_cast<std::size_t>(std::llround(T / dt)) + 1;
        record.acceleration.resize(n);
        for (std::size_t i = 0; i < n; ++i)
          record.acceleration[i] = a * std::sin(harmonic_omega * i * dt);
        d << "harmonic " << a << " g x sin(2 pi " << f << " Hz t), " << T
          << " s, dt = " << dt << " s";
      }
    else
      {
        const std::string name = prm.get("Record file");
        if (name.empty())
          throw InputError(prm_file
                           + ": key 'Ground motion/Record file' is empty; give "
                             "a record file (or set Source = harmonic)");
        const std::string file
          = io::resolve_path(name, prm_file, "Ground motion/Record file");
        const double to_g = prm.get("Units") == "g" ? 1. : 1. / 9.80665;
        record            = read_record(file, dt, to_g);
        d << record.name << " (" << record.acceleration.size()
          << " samples, dt = " << record.dt << " s, PGA " << record.peak()
          << " g)";
      }

    const std::string scaling = prm.get("Scaling");
    if (scaling == "target PGA")
      {
        const double pga = prm.get_double("Target PGA");
        io::require(
          pga > 0., prm_file, "Ground motion/Target PGA", pga, "PGA > 0 g");
        scale_to_pga(record, pga);
        d << ", scaled to PGA " << pga << " g";
        harmonic_amplitude = record.peak();
      }
    else if (scaling == "factor")
      {
        const double f = prm.get_double("Scale factor");
        scale(record, f);
        harmonic_amplitude *= f;
        d << ", scaled by " << f;
      }
    const std::string p = prm.get("Polarity");
    polarity            = p == "normal"     ? Polarity::normal
                          : p == "inverted" ? Polarity::inverted
                                            : Polarity::both;
    d << ", polarity " << p;
    description = d.str();
    prm.leave_subsection();
  }
} // namespace rockdda::seismic
