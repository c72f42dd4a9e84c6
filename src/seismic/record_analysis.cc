/**
 * @file
 * Analysis type "record": read a record in its units, process and scale it
 * as the "Ground motion" section says, and write its time series, Fourier
 * and response spectra and intensity measures before and after processing.
 */
#include <rockdda/io/error.h>
#include <rockdda/io/parameters.h>
#include <rockdda/io/plot.h>
#include <rockdda/seismic/analyses.h>
#include <rockdda/seismic/ground_motion.h>
#include <rockdda/seismic/intensity.h>
#include <rockdda/seismic/spectra.h>

#include <algorithm>
#include <chrono>
#include <cmath>

namespace rockdda::seismic
{
  namespace
  {
    using dealii::Patterns::Integer;

    /// The "record" analysis.
    class RecordAnalysis : public io::Analysis
    {
    public:
      std::string
      name() const override
      {
        return "record";
      }

      std::string
      description() const override
      {
        return "read, process (baseline, acausal Butterworth filters, "
               "resampling) and scale (BJF97) an acceleration record; its "
               "intensity measures, Fourier and response spectra";
      }

      void
      declare_parameters(dealii::ParameterHandler &prm) const override
      {
        prm.enter_subsection("Record");
        io::declare(prm,
                    "Minimum period",
                    "0.01",
                    io::DoubleInterval::positive(),
                    "s",
                    "Shortest period of the response spectrum. Must be > 0.");
        io::declare(prm,
                    "Maximum period",
                    "10",
                    io::DoubleInterval::positive(),
                    "s",
                    "Longest period of the response spectrum (at least the "
                    "shortest). Must be > 0.");
        io::declare(prm,
                    "Number of periods",
                    "100",
                    Integer(2, 100000),
                    "-",
                    "Periods of the response spectrum, evenly spaced in "
                    "log T (2 to 100000).");
        io::declare(prm,
                    "Damping ratio",
                    "0.05",
                    io::DoubleInterval::right_open(0., 1.),
                    "-",
                    "Damping ratio zeta of the oscillators, 0 <= zeta < 1 "
                    "(0.05: the usual 5 %).");
        io::declare(prm,
                    "Spectrum subdivisions",
                    "0",
                    Integer(0, 1000),
                    "-",
                    "Sub-steps per sample interval of the oscillator "
                    "recursion (0 to 1000); 0: automatic, at least 20 "
                    "points per oscillator period. The recursion is exact "
                    "for the piecewise-linear record; sub-steps only locate "
                    "the peak between samples (benchmarks/seismic-chain has "
                    "the error against cost).");
        io::declare(prm,
                    "Plot",
                    "true",
                    dealii::Patterns::Bool(),
                    "-",
                    "Draw record.png with scripts/plot_record.py "
                    "(python3-matplotlib).");
        prm.leave_subsection();
      }

      void
      parse_parameters(dealii::ParameterHandler &prm,
                       const std::string        &prm_file) override
      {
        motion.parse_parameters(prm, prm_file);
        prm.enter_subsection("Record");
        const double first = prm.get_double("Minimum period");
        const double last  = prm.get_double("Maximum period");
        const auto   n     = prm.get_integer("Number of periods");
        damping            = prm.get_double("Damping ratio");
        subdivisions       = prm.get_integer("Spectrum subdivisions");
        plot               = prm.get_bool("Plot");
        prm.leave_subsection();
        io::require(last >= first,
                    prm_file,
                    "Record/Maximum period",
                    last,
                    ">= Minimum period " + io::format_number(first, 6) + " s");
        periods = log_spaced_periods(first, last, n);
      }

      void
      run(io::RunContext &context) override
      {
        auto &log = context.log;
        log.line("input motion: " + motion.description);
        for (const auto &w : motion.warnings)
          log.line("warning: " + w);
        Record unprocessed = motion.raw_record;
        scale(unprocessed, motion.scale_factor);
        unprocessed.name        = motion.raw_record.name + " (unprocessed)";
        const Record &processed = motion.record;
        const double  padding   = motion.processing_report.padding;

        const auto start = std::chrono::steady_clock::now();
        // Times of the processed record count from the original start.
        auto im = intensity_measures(processed);
        im.t5 -= padding;
        im.t95 -= padding;
        const auto im0 = intensity_measures(unprocessed);
        const auto rs
          = response_spectrum(processed, periods, damping, subdivisions);
        const auto rs0
          = response_spectrum(unprocessed, periods, damping, subdivisions);
        const auto   fs      = fourier_amplitude_spectrum(processed);
        const auto   fs0     = fourier_amplitude_spectrum(unprocessed);
        const double seconds = std::chrono::duration<double>(
                                 std::chrono::steady_clock::now() - start)
                                 .count();

        // Time series, the processed one shifted so that the original first
        // sample is at t = 0 (the kept pads lie before 0 and after the end).
        const auto write_series
          = [&](const std::string &file, const Record &r, const double t0) {
              const auto m = integrate(r);
              io::Table  t;
              t.add_column("time", "s");
              t.add_column("acceleration", "g");
              t.add_column("velocity", "m/s");
              t.add_column("displacement", "m");
              for (std::size_t i = 0; i < r.acceleration.size(); ++i)
                t.add_row({i * r.dt - t0,
                           r.acceleration[i],
                           m.velocity[i],
                           m.displacement[i]});
              context.output.write(file, t.csv());
            };
        write_series("statistics.csv", processed, padding);
        write_series("unprocessed.csv", unprocessed, 0.);

        // Fourier spectra on the processed record's frequencies (the
        // unprocessed one interpolated linearly), up to the lower Nyquist.
        {
          io::Table t;
          t.add_column("frequency", "Hz");
          t.add_column("amplitude", "g*s");
          t.add_column("amplitude_unprocessed", "g*s");
          std::size_t j = 0;
          for (std::size_t k = 0; k < fs.frequency.size(); ++k)
            {
              const double f = fs.frequency[k];
              if (f > fs0.frequency.back())
                break;
              while (j + 2 < fs0.frequency.size() && fs0.frequency[j + 1] < f)
                ++j;
              const double w = (f - fs0.frequency[j])
                               / (fs0.frequency[j + 1] - fs0.frequency[j]);
              t.add_row(
                {f,
                 fs.amplitude[k],
                 (1. - w) * fs0.amplitude[j] + w * fs0.amplitude[j + 1]});
            }
          context.output.write("fourier.csv", t.csv());
        }
        {
          io::Table t;
          t.add_column("period", "s");
          t.add_column("pseudo_acceleration", "g");
          t.add_column("pseudo_acceleration_unprocessed", "g");
          t.add_column("displacement", "m");
          t.add_column("pseudo_velocity", "m/s");
          for (std::size_t i = 0; i < periods.size(); ++i)
            t.add_row({periods[i],
                       rs.pseudo_acceleration[i],
                       rs0.pseudo_acceleration[i],
                       rs.displacement[i],
                       rs.pseudo_velocity[i]});
          context.output.write("response_spectrum.csv", t.csv());
        }

        auto      &s   = context.summary;
        const auto add = [&](const IntensityMeasures &m, const std::string &x) {
          s.add("pga" + x, m.pga, "g");
          s.add("pgv" + x, m.pgv, "m/s");
          s.add("pgd" + x, m.pgd, "m");
          s.add("arias_intensity" + x, m.arias, "m/s");
          s.add("t5" + x, m.t5, "s");
          s.add("t95" + x, m.t95, "s");
          s.add("d5_95" + x, m.d5_95, "s");
          s.add("final_velocity" + x, m.final_velocity, "m/s");
          s.add("final_displacement" + x, m.final_displacement, "m");
        };
        add(im, "");
        add(im0, "_unprocessed");
        s.add("padding", padding, "s");
        s.add("samples", processed.acceleration.size(), "-");
        s.add("time_step", processed.dt, "s");
        s.add("scale_factor", motion.scale_factor, "-");
        if (motion.attenuation_pga > 0.)
          s.add("bjf97_pga", motion.attenuation_pga, "g");
        const auto peak = std::max_element(rs.pseudo_acceleration.begin(),
                                           rs.pseudo_acceleration.end());
        s.add("peak_pseudo_acceleration", *peak, "g");
        s.add("period_of_peak",
              periods[peak - rs.pseudo_acceleration.begin()],
              "s");
        s.add("warnings", motion.warnings.size(), "-");

        log.line("processed: PGA " + io::format_number(im.pga, 6) + " g, PGV "
                 + io::format_number(im.pgv, 6) + " m/s, PGD "
                 + io::format_number(im.pgd, 6) + " m, Arias "
                 + io::format_number(im.arias, 6) + " m/s, D5-95 "
                 + io::format_number(im.d5_95, 6) + " s");
        log.line(
          "drift: final velocity " + io::format_number(im.final_velocity, 4)
          + " m/s, final displacement "
          + io::format_number(im.final_displacement, 4)
          + " m (unprocessed: " + io::format_number(im0.final_velocity, 4)
          + " m/s, " + io::format_number(im0.final_displacement, 4) + " m)");
        log.line("spectra: " + std::to_string(periods.size())
                 + " periods x 2 records, "
                 + (subdivisions == 0 ? std::string("automatic")
                                      : std::to_string(subdivisions))
                 + " sub-steps, in " + io::format_number(seconds, 3) + " s");
        if (plot)
          io::run_plot_script(context.output,
                              log,
                              "plot_record.py",
                              {"record.png"});
      }

    private:
      GroundMotionInput   motion;
      std::vector<double> periods;
      double              damping      = 0.05;
      unsigned int        subdivisions = 0;
      bool                plot         = true;
    };
  } // namespace



  std::unique_ptr<io::Analysis>
  internal::make_record_analysis()
  {
    return std::make_unique<RecordAnalysis>();
  }
} // namespace rockdda::seismic
