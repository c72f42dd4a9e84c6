#include <rockdda/io/error.h>
#include <rockdda/io/output.h>
#include <rockdda/io/parameters.h>
#include <rockdda/seismic/ground_motion.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <sstream>
#include <utility>

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
                Selection("g|m/s^2|cm/s^2"),
                "-",
                "Units of the acceleration values in the record file (g = "
                "9.80665 m/s^2). A PEER AT2 file's stated units must agree. "
                "A record whose PGA exceeds 5 g in these units is rejected "
                "as implausible (e.g. cm/s^2 read as g).");
    io::declare(prm,
                "Record format",
                "auto",
                Selection("auto|one column|columns|PEER AT2"),
                "-",
                "'one column': one acceleration value per line (SLAMMER; "
                "'Time step' gives dt); 'columns': time (s) in the first "
                "column and the acceleration in 'Acceleration column', "
                "separated by commas, semicolons or blanks, one header line "
                "allowed; 'PEER AT2': the PEER NGA format (4 header lines: "
                "title, event, units, 'NPTS= N, DT= dt SEC'); 'auto': AT2 "
                "for a .AT2 name or a first line naming PEER, else by the "
                "number of values on the first data line.");
    io::declare(prm,
                "Acceleration column",
                "2",
                dealii::Patterns::Integer(2, 1000),
                "-",
                "Column (counted from 1) of the acceleration in a 'columns' "
                "record file, 2 to 1000; column 1 is the time.");
    io::declare(prm,
                "Vertical record file",
                "",
                dealii::Patterns::Anything(),
                "-",
                "Optional vertical acceleration record (positive upward), "
                "read with the same Units, Record format, Time step and "
                "Acceleration column as the record; it gets the same "
                "Processing and the same scaling factor (times 'Vertical "
                "scale'), and the Polarity does not invert it. Empty = no "
                "vertical motion. Used by the dda analysis (Seismic input "
                "inertial or displacement); other analyses ignore it.");
    io::declare(prm,
                "Transverse record file",
                "",
                dealii::Patterns::Anything(),
                "-",
                "Optional second horizontal acceleration record, at 90 deg "
                "clockwise from the record's direction (seen from above), "
                "read, processed, scaled and inverted by the Polarity like "
                "the record. Empty = none. Used by the dda3d analysis "
                "(three-component input); other analyses ignore it.");
    io::declare(prm,
                "Vertical scale",
                "1",
                Double(-10., 10.),
                "-",
                "Multiplier of the vertical record after the common "
                "scaling, in [-10, 10]; -1 for a record that is positive "
                "downward.");
    io::declare(prm,
                "Scaling",
                "none",
                Selection("none|target PGA|factor|BJF97"),
                "-",
                "Applied after the Processing subsection. 'target PGA': scale "
                "linearly so max |a| equals 'Target PGA'; 'factor': multiply "
                "by 'Scale factor'; 'BJF97': scale so max |a| equals the PGA "
                "of Boore, Joyner & Fumal (1997) for the scenario of the "
                "Attenuation subsection.");
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
                "Harmonic ramp duration",
                "0",
                Double(0.),
                "s",
                "The harmonic amplitude grows linearly from 0 at t = 0 to A "
                "at this time (a shaking table's ramp, thesis Sec. 4.6: 5 "
                "s); >= 0, 0 = no ramp.");
    io::declare(prm,
                "Duration",
                "10",
                io::DoubleInterval::positive(),
                "s",
                "Length of the harmonic input. Must be > 0.");

    prm.enter_subsection("Processing");
    io::declare(prm,
                "Resampling time step",
                "0",
                Double(0.),
                "s",
                "Resample the record to this step first (>= 0; 0 keeps the "
                "record's step).");
    io::declare(prm,
                "Resampling method",
                "Fourier",
                Selection("Fourier|linear"),
                "-",
                "'Fourier': band-limited (FFTW), exact for a record with no "
                "energy above the lower Nyquist frequency, an ideal "
                "anti-alias filter when the step grows; needs the two steps "
                "in a ratio of integers up to 1000. 'linear': linear "
                "interpolation (aliases when the step grows).");
    io::declare(prm,
                "Baseline correction",
                "none",
                Selection("none|mean|linear|quadratic"),
                "-",
                "Remove a polynomial of degree 0 ('mean'), 1 or 2 from the "
                "acceleration: the one whose integral best fits the "
                "velocity in least squares while making the final velocity "
                "zero. Applied after resampling, before filtering.");
    io::declare(prm,
                "High-pass corner",
                "0",
                Double(0.),
                "Hz",
                "Corner frequency fc of the acausal (zero-phase) Butterworth "
                "high-pass, gain 1/sqrt(1 + (fc/f)^(2n)) (-3 dB at fc); 0 = "
                "no high-pass; >= 0.");
    io::declare(prm,
                "Low-pass corner",
                "0",
                Double(0.),
                "Hz",
                "Corner frequency fc of the acausal Butterworth low-pass, "
                "gain 1/sqrt(1 + (f/fc)^(2n)); 0 = no low-pass; >= 0. Must "
                "lie below the Nyquist frequency 1/(2 dt).");
    io::declare(prm,
                "Filter order",
                "4",
                dealii::Patterns::Integer(1, 12),
                "-",
                "Order n of the Butterworth gains (1 to 12). Zero padding of "
                "0.75 n/fc (fc the high-pass corner if any) is added at "
                "each end before filtering (Boore & Bommer 2005).");
    io::declare(prm,
                "Keep padding",
                "true",
                Bool(),
                "-",
                "Keep the zero pads (with the filter transients in them) in "
                "the filtered record, as Boore & Bommer (2005) recommend so "
                "that its velocity and displacement are consistent; false "
                "cuts the record back to its original span.");
    prm.leave_subsection();

    prm.enter_subsection("Attenuation");
    io::declare(prm,
                "Magnitude",
                "6",
                Double(0., 10.),
                "-",
                "Moment magnitude M of the BJF97 scenario, in [0, 10]; "
                "BJF97 was fitted to M 4-8 (a warning outside).");
    io::declare(prm,
                "Joyner-Boore distance",
                "10000",
                Double(0., 1e6),
                "m",
                "Distance Rjb to the surface projection of the rupture, in "
                "[0, 1e6]; BJF97 was fitted to Rjb up to 80000 m (a warning "
                "beyond).");
    io::declare(prm,
                "Vs30",
                "360",
                io::DoubleInterval::positive(),
                "m/s",
                "Average shear-wave velocity of the top 30 m at the site. "
                "Must be > 0.");
    io::declare(prm,
                "Mechanism",
                "unspecified",
                Selection("strike-slip|reverse|unspecified"),
                "-",
                "Fault mechanism; sets b1 of BJF97 (-0.313, -0.117, -0.242).");
    io::declare(prm,
                "Number of sigma",
                "0",
                Double(-5., 5.),
                "-",
                "PGA at ln Y + n sigma_lnY (sigma_lnY = 0.495); 0 is the "
                "median; in [-5, 5].");
    prm.leave_subsection();
    prm.leave_subsection();
  }



  double
  GroundMotionInput::single_polarity_sign(const std::string &prm_file,
                                          const std::string &analysis) const
  {
    if (polarity == Polarity::both)
      throw InputError(prm_file
                       + ": key 'Ground motion/Polarity' = both is not "
                         "supported by "
                       + analysis
                       + " (one simulation per file); valid: normal or "
                         "inverted");
    return polarity == Polarity::inverted ? -1. : 1.;
  }



  void
  GroundMotionInput::parse_parameters(dealii::ParameterHandler &prm,
                                      const std::string        &prm_file)
  {
    prm.enter_subsection("Ground motion");
    const std::string source = prm.get("Source");
    const double      dt     = prm.get_double("Time step");
    io::require(dt > 0., prm_file, "Ground motion/Time step", dt, "dt > 0 s");
    warnings.clear();
    // Read a record file with the Units, Record format, Time step and
    // Acceleration column keys; @p key names the file's key in messages.
    const auto read_file = [&](const std::string &name,
                               const std::string &key) {
      const std::string file   = io::resolve_path(name, prm_file, key);
      const std::string units  = prm.get("Units");
      const std::string format = prm.get("Record format");
      RecordFileOptions options;
      options.unit   = units == "g" ? AccelerationUnit::g
                       : units == "m/s^2"
                         ? AccelerationUnit::metre_per_second2
                         : AccelerationUnit::centimetre_per_second2;
      options.format = format == "one column" ? RecordFormat::one_column
                       : format == "columns"  ? RecordFormat::columns
                       : format == "PEER AT2" ? RecordFormat::peer_at2
                                              : RecordFormat::automatic;
      options.dt     = dt;
      options.column = prm.get_integer("Acceleration column");
      Record r       = read_record(file, options);
      // A SLAMMER library file: its step is listed in records.csv.
      unsigned int listed_line = 0;
      const double listed      = listed_time_step(file, listed_line);
      if (listed > 0. && std::abs(listed - r.dt) > 1e-9 * listed)
        throw InputError(
          prm_file + ": key 'Ground motion/Time step' = "
          + io::format_number(r.dt, 8) + " s, but " + r.name
          + " is listed with dt = " + io::format_number(listed, 8) + " s in "
          + (std::filesystem::path(file).parent_path() / "records.csv").string()
          + ":" + std::to_string(listed_line)
          + "; set Time step = " + io::format_number(listed, 8));
      const std::string w
        = check_units_plausible(r, options.unit, file, "Ground motion/Units");
      if (!w.empty())
        warnings.push_back(w);
      return r;
    };
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
        const double ramp  = prm.get_double("Harmonic ramp duration");
        harmonic_amplitude = a;
        harmonic_omega     = 2. * M_PI * f;
        record.name        = "harmonic";
        record.dt          = dt;
        const auto n       = static_cast<std::size_t>(std::llround(T / dt)) + 1;
        record.acceleration.resize(n);
        for (std::size_t i = 0; i < n; ++i)
          record.acceleration[i]
            = a * std::sin(harmonic_omega * i * dt)
              * (ramp > 0. ? std::min(1., i * dt / ramp) : 1.);
        d << "harmonic " << a << " g x sin(2 pi " << f << " Hz t), " << T
          << " s, dt = " << dt << " s";
        if (ramp > 0.)
          {
            // The closed forms take a steady harmonic.
            d << ", linear ramp over " << ramp << " s";
            harmonic_omega = 0.;
          }
      }
    else
      {
        const std::string name = prm.get("Record file");
        if (name.empty())
          throw InputError(prm_file
                           + ": key 'Ground motion/Record file' is empty; give "
                             "a record file (or set Source = harmonic)");
        record = read_file(name, "Ground motion/Record file");
        d << record.name << " (" << record.acceleration.size()
          << " samples, dt = " << record.dt << " s, PGA " << record.peak()
          << " g)";
      }
    const std::string vertical_name = prm.get("Vertical record file");
    vertical_scale                  = prm.get_double("Vertical scale");
    vertical_record                 = Record();
    if (!vertical_name.empty())
      {
        vertical_record
          = read_file(vertical_name, "Ground motion/Vertical record file");
        d << "; vertical " << vertical_record.name << " ("
          << vertical_record.acceleration.size()
          << " samples, dt = " << vertical_record.dt << " s, PGA "
          << vertical_record.peak() << " g)";
      }
    const std::string transverse_name = prm.get("Transverse record file");
    transverse_record                 = Record();
    if (!transverse_name.empty())
      {
        transverse_record
          = read_file(transverse_name, "Ground motion/Transverse record file");
        d << "; transverse " << transverse_record.name << " ("
          << transverse_record.acceleration.size()
          << " samples, dt = " << transverse_record.dt << " s, PGA "
          << transverse_record.peak() << " g)";
      }
    raw_record = record;

    // Processing.
    prm.enter_subsection("Processing");
    const std::string baseline = prm.get("Baseline correction");
    processing.resample_dt     = prm.get_double("Resampling time step");
    processing.method          = prm.get("Resampling method") == "Fourier"
                                   ? ResampleMethod::fourier
                                   : ResampleMethod::linear;
    processing.baseline_degree = baseline == "none"     ? -1
                                 : baseline == "mean"   ? 0
                                 : baseline == "linear" ? 1
                                                        : 2;
    processing.high_pass       = prm.get_double("High-pass corner");
    processing.low_pass        = prm.get_double("Low-pass corner");
    processing.order           = prm.get_integer("Filter order");
    processing.keep_padding    = prm.get_bool("Keep padding");
    prm.leave_subsection();
    const double step
      = processing.resample_dt > 0. ? processing.resample_dt : record.dt;
    const double nyquist = 0.5 / step;
    io::require(processing.low_pass < nyquist,
                prm_file,
                "Ground motion/Processing/Low-pass corner",
                processing.low_pass,
                "0 <= fc < " + io::format_number(nyquist, 6)
                  + " Hz (the Nyquist frequency of the record)");
    io::require(processing.high_pass < nyquist,
                prm_file,
                "Ground motion/Processing/High-pass corner",
                processing.high_pass,
                "0 <= fc < " + io::format_number(nyquist, 6)
                  + " Hz (the Nyquist frequency of the record)");
    io::require(processing.low_pass == 0.
                  || processing.high_pass < processing.low_pass,
                prm_file,
                "Ground motion/Processing/High-pass corner",
                processing.high_pass,
                "below the low-pass corner "
                  + io::format_number(processing.low_pass, 6) + " Hz");
    const bool processed
      = processing.resample_dt > 0. || processing.baseline_degree >= 0
        || processing.high_pass > 0. || processing.low_pass > 0.;
    if (processed)
      {
        io::with_parameter_file(prm_file, [&]() {
          record = process(record, processing, &processing_report);
        });
        d << ", " << processing_report.description;
        for (auto [other, what] :
             {std::make_pair(&vertical_record, "vertical"),
              std::make_pair(&transverse_record, "transverse")})
          if (!other->acceleration.empty())
            {
              const double other_step = processing.resample_dt > 0.
                                          ? processing.resample_dt
                                          : other->dt;
              io::require(processing.low_pass < 0.5 / other_step
                            && processing.high_pass < 0.5 / other_step,
                          prm_file,
                          "Ground motion/Processing/Low-pass corner",
                          std::max(processing.low_pass, processing.high_pass),
                          "corners below "
                            + io::format_number(0.5 / other_step, 6)
                            + " Hz (the Nyquist frequency of the " + what
                            + " record)");
              io::with_parameter_file(prm_file, [&]() {
                *other = process(*other, processing);
              });
            }
        // A processed harmonic is no longer the closed form's input.
        harmonic_omega = 0.;
      }

    // Scaling.
    const std::string scaling = prm.get("Scaling");
    scale_factor              = 1.;
    attenuation_pga           = 0.;
    if (scaling == "target PGA")
      {
        const double pga = prm.get_double("Target PGA");
        io::require(
          pga > 0., prm_file, "Ground motion/Target PGA", pga, "PGA > 0 g");
        scale_factor = pga / record.peak();
        scale_to_pga(record, pga);
        d << ", scaled to PGA " << pga << " g";
        harmonic_amplitude = record.peak();
      }
    else if (scaling == "factor")
      {
        const double f = prm.get_double("Scale factor");
        scale(record, f);
        scale_factor = f;
        harmonic_amplitude *= f;
        d << ", scaled by " << f;
      }
    else if (scaling == "BJF97")
      {
        prm.enter_subsection("Attenuation");
        scenario.magnitude     = prm.get_double("Magnitude");
        scenario.distance_km   = 1e-3 * prm.get_double("Joyner-Boore distance");
        scenario.vs30          = prm.get_double("Vs30");
        const std::string mech = prm.get("Mechanism");
        scenario.mechanism = mech == "strike-slip" ? FaultMechanism::strike_slip
                             : mech == "reverse"   ? FaultMechanism::reverse
                                                 : FaultMechanism::unspecified;
        scenario.n_sigma   = prm.get_double("Number of sigma");
        prm.leave_subsection();
        io::require(scenario.vs30 > 0.,
                    prm_file,
                    "Ground motion/Attenuation/Vs30",
                    scenario.vs30,
                    "Vs30 > 0 m/s");
        for (const auto &w : bjf97_warnings(scenario))
          warnings.push_back(w
                             + " (keys 'Ground motion/Attenuation/Magnitude', "
                               "'Joyner-Boore distance')");
        attenuation_pga = bjf97_pga(scenario);
        if (!(record.peak() > 0.))
          throw InputError(prm_file + ": the record " + record.name
                           + " has a zero peak and cannot be scaled to the "
                             "BJF97 PGA (key 'Ground motion/Scaling')");
        scale_factor = attenuation_pga / record.peak();
        scale_to_pga(record, attenuation_pga);
        harmonic_amplitude = record.peak();
        d << ", scaled to the BJF97 PGA "
          << io::format_number(attenuation_pga, 7) << " g (M "
          << scenario.magnitude << ", Rjb " << scenario.distance_km
          << " km, Vs30 " << scenario.vs30 << " m/s, " << mech << ", "
          << scenario.n_sigma << " sigma)";
      }
    if (!vertical_record.acceleration.empty())
      {
        scale(vertical_record, scale_factor * vertical_scale);
        d << "; vertical x " << scale_factor * vertical_scale << ", PGA "
          << io::format_number(vertical_record.peak(), 6) << " g";
      }
    if (!transverse_record.acceleration.empty())
      scale(transverse_record, scale_factor);
    const std::string p = prm.get("Polarity");
    polarity            = p == "normal"     ? Polarity::normal
                          : p == "inverted" ? Polarity::inverted
                                            : Polarity::both;
    d << ", polarity " << p;
    for (const auto &w : warnings)
      d << "; warning: " << w;
    description = d.str();
    prm.leave_subsection();
  }
} // namespace rockdda::seismic
