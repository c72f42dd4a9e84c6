/**
 * @file
 * Analysis type "earthquakes": Masada Block 1 without infill under seeded
 * synthetic earthquakes (thesis 5.5.3, Fig. 5-18, 5.6.2): per magnitude the
 * spread over seeds of the DDA and analytical displacement, the yield
 * acceleration, the distance up to which each magnitude triggers sliding
 * and the displacement rate from recurrence intervals.
 */
#include <rockdda/analytical/yield.h>
#include <rockdda/coupling/block1_parameters.h>
#include <rockdda/coupling/earthquakes.h>
#include <rockdda/coupling/earthquakes_analysis.h>
#include <rockdda/io/error.h>
#include <rockdda/io/interrupt.h>
#include <rockdda/io/parameters.h>
#include <rockdda/io/plot.h>

#include <deal.II/base/utilities.h>

#include <chrono>
#include <cmath>
#include <limits>

namespace rockdda::coupling
{
  namespace
  {
    using dealii::Patterns::Bool;
    using dealii::Patterns::Double;
    using dealii::Patterns::Integer;
    using dealii::Patterns::List;
    using dealii::Patterns::Selection;
    using io::DoubleInterval;

    class EarthquakesAnalysis : public io::Analysis
    {
    public:
      std::string
      name() const override
      {
        return "earthquakes";
      }

      std::string
      description() const override
      {
        return "Masada Block 1 without infill under seeded synthetic "
               "earthquakes (Boore 2003, Masada site amplification) in DDA "
               "and analytically: displacement per magnitude over seeds, "
               "yield acceleration, trigger distance, mm/yr from recurrence "
               "intervals (thesis 5.5.3, Fig. 5-18)";
      }

      void
      declare_parameters(dealii::ParameterHandler &prm) const override;

      void
      parse_parameters(dealii::ParameterHandler &prm,
                       const std::string        &prm_file) override;

      void
      run(io::RunContext &context) override;

    private:
      EarthquakeOptions   options;
      std::vector<double> recurrence{300., 1100., 4000.};
      double              max_distance = 3e5, tolerance = 10.;
      bool                plot = true;
      Block1Geometry      geometry;
      Block1Materials     materials;
    };



    void
    EarthquakesAnalysis::declare_parameters(dealii::ParameterHandler &prm) const
    {
      const auto num = [](const double x) { return io::format_number(x, 12); };
      prm.enter_subsection("Earthquakes");
      io::declare(prm,
                  "Magnitudes",
                  "6, 6.5, 7, 7.5",
                  List(Double(3., 8.5), 1, 20, ","),
                  "-",
                  "Moment magnitudes of the events, strictly increasing, "
                  "each 3 to 8.5 (1 to 20 values; thesis Fig. 5-18: 6.0, "
                  "6.5, 7.0, 7.5).");
      io::declare(prm,
                  "Number of realisations",
                  "12",
                  Integer(1, 10000),
                  "-",
                  "Seeded synthetic motions per magnitude, 1 to 10000 (the "
                  "same seeds for every magnitude).");
      io::declare(prm,
                  "Seed",
                  "1",
                  Integer(0, std::numeric_limits<int>::max()),
                  "-",
                  "Seed of the first realisation, 0 to 2147483647; "
                  "realisation i (1-based) uses seed + i - 1.");
      io::declare(prm,
                  "Stress parameter",
                  num(options.motion.stress_parameter),
                  DoubleInterval(0., true, 1e9, false),
                  "Pa",
                  "Brune stress parameter of the stochastic model, 0 < value "
                  "<= 1e9 Pa (other SMSIM parameters: the synthetic-motion "
                  "defaults).");
      io::declare(prm,
                  "Recurrence intervals",
                  "300, 1100, 4000",
                  List(DoubleInterval::positive(), 1, 20, ","),
                  "yr",
                  "Mean interval between events of magnitude >= the first, "
                  "second, ... magnitude, each > 0 yr and increasing (1 up "
                  "to the number of magnitudes; thesis 5.6.2: 1100 yr for "
                  "Mw 6.5 and 4000 yr for Mw 7.0). Bin i = [M_i, M_i+1) "
                  "occurs 1/T_i - 1/T_i+1 times per year with the median "
                  "displacement at M_i.");
      io::declare(prm,
                  "Maximum distance",
                  "300000",
                  DoubleInterval(0., true, 1e6, false),
                  "m",
                  "Upper end of the bisection for the trigger distance, 0 < "
                  "value <= 1e6 m.");
      io::declare(prm,
                  "Distance tolerance",
                  "10",
                  DoubleInterval::positive(),
                  "m",
                  "Bisection tolerance of the trigger distance, > 0 m.");
      io::declare(prm,
                  "Loading mode",
                  "loading",
                  Selection("loading|displacement"),
                  "-",
                  "How DDA applies the motion: loading (inertial body "
                  "force) or displacement (the base follows the ground).");
      io::declare(prm,
                  "Analytical time step",
                  "1e-4",
                  DoubleInterval::positive(),
                  "s",
                  "Integration step of the analytical sliding block, > 0 "
                  "s.");
      io::declare(prm,
                  "Settling steps",
                  "50",
                  Integer(0, 100000),
                  "-",
                  "Static DDA steps under gravity before t = 0, 0 to 100000.");
      declare_block1_keys(prm, "earthquakes");
      prm.leave_subsection();
    }



    void
    EarthquakesAnalysis::parse_parameters(dealii::ParameterHandler &prm,
                                          const std::string        &prm_file)
    {
      prm.enter_subsection("Earthquakes");
      options.magnitudes   = number_list(prm, "Magnitudes");
      options.realisations = prm.get_integer("Number of realisations");
      options.first_seed   = prm.get_integer("Seed");
      options.motion.stress_parameter = prm.get_double("Stress parameter");
      recurrence              = number_list(prm, "Recurrence intervals");
      max_distance            = prm.get_double("Maximum distance");
      tolerance               = prm.get_double("Distance tolerance");
      options.mode            = prm.get("Loading mode") == "displacement"
                                  ? dda::SeismicInput::Mode::displacement
                                  : dda::SeismicInput::Mode::inertial;
      options.analytical_dt   = prm.get_double("Analytical time step");
      options.settle_steps    = prm.get_integer("Settling steps");
      const Block1Keys block1 = parse_block1_keys(prm);
      geometry                = block1.geometry;
      materials               = block1.materials;
      options.penalty         = block1.penalty;
      options.dt              = block1.dt;
      options.threads         = block1.threads;
      options.distance        = block1.distance;
      plot                    = block1.plot;
      if (!block1.masada_site)
        options.motion.site = seismic::SiteAmplification();
      prm.leave_subsection();

      for (std::size_t i = 1; i < options.magnitudes.size(); ++i)
        io::require(options.magnitudes[i] > options.magnitudes[i - 1],
                    prm_file,
                    "Earthquakes/Magnitudes",
                    options.magnitudes[i],
                    "strictly increasing, each 3 to 8.5");
      io::require(materials.friction_deg > geometry.slope_deg,
                  prm_file,
                  "Earthquakes/Friction angle",
                  materials.friction_deg,
                  "> 'Slope' (else the block slides under gravity alone)");
      io::with_parameter_file(prm_file, [&]() {
        make_block1_seismic_scene(geometry, materials, "Earthquakes");
        // Checks the recurrence intervals (> 0, increasing, count).
        displacement_rate(options.magnitudes,
                          std::vector<double>(options.magnitudes.size(), 0.),
                          recurrence);
      });
    }



    void
    EarthquakesAnalysis::run(io::RunContext &context)
    {
      const auto   start = std::chrono::steady_clock::now();
      const double ky
        = analytical::plane_yield_acceleration(geometry.slope_deg,
                                               materials.friction_deg);
      context.log.line(
        "Block 1: dip " + io::format_number(geometry.slope_deg, 4)
        + " deg, friction " + io::format_number(materials.friction_deg, 4)
        + " deg: yield acceleration " + io::format_number(ky, 4)
        + " g, rocking about the toe from "
        + io::format_number(block1_rocking_acceleration(geometry), 4) + " g");
      context.log.line("motion: " + seismic::describe(options.motion)
                       + "; site: " + options.motion.site.description());

      unsigned int threads = 1;
      const auto   events
        = run_earthquakes(geometry, materials, options, &threads);
      // SIGINT / SIGTERM: the events done are kept, the rest are NaN; the
      // trigger distances (bisections) are skipped.
      const bool interrupted = io::interrupt_signal() != 0;
      if (interrupted)
        {
          std::size_t done = 0;
          for (const auto &e : events)
            done += std::isfinite(e.dda) ? 1 : 0;
          context.stopped_early = true;
          context.stopped_note
            = std::to_string(done) + " of " + std::to_string(events.size())
              + " events done (events.csv; the others are NaN, no trigger "
                "distances).";
        }
      const double events_seconds = std::chrono::duration<double>(
                                      std::chrono::steady_clock::now() - start)
                                      .count();

      io::Table table;
      table.add_column("magnitude", "-");
      table.add_column("seed", "-");
      table.add_column("pga", "g");
      table.add_column("duration", "s");
      table.add_column("dda", "m");
      table.add_column("analytical", "m");
      table.add_column("max_rotation", "rad");
      table.add_column("steps", "-");
      table.add_column("cuts", "-");
      table.add_column("wall_time", "s");
      unsigned int failed   = 0;
      double       wall_sum = 0.;
      double       wall_max = 0.;
      for (const auto &e : events)
        {
          table.add_row({e.magnitude,
                         static_cast<double>(e.seed),
                         e.pga,
                         e.duration,
                         e.dda,
                         e.analytical,
                         e.max_rotation,
                         static_cast<double>(e.steps),
                         static_cast<double>(e.cuts),
                         e.wall_time});
          wall_sum += e.wall_time;
          wall_max = std::max(wall_max, e.wall_time);
          if (!e.failure.empty())
            {
              ++failed;
              context.log.line("Mw " + io::format_number(e.magnitude, 3)
                               + ", seed " + std::to_string(e.seed)
                               + ": DDA failed: " + e.failure);
            }
        }
      context.output.write("events.csv", table.csv());

      // Per magnitude: spreads and the trigger distance.
      io::Table per;
      per.add_column("magnitude", "-");
      per.add_column("pga_median", "g");
      per.add_column("dda_p16", "m");
      per.add_column("dda_median", "m");
      per.add_column("dda_p84", "m");
      per.add_column("analytical_p16", "m");
      per.add_column("analytical_median", "m");
      per.add_column("analytical_p84", "m");
      per.add_column("trigger_distance", "m");
      per.add_column("wall_time_median", "s");
      std::vector<double> medians;
      for (const double m : options.magnitudes)
        {
          std::vector<double> pga, d, a, w;
          for (const auto &e : events)
            if (e.magnitude == m)
              {
                pga.push_back(e.pga);
                d.push_back(e.dda);
                a.push_back(e.analytical);
                w.push_back(e.wall_time);
              }
          const Spread sd = spread(d), sa = spread(a);
          const double r = interrupted
                             ? std::numeric_limits<double>::quiet_NaN()
                             : trigger_distance(options.motion,
                                                m,
                                                ky,
                                                options.realisations,
                                                options.first_seed,
                                                max_distance,
                                                tolerance);
          per.add_row({m,
                       spread(pga).median,
                       sd.p16,
                       sd.median,
                       sd.p84,
                       sa.p16,
                       sa.median,
                       sa.p84,
                       r,
                       spread(w).median});
          medians.push_back(sd.median);
          const std::string tag = "_Mw" + io::format_number(m, 4);
          context.summary.add("pga_median" + tag, spread(pga).median, "g");
          context.summary.add("dda_median" + tag, sd.median, "m");
          context.summary.add("dda_p16" + tag, sd.p16, "m");
          context.summary.add("dda_p84" + tag, sd.p84, "m");
          context.summary.add("analytical_median" + tag, sa.median, "m");
          context.summary.add("analytical_p16" + tag, sa.p16, "m");
          context.summary.add("analytical_p84" + tag, sa.p84, "m");
          context.summary.add("trigger_distance" + tag, r, "m");
          context.log.line(
            "Mw " + io::format_number(m, 3) + " at "
            + io::format_number(options.distance, 6) + " m: median PGA "
            + io::format_number(spread(pga).median, 4) + " g; DDA "
            + io::format_number(1e3 * sd.median, 4) + " mm ("
            + io::format_number(1e3 * sd.p16, 4) + "-"
            + io::format_number(1e3 * sd.p84, 4) + "), analytical "
            + io::format_number(1e3 * sa.median, 4) + " mm ("
            + io::format_number(1e3 * sa.p16, 4) + "-"
            + io::format_number(1e3 * sa.p84, 4) + "); median PGA >= ky up to "
            + io::format_number(r, 6) + " m");
        }
      context.output.write("magnitudes.csv", per.csv());

      // The rate.
      const auto bins
        = displacement_rate(options.magnitudes, medians, recurrence);
      io::Table rates;
      rates.add_column("magnitude", "-");
      rates.add_column("recurrence", "yr");
      rates.add_column("annual_rate", "1/yr");
      rates.add_column("displacement", "m");
      rates.add_column("rate", "mm/yr");
      rates.add_column("rate_single", "mm/yr");
      double total = 0.;
      for (const auto &b : bins)
        {
          rates.add_row({b.magnitude,
                         b.recurrence,
                         b.annual_rate,
                         b.displacement,
                         b.rate,
                         b.rate_single});
          total += b.rate;
          const std::string tag = "_Mw" + io::format_number(b.magnitude, 4);
          context.summary.add("rate_bin" + tag, b.rate, "mm/yr");
          context.summary.add("rate_single" + tag, b.rate_single, "mm/yr");
        }
      context.output.write("rates.csv", rates.csv());
      context.log.line("displacement rate: " + io::format_number(total, 4)
                       + " mm/yr (" + std::to_string(bins.size())
                       + " magnitude bins)");

      const double seconds = std::chrono::duration<double>(
                               std::chrono::steady_clock::now() - start)
                               .count();
      context.summary.add("yield_acceleration", ky, "g");
      // Rocking about the toe (pseudo-static): near ky the block rocks as
      // it slides at large magnitudes and DDA slides further than the rigid
      // block (doc/theory/earthquakes.md).
      context.summary.add("rocking_acceleration",
                          block1_rocking_acceleration(geometry),
                          "g");
      context.summary.add("rate_total", total, "mm/yr");
      context.summary.add("events", static_cast<double>(events.size()), "-");
      context.summary.add("failed_runs", failed, "-");
      context.summary.add("concurrent_runs", threads, "-");
      context.summary.add("events_wall_time", events_seconds, "s");
      context.summary.add("run_wall_time_median",
                          spread([&]() {
                            std::vector<double> w;
                            for (const auto &e : events)
                              w.push_back(e.wall_time);
                            return w;
                          }())
                            .median,
                          "s");
      context.summary.add("run_wall_time_max", wall_max, "s");
      context.summary.add("run_wall_time_sum", wall_sum, "s");
      context.summary.add("wall_time", seconds, "s");
      context.log.line(std::to_string(events.size()) + " events in "
                       + io::format_number(events_seconds, 4)
                       + " s; whole analysis " + io::format_number(seconds, 4)
                       + " s");
      context.output.write("statistics.csv", per.csv());
      if (plot)
        io::run_plot_script(context.output,
                            context.log,
                            "plot_earthquakes.py",
                            {"earthquakes.png"});
    }
  } // namespace



  std::unique_ptr<io::Analysis>
  make_earthquakes_analysis()
  {
    return std::make_unique<EarthquakesAnalysis>();
  }
} // namespace rockdda::coupling
