/**
 * @file
 * Analysis type "synthetic-motion": seeded realisations of the stochastic
 * point-source method (Boore 2003) for one scenario, each written as a
 * record file (time s, acceleration g), their PGA against BJF97 and their
 * mean Fourier spectrum against the target.
 */
#include <rockdda/io/error.h>
#include <rockdda/io/parameters.h>
#include <rockdda/io/plot.h>
#include <rockdda/seismic/attenuation.h>
#include <rockdda/seismic/intensity.h>
#include <rockdda/seismic/site_amplification.h>
#include <rockdda/seismic/stochastic.h>
#include <rockdda/seismic/synthetic_analysis.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <limits>

namespace rockdda::seismic
{
  namespace
  {
    using dealii::Patterns::Bool;
    using dealii::Patterns::Double;
    using dealii::Patterns::FileName;
    using dealii::Patterns::Integer;
    using dealii::Patterns::List;
    using dealii::Patterns::Selection;
    using io::DoubleInterval;

    /// The Masada modes as the parameter file writes them.
    std::string
    masada_modes_text()
    {
      std::string text;
      for (const auto &m : SiteAmplification::masada_modes())
        text += (text.empty() ? "" : "; ") + io::format_number(m.frequency, 6)
                + ", " + io::format_number(m.peak, 6) + ", "
                + io::format_number(m.width, 6);
      return text;
    }

    /// Median of @p v (not empty).
    double
    median(std::vector<double> v)
    {
      std::sort(v.begin(), v.end());
      const std::size_t n = v.size();
      return n % 2 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
    }

    /// Standard deviation of ln v (0 for fewer than 2 values).
    double
    sigma_ln(const std::vector<double> &v)
    {
      if (v.size() < 2)
        return 0.;
      double m = 0.;
      for (const double x : v)
        m += std::log(x) / v.size();
      double s = 0.;
      for (const double x : v)
        s += (std::log(x) - m) * (std::log(x) - m);
      return std::sqrt(s / (v.size() - 1));
    }

    /// The "synthetic-motion" analysis.
    class SyntheticAnalysis : public io::Analysis
    {
    public:
      std::string
      name() const override
      {
        return "synthetic-motion";
      }

      std::string
      description() const override
      {
        return "synthetic acceleration records by the stochastic "
               "point-source method (Boore 2003): seeded realisations, "
               "site amplification, PGA against BJF97, mean Fourier "
               "spectrum against the target";
      }

      void
      declare_parameters(dealii::ParameterHandler &prm) const override;

      void
      parse_parameters(dealii::ParameterHandler &prm,
                       const std::string        &prm_file) override;

      std::vector<std::string>
      warnings() const override
      {
        return bjf97_warnings(scenario);
      }

      void
      run(io::RunContext &context) override;

    private:
      StochasticParameters parameters;
      Bjf97Scenario        scenario;
      unsigned int         realisations  = 50;
      std::uint64_t        seed          = 1;
      bool                 write_records = true, plot = true;
      std::string          site_text;
    };



    void
    SyntheticAnalysis::declare_parameters(dealii::ParameterHandler &prm) const
    {
      const StochasticParameters d;
      const auto num = [](const double x) { return io::format_number(x, 12); };
      prm.enter_subsection("Synthetic motion");
      io::declare(prm,
                  "Magnitude",
                  num(d.magnitude),
                  Double(3., 8.5),
                  "-",
                  "Moment magnitude M, 3 to 8.5; M0 = 10^(1.5 M + 9.05) N m. "
                  "BJF97, the comparison, was fitted to magnitudes "
                  "between 4 and 8 (outside: a warning).");
      io::declare(prm,
                  "Joyner-Boore distance",
                  num(d.distance),
                  Double(0., 1e6),
                  "m",
                  "Distance Rjb from the site to the surface projection of "
                  "the source, 0 to 1e6 m (BJF97 is fitted to 80 km).");
      io::declare(prm,
                  "Point-source depth",
                  num(d.depth),
                  Double(0., 1e5),
                  "m",
                  "Depth h of the equivalent point source, 0 to 1e5 m; the "
                  "distance is R = sqrt(Rjb^2 + h^2). 0: the pseudo-depth "
                  "of Atkinson & Silva (2000), log10(h/km) = -0.05 + 0.15 M, "
                  "which stands for the extent of a large fault.");
      io::declare(prm,
                  "Stress parameter",
                  num(d.stress_parameter),
                  DoubleInterval(0., true, 1e9, false),
                  "Pa",
                  "Brune stress parameter, 0 < value <= 1e9 Pa (7e6 Pa = 70 "
                  "bar); sets the corner frequency fc = 0.4906 beta "
                  "(stress / M0)^(1/3).");
      io::declare(prm,
                  "Density",
                  num(d.density),
                  DoubleInterval(0., true, 1e4, false),
                  "kg/m^3",
                  "Density rho near the source, 0 < rho <= 1e4 kg/m^3.");
      io::declare(prm,
                  "Shear-wave velocity",
                  num(d.shear_velocity),
                  DoubleInterval(0., true, 1e4, false),
                  "m/s",
                  "Shear-wave velocity beta near the source, 0 < beta <= "
                  "1e4 m/s (also the velocity of the path in Q).");
      io::declare(prm,
                  "Radiation pattern",
                  num(d.radiation_pattern),
                  DoubleInterval(0., true, 1., false),
                  "-",
                  "Average S-wave radiation coefficient, 0 < value <= 1 "
                  "(0.55: Boore & Boatwright 1984).");
      io::declare(prm,
                  "Free-surface factor",
                  num(d.free_surface),
                  DoubleInterval(0., true, 2., false),
                  "-",
                  "Free-surface amplification F, 0 < F <= 2.");
      io::declare(prm,
                  "Partition factor",
                  num(d.partition),
                  DoubleInterval(0., true, 1., false),
                  "-",
                  "Partition of the S-wave energy onto one horizontal "
                  "component V, 0 < V <= 1 (1/sqrt(2)).");
      io::declare(prm,
                  "Spreading exponent near",
                  num(d.spreading_near),
                  Double(0., 3.),
                  "-",
                  "Geometric spreading G = (1 km / R)^b1 up to the "
                  "transition distance; b1 from 0 to 3.");
      io::declare(prm,
                  "Spreading transition distance",
                  num(d.spreading_transition),
                  DoubleInterval(0., true, 1e7, false),
                  "m",
                  "Distance R1 where the spreading changes exponent, 0 < R1 "
                  "<= 1e7 m.");
      io::declare(prm,
                  "Spreading exponent far",
                  num(d.spreading_far),
                  Double(0., 3.),
                  "-",
                  "Spreading beyond R1: G = G(R1) (R1 / R)^b2; b2 from 0 to "
                  "3.");
      io::declare(prm,
                  "Q0",
                  num(d.q0),
                  DoubleInterval(0., true, 1e5, false),
                  "-",
                  "Quality factor Q(f) = Q0 (f / 1 Hz)^eta of the path, 0 < "
                  "Q0 <= 1e5. The default 600 makes the median PGA follow "
                  "BJF97 at 10-50 km (doc/theory/seismic-synthetic.md); "
                  "Atkinson & Silva (2000) use 180.");
      io::declare(prm,
                  "Q exponent",
                  num(d.q_exponent),
                  Double(0., 1.5),
                  "-",
                  "Exponent eta of Q(f), 0 to 1.5.");
      io::declare(prm,
                  "Kappa",
                  num(d.kappa),
                  Double(0., 0.2),
                  "s",
                  "High-frequency diminution exp(-pi kappa0 f) near the "
                  "site, 0 to 0.2 s.");
      io::declare(prm,
                  "Crustal amplification",
                  "generic rock",
                  Selection("none|generic rock"),
                  "-",
                  "Amplification by the crust above the source: none, or "
                  "generic rock of Boore & Joyner (1997) (Vs30 620 m/s).");
      io::declare(prm,
                  "Source duration factor",
                  num(d.source_duration),
                  Double(0., 10.),
                  "-",
                  "Source duration = factor / fc, factor 0 to 10 (Boore "
                  "2003: 1).");
      io::declare(prm,
                  "Path duration",
                  num(d.path_duration),
                  Double(0., 1e-3),
                  "s/m",
                  "Path duration per metre of R, 0 to 1e-3 s/m (Atkinson & "
                  "Silva 2000: 0.05 s/km = 5e-5 s/m).");
      io::declare(prm,
                  "Window epsilon",
                  num(d.window_epsilon),
                  DoubleInterval(0., true, 1., true),
                  "-",
                  "Saragoni-Hart window: fraction of t_eta at which it "
                  "peaks, 0 < epsilon < 1 (Boore 2003: 0.2).");
      io::declare(prm,
                  "Window eta",
                  num(d.window_eta),
                  DoubleInterval(0., true, 1., true),
                  "-",
                  "Saragoni-Hart window: its value at t_eta, 0 < eta < 1 "
                  "(Boore 2003: 0.05).");
      io::declare(prm,
                  "Window length factor",
                  num(d.window_factor),
                  DoubleInterval(0., true, 10., false),
                  "-",
                  "t_eta = factor x duration of motion, 0 < factor <= 10 "
                  "(Boore 2003: 2).");
      io::declare(prm,
                  "Time step",
                  num(d.dt),
                  DoubleInterval(0., true, 0.02, false),
                  "s",
                  "Sampling interval of the records, 0 < dt <= 0.02 s "
                  "(Nyquist frequency at least 25 Hz).");
      io::declare(prm,
                  "Number of realisations",
                  "50",
                  Integer(1, 10000),
                  "-",
                  "Realisations (seeds) simulated, 1 to 10000.");
      io::declare(prm,
                  "Seed",
                  "1",
                  Integer(0, std::numeric_limits<int>::max()),
                  "-",
                  "Seed of the first realisation, 0 to 2147483647; "
                  "realisation i (1-based) uses seed + i - 1 for its "
                  "std::mt19937_64, so every record can be made again "
                  "alone.");
      io::declare(prm,
                  "Vs30",
                  "620",
                  DoubleInterval(0., true, 1e4, false),
                  "m/s",
                  "Vs30 of the BJF97 comparison, 0 < Vs30 <= 1e4 m/s (620: "
                  "the generic rock of the crustal amplification).");
      io::declare(prm,
                  "Mechanism",
                  "unspecified",
                  Selection("strike-slip|reverse|unspecified"),
                  "-",
                  "Fault mechanism of the BJF97 comparison.");
      io::declare(prm,
                  "Write records",
                  "true",
                  Bool(),
                  "-",
                  "Write each realisation as record-NNNN.csv (time s, "
                  "acceleration g; 'Record format = columns' reads it).");
      io::declare(prm,
                  "Plot",
                  "true",
                  Bool(),
                  "-",
                  "Draw synthetic.png with scripts/plot_synthetic.py "
                  "(python3-matplotlib).");
      prm.enter_subsection("Site amplification");
      io::declare(prm,
                  "Type",
                  "none",
                  Selection("none|table|modes"),
                  "-",
                  "Site (topographic) amplification multiplied into the "
                  "target spectrum: none, a table file, or resonant modes.");
      io::declare(prm,
                  "Table file",
                  "",
                  FileName(),
                  "-",
                  "Type = table: two columns frequency (Hz) and "
                  "amplification (>= 0), log-log interpolation, constant "
                  "beyond the ends; relative to the parameter file. "
                  "parameter-files/data/masada-site-amplification.csv is "
                  "Masada's.");
      io::declare(prm,
                  "Modes",
                  masada_modes_text(),
                  List(List(Double(0.), 3, 3, ","), 1, 20, ";"),
                  "-",
                  "Type = modes: 'frequency (Hz), peak (-), width (Hz)' per "
                  "mode, modes separated by ';' (1 to 20); A(f) equals each "
                  "peak at its frequency, the width is the full width at "
                  "half the mode's excess. Default: the Masada "
                  "approximation (thesis Fig. 5-14B).");
      io::declare(prm,
                  "Cut frequency",
                  "10",
                  Double(0., 1e3),
                  "Hz",
                  "Type = modes: corner of a Butterworth high cut, 0 to "
                  "1000 Hz (0: none; Masada: 10).");
      io::declare(prm,
                  "Cut order",
                  "8",
                  Integer(1, 20),
                  "-",
                  "Type = modes: order of the high cut, 1 to 20.");
      prm.leave_subsection();
      prm.leave_subsection();
    }



    void
    SyntheticAnalysis::parse_parameters(dealii::ParameterHandler &prm,
                                        const std::string        &prm_file)
    {
      StochasticParameters &p = parameters;
      prm.enter_subsection("Synthetic motion");
      p.magnitude            = prm.get_double("Magnitude");
      p.distance             = prm.get_double("Joyner-Boore distance");
      p.depth                = prm.get_double("Point-source depth");
      p.stress_parameter     = prm.get_double("Stress parameter");
      p.density              = prm.get_double("Density");
      p.shear_velocity       = prm.get_double("Shear-wave velocity");
      p.radiation_pattern    = prm.get_double("Radiation pattern");
      p.free_surface         = prm.get_double("Free-surface factor");
      p.partition            = prm.get_double("Partition factor");
      p.spreading_near       = prm.get_double("Spreading exponent near");
      p.spreading_transition = prm.get_double("Spreading transition distance");
      p.spreading_far        = prm.get_double("Spreading exponent far");
      p.q0                   = prm.get_double("Q0");
      p.q_exponent           = prm.get_double("Q exponent");
      p.kappa                = prm.get_double("Kappa");
      p.crustal              = prm.get("Crustal amplification") == "none"
                                 ? CrustalAmplification::none
                                 : CrustalAmplification::generic_rock;
      p.source_duration      = prm.get_double("Source duration factor");
      p.path_duration        = prm.get_double("Path duration");
      p.window_epsilon       = prm.get_double("Window epsilon");
      p.window_eta           = prm.get_double("Window eta");
      p.window_factor        = prm.get_double("Window length factor");
      p.dt                   = prm.get_double("Time step");
      realisations           = prm.get_integer("Number of realisations");
      seed                   = prm.get_integer("Seed");
      scenario.vs30          = prm.get_double("Vs30");
      const std::string mech = prm.get("Mechanism");
      scenario.mechanism = mech == "strike-slip" ? FaultMechanism::strike_slip
                           : mech == "reverse"   ? FaultMechanism::reverse
                                                 : FaultMechanism::unspecified;
      write_records      = prm.get_bool("Write records");
      plot               = prm.get_bool("Plot");

      prm.enter_subsection("Site amplification");
      const std::string type = prm.get("Type");
      if (type == "table")
        {
          const std::string name = prm.get("Table file");
          if (name.empty())
            throw InputError(prm_file
                             + ": key 'Synthetic motion/Site amplification/"
                               "Table file' is empty; Type = table needs a "
                               "file of frequency (Hz) and amplification");
          const std::string file = io::resolve_path(
            name, prm_file, "Synthetic motion/Site amplification/Table file");
          io::with_parameter_file(prm_file, [&]() {
            p.site = SiteAmplification::read_table(file);
          });
        }
      else if (type == "modes")
        {
          std::vector<ResonantMode> modes;
          for (const auto &mode :
               dealii::Utilities::split_string_list(prm.get("Modes"), ';'))
            {
              const auto v = dealii::Utilities::string_to_double(
                dealii::Utilities::split_string_list(mode, ','));
              modes.push_back({v[0], v[1], v[2]});
            }
          const double       cut   = prm.get_double("Cut frequency");
          const unsigned int order = prm.get_integer("Cut order");
          try
            {
              p.site = SiteAmplification::from_modes(modes, cut, order);
            }
          catch (const InputError &e)
            {
              throw InputError(prm_file
                               + ": key 'Synthetic motion/Site "
                                 "amplification/Modes': "
                               + e.what());
            }
        }
      prm.leave_subsection();
      prm.leave_subsection();

      scenario.magnitude   = p.magnitude;
      scenario.distance_km = p.distance / 1e3;
      // The record must resolve the corner of the source and the window:
      // more than 2^24 samples is a mistake (dt far too small for M).
      const double samples = (2. * std::max(2., 1. / corner_frequency(p))
                              + 1.5 * p.window_factor * motion_duration(p))
                             / p.dt;
      io::require(samples < 16777216.,
                  prm_file,
                  "Synthetic motion/Time step",
                  p.dt,
                  "a step giving fewer than 2^24 samples per record ("
                    + io::format_number(samples, 4) + " now)");
    }



    void
    SyntheticAnalysis::run(io::RunContext &context)
    {
      auto       &log      = context.log;
      const auto &p        = parameters;
      const bool  has_site = !p.site.is_unity();
      log.line("stochastic point source (Boore 2003): " + describe(p));
      log.line("site amplification: " + p.site.description());
      for (const auto &w : bjf97_warnings(scenario))
        log.line("warning: " + w);
      const double bjf = bjf97_pga(scenario);

      const auto          start = std::chrono::steady_clock::now();
      SpectrumAverager    spectra(p, true), spectra_rock(p, false);
      std::vector<double> pga, pga_rock;
      io::Table           stats;
      stats.add_column("realisation", "-");
      stats.add_column("seed", "-");
      stats.add_column("pga", "g");
      stats.add_column("pga_rock", "g");
      stats.add_column("bjf97_median", "g");
      stats.add_column("ratio_rock_to_bjf97", "-");
      stats.add_column("pgv", "m/s");
      stats.add_column("arias_intensity", "m/s");
      stats.add_column("d5_95", "s");
      std::size_t samples = 0;
      for (unsigned int i = 0; i < realisations; ++i)
        {
          const std::uint64_t s    = seed + i;
          const Record        rock = simulate(p, s, false);
          const Record        site = has_site ? simulate(p, s, true) : rock;
          samples                  = site.acceleration.size();
          spectra.add(site);
          spectra_rock.add(rock);
          const auto im = intensity_measures(site);
          pga.push_back(im.pga);
          pga_rock.push_back(rock.peak());
          stats.add_row({double(i + 1),
                         double(s),
                         im.pga,
                         pga_rock.back(),
                         bjf,
                         pga_rock.back() / bjf,
                         im.pgv,
                         im.arias,
                         im.d5_95});
          if (write_records)
            {
              // A '#' comment (no commas: it is not a CSV record), then
              // the header and the samples.
              const std::string comment
                = "# rockdda synthetic-motion: " + site.name
                  + (has_site ? " with site amplification" : "") + "\n";
              io::CsvWriter csv;
              csv.record({"time_s", "acceleration_g"});
              for (std::size_t k = 0; k < site.acceleration.size(); ++k)
                csv.number(k * site.dt)
                  .number(site.acceleration[k])
                  .end_record();
              char name[32];
              std::snprintf(name, sizeof name, "record-%04u.csv", i + 1);
              context.output.write(name, comment + csv.text());
            }
        }
      const double seconds = std::chrono::duration<double>(
                               std::chrono::steady_clock::now() - start)
                               .count();
      context.output.write("statistics.csv", stats.csv());

      // Spectra in 1/6-octave bands from 0.1 Hz to the Nyquist frequency.
      const double nyquist = 0.5 / p.dt;
      const auto   b       = spectra.bands(0.1, nyquist, 6);
      const auto   br      = spectra_rock.bands(0.1, nyquist, 6);
      double       worst = 0., worst_f = 0.;
      {
        io::Table t;
        t.add_column("frequency", "Hz");
        t.add_column("target", "g*s");
        t.add_column("mean", "g*s");
        t.add_column("target_rock", "g*s");
        t.add_column("mean_rock", "g*s");
        t.add_column("site_amplification", "-");
        for (std::size_t j = 0; j < b.frequency.size(); ++j)
          {
            t.add_row({b.frequency[j],
                       b.target[j],
                       b.mean[j],
                       br.target[j],
                       br.mean[j],
                       p.site(b.frequency[j])});
            const double e = std::abs(b.mean[j] / b.target[j] - 1.);
            if (b.frequency[j] >= 0.5 && b.frequency[j] <= 10. && e > worst)
              {
                worst   = e;
                worst_f = b.frequency[j];
              }
          }
        context.output.write("fourier.csv", t.csv());
      }
      if (has_site)
        {
          io::Table t;
          t.add_column("frequency", "Hz");
          t.add_column("amplification", "-");
          for (unsigned int k = 0; k <= 300; ++k)
            {
              const double f = 0.05 * std::pow(1000., k / 300.);
              t.add_row({f, p.site(f)});
            }
          context.output.write("site_amplification.csv", t.csv());
        }

      const double med = median(pga), med_rock = median(pga_rock);
      auto        &s = context.summary;
      s.add("magnitude", p.magnitude, "-");
      s.add("joyner_boore_distance", p.distance, "m");
      s.add("source_depth", source_depth(p), "m");
      s.add("source_distance", source_distance(p), "m");
      s.add("corner_frequency", corner_frequency(p), "Hz");
      s.add("motion_duration", motion_duration(p), "s");
      s.add("realisations", realisations, "-");
      s.add("first_seed", double(seed), "-");
      s.add("samples", samples, "-");
      s.add("median_pga", med, "g");
      s.add("median_pga_rock", med_rock, "g");
      s.add("bjf97_pga", bjf, "g");
      s.add("ratio_rock_to_bjf97", med_rock / bjf, "-");
      s.add("sigma_ln_pga_rock", sigma_ln(pga_rock), "-");
      s.add("site_pga_amplification", med / med_rock, "-");
      s.add("spectrum_max_deviation", worst, "-");
      s.add("warnings", bjf97_warnings(scenario).size(), "-");
      log.line(std::to_string(realisations) + " realisations of "
               + std::to_string(samples) + " samples in "
               + io::format_number(seconds, 3) + " s");
      log.line("median PGA on rock " + io::format_number(med_rock, 5)
               + " g = " + io::format_number(med_rock / bjf, 4) + " x BJF97 ("
               + io::format_number(bjf, 5) + " g, Vs30 "
               + io::format_number(scenario.vs30, 4) + " m/s), sigma ln "
               + io::format_number(sigma_ln(pga_rock), 3)
               + (has_site
                    ? "; with the site " + io::format_number(med, 5) + " g (x"
                        + io::format_number(med / med_rock, 4) + ")"
                    : std::string()));
      log.line("mean Fourier spectrum (quadratic mean, 1/6-octave bands) "
               "within "
               + io::format_number(100. * worst, 3)
               + " % of the target in 0.5-10 Hz (largest at "
               + io::format_number(worst_f, 4) + " Hz)");
      if (plot)
        io::run_plot_script(context.output,
                            log,
                            "plot_synthetic.py",
                            {"synthetic.png"});
    }
  } // namespace



  std::unique_ptr<io::Analysis>
  make_synthetic_analysis()
  {
    return std::make_unique<SyntheticAnalysis>();
  }
} // namespace rockdda::seismic
