/**
 * @file
 * Analysis type "newmark": rigid-block sliding under one acceleration
 * component (Newmark 1965), or a flexible sliding mass (decoupled or
 * coupled, Rathje & Bray 2000, as SLAMMER), driven by the "Ground motion"
 * and "Newmark" sections.
 */
#include <rockdda/analytical/analyses.h>
#include <rockdda/analytical/newmark.h>
#include <rockdda/io/data_file.h>
#include <rockdda/io/error.h>
#include <rockdda/io/parameters.h>
#include <rockdda/io/progress.h>
#include <rockdda/seismic/flexible_sliding.h>
#include <rockdda/seismic/ground_motion.h>

#include <cmath>

namespace rockdda::analytical
{
  namespace
  {
    using dealii::Patterns::Double;

    /// The "newmark" analysis.
    class NewmarkAnalysis : public io::Analysis
    {
    public:
      std::string
      name() const override
      {
        return "newmark";
      }

      std::string
      description() const override
      {
        return "1D rigid-block (Newmark) or flexible (decoupled, coupled) "
               "sliding under an acceleration record";
      }

      void
      declare_parameters(dealii::ParameterHandler &prm) const override
      {
        declare_friction_parameters(prm);
        prm.enter_subsection("Newmark");
        io::declare(prm,
                    "Sliding direction",
                    "downslope",
                    dealii::Patterns::Selection("downslope|two-way"),
                    "-",
                    "'downslope': the block slides only when a > ky (as "
                    "SLAMMER); 'two-way': also upslope when a < -ky "
                    "(symmetric yield), or by the plane geometry.");
        io::declare(prm,
                    "Yield model",
                    "constant",
                    dealii::Patterns::Selection("constant|table|plane"),
                    "-",
                    "'constant': ky below; 'table': ky against cumulative "
                    "sliding distance from 'Yield table file'; 'plane': a "
                    "block on a plane of dip 'Plane dip' with the 'Friction' "
                    "law, loaded by horizontal inertial acceleration "
                    "(positive downslope).");
        io::declare(prm,
                    "Yield acceleration",
                    "0.1",
                    Double(0.),
                    "g",
                    "Constant yield (critical) acceleration ky.");
        io::declare(prm,
                    "Yield table file",
                    "",
                    dealii::Patterns::Anything(),
                    "-",
                    "Two columns: cumulative sliding distance (m, "
                    "increasing) and ky (g); linear in between, constant "
                    "beyond the ends.");
        io::declare(prm,
                    "Plane dip",
                    "20",
                    io::DoubleInterval::right_open(0., 90.),
                    "deg",
                    "Dip of the sliding plane (plane model), 0 <= dip < 90.");
        io::declare(prm,
                    "Friction angle",
                    "30",
                    io::DoubleInterval::right_open(0., 90.),
                    "deg",
                    "Friction angle phi of the plane (plane model), 0 <= phi "
                    "< 90; the reference coefficient of the Friction law.");
        io::declare(prm,
                    "Integration time step",
                    "0",
                    Double(0.),
                    "s",
                    "Time step of the integration; 0 uses the record's dt. "
                    "A smaller step sub-steps with linear interpolation of "
                    "the record.");
        io::declare(prm,
                    "Event location",
                    "within step",
                    dealii::Patterns::Selection("within step|at samples"),
                    "-",
                    "'within step': sliding starts where the interpolated "
                    "input crosses ky and stops where the relative velocity "
                    "returns to zero inside the step (exact for the linearly "
                    "interpolated "
                    "record); 'at "
                    "samples': both at step ends, as SLAMMER (less accurate in "
                    "general; "
                    "reproduces SLAMMER's published results).");
        io::declare(prm,
                    "Output interval",
                    "0",
                    Double(0.),
                    "s",
                    "Spacing of rows in statistics.csv; 0 writes every "
                    "step.");
        io::declare(prm,
                    "Sliding mass",
                    "rigid",
                    dealii::Patterns::Selection("rigid|decoupled|coupled"),
                    "-",
                    "'rigid': a rigid block (Newmark 1965); 'decoupled': a "
                    "deformable mass whose first-mode average acceleration "
                    "k(t) drives a rigid block; 'coupled': the mode and the "
                    "sliding are integrated together, the base force capped "
                    "at ky times the weight (Rathje & Bray 2000, as USGS "
                    "SLAMMER). Flexible masses need 'Yield model' constant "
                    "and 'Sliding direction' downslope; see 'Site response' "
                    "and doc/theory/flexible-sliding.md.");
        prm.enter_subsection("Site response");
        io::declare(prm,
                    "Model",
                    "linear-elastic",
                    dealii::Patterns::Selection(
                      "linear-elastic|equivalent-linear"),
                    "-",
                    "Properties of the flexible sliding mass: "
                    "'linear-elastic' uses Vs and damping as given; "
                    "'equivalent-linear' iterates strain-compatible Vs and "
                    "damping (hyperbolic G/Gmax with the reference strain, "
                    "Darendeli damping), as SLAMMER.");
        io::declare(prm,
                    "Height",
                    "10",
                    io::DoubleInterval::positive(),
                    "m",
                    "Height H of the sliding mass (> 0); its fundamental "
                    "period is 4 H / Vs.");
        io::declare(prm,
                    "Shear-wave velocity",
                    "300",
                    io::DoubleInterval::positive(),
                    "m/s",
                    "Shear-wave velocity Vs of the sliding mass (> 0); the "
                    "small-strain value for 'equivalent-linear'.");
        io::declare(prm,
                    "Base shear-wave velocity",
                    "600",
                    io::DoubleInterval::positive(),
                    "m/s",
                    "Shear-wave velocity Vr of the base (> 0); it sets the "
                    "base-impedance damping 0.55016 (Vr/Vs)^-0.9904, at most "
                    "0.20, added to 'Damping ratio'.");
        io::declare(prm,
                    "Damping ratio",
                    "0.05",
                    Double(-1., 1.),
                    "-",
                    "Damping ratio of the sliding mass, a fraction in [-1, "
                    "1] (0.05 = 5 %), to which the base-impedance damping is "
                    "added; the sum may not be negative (SLAMMER accepts a "
                    "negative ratio). 'equivalent-linear' uses it in the "
                    "first iteration only.");
        io::declare(prm,
                    "Reference strain",
                    "0.0005",
                    io::DoubleInterval::positive(),
                    "-",
                    "Reference shear strain gamma_r of G/Gmax = 1/(1 + "
                    "gamma/gamma_r), a fraction (> 0; 0.0005 = 0.05 %, "
                    "SLAMMER's default); 'equivalent-linear' only.");
        io::declare(prm,
                    "Substeps",
                    "1",
                    dealii::Patterns::Integer(1),
                    "-",
                    "Integration steps per record sample, >= 1 (1 = "
                    "SLAMMER); the record is interpolated linearly between "
                    "samples. Raise it for a stiff mass whose period 4 H / "
                    "Vs is below about ten samples.");
        prm.leave_subsection();
        prm.leave_subsection();
      }

      void
      parse_parameters(dealii::ParameterHandler &prm,
                       const std::string        &prm_file) override
      {
        motion.parse_parameters(prm, prm_file);
        prm.enter_subsection("Newmark");
        options.direction       = prm.get("Sliding direction") == "downslope"
                                    ? NewmarkOptions::Direction::downslope
                                    : NewmarkOptions::Direction::two_way;
        const std::string model = prm.get("Yield model");
        options.yield_model
          = model == "constant" ? NewmarkOptions::YieldModel::constant
            : model == "table"  ? NewmarkOptions::YieldModel::table
                                : NewmarkOptions::YieldModel::plane;
        options.ky              = prm.get_double("Yield acceleration");
        options.dip_deg         = prm.get_double("Plane dip");
        options.time_step       = prm.get_double("Integration time step");
        options.output_interval = prm.get_double("Output interval");
        options.event_location  = prm.get("Event location") == "within step"
                                    ? NewmarkOptions::EventLocation::within_step
                                    : NewmarkOptions::EventLocation::at_samples;
        const double      phi   = prm.get_double("Friction angle");
        const std::string table = prm.get("Yield table file");
        const std::string mass  = prm.get("Sliding mass");
        flexible                = mass != "rigid";
        flexible_options.coupling
          = mass == "coupled"
              ? seismic::FlexibleSlidingOptions::Coupling::coupled
              : seismic::FlexibleSlidingOptions::Coupling::decoupled;
        flexible_options.ky = options.ky;
        prm.enter_subsection("Site response");
        auto &site            = flexible_options.site;
        site.model            = prm.get("Model") == "equivalent-linear"
                                  ? seismic::SiteResponseOptions::Model::equivalent_linear
                                  : seismic::SiteResponseOptions::Model::linear_elastic;
        site.height           = prm.get_double("Height");
        site.vs_slope         = prm.get_double("Shear-wave velocity");
        site.vs_base          = prm.get_double("Base shear-wave velocity");
        site.damping          = prm.get_double("Damping ratio");
        site.reference_strain = prm.get_double("Reference strain");
        site.substeps         = prm.get_integer("Substeps");
        site.g                = options.g;
        prm.leave_subsection();
        prm.leave_subsection();

        if (flexible)
          {
            if (options.yield_model != NewmarkOptions::YieldModel::constant)
              throw InputError(prm_file
                               + ": key 'Newmark/Yield model' must be "
                                 "constant when 'Newmark/Sliding mass' is "
                               + mass + " (valid: constant)");
            if (options.direction != NewmarkOptions::Direction::downslope)
              throw InputError(prm_file
                               + ": key 'Newmark/Sliding direction' must be "
                                 "downslope when 'Newmark/Sliding mass' is "
                               + mass + " (valid: downslope)");
            io::with_parameter_file(prm_file, [&]() {
              try
                {
                  seismic::validate(site);
                }
              catch (const InputError &e)
                {
                  throw InputError(std::string("section 'Newmark/Site "
                                               "response': ")
                                   + e.what());
                }
            });
          }

        if (options.yield_model == NewmarkOptions::YieldModel::plane)
          {
            io::require(options.dip_deg >= 0. && options.dip_deg < 90.,
                        prm_file,
                        "Newmark/Plane dip",
                        options.dip_deg,
                        "0 <= dip < 90 deg");
            options.friction
              = parse_friction(prm, prm_file, phi, "Newmark/Friction angle");
          }
        if (options.yield_model == NewmarkOptions::YieldModel::table)
          {
            if (table.empty())
              throw InputError(prm_file
                               + ": key 'Newmark/Yield table file' is empty "
                                 "but 'Yield model' is table");
            const auto columns = io::read_columns(
              io::resolve_path(table, prm_file, "Newmark/Yield table file"),
              2,
              2);
            options.table_displacement = columns[0];
            options.table_ky           = columns[1];
          }
        io::with_parameter_file(prm_file, [&]() { validate(options); });
      }

      void
      run(io::RunContext &context) override
      {
        context.log.line("input motion: " + motion.description);
        if (flexible)
          {
            run_flexible(context);
            return;
          }
        std::vector<std::pair<std::string, double>> runs;
        if (motion.polarity != seismic::GroundMotionInput::Polarity::inverted)
          runs.emplace_back("normal", 1.);
        if (motion.polarity != seismic::GroundMotionInput::Polarity::normal)
          runs.emplace_back("inverted", -1.);

        io::Table                  table;
        std::vector<NewmarkResult> results;
        for (const auto &[label, sign] : runs)
          {
            seismic::Record record = motion.record;
            seismic::scale(record, sign);
            io::ProgressBar progress("newmark " + label, record.duration());
            results.push_back(newmark_sliding(record, options));
            const NewmarkResult &r = results.back();
            const std::string    s = runs.size() > 1 ? "_" + label : "";
            context.summary.add("final_displacement" + s,
                                r.final_displacement,
                                "m");
            context.summary.add("max_velocity" + s, r.max_velocity, "m/s");
            context.summary.add("slip_events" + s, r.n_slip_events, "-");
            context.summary.add("sliding_duration" + s,
                                r.sliding_duration,
                                "s");
            context.summary.add("steps" + s, r.n_steps, "-");
            context.log.line("polarity " + label + ": final displacement "
                             + io::format_number(100. * r.final_displacement, 6)
                             + " cm after " + std::to_string(r.n_slip_events)
                             + " slip events");
          }

        // Harmonic input with constant ky, downslope only: the exact
        // displacement is known in closed form (doc/theory/newmark-harmonic).
        if (motion.harmonic_omega > 0. && runs.size() == 1
            && runs[0].second > 0. && motion.harmonic_amplitude > options.ky
            && options.yield_model == NewmarkOptions::YieldModel::constant
            && options.direction == NewmarkOptions::Direction::downslope)
          {
            const double exact
              = options.g
                * harmonic_sliding_displacement(motion.harmonic_amplitude,
                                                motion.harmonic_omega,
                                                options.ky,
                                                motion.record.duration());
            const double error
              = std::abs(results[0].final_displacement - exact) / exact;
            context.summary.add("exact_displacement", exact, "m");
            context.summary.add("relative_error", error, "-");
            context.log.line(
              "closed-form displacement " + io::format_number(exact, 8)
              + " m, relative error " + io::format_number(error, 3));
          }

        table.add_column("time", "s");
        for (const auto &[label, sign] : runs)
          {
            const std::string s = runs.size() > 1 ? "_" + label : "";
            table.add_column("acceleration" + s, "g");
            table.add_column("velocity" + s, "m/s");
            table.add_column("displacement" + s, "m");
            table.add_column("sliding" + s, "-");
          }
        const auto         &t0 = results[0].time;
        std::vector<double> row(1 + 4 * results.size());
        for (std::size_t i = 0; i < t0.size(); ++i)
          {
            row[0] = t0[i];
            for (std::size_t k = 0; k < results.size(); ++k)
              {
                const auto &r      = results[k];
                row[1 + 4 * k]     = r.acceleration[i];
                row[1 + 4 * k + 1] = r.velocity[i];
                row[1 + 4 * k + 2] = r.displacement[i];
                row[1 + 4 * k + 3] = r.state[i];
              }
            table.add_row(row);
          }
        context.output.write("statistics.csv", table.csv());
      }

    private:
      /// The decoupled or coupled analysis of a flexible sliding mass, in
      /// the requested polarities; the summary adds the site response.
      void
      run_flexible(io::RunContext &context) const
      {
        std::vector<std::pair<std::string, double>> runs;
        if (motion.polarity != seismic::GroundMotionInput::Polarity::inverted)
          runs.emplace_back("normal", 1.);
        if (motion.polarity != seismic::GroundMotionInput::Polarity::normal)
          runs.emplace_back("inverted", -1.);

        const auto  &site   = flexible_options.site;
        const double period = 4. * site.height / site.vs_slope;
        const double step   = motion.record.dt / site.substeps;
        context.log.line(
          std::string("flexible sliding mass, ")
          + (flexible_options.coupling
                 == seismic::FlexibleSlidingOptions::Coupling::coupled
               ? "coupled"
               : "decoupled")
          + " analysis, "
          + (site.model
                 == seismic::SiteResponseOptions::Model::equivalent_linear
               ? "equivalent-linear"
               : "linear-elastic")
          + " site response; small-strain period "
          + io::format_number(period, 4) + " s");
        if (period < 10. * step)
          context.log.line(
            "warning: the period 4 H / Vs = " + io::format_number(period, 4)
            + " s is shorter than ten integration steps ("
            + io::format_number(step, 4)
            + " s): raise 'Newmark/Site response/Substeps' (the coupled "
              "analysis is inaccurate for a stiff mass)");

        std::vector<seismic::FlexibleSlidingResult> results;
        for (const auto &[label, sign] : runs)
          {
            seismic::Record record = motion.record;
            seismic::scale(record, sign);
            results.push_back(
              seismic::flexible_sliding(record, flexible_options));
            const auto       &r = results.back();
            const std::string s = runs.size() > 1 ? "_" + label : "";
            context.summary.add("final_displacement" + s,
                                r.final_displacement,
                                "m");
            context.summary.add("max_velocity" + s, r.max_velocity, "m/s");
            context.summary.add("slip_events" + s, r.n_slip_events, "-");
            context.summary.add("sliding_duration" + s,
                                r.sliding_duration,
                                "s");
            context.summary.add("steps" + s, r.time.size() - 1, "-");
            context.log.line("polarity " + label + ": final displacement "
                             + io::format_number(100. * r.final_displacement, 6)
                             + " cm after " + std::to_string(r.n_slip_events)
                             + " slip events");
          }
        const seismic::SiteResponse &response = results[0].site;
        context.summary.add("kmax", std::abs(response.kmax), "g");
        context.summary.add("vs_final", response.vs, "m/s");
        context.summary.add("damping_final", response.damping, "-");
        context.summary.add("period_final", response.period, "s");
        context.summary.add("site_iterations", response.iterations, "-");
        context.log.line(
          "site response: kmax " + io::format_number(std::abs(response.kmax), 5)
          + " g, Vs " + io::format_number(response.vs, 5) + " m/s, damping "
          + io::format_number(response.damping, 4) + ", period "
          + io::format_number(response.period, 4) + " s"
          + (response.iterations > 0
               ? ", " + std::to_string(response.iterations)
                   + " equivalent-linear iterations"
               : std::string()));
        if (!response.converged)
          context.log.line("warning: the equivalent-linear iteration did not "
                           "converge");

        io::Table table;
        table.add_column("time", "s");
        for (const auto &[label, sign] : runs)
          {
            const std::string s = runs.size() > 1 ? "_" + label : "";
            table.add_column("acceleration" + s, "g");
            table.add_column("k" + s, "g");
            table.add_column("velocity" + s, "m/s");
            table.add_column("displacement" + s, "m");
            table.add_column("sliding" + s, "-");
          }
        const auto         &time = results[0].time;
        std::vector<double> row(1 + 5 * results.size());
        double              next_output = 0.;
        for (std::size_t i = 0; i < time.size(); ++i)
          {
            if (options.output_interval > 0. && i + 1 < time.size()
                && time[i] < next_output - 1e-9 * step)
              continue;
            while (options.output_interval > 0.
                   && next_output <= time[i] + 1e-9 * step)
              next_output += options.output_interval;
            row[0] = time[i];
            for (std::size_t k = 0; k < results.size(); ++k)
              {
                const auto &r      = results[k];
                row[1 + 5 * k]     = runs[k].second * motion.record.at(time[i]);
                row[1 + 5 * k + 1] = r.driving[i];
                row[1 + 5 * k + 2] = r.velocity[i];
                row[1 + 5 * k + 3] = r.displacement[i];
                row[1 + 5 * k + 4] = r.state[i];
              }
            table.add_row(row);
          }
        context.output.write("statistics.csv", table.csv());
      }

      seismic::GroundMotionInput      motion;
      NewmarkOptions                  options;
      bool                            flexible = false;
      seismic::FlexibleSlidingOptions flexible_options;
    };
  } // namespace



  std::unique_ptr<io::Analysis>
  internal::make_newmark_analysis()
  {
    return std::make_unique<NewmarkAnalysis>();
  }
} // namespace rockdda::analytical
