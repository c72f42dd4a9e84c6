/**
 * @file
 * Analysis types "rate-and-state" (Dieterich-Ruina friction integrated with
 * CVODE: velocity step, spring-slider, sliding block) and "back-analysis"
 * (piecewise-constant friction angles from a measured displacement history,
 * and a fit of A - B to friction-velocity data; thesis Sec. 4.7, Table 4-2).
 */
#include <rockdda/analytical/analyses.h>
#include <rockdda/analytical/back_analysis.h>
#include <rockdda/analytical/rate_state.h>
#include <rockdda/io/data_file.h>
#include <rockdda/io/error.h>
#include <rockdda/io/parameters.h>
#include <rockdda/seismic/ground_motion.h>

#include <cmath>

namespace rockdda::analytical
{
  namespace
  {
    using dealii::Patterns::Double;

    /// Write a rate-and-state history as statistics.csv.
    void
    write_history(const RateStateHistory &h, io::RunContext &context)
    {
      io::Table table;
      table.add_column("time", "s");
      table.add_column("slip", "m");
      table.add_column("slip_rate", "m/s");
      table.add_column("state", "s");
      table.add_column("friction", "-");
      for (std::size_t i = 0; i < h.time.size(); ++i)
        table.add_row(
          {h.time[i], h.displacement[i], h.velocity[i], h.theta[i], h.mu[i]});
      context.output.write("statistics.csv", table.csv());
      context.summary.add("final_slip", h.displacement.back(), "m");
      context.summary.add("final_slip_rate", h.velocity.back(), "m/s");
      context.summary.add("final_state", h.theta.back(), "s");
      context.summary.add("final_friction", h.mu.back(), "-");
      // Over every integrator step, not only the rows of statistics.csv.
      double vmax = h.max_abs_velocity;
      for (const double v : h.velocity)
        vmax = std::max(vmax, std::abs(v));
      context.summary.add("max_slip_rate", vmax, "m/s");
    }

    /// The "rate-and-state" analysis.
    class RateStateAnalysis : public io::Analysis
    {
    public:
      std::string
      name() const override
      {
        return "rate-and-state";
      }

      std::string
      description() const override
      {
        return "Dieterich-Ruina rate-and-state friction (aging law) "
               "integrated with CVODE: velocity step, spring-slider or "
               "sliding block";
      }

      void
      declare_parameters(dealii::ParameterHandler &prm) const override
      {
        prm.enter_subsection("Rate and state");
        io::declare(prm,
                    "Experiment",
                    "velocity step",
                    dealii::Patterns::Selection(
                      "velocity step|spring-slider|sliding block"),
                    "-",
                    "'velocity step': imposed slip rate V1 then V2; "
                    "'spring-slider': a block pulled through a spring at "
                    "the load-point velocity; 'sliding block': a block on a "
                    "plane under gravity and the Ground motion record "
                    "(horizontal, + downslope).");
        io::declare(prm,
                    "Reference friction coefficient",
                    "0.6",
                    Double(0.),
                    "-",
                    "mu0 of Eq. 2.1, at the reference slip rate V0.");
        io::declare(prm,
                    "A",
                    "0.01",
                    io::DoubleInterval::positive(),
                    "-",
                    "Direct-effect parameter A (> 0).");
        io::declare(prm,
                    "B",
                    "0.015",
                    Double(0.),
                    "-",
                    "Evolution-effect parameter B (>= 0).");
        io::declare(prm,
                    "Reference velocity",
                    "1e-6",
                    io::DoubleInterval::positive(),
                    "m/s",
                    "Reference slip rate V0 (> 0).");
        io::declare(prm,
                    "Characteristic slip distance",
                    "1e-5",
                    io::DoubleInterval::positive(),
                    "m",
                    "Dc of the aging law, Eq. 2.2 (> 0).");
        io::declare(prm,
                    "Initial velocity",
                    "1e-6",
                    io::DoubleInterval::positive(),
                    "m/s",
                    "Velocity step: slip rate V1 before the step; "
                    "spring-slider: initial slip rate (a value other than "
                    "the load-point velocity perturbs steady sliding) (> "
                    "0).");
        io::declare(prm,
                    "Final velocity",
                    "1e-5",
                    io::DoubleInterval::positive(),
                    "m/s",
                    "Velocity step: slip rate V2 after the step (> 0).");
        io::declare(prm,
                    "Load point velocity",
                    "1e-6",
                    io::DoubleInterval::positive(),
                    "m/s",
                    "Spring-slider: velocity of the load point (> 0).");
        io::declare(prm,
                    "Stiffness",
                    "100",
                    io::DoubleInterval::positive(),
                    "1/m",
                    "Spring-slider: stiffness per unit normal stress "
                    "K/(sigma S) (> 0). Steady sliding is unstable below "
                    "(B - A)/Dc.");
        io::declare(prm,
                    "Radiation damping",
                    "0",
                    Double(0.),
                    "s/m",
                    "Spring-slider: radiation damping per unit normal "
                    "stress G/(2 c_s sigma) (Rice 1993); 0 = none.");
        io::declare(prm,
                    "Mass",
                    "0",
                    Double(0.),
                    "s^2/m",
                    "Spring-slider: mass per unit normal force M/(sigma "
                    "S); 0 = quasi-static.");
        io::declare(prm,
                    "Plane dip",
                    "30",
                    io::DoubleInterval::right_open(0., 90.),
                    "deg",
                    "Sliding block: dip of the plane, 0 <= dip < 90.");
        io::declare(prm,
                    "Use ground motion",
                    "false",
                    dealii::Patterns::Bool(),
                    "-",
                    "Sliding block: load by the Ground motion record "
                    "(true) or by gravity alone (false).");
        io::declare(prm,
                    "Duration",
                    "100",
                    io::DoubleInterval::positive(),
                    "s",
                    "End time (> 0).");
        io::declare(prm,
                    "Output interval",
                    "1",
                    io::DoubleInterval::positive(),
                    "s",
                    "Spacing of rows in statistics.csv (> 0).");
        io::declare(prm,
                    "Relative tolerance",
                    "1e-8",
                    io::DoubleInterval::positive(),
                    "-",
                    "CVODE relative tolerance (> 0): the accuracy knob.");
        io::declare(prm,
                    "Absolute tolerance",
                    "1e-12",
                    io::DoubleInterval::positive(),
                    "-",
                    "CVODE absolute tolerance on each unknown, in its "
                    "unit (> 0).");
        prm.leave_subsection();
      }

      void
      parse_parameters(dealii::ParameterHandler &prm,
                       const std::string        &prm_file) override
      {
        prm.enter_subsection("Rate and state");
        experiment   = prm.get("Experiment");
        friction.mu0 = prm.get_double("Reference friction coefficient");
        friction.a   = prm.get_double("A");
        friction.b   = prm.get_double("B");
        friction.v0  = prm.get_double("Reference velocity");
        friction.dc  = prm.get_double("Characteristic slip distance");
        v1           = prm.get_double("Initial velocity");
        v2           = prm.get_double("Final velocity");
        slider.load_point_velocity  = prm.get_double("Load point velocity");
        slider.stiffness            = prm.get_double("Stiffness");
        slider.radiation_damping    = prm.get_double("Radiation damping");
        slider.mass                 = prm.get_double("Mass");
        block.dip_deg               = prm.get_double("Plane dip");
        use_motion                  = prm.get_bool("Use ground motion");
        duration                    = prm.get_double("Duration");
        output_interval             = prm.get_double("Output interval");
        settings.relative_tolerance = prm.get_double("Relative tolerance");
        settings.absolute_tolerance = prm.get_double("Absolute tolerance");
        prm.leave_subsection();

        const std::string s = "Rate and state/";
        io::require(duration > 0., prm_file, s + "Duration", duration, "> 0 s");
        io::require(output_interval > 0. && duration / output_interval < 1e8,
                    prm_file,
                    s + "Output interval",
                    output_interval,
                    "> 0 s and at most 1e8 rows");
        io::require(settings.relative_tolerance > 0.
                      && settings.relative_tolerance < 1.,
                    prm_file,
                    s + "Relative tolerance",
                    settings.relative_tolerance,
                    "0 < rtol < 1");
        io::require(settings.absolute_tolerance > 0.,
                    prm_file,
                    s + "Absolute tolerance",
                    settings.absolute_tolerance,
                    "atol > 0");
        io::with_parameter_file(prm_file, [&]() { friction.validate(); });
        slider.friction = friction;
        block.friction  = friction;
        if (experiment == "velocity step")
          {
            io::require(
              v1 > 0., prm_file, s + "Initial velocity", v1, "> 0 m/s");
            io::require(v2 > 0., prm_file, s + "Final velocity", v2, "> 0 m/s");
          }
        else if (experiment == "spring-slider")
          {
            slider.initial_velocity = v1;
            io::with_parameter_file(prm_file, [&]() { slider.validate(); });
          }
        else
          {
            io::require(block.dip_deg < 90.,
                        prm_file,
                        s + "Plane dip",
                        block.dip_deg,
                        "0 <= dip < 90 deg");
            io::with_parameter_file(prm_file, [&]() { block.validate(); });
            if (use_motion)
              {
                motion.parse_parameters(prm, prm_file);
                if (motion.polarity
                    == seismic::GroundMotionInput::Polarity::both)
                  throw InputError(prm_file
                                   + ": key 'Ground motion/Polarity' = both is "
                                     "not supported here; valid: normal or "
                                     "inverted");
              }
          }
      }

      void
      run(io::RunContext &context) override
      {
        const auto n
          = static_cast<unsigned int>(std::ceil(duration / output_interval));
        context.log.line("experiment: " + experiment);
        RateStateHistory h;
        if (experiment == "velocity step")
          {
            h = velocity_step(friction, v1, v2, duration, n, settings);
            context.summary.add("direct_effect",
                                h.mu.front()
                                  - steady_state_friction(friction, v1),
                                "-");
            context.summary.add("expected_direct_effect",
                                friction.a * std::log(v2 / v1),
                                "-");
            context.summary.add("expected_steady_state_friction",
                                steady_state_friction(friction, v2),
                                "-");
          }
        else if (experiment == "spring-slider")
          {
            h = spring_slider(slider, duration, n, settings);
            context.summary.add("critical_stiffness",
                                critical_stiffness(friction),
                                "1/m");
          }
        else
          {
            seismic::Record record;
            if (use_motion)
              {
                record = motion.record;
                if (motion.polarity
                    == seismic::GroundMotionInput::Polarity::inverted)
                  seismic::scale(record, -1.);
                context.log.line("input motion: " + motion.description);
              }
            h = sliding_block(
              block, record, duration, output_interval, settings);
          }
        write_history(h, context);
      }

    private:
      std::string                experiment;
      RateStateParameters        friction;
      SpringSliderParameters     slider;
      SlidingBlockParameters     block;
      StiffOdeSettings           settings;
      seismic::GroundMotionInput motion;
      bool                       use_motion = false;
      double v1 = 1e-6, v2 = 1e-5, duration = 1., output_interval = 1.;
    };



    /// The "back-analysis" analysis.
    class BackAnalysis : public io::Analysis
    {
    public:
      std::string
      name() const override
      {
        return "back-analysis";
      }

      std::string
      description() const override
      {
        return "friction angles per time segment fitted to a measured "
               "displacement history (thesis Table 4-2), and A - B fitted "
               "to friction-velocity data";
      }

      void
      declare_parameters(dealii::ParameterHandler &prm) const override
      {
        prm.enter_subsection("Back analysis");
        io::declare(prm,
                    "Measured displacement file",
                    "",
                    dealii::Patterns::Anything(),
                    "-",
                    "Two columns: time (s, increasing) and downslope "
                    "displacement (m) of the block; empty = skip the "
                    "friction-angle fit. The input motion is the Ground "
                    "motion section (horizontal, + downslope).");
        io::declare(prm,
                    "Segment boundaries",
                    "",
                    dealii::Patterns::List(Double(0.)),
                    "s",
                    "Comma-separated times that delimit the segments; one "
                    "friction angle is fitted per segment (at least two "
                    "times, strictly increasing).");
        io::declare(prm,
                    "Plane dip",
                    "20",
                    io::DoubleInterval::right_open(0., 90.),
                    "deg",
                    "Dip of the sliding plane, 0 <= dip < 90.");
        io::declare(prm,
                    "Time step",
                    "0.001",
                    io::DoubleInterval::positive(),
                    "s",
                    "Largest integration step of the forward model (> 0).");
        io::declare(prm,
                    "Angle tolerance",
                    "1e-9",
                    io::DoubleInterval::positive(),
                    "deg",
                    "Bisection stops when the friction-angle bracket is "
                    "narrower (> 0).");
        io::declare(prm,
                    "Friction velocity file",
                    "",
                    dealii::Patterns::Anything(),
                    "-",
                    "Two columns: slip rate (m/s, > 0) and friction "
                    "coefficient (-); empty = skip the fit of mu = mu0 + "
                    "(A - B) ln(V/V0).");
        io::declare(prm,
                    "Reference velocity",
                    "1e-6",
                    io::DoubleInterval::positive(),
                    "m/s",
                    "V0 of the fitted steady-state law (> 0).");
        prm.leave_subsection();
      }

      void
      parse_parameters(dealii::ParameterHandler &prm,
                       const std::string        &prm_file) override
      {
        prm.enter_subsection("Back analysis");
        const std::string measured_file = prm.get("Measured displacement file");
        boundaries.clear();
        for (const auto &t : dealii::Utilities::split_string_list(
               prm.get("Segment boundaries")))
          boundaries.push_back(std::stod(t));
        dip                       = prm.get_double("Plane dip");
        time_step                 = prm.get_double("Time step");
        settings.tolerance_deg    = prm.get_double("Angle tolerance");
        const std::string fv_file = prm.get("Friction velocity file");
        v0                        = prm.get_double("Reference velocity");
        prm.leave_subsection();

        parameter_file      = prm_file;
        const std::string s = "Back analysis/";
        if (measured_file.empty() && fv_file.empty())
          throw InputError(prm_file + ": give '" + s
                           + "Measured displacement file' or '" + s
                           + "Friction velocity file' (both are empty)");
        io::require(
          dip < 90., prm_file, s + "Plane dip", dip, "0 <= dip < 90 deg");
        io::require(
          time_step > 0., prm_file, s + "Time step", time_step, "> 0 s");
        io::require(settings.tolerance_deg > 0.,
                    prm_file,
                    s + "Angle tolerance",
                    settings.tolerance_deg,
                    "> 0 deg");
        io::require(v0 > 0., prm_file, s + "Reference velocity", v0, "> 0 m/s");
        if (!measured_file.empty())
          {
            const auto c = io::read_columns(
              io::resolve_path(measured_file,
                               prm_file,
                               s + "Measured displacement file"),
              2,
              2);
            measured.time         = c[0];
            measured.displacement = c[1];
            if (boundaries.size() < 2)
              throw InputError(prm_file + ": key '" + s
                               + "Segment boundaries' needs at least two "
                                 "times (s), strictly increasing");
            motion.parse_parameters(prm, prm_file);
            if (motion.polarity == seismic::GroundMotionInput::Polarity::both)
              throw InputError(prm_file
                               + ": key 'Ground motion/Polarity' = both is not "
                                 "supported here; valid: normal or inverted");
            if (motion.polarity
                == seismic::GroundMotionInput::Polarity::inverted)
              seismic::scale(motion.record, -1.);
          }
        if (!fv_file.empty())
          {
            const auto c = io::read_columns(
              io::resolve_path(fv_file, prm_file, s + "Friction velocity file"),
              2,
              2);
            velocity = c[0];
            mu       = c[1];
          }
        // Run the checks of the fits now, so that bad data is reported by
        // --validate and before anything is written.
        io::with_parameter_file(prm_file, [&]() {
          if (!velocity.empty())
            fit_steady_state_friction(velocity, mu, v0);
        });
      }

      void
      run(io::RunContext &context) override
      {
        io::Table table;
        if (!measured.time.empty())
          {
            std::vector<SegmentFit> fits;
            io::with_parameter_file(parameter_file, [&]() {
              fits = back_analyse_friction_angles(
                measured,
                boundaries,
                plane_sliding_forward_model(motion.record, dip, time_step),
                settings);
            });
            table.add_column("segment_start", "s");
            table.add_column("segment_end", "s");
            table.add_column("friction_angle", "deg");
            table.add_column("measured_displacement", "m");
            table.add_column("computed_displacement", "m");
            table.add_column("average_velocity", "m/s");
            table.add_column("moved", "-");
            table.add_column("bracketed", "-");
            for (std::size_t k = 0; k < fits.size(); ++k)
              {
                const auto &f = fits[k];
                table.add_row({f.t_begin,
                               f.t_end,
                               f.phi_deg,
                               f.measured_displacement,
                               f.computed_displacement,
                               f.average_velocity,
                               static_cast<double>(f.moved),
                               static_cast<double>(f.bracketed)});
                context.summary.add("friction_angle_" + std::to_string(k + 1),
                                    f.phi_deg,
                                    "deg");
                if (!f.bracketed || !f.moved)
                  context.log.line(
                    "warning: segment " + std::to_string(k + 1)
                    + (f.moved ? " is outside the range the model reaches"
                               : " did not move: its angle is a lower bound"));
              }
            context.output.write("statistics.csv", table.csv());
          }
        if (!velocity.empty())
          {
            const auto fit = fit_steady_state_friction(velocity, mu, v0);
            context.summary.add("mu0", fit.mu0, "-");
            context.summary.add("mu0_standard_error",
                                fit.mu0_standard_error,
                                "-");
            context.summary.add("a_minus_b", fit.a_minus_b, "-");
            context.summary.add("a_minus_b_standard_error",
                                fit.a_minus_b_standard_error,
                                "-");
            context.summary.add("r_squared", fit.r_squared, "-");
            if (measured.time.empty())
              {
                io::Table t;
                t.add_column("slip_rate", "m/s");
                t.add_column("friction", "-");
                t.add_column("fitted_friction", "-");
                for (std::size_t i = 0; i < velocity.size(); ++i)
                  t.add_row(
                    {velocity[i],
                     mu[i],
                     fit.mu0 + fit.a_minus_b * std::log(velocity[i] / fit.v0)});
                context.output.write("statistics.csv", t.csv());
              }
          }
      }

    private:
      std::string                parameter_file;
      DisplacementHistory        measured;
      std::vector<double>        boundaries, velocity, mu;
      BackAnalysisSettings       settings;
      seismic::GroundMotionInput motion;
      double                     dip = 20., time_step = 1e-3, v0 = 1e-6;
    };
  } // namespace



  std::unique_ptr<io::Analysis>
  internal::make_rate_state_analysis()
  {
    return std::make_unique<RateStateAnalysis>();
  }



  std::unique_ptr<io::Analysis>
  internal::make_back_analysis()
  {
    return std::make_unique<BackAnalysis>();
  }
} // namespace rockdda::analytical
