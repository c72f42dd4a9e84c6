/**
 * @file
 * Analysis type "calibrate": calibration of DDA's numerical control
 * (thesis 5.5.2, Fig. 5-16). For every penalty k, time step dt, input
 * (a sinusoid A sin(2 pi f t) per frequency f, or the record of the
 * 'Ground motion' section in one or both polarities) and loading mode,
 * Block 1 without infill runs in DDA and is compared with the analytical
 * sliding block by the relative error of the final displacement, Eq. 5.10.
 * The runs are independent and run concurrently, one linear-solver thread
 * each.
 */
#include <rockdda/coupling/analyses.h>
#include <rockdda/coupling/block1_parameters.h>
#include <rockdda/coupling/block1_seismic.h>
#include <rockdda/coupling/calibrate_analysis.h>
#include <rockdda/coupling/concurrent_runs.h>
#include <rockdda/io/error.h>
#include <rockdda/io/interrupt.h>
#include <rockdda/io/parameters.h>
#include <rockdda/io/plot.h>
#include <rockdda/seismic/ground_motion.h>

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
    using dealii::Patterns::Integer;
    using dealii::Patterns::List;
    using dealii::Patterns::Selection;
    using io::DoubleInterval;

    /// One input motion of the grid and its analytical solution.
    struct GridInput
    {
      /// For the log ("f = 1.3 Hz", "record NAME inverted") and the
      /// summary's keys ("_f1.3Hz", "_record", "_record_inverted").
      std::string label, tag;
      /// Sinusoid frequency (Hz); 0 for the record.
      double frequency = 0.;
      /// +1, or -1 for the inverted record.
      double          polarity = 1.;
      seismic::Record record;
      /// Length of the runs (s) and the analytical slip at its end (m).
      double duration = 0., exact = 0.;
    };

    /// One run of the grid and its outcome.
    struct GridRun
    {
      /// Indices into the inputs and the loading modes.
      std::size_t   input = 0, mode = 0;
      double        frequency = 0., penalty = 0., dt = 0.;
      double        analytical = 0., dda = 0., error = 0.;
      double        max_rotation = 0., wall_time = 0.;
      unsigned long steps = 0, cuts = 0;
      /// Empty if the run finished, else why DDA stopped.
      std::string failure;
    };

    /// The values of the list key @p key (all > 0: the pattern checked).
    std::vector<double>
    positive_list(dealii::ParameterHandler &prm,
                  const std::string        &key,
                  const std::string        &prm_file,
                  const std::string        &unit)
    {
      std::vector<double> v;
      for (const auto &s : dealii::Utilities::split_string_list(prm.get(key)))
        {
          const double x = dealii::Utilities::string_to_double(s);
          io::require(x > 0., prm_file, "Calibration/" + key, x, "> 0 " + unit);
          v.push_back(x);
        }
      if (v.empty())
        throw InputError(prm_file + ": key 'Calibration/" + key
                         + "' is empty; give at least one value > 0 " + unit);
      return v;
    }

    class CalibrateAnalysis : public io::Analysis
    {
    public:
      std::string
      name() const override
      {
        return "calibrate";
      }

      std::string
      description() const override
      {
        return "calibration of DDA's penalty and time step on Masada Block 1 "
               "without infill under sinusoids or a record against the "
               "analytical sliding block (thesis 5.5.2, Eq. 5.10, "
               "Fig. 5-16)";
      }

      void
      declare_parameters(dealii::ParameterHandler &prm) const override
      {
        const Block1Geometry  g;
        const Block1Materials m;
        const auto            num
          = [](const double x) { return io::format_number(x, 12); };
        prm.enter_subsection("Calibration");
        io::declare(prm,
                    "Penalties",
                    "1e9, 5e9, 1e10, 1e11, 5e11, 1e12",
                    List(DoubleInterval::positive(), 1, 50, ","),
                    "N/m",
                    "Normal contact penalties k of the grid, each > 0 N/m "
                    "(1 to 50 values; the shear penalty is 0.4 k). Thesis "
                    "Fig. 5-16: 1, 5, 10, 100, 500, 1000 GN/m.");
        io::declare(prm,
                    "Time steps",
                    "0.01, 0.005, 0.002",
                    List(DoubleInterval::positive(), 1, 50, ","),
                    "s",
                    "DDA time steps dt of the grid (maximum step; the engine "
                    "may cut it), each > 0 s (1 to 50 values).");
        io::declare(prm,
                    "Input",
                    "sinusoids",
                    Selection("sinusoids|record"),
                    "-",
                    "What shakes the block: 'sinusoids' (A sin(2 pi f t) "
                    "for each of 'Frequencies', with 'Amplitude', "
                    "'Duration' and 'Record time step') or 'record' (the "
                    "horizontal acceleration of the 'Ground motion' "
                    "section, read, processed and scaled there, e.g. El "
                    "Centro scaled to a target PGA; each run lasts the "
                    "whole processed record, and 'Ground motion/Polarity' = "
                    "both runs the grid for each polarity; its vertical and "
                    "transverse records are not used).");
        io::declare(prm,
                    "Frequencies",
                    "1.3, 3.8",
                    List(DoubleInterval::positive(), 1, 20, ","),
                    "Hz",
                    "Frequencies f of the sinusoidal input A sin(2 pi f t), "
                    "each > 0 Hz (1 to 20 values; Masada's modes: 1.3 and "
                    "3.8 Hz). Input = sinusoids only.");
        io::declare(prm,
                    "Amplitude",
                    "0.5",
                    DoubleInterval(0., true, 5., false),
                    "g",
                    "Amplitude A of the horizontal ground acceleration, "
                    "0 < A <= 5 g (thesis: 0.5 g). Input = sinusoids only.");
        io::declare(prm,
                    "Duration",
                    "5",
                    DoubleInterval(0., true, 1e4, false),
                    "s",
                    "Length of each run and of the input, 0 < T <= 1e4 s; "
                    "Eq. 5.10 compares the displacements at its end. Input "
                    "= sinusoids only (a record runs to its end).");
        io::declare(prm,
                    "Record time step",
                    "0.001",
                    DoubleInterval::positive(),
                    "s",
                    "Sampling of the sinusoid, > 0 s (both solutions "
                    "interpolate it linearly). Input = sinusoids only.");
        io::declare(prm,
                    "Analytical time step",
                    "1e-4",
                    DoubleInterval::positive(),
                    "s",
                    "Integration step of the analytical sliding block, > 0 "
                    "s.");
        io::declare(prm,
                    "Loading mode",
                    "loading",
                    Selection("loading|displacement|both"),
                    "-",
                    "How DDA applies the input: loading (an inertial body "
                    "force -a(t) g on the block), displacement (the base "
                    "follows the double integral of a(t)), or both (the "
                    "whole grid in each mode).");
        io::declare(prm,
                    "Settling steps",
                    "50",
                    Integer(0, 100000),
                    "-",
                    "Static steps under gravity before t = 0, 0 to 100000.");
        io::declare(prm,
                    "Threads",
                    "0",
                    Integer(0, 256),
                    "-",
                    "Runs of the grid at once, 0 to 256 (0: one per core); "
                    "each run's linear solver uses one thread.");
        declare_block1_geometry_keys(prm);
        io::declare(prm,
                    "Toe length",
                    num(g.toe_length),
                    DoubleInterval::positive(),
                    "m",
                    "Horizontal length of the bedding plane beyond the "
                    "block's toe, > 0 m (room to slide).");
        io::declare(prm,
                    "Density",
                    num(m.rock.density),
                    DoubleInterval::positive(),
                    "kg/m^3",
                    "Density of the rock, > 0 kg/m^3.");
        io::declare(prm,
                    "Young's modulus",
                    num(m.rock.young),
                    DoubleInterval::positive(),
                    "Pa",
                    "Young's modulus of the rock, > 0 Pa (plane strain).");
        io::declare(prm,
                    "Poisson's ratio",
                    num(m.rock.poisson),
                    DoubleInterval::right_open(0., 0.5),
                    "-",
                    "Poisson's ratio of the rock, 0 <= nu < 0.5.");
        io::declare(prm,
                    "Plot",
                    "true",
                    Bool(),
                    "-",
                    "Write calibration.png (scripts/plot_calibration.py).");
        prm.leave_subsection();
      }

      void
      parse_parameters(dealii::ParameterHandler &prm,
                       const std::string        &prm_file) override
      {
        prm.enter_subsection("Calibration");
        penalties     = positive_list(prm, "Penalties", prm_file, "N/m");
        time_steps    = positive_list(prm, "Time steps", prm_file, "s");
        record_input  = prm.get("Input") == "record";
        frequencies   = positive_list(prm, "Frequencies", prm_file, "Hz");
        amplitude     = prm.get_double("Amplitude");
        duration      = prm.get_double("Duration");
        record_dt     = prm.get_double("Record time step");
        analytical_dt = prm.get_double("Analytical time step");
        const std::string mode = prm.get("Loading mode");
        modes.clear();
        if (mode != "displacement")
          modes.push_back(dda::SeismicInput::Mode::inertial);
        if (mode != "loading")
          modes.push_back(dda::SeismicInput::Mode::displacement);
        settle_steps = prm.get_integer("Settling steps");
        threads      = prm.get_integer("Threads");
        parse_block1_geometry_keys(prm, geometry, materials);
        geometry.toe_length    = prm.get_double("Toe length");
        materials.rock.density = prm.get_double("Density");
        materials.rock.young   = prm.get_double("Young's modulus");
        materials.rock.poisson = prm.get_double("Poisson's ratio");
        plot                   = prm.get_bool("Plot");
        prm.leave_subsection();
        if (record_input)
          {
            motion = seismic::GroundMotionInput();
            motion.parse_parameters(prm, prm_file);
            if (motion.record.acceleration.size() < 2
                || !(motion.record.peak() > 0.))
              throw InputError(prm_file
                               + ": key 'Ground motion/Record file': the "
                                 "record "
                               + motion.record.name
                               + " has fewer than 2 samples or a zero peak; "
                                 "Eq. 5.10 needs a motion that makes the "
                                 "block slide");
          }
        else
          io::require(record_dt <= duration,
                      prm_file,
                      "Calibration/Record time step",
                      record_dt,
                      "> 0 s and at most 'Duration'");
        io::require(materials.friction_deg > geometry.slope_deg,
                    prm_file,
                    "Calibration/Friction angle",
                    materials.friction_deg,
                    "> 'Slope' (else the block slides under gravity alone)");
        io::with_parameter_file(prm_file, [&]() {
          make_block1_seismic_scene(geometry, materials);
        });
      }

      std::vector<std::string>
      warnings() const override
      {
        std::vector<std::string> w;
        const double ky = block1_yield_acceleration(geometry, materials);
        if (record_input)
          {
            w                = motion.warnings;
            const double pga = motion.record.peak();
            if (pga <= ky)
              w.push_back("keys 'Ground motion/Scaling', 'Target PGA': the "
                          "record's PGA "
                          + io::format_number(pga, 4)
                          + " g does not exceed the yield acceleration "
                          + io::format_number(ky, 4)
                          + " g: the block does not slide and Eq. 5.10 is "
                            "undefined (scale the record above ky)");
            return w;
          }
        if (amplitude <= ky)
          w.push_back("key 'Calibration/Amplitude' = "
                      + io::format_number(amplitude, 4)
                      + " g does not exceed the yield acceleration "
                      + io::format_number(ky, 4)
                      + " g: the block does not slide and Eq. 5.10 is "
                        "undefined (use A > ky)");
        for (const double f : frequencies)
          for (const double dt : time_steps)
            if (dt > 0.05 / f)
              w.push_back("key 'Calibration/Time steps': dt = "
                          + io::format_number(dt, 4) + " s resolves "
                          + io::format_number(f, 4)
                          + " Hz with fewer than 20 steps per period");
        return w;
      }

      void
      run(io::RunContext &context) override;

    private:
      std::vector<double> penalties, time_steps, frequencies;
      double              amplitude = 0.5, duration = 5., record_dt = 1e-3,
             analytical_dt = 1e-4;
      /// Input = record: the 'Ground motion' section's record.
      bool                                 record_input = false, plot = true;
      seismic::GroundMotionInput           motion;
      std::vector<dda::SeismicInput::Mode> modes;
      unsigned int                         settle_steps = 50, threads = 0;
      Block1Geometry                       geometry;
      Block1Materials                      materials;
    };



    void
    CalibrateAnalysis::run(io::RunContext &context)
    {
      const auto   start = std::chrono::steady_clock::now();
      const double ky    = block1_yield_acceleration(geometry, materials);
      context.log.line("Block 1: L_B = " + io::format_number(geometry.length, 4)
                       + " m, H = " + io::format_number(geometry.height, 4)
                       + " m, dip " + io::format_number(geometry.slope_deg, 4)
                       + " deg, friction "
                       + io::format_number(materials.friction_deg, 4)
                       + " deg: horizontal yield acceleration "
                       + io::format_number(ky, 4) + " g");

      // The inputs and their analytical solutions.
      std::vector<GridInput> inputs;
      if (record_input)
        {
          context.log.line("input motion: " + motion.description);
          std::vector<std::pair<std::string, double>> polarities;
          if (motion.polarity != seismic::GroundMotionInput::Polarity::inverted)
            polarities.emplace_back("normal", 1.);
          if (motion.polarity != seismic::GroundMotionInput::Polarity::normal)
            polarities.emplace_back("inverted", -1.);
          for (const auto &[name, sign] : polarities)
            {
              GridInput in;
              in.label = "record " + motion.record.name
                         + (sign < 0. ? " inverted" : "");
              in.tag = "_record"
                       + (polarities.size() > 1 ? "_" + name : std::string());
              in.polarity = sign;
              in.record   = motion.record;
              seismic::scale(in.record, sign);
              in.duration = in.record.duration();
              inputs.push_back(in);
            }
        }
      else
        for (const double f : frequencies)
          {
            GridInput in;
            in.label     = "f = " + io::format_number(f, 4) + " Hz";
            in.tag       = "_f" + io::format_number(f, 6) + "Hz";
            in.frequency = f;
            in.record    = sinusoid_record(amplitude, f, duration, record_dt);
            in.duration  = duration;
            inputs.push_back(in);
          }
      for (auto &in : inputs)
        {
          in.exact = block1_analytical_slip(
            geometry, materials, in.record, in.duration, analytical_dt);
          context.log.line(in.label + ": analytical slip "
                           + io::format_number(in.exact, 6) + " m over "
                           + io::format_number(in.duration, 6) + " s");
        }
      const auto mode_name = [&](const std::size_t m) {
        return modes[m] == dda::SeismicInput::Mode::displacement
                 ? std::string("displacement")
                 : std::string("loading");
      };

      std::vector<GridRun> grid;
      for (std::size_t m = 0; m < modes.size(); ++m)
        for (std::size_t i = 0; i < inputs.size(); ++i)
          for (const double k : penalties)
            for (const double dt : time_steps)
              {
                GridRun r;
                r.input      = i;
                r.mode       = m;
                r.frequency  = inputs[i].frequency;
                r.penalty    = k;
                r.dt         = dt;
                r.analytical = inputs[i].exact;
                grid.push_back(r);
              }

      // Run the grid concurrently (TBB), stopped between runs and within a
      // run by SIGINT / SIGTERM.
      Block1RunControls controls;
      controls.settle_steps = settle_steps;
      controls.stop         = []() { return io::interrupt_signal() != 0; };
      const auto runs
        = run_concurrently(grid.size(), threads, [&](const std::size_t j) {
            GridRun          &r  = grid[j];
            const GridInput  &in = inputs[r.input];
            Block1RunControls c  = controls;
            c.mode               = modes[r.mode];
            c.penalty            = r.penalty;
            c.dt                 = r.dt;
            try
              {
                const Block1Run run = run_block1_dda(
                  geometry, materials, in.record, c, in.duration);
                r.dda          = run.slip;
                r.max_rotation = run.max_rotation;
                r.steps        = run.steps;
                r.cuts         = run.cuts;
                r.wall_time    = run.wall_time;
                r.error        = 100. * std::abs(r.analytical - r.dda)
                          / std::abs(r.analytical);
                if (run.stopped)
                  r.failure = "interrupted";
              }
            catch (const std::exception &e)
              {
                r.failure = e.what();
              }
            if (!r.failure.empty())
              r.dda = r.error = std::numeric_limits<double>::quiet_NaN();
          });
      const unsigned int n_workers = runs.threads;
      for (std::size_t j = 0; j < grid.size(); ++j)
        if (!runs.done[j])
          {
            grid[j].failure = "not run (interrupted)";
            grid[j].dda     = grid[j].error
              = std::numeric_limits<double>::quiet_NaN();
          }
      if (io::interrupt_signal() != 0)
        {
          std::size_t finished = 0;
          for (const auto &r : grid)
            finished += r.failure.empty() ? 1 : 0;
          context.stopped_early = true;
          context.stopped_note  = std::to_string(finished) + " of "
                                 + std::to_string(grid.size())
                                 + " runs done (calibration.csv; the others "
                                   "are NaN).";
        }
      const double grid_seconds = std::chrono::duration<double>(
                                    std::chrono::steady_clock::now() - start)
                                    .count();

      io::Table table;
      table.add_column("frequency", "Hz");
      table.add_column("penalty", "N/m");
      table.add_column("time_step", "s");
      table.add_column("analytical", "m");
      table.add_column("dda", "m");
      table.add_column("error", "%");
      table.add_column("max_rotation", "rad");
      table.add_column("steps", "-");
      table.add_column("cuts", "-");
      table.add_column("wall_time", "s");
      table.add_column("mode", "-");
      table.add_column("polarity", "-");
      double cpu_seconds = 0.;
      for (const auto &r : grid)
        {
          table.add_row(
            {r.frequency,
             r.penalty,
             r.dt,
             r.analytical,
             r.dda,
             r.error,
             r.max_rotation,
             static_cast<double>(r.steps),
             static_cast<double>(r.cuts),
             r.wall_time,
             modes[r.mode] == dda::SeismicInput::Mode::displacement ? 1. : 0.,
             inputs[r.input].polarity});
          cpu_seconds += r.wall_time;
          if (!r.failure.empty())
            context.log.line(inputs[r.input].label + ", " + mode_name(r.mode)
                             + " mode, k = " + io::format_number(r.penalty, 4)
                             + " N/m, dt = " + io::format_number(r.dt, 4)
                             + " s: DDA failed: " + r.failure);
        }
      context.output.write("calibration.csv", table.csv());
      context.output.write("statistics.csv", table.csv());

      // Best pair per input and mode, and for the product of the errors.
      const auto finite = [](const double x) { return std::isfinite(x); };
      for (const auto &in : inputs)
        context.summary.add("analytical" + in.tag, in.exact, "m");
      for (std::size_t m = 0; m < modes.size(); ++m)
        for (std::size_t i = 0; i < inputs.size(); ++i)
          {
            const GridRun *best = nullptr;
            for (const auto &r : grid)
              if (r.input == i && r.mode == m && finite(r.error)
                  && (!best || r.error < best->error))
                best = &r;
            if (!best)
              continue;
            const std::string tag
              = inputs[i].tag + (modes.size() > 1 ? "_" + mode_name(m) : "");
            context.summary.add("best_penalty" + tag, best->penalty, "N/m");
            context.summary.add("best_time_step" + tag, best->dt, "s");
            context.summary.add("best_error" + tag, best->error, "%");
            context.log.line(
              inputs[i].label + ", " + mode_name(m)
              + " mode: best k = " + io::format_number(best->penalty, 4)
              + " N/m, dt = " + io::format_number(best->dt, 4) + " s, error "
              + io::format_number(best->error, 4) + " %");
          }
      double    best_product = std::numeric_limits<double>::infinity();
      double    best_k = 0., best_dt = 0.;
      io::Table products;
      products.add_column("penalty", "N/m");
      products.add_column("time_step", "s");
      products.add_column("error_product", "%^n");
      for (const double k : penalties)
        for (const double dt : time_steps)
          {
            double p = 1.;
            for (const auto &r : grid)
              if (r.penalty == k && r.dt == dt)
                p *= r.error;
            products.add_row({k, dt, p});
            if (finite(p) && p < best_product)
              {
                best_product = p;
                best_k       = k;
                best_dt      = dt;
              }
          }
      context.output.write("error_products.csv", products.csv());
      if (std::isfinite(best_product))
        {
          context.summary.add("best_penalty_product", best_k, "N/m");
          context.summary.add("best_time_step_product", best_dt, "s");
          context.summary.add("best_error_product", best_product, "%^n");
          context.log.line(
            "product of the errors: best k = " + io::format_number(best_k, 4)
            + " N/m, dt = " + io::format_number(best_dt, 4) + " s");
        }
      unsigned int failed = 0;
      for (const auto &r : grid)
        failed += r.failure.empty() ? 0 : 1;
      context.summary.add("yield_acceleration", ky, "g");
      context.summary.add("runs", static_cast<double>(grid.size()), "-");
      context.summary.add("failed_runs", failed, "-");
      context.summary.add("concurrent_runs", n_workers, "-");
      context.summary.add("grid_wall_time", grid_seconds, "s");
      context.summary.add("run_wall_time_sum", cpu_seconds, "s");
      context.log.line("grid of " + std::to_string(grid.size()) + " runs in "
                       + io::format_number(grid_seconds, 4) + " s ("
                       + std::to_string(n_workers) + " at once; "
                       + io::format_number(cpu_seconds, 4)
                       + " s summed over the runs)");
      if (plot)
        io::run_plot_script(context.output,
                            context.log,
                            "plot_calibration.py",
                            {"calibration.png"});
    }
  } // namespace



  std::unique_ptr<io::Analysis>
  make_calibrate_analysis()
  {
    return std::make_unique<CalibrateAnalysis>();
  }
} // namespace rockdda::coupling
