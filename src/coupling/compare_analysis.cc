/**
 * @file
 * Analysis type "compare": thermal against seismic displacement of Masada
 * Block 1 (thesis 5.6.2, Fig. 5-19) and the combined history over seeded
 * Gutenberg-Richter catalogues (issue 15, item 3). The thermal rate is the
 * analytical ratchet of Pasten (2012) as a function of the wedge length;
 * each earthquake of a catalogue that can slide the block (PGA >= ky) runs
 * through DDA of Block 1 (the calibrated penalty and time step); the
 * histories combine them year by year (coupling::combined_history).
 */
#include <rockdda/analytical/yield.h>
#include <rockdda/coupling/block1_parameters.h>
#include <rockdda/coupling/block1_seismic.h>
#include <rockdda/coupling/compare.h>
#include <rockdda/coupling/compare_analysis.h>
#include <rockdda/coupling/concurrent_runs.h>
#include <rockdda/coupling/earthquakes.h>
#include <rockdda/io/error.h>
#include <rockdda/io/interrupt.h>
#include <rockdda/io/parameters.h>
#include <rockdda/io/plot.h>

#include <deal.II/base/utilities.h>

#include <algorithm>
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

    constexpr double nan = std::numeric_limits<double>::quiet_NaN();

    /// One event of one catalogue and its slips (m).
    struct EventRun
    {
      unsigned int   catalogue = 0;
      CatalogueEvent event;
      double         pga = 0., duration = 0.;
      double         dda = 0., analytical = 0., max_rotation = 0.;
      double         wall_time = 0.;
      bool           triggers  = false;
      std::string    failure;
    };

    class CompareAnalysis : public io::Analysis
    {
    public:
      std::string
      name() const override
      {
        return "compare";
      }

      std::string
      description() const override
      {
        return "thermal (Pasten 2012 ratchet) against seismic (DDA under "
               "seeded Gutenberg-Richter catalogues of synthetic motions) "
               "displacement of Masada Block 1 over a window, and their "
               "combined history (thesis 5.6.2, Fig. 5-19)";
      }

      void
      declare_parameters(dealii::ParameterHandler &prm) const override;

      void
      parse_parameters(dealii::ParameterHandler &prm,
                       const std::string        &prm_file) override;

      std::vector<std::string>
      warnings() const override
      {
        std::vector<std::string> w;
        if (gr.b_value < 0.5 || gr.b_value > 2.)
          w.push_back("key 'Compare/b-value' = "
                      + io::format_number(gr.b_value, 4)
                      + " is outside 0.5-2, the range of b-values of "
                        "tectonic seismicity (Gutenberg & Richter 1944; "
                        "about 1 for most regions)");
        return w;
      }

      void
      run(io::RunContext &context) override;

    private:
      /// The ratchet model of thermal curve @p i with the block's geometry.
      analytical::RatchetInput
      ratchet_input(const std::size_t i) const
      {
        analytical::RatchetInput in;
        in.set_section(geometry);
        in.friction_angle_deg = materials.friction_deg;
        in.beta               = betas[i];
        in.thermal_expansion  = alphas[i];
        in.wedge_length       = initial_wedge;
        return in;
      }

      GutenbergRichter    gr;
      double              window     = 5000.;
      unsigned int        catalogues = 20;
      std::uint64_t       first_seed = 1;
      double              distance   = 1e3;
      std::vector<double> betas{0.45, 0.7}, alphas{8e-6, 6e-6};
      double              initial_wedge = 0.;
      Block1Geometry      geometry;
      Block1Materials     materials;
      Block1RunControls   controls;
      unsigned int        threads     = 0;
      bool                masada_site = true, plot = true;
    };



    void
    CompareAnalysis::declare_parameters(dealii::ParameterHandler &prm) const
    {
      prm.enter_subsection("Compare");
      io::declare(prm,
                  "Window",
                  "5000",
                  Double(1., 1e6),
                  "yr",
                  "Length of the window, 1 to 1e6 yr, one thermal cycle a "
                  "year (thesis Fig. 5-19: 5000 yr).");
      io::declare(prm,
                  "Number of catalogues",
                  "20",
                  Integer(1, 100000),
                  "-",
                  "Seeded earthquake catalogues over the window, 1 to "
                  "100000; catalogue i (1-based) uses seed + i - 1.");
      io::declare(prm,
                  "Seed",
                  "1",
                  Integer(0, std::numeric_limits<int>::max()),
                  "-",
                  "Seed of the first catalogue, 0 to 2147483647.");
      io::declare(prm,
                  "b-value",
                  "1",
                  DoubleInterval(0., true, 5., false),
                  "-",
                  "Gutenberg-Richter b-value, 0 < b <= 5 (a warning outside "
                  "the tectonic range, one half to two). With the "
                  "truncation at the maximum magnitude 7.5, b = 1 gives "
                  "recurrence intervals of 1021 and 4249 yr for Mw >= 6.5 "
                  "and 7 from 300 yr for Mw >= 6 (thesis 5.6.2: 1100 and "
                  "4000 yr).");
      io::declare(prm,
                  "Minimum magnitude",
                  "6",
                  Double(3., 8.5),
                  "-",
                  "Smallest magnitude of the catalogue, 3 to 8.5 (smaller "
                  "events are left out: at 1 km their median PGA is below "
                  "the yield acceleration; see doc/theory/compare.md).");
      io::declare(prm,
                  "Maximum magnitude",
                  "7.5",
                  Double(3., 8.5),
                  "-",
                  "Largest magnitude of the catalogue, 3 to 8.5, above the "
                  "minimum (thesis: the largest expected Dead Sea rift "
                  "event, Mw 7.5).");
      io::declare(prm,
                  "Recurrence interval",
                  "300",
                  DoubleInterval::positive(),
                  "yr",
                  "Mean interval between events of at least the minimum "
                  "magnitude, > 0 yr (thesis 5.6.2: 300 yr for Mw >= 6).");
      io::declare(prm,
                  "Betas",
                  "0.45, 0.7",
                  List(DoubleInterval(0., true, 1., false), 1, 10, ","),
                  "-",
                  "Coefficients beta of the non-uniform temperature "
                  "distribution of the thermal curves, each 0 < beta <= 1 "
                  "(thesis Fig. 5-19: 0.45 and 0.7); the first drives the "
                  "combined history.");
      io::declare(prm,
                  "Thermal expansion coefficients",
                  "8e-6, 6e-6",
                  List(Double(0., 1e-3), 1, 10, ","),
                  "1/K",
                  "alpha of each thermal curve, each 0 to 1e-3 1/K, as many "
                  "as 'Betas' (thesis Fig. 5-13: 8e-6 with 0.45, 6e-6 with "
                  "0.7).");
      io::declare(prm,
                  "Initial wedge length",
                  "0",
                  Double(0., 10.),
                  "m",
                  "Wedge length L_W (the crack opening filled by infill) at "
                  "the start of the window, 0 to 10 m.");
      declare_block1_keys(prm, "compare");
      prm.leave_subsection();
    }



    void
    CompareAnalysis::parse_parameters(dealii::ParameterHandler &prm,
                                      const std::string        &prm_file)
    {
      prm.enter_subsection("Compare");
      window           = prm.get_double("Window");
      catalogues       = prm.get_integer("Number of catalogues");
      first_seed       = prm.get_integer("Seed");
      gr.b_value       = prm.get_double("b-value");
      gr.min_magnitude = prm.get_double("Minimum magnitude");
      gr.max_magnitude = prm.get_double("Maximum magnitude");
      gr.recurrence    = prm.get_double("Recurrence interval");
      betas            = number_list(prm, "Betas");
      alphas           = number_list(prm, "Thermal expansion coefficients");
      initial_wedge    = prm.get_double("Initial wedge length");
      const Block1Keys block1 = parse_block1_keys(prm);
      geometry                = block1.geometry;
      materials               = block1.materials;
      controls.penalty        = block1.penalty;
      controls.dt             = block1.dt;
      threads                 = block1.threads;
      distance                = block1.distance;
      masada_site             = block1.masada_site;
      plot                    = block1.plot;
      prm.leave_subsection();
      io::require(gr.max_magnitude > gr.min_magnitude,
                  prm_file,
                  "Compare/Maximum magnitude",
                  gr.max_magnitude,
                  "> 'Minimum magnitude' and <= 8.5");
      io::require(alphas.size() == betas.size(),
                  prm_file,
                  "Compare/Thermal expansion coefficients",
                  static_cast<double>(alphas.size()),
                  "as many values as 'Betas' (" + std::to_string(betas.size())
                    + ")");
      io::require(materials.friction_deg > geometry.slope_deg,
                  prm_file,
                  "Compare/Friction angle",
                  materials.friction_deg,
                  "> 'Slope' (else the block slides under gravity alone)");
      controls.penalty_key      = "Compare/Penalty";
      controls.time_step_key    = "Compare/Time step";
      controls.section          = "Compare";
      controls.max_steps_per_dt = 20.;
      controls.wall_time_limit  = 60.;
      io::with_parameter_file(prm_file, [&]() {
        make_block1_seismic_scene(geometry, materials, "Compare");
        for (std::size_t i = 0; i < betas.size(); ++i)
          analytical::validate(ratchet_input(i));
      });
    }



    void
    CompareAnalysis::run(io::RunContext &context)
    {
      const auto start = std::chrono::steady_clock::now();
      const auto since = [&]() {
        return std::chrono::duration<double>(std::chrono::steady_clock::now()
                                             - start)
          .count();
      };
      const double ky
        = analytical::plane_yield_acceleration(geometry.slope_deg,
                                               materials.friction_deg);
      const unsigned int years = static_cast<unsigned int>(std::ceil(window));
      context.log.line(
        "Block 1: dip " + io::format_number(geometry.slope_deg, 4)
        + " deg, friction " + io::format_number(materials.friction_deg, 4)
        + " deg, yield acceleration " + io::format_number(ky, 4) + " g; window "
        + std::to_string(years) + " yr, " + std::to_string(catalogues)
        + " catalogues");

      // Thermal: rates at the start and at L_W = 0.2 m (Fig. 5-13), and
      // the thermal history alone over the window per curve.
      io::Table rates;
      rates.add_column("curve", "-");
      rates.add_column("beta", "-");
      rates.add_column("alpha", "1/K");
      rates.add_column("rate_initial", "mm/yr");
      rates.add_column("rate_wedge_0.2m", "mm/yr");
      rates.add_column("rate_window", "mm/yr");
      rates.add_column("wedge_over_skin_depth", "-");
      std::vector<HistoryResult> thermal;
      for (std::size_t i = 0; i < betas.size(); ++i)
        {
          analytical::RatchetInput in = ratchet_input(i);
          const double r0 = analytical::ratchet(in).plastic_displacement;
          in.wedge_length = 0.2;
          const double r1 = analytical::ratchet(in).plastic_displacement;
          thermal.push_back(
            combined_history(ratchet_input(i), years, {}, {}, i == 0));
          const double rate = 1e3 * thermal.back().total / years;
          rates.add_row({static_cast<double>(i + 1),
                         betas[i],
                         alphas[i],
                         1e3 * r0,
                         1e3 * r1,
                         rate,
                         thermal.back().wedge_over_skin_depth});
          const std::string tag = "_" + std::to_string(i + 1);
          context.summary.add("thermal_rate" + tag, rate, "mm/yr");
          context.summary.add("thermal_rate_initial" + tag, 1e3 * r0, "mm/yr");
          context.summary.add("thermal_displacement" + tag,
                              thermal.back().total,
                              "m");
          context.log.line("thermal curve " + std::to_string(i + 1) + " (beta "
                           + io::format_number(betas[i], 3) + ", alpha "
                           + io::format_number(alphas[i], 3) + " 1/K): "
                           + io::format_number(1e3 * r0, 4) + " mm/yr at L_W = "
                           + io::format_number(initial_wedge, 3) + " m, "
                           + io::format_number(1e3 * r1, 4)
                           + " mm/yr at 0.2 m; mean over the window "
                           + io::format_number(rate, 4) + " mm/yr");
          if (thermal.back().wedge_over_skin_depth > 1.)
            context.log.record(
              "WARNING: curve " + std::to_string(i + 1)
              + ": the wedge grows beyond the skin depth within the window; "
                "the ratchet model (S_d > L_W) no longer holds there");
        }

      // The catalogues and their motions (serially: FFTW planning).
      seismic::StochasticParameters motion
        = EarthquakeOptions::default_motion();
      if (!masada_site)
        motion.site = seismic::SiteAmplification();
      motion.distance = distance;
      std::vector<std::vector<CatalogueEvent>> catalogue(catalogues);
      std::vector<EventRun>                    runs;
      std::vector<seismic::Record>             records;
      // Catalogues whose motions were made (fewer after SIGINT / SIGTERM).
      unsigned int generated = 0;
      for (unsigned int c = 0; c < catalogues; ++c)
        {
          ++generated;
          catalogue[c]
            = gutenberg_richter_catalogue(gr, window, first_seed + c);
          for (const auto &e : catalogue[c])
            {
              motion.magnitude = e.magnitude;
              EventRun r;
              r.catalogue = c;
              r.event     = e;
              records.push_back(seismic::simulate(motion, e.motion_seed, true));
              r.pga      = records.back().peak();
              r.duration = records.back().duration();
              // Below ky the rigid block does not slide at all (DDA: the
              // contact's elastic give, < 1e-4 m, see test_earthquakes).
              r.triggers = r.pga >= ky;
              if (!r.triggers)
                records.back() = seismic::Record();
              runs.push_back(r);
            }
          if (io::interrupt_signal() != 0)
            break;
        }
      const double motion_seconds = since();

      // DDA and the rigid block for the events that can slide the block.
      std::vector<std::size_t> active;
      for (std::size_t j = 0; j < runs.size(); ++j)
        if (runs[j].triggers)
          active.push_back(j);
      Block1RunControls c = controls;
      c.stop              = []() { return io::interrupt_signal() != 0; };
      const auto done
        = run_concurrently(active.size(), threads, [&](const std::size_t a) {
            EventRun &r  = runs[active[a]];
            r.analytical = block1_analytical_slip(geometry,
                                                  materials,
                                                  records[active[a]],
                                                  r.duration);
            try
              {
                const Block1Run d = run_block1_dda(
                  geometry, materials, records[active[a]], c, r.duration);
                r.dda          = d.slip;
                r.max_rotation = d.max_rotation;
                r.wall_time    = d.wall_time;
                if (d.stopped)
                  r.failure = "interrupted";
              }
            catch (const std::exception &x)
              {
                r.failure = x.what();
              }
            if (!r.failure.empty())
              r.dda = nan;
          });
      for (std::size_t a = 0; a < active.size(); ++a)
        if (!done.done[a])
          {
            runs[active[a]].failure = "not run (interrupted)";
            runs[active[a]].dda = runs[active[a]].analytical = nan;
          }
      const double dda_seconds = since() - motion_seconds;

      io::Table events;
      events.add_column("catalogue", "-");
      events.add_column("time", "yr");
      events.add_column("magnitude", "-");
      events.add_column("motion_seed", "-");
      events.add_column("pga", "g");
      events.add_column("dda", "m");
      events.add_column("analytical", "m");
      events.add_column("max_rotation", "rad");
      events.add_column("wall_time", "s");
      unsigned int failed = 0, triggering = 0;
      for (const auto &r : runs)
        {
          events.add_row({static_cast<double>(r.catalogue + 1),
                          r.event.time,
                          r.event.magnitude,
                          static_cast<double>(r.event.motion_seed),
                          r.pga,
                          r.dda,
                          r.analytical,
                          r.max_rotation,
                          r.wall_time});
          triggering += r.triggers ? 1 : 0;
          if (!r.failure.empty())
            {
              ++failed;
              context.log.line("catalogue " + std::to_string(r.catalogue + 1)
                               + ", year " + io::format_number(r.event.time, 6)
                               + ", Mw "
                               + io::format_number(r.event.magnitude, 3)
                               + ": DDA failed: " + r.failure);
            }
        }
      context.output.write("events.csv", events.csv());

      // Per catalogue: seismic alone, thermal alone (curve 1), combined.
      io::Table per;
      per.add_column("catalogue", "-");
      per.add_column("events", "-");
      per.add_column("triggering_events", "-");
      per.add_column("seismic", "m");
      per.add_column("seismic_analytical", "m");
      per.add_column("thermal", "m");
      per.add_column("sum", "m");
      per.add_column("combined", "m");
      per.add_column("interaction", "m");
      per.add_column("combined_over_sum", "-");
      per.add_column("final_wedge_length", "m");
      std::vector<double>              seismic, combined, sum, interaction;
      std::vector<double>              ratio, seismic_rigid;
      std::vector<std::vector<double>> yearly;
      unsigned int                     complete = 0;
      for (unsigned int k = 0; k < generated; ++k)
        {
          std::vector<CatalogueEvent> ev;
          std::vector<double>         slip;
          double                      rigid     = 0.;
          bool                        ok        = true;
          unsigned int                n_trigger = 0, n_events = 0;
          for (const auto &r : runs)
            if (r.catalogue == k)
              {
                ++n_events;
                n_trigger += r.triggers ? 1 : 0;
                ev.push_back(r.event);
                slip.push_back(r.triggers ? r.dda : 0.);
                rigid += r.triggers ? r.analytical : 0.;
                ok = ok && r.failure.empty();
              }
          if (!ok || (n_events < catalogue[k].size()))
            continue;
          ++complete;
          double s = 0.;
          for (const double x : slip)
            s += x;
          const HistoryResult h
            = combined_history(ratchet_input(0), years, ev, slip, true);
          const double both = thermal[0].total + s;
          per.add_row({static_cast<double>(k + 1),
                       static_cast<double>(n_events),
                       static_cast<double>(n_trigger),
                       s,
                       rigid,
                       thermal[0].total,
                       both,
                       h.total,
                       h.total - both,
                       h.total / both,
                       h.wedge_length});
          seismic.push_back(s);
          seismic_rigid.push_back(rigid);
          combined.push_back(h.total);
          sum.push_back(both);
          interaction.push_back(h.total - both);
          ratio.push_back(h.total / both);
          yearly.push_back(h.yearly);
        }
      context.output.write("catalogues.csv", per.csv());
      context.output.write("statistics.csv", per.csv());

      // Cumulative histories every 10 years: thermal alone, and the
      // spread of the combined history over the catalogues.
      io::Table hist;
      hist.add_column("year", "-");
      hist.add_column("thermal", "m");
      hist.add_column("combined_p16", "m");
      hist.add_column("combined_median", "m");
      hist.add_column("combined_p84", "m");
      const unsigned int every = std::max(1u, years / 500);
      for (unsigned int y = 0; y < years; ++y)
        if ((y + 1) % every == 0 || y + 1 == years)
          {
            std::vector<double> v;
            for (const auto &h : yearly)
              v.push_back(h[y]);
            const Spread sp = spread(v);
            hist.add_row({static_cast<double>(y + 1),
                          thermal[0].yearly[y],
                          sp.p16,
                          sp.median,
                          sp.p84});
          }
      context.output.write("histories.csv", hist.csv());

      // Fig. 5-19: the rates.
      const auto   rate = [&](const double x) { return 1e3 * x / years; };
      const Spread ss = spread(seismic), sr = spread(seismic_rigid),
                   sc = spread(combined), su = spread(sum),
                   si = spread(interaction), sq = spread(ratio);
      // The spreads also go to spreads.csv: the plot runs before the driver
      // writes summary.csv.
      io::Table spreads;
      spreads.add_column("quantity", "-");
      spreads.add_column("rate_median", "mm/yr");
      spreads.add_column("rate_p16", "mm/yr");
      spreads.add_column("rate_p84", "mm/yr");
      double quantity = 0.;
      for (const auto &[name, sp] :
           std::vector<std::pair<std::string, Spread>>{{"seismic", ss},
                                                       {"seismic_rigid", sr},
                                                       {"combined", sc},
                                                       {"sum", su}})
        {
          context.summary.add(name + "_rate_median", rate(sp.median), "mm/yr");
          context.summary.add(name + "_rate_p16", rate(sp.p16), "mm/yr");
          context.summary.add(name + "_rate_p84", rate(sp.p84), "mm/yr");
          spreads.add_row(
            {quantity++, rate(sp.median), rate(sp.p16), rate(sp.p84)});
        }
      context.output.write("spreads.csv", spreads.csv());
      context.summary.add("interaction_median", si.median, "m");
      context.summary.add("interaction_p16", si.p16, "m");
      context.summary.add("interaction_p84", si.p84, "m");
      context.summary.add("combined_over_sum_median", sq.median, "-");
      context.summary.add("combined_over_sum_p16", sq.p16, "-");
      context.summary.add("combined_over_sum_p84", sq.p84, "-");
      context.summary.add("yield_acceleration", ky, "g");
      context.summary.add("catalogues_complete", complete, "-");
      context.summary.add("events", static_cast<double>(runs.size()), "-");
      context.summary.add("triggering_events", triggering, "-");
      context.summary.add("failed_runs", failed, "-");
      context.summary.add("concurrent_runs", done.threads, "-");
      context.summary.add("motion_wall_time", motion_seconds, "s");
      context.summary.add("dda_wall_time", dda_seconds, "s");
      context.output.write("rates.csv", rates.csv());
      context.log.line(
        std::to_string(runs.size()) + " events (" + std::to_string(triggering)
        + " with PGA >= ky through DDA) in " + std::to_string(complete)
        + " complete catalogues; motions "
        + io::format_number(motion_seconds, 3) + " s, DDA "
        + io::format_number(dda_seconds, 3) + " s");
      context.log.line(
        "rates over " + std::to_string(years)
        + " yr (median, 16-84 %): "
          "seismic "
        + io::format_number(rate(ss.median), 3) + " ("
        + io::format_number(rate(ss.p16), 3) + "-"
        + io::format_number(rate(ss.p84), 3) + ") mm/yr, thermal "
        + io::format_number(rate(thermal[0].total), 3) + " mm/yr, combined "
        + io::format_number(rate(sc.median), 3) + " ("
        + io::format_number(rate(sc.p16), 3) + "-"
        + io::format_number(rate(sc.p84), 3)
        + ") mm/yr; combined / (thermal + seismic) "
        + io::format_number(sq.median, 4) + " (" + io::format_number(sq.p16, 4)
        + "-" + io::format_number(sq.p84, 4) + ")");
      if (io::interrupt_signal() != 0)
        {
          context.stopped_early = true;
          context.stopped_note  = std::to_string(complete) + " of "
                                 + std::to_string(catalogues)
                                 + " catalogues complete (catalogues.csv, "
                                   "events.csv; the others left out).";
        }
      else if (plot)
        io::run_plot_script(context.output,
                            context.log,
                            "plot_compare.py",
                            {"compare.png"});
    }
  } // namespace



  std::unique_ptr<io::Analysis>
  make_compare_analysis()
  {
    return std::make_unique<CompareAnalysis>();
  }
} // namespace rockdda::coupling
