/**
 * @file
 * Analysis type "dda": 2D discontinuous deformation analysis of a block
 * system read from a block file, with optional seismic input.
 */
#include <rockdda/dda/analyses.h>
#include <rockdda/dda/analysis_parameters.h>
#include <rockdda/dda/block_file.h>
#include <rockdda/dda/engine.h>
#include <rockdda/dda/hdf5_output.h>
#include <rockdda/dda/run_loop.h>
#include <rockdda/dda/snapshot_series.h>
#include <rockdda/dda/vtu_output.h>
#include <rockdda/io/checkpoint.h>
#include <rockdda/io/error.h>
#include <rockdda/io/parameters.h>
#include <rockdda/seismic/ground_motion.h>

#include <deal.II/base/mpi.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <sstream>

namespace rockdda::dda
{
  namespace
  {
    using dealii::Patterns::Bool;
    using dealii::Patterns::Double;
    using dealii::Patterns::Integer;
    using dealii::Patterns::Selection;

    /**
     * Log lines on the ground motion the fixed points follow: for each
     * record its peak velocity and the velocity and displacement at its
     * end (the integration drift: after the record the ground moves on at
     * the final velocity), with a warning when the final velocity exceeds
     * 1 % of the peak; and the zero padding kept before the record.
     */
    std::vector<std::string>
    integration_drift(const SeismicInput &input, const double padding)
    {
      std::vector<std::string> lines;
      if (padding > 0.)
        lines.push_back(
          "seismic input: the processed record starts with "
          + io::format_number(padding, 6)
          + " s of filter padding (t = 0 is the start of the padding)");
      const auto add = [&](const seismic::Record &r, const char *what) {
        if (r.acceleration.empty())
          return;
        const GroundMotionIntegral m(r, input.g);
        const double               v   = m.final_velocity();
        const double               pgv = m.peak_velocity();
        lines.push_back(std::string("ground motion integration (") + what
                        + "): peak velocity " + io::format_number(pgv, 6)
                        + " m/s; at the end of the record (t = "
                        + io::format_number(r.duration(), 6) + " s) velocity "
                        + io::format_number(v, 6) + " m/s, displacement "
                        + io::format_number(m.final_displacement(), 6) + " m");
        if (input.mode == SeismicInput::Mode::displacement
            && std::abs(v) > 0.01 * pgv)
          lines.push_back(
            std::string("warning: the ") + what + " ground velocity drifts to "
            + io::format_number(v, 4)
            + " m/s at the end of the record (more than 1 % of its peak): "
              "the foundation keeps moving; baseline-correct or high-pass "
              "the record ('Ground motion/Processing')");
      };
      add(input.record, "horizontal");
      add(input.vertical_record, "vertical");
      return lines;
    }

    /// The "dda" analysis.
    class DdaAnalysis : public io::Analysis
    {
    public:
      std::string
      name() const override
      {
        return "dda";
      }

      std::string
      description() const override
      {
        return "2D discontinuous deformation analysis (DDA) of a block "
               "system";
      }

      void
      declare_parameters(dealii::ParameterHandler &prm) const override
      {
        seismic::GroundMotionInput::declare_parameters(prm);
        prm.enter_subsection(AnalysisParameters<2>::section());
        AnalysisParameters<2>::declare_parameters(prm);
        io::declare(prm,
                    "Minimum time step",
                    "0",
                    Double(0.),
                    "s",
                    "The run stops with a diagnosis if a step must be cut "
                    "below this; 0 = 1e-6 x Time step.");
        io::declare(prm,
                    "Line search",
                    "true",
                    Bool(),
                    "-",
                    "Globalise the open-close iteration with an exact line "
                    "search on the convex energy of the step (semismooth "
                    "Newton with step-length control): from the second "
                    "iteration on, each step goes only as far as the energy "
                    "decreases, which stops the iteration from cycling "
                    "between contact states. false: full steps (Shi 1988).");
        io::declare(prm,
                    "Hold fraction",
                    "1e-7",
                    Double(0., 1e-3),
                    "-",
                    "A contact that changes state four times in one step "
                    "cycles and is held in its open or locked state while "
                    "the force needed to change it (compression, tension, "
                    "shear beyond the strength) is at most p_s x this x "
                    "the smaller block's size, i.e. a penetration or "
                    "elastic slip of at most this fraction of the block "
                    "size, and at most 1 % of the lighter block's weight; "
                    "a contact that still changes state 12 times cuts the "
                    "step. In static "
                    "steps a held contact stays held in the next step. Holding "
                    "cannot create energy. 0: no "
                    "holding.");
        io::declare(prm,
                    "Contact penalty",
                    "auto",
                    dealii::Patterns::Anything(),
                    "N/m",
                    "Normal contact spring stiffness per metre of thickness: "
                    "a positive number, or 'auto' (also 0) = the larger of "
                    "10 x the largest Young's modulus (x 1 m) and the "
                    "stiffness with which the heaviest block, on one "
                    "contact under its own weight, sinks by at most 1e-4 of "
                    "its size. The value used is in log.txt. A joint with "
                    "a normal or shear stiffness (block file, 'joint' "
                    "lines, Pa/m) acts in series with the penalty over "
                    "each contact's length l: keep the penalty at 100 x "
                    "k l or more for the joint's own stiffness within 1 % "
                    "(doc/theory/dda.md, Joint stiffness).");
        SolverParameters<2>::declare_parameters(prm);
        io::RunCheckpoint::declare_parameters(
          prm,
          "at multiples of this interval (steps land on them, as on output "
          "times) and at the End time");
        io::declare(prm,
                    "Seismic input",
                    "none",
                    Selection("none|inertial|loading|displacement"),
                    "-",
                    "Ground acceleration from the 'Ground motion' section "
                    "(horizontal, towards +x, and the optional vertical "
                    "record, upward; processed and scaled there): "
                    "'inertial' or 'loading' (the loading mode, as in "
                    "dda3d) loads every block with "
                    "-a(t) (fixed points stay put); 'displacement' moves "
                    "the fixed points (the foundation) with the ground "
                    "displacement, the double integral of a(t) from rest "
                    "(Kamai & Hatzor 2008); low-pass the record first "
                    "(e.g. at 2.5 Hz as Bakun-Mazor 2011, Sec. 4.7.2) and "
                    "baseline-correct it "
                    "so that the foundation ends at rest (the drift is in "
                    "log.txt).");
        io::declare(prm,
                    "Measurement point file",
                    "none",
                    Selection("none|hdf5"),
                    "-",
                    "'hdf5': also write measurement_points.h5, the time "
                    "series of the block file's measurement points (the "
                    "rows of statistics.csv, rewritten atomically with "
                    "it): time (rows, s), ux and uy (rows x points, m; "
                    "displacement since t = 0), sigma_x, sigma_y, tau_xy "
                    "(rows x points, Pa; stress of the point's block, "
                    "tension positive) and initial_position (points x 2, "
                    "m); see doc/user-guide.md. 'none': no such file.");
        prm.leave_subsection();
      }

      void
      parse_parameters(dealii::ParameterHandler &prm,
                       const std::string        &prm_file) override
      {
        prm.enter_subsection(AnalysisParameters<2>::section());
        AnalysisParameters<2> shared;
        shared.parse_parameters(prm, prm_file);
        settings = run_settings(shared, prm);
        Controls c;
        c.time_step                      = shared.time_step;
        c.min_time_step                  = prm.get_double("Minimum time step");
        c.dynamic                        = shared.dynamic;
        c.strain_damping                 = shared.strain_damping;
        c.contact_damping                = shared.contact_damping;
        c.contact_step_damping           = shared.contact_step_damping;
        c.max_iterations                 = shared.max_open_close;
        c.line_search                    = prm.get_bool("Line search");
        c.hold_fraction                  = prm.get_double("Hold fraction");
        c.inexact_factor                 = shared.inexact_factor;
        c.plausibility.penetration_ratio = shared.penetration_ratio;
        c.max_displacement_ratio         = shared.max_displacement_ratio;
        {
          const std::string p   = prm.get("Contact penalty");
          char             *end = nullptr;
          const double      v   = std::strtod(p.c_str(), &end);
          if (p == "auto")
            c.law.normal_penalty = 0.;
          else if (end != p.c_str() && *end == '\0' && std::isfinite(v)
                   && v >= 0.)
            c.law.normal_penalty = v;
          else
            throw InputError(prm_file + ": key 'DDA/Contact penalty' = '" + p
                             + "'; valid: 'auto' or a stiffness >= 0 N/m "
                               "(0 = auto)");
        }
        c.law.shear_ratio         = shared.shear_ratio;
        c.law.fixed_shear_penalty = shared.shear_penalty;
        c.law.force_tolerance     = shared.force_tolerance;
        c.fixed_penalty           = shared.fixed_penalty;
        c.solver = SolverParameters<2>::parse_parameters(prm, prm_file);
        const std::string mode = prm.get("Seismic input");
        hdf5_snapshots         = shared.hdf5_output;
        point_file             = prm.get("Measurement point file") == "hdf5";
        const double gravity   = shared.gravity;
        prm.leave_subsection();

        const std::string &path  = shared.block_file;
        BlockSystem        scene = read_block_file(path);
        if (point_file && scene.measurement_points.empty())
          throw InputError(prm_file
                           + ": key 'DDA/Measurement point file' = hdf5, but "
                             "the block file "
                           + path
                           + " has no measurement points ('measure' lines); "
                             "valid: none, or hdf5 with at least one point");
        scene.gravity = geometry::Point(0., -gravity);
        shared.apply_friction_law(scene.joints);
        if (c.law.normal_penalty == 0.)
          c.law.normal_penalty = automatic_penalty(scene, gravity);
        if (mode != "none")
          {
            motion.parse_parameters(prm, prm_file);
            if (motion.single_polarity_sign(prm_file, "dda") < 0.)
              for (auto &a : motion.record.acceleration)
                a = -a;
            // ('loading' is the thesis's and the dda3d analysis's name.)
            scene.seismic.mode   = mode == "inertial" || mode == "loading"
                                     ? SeismicInput::Mode::inertial
                                     : SeismicInput::Mode::displacement;
            scene.seismic.record = motion.record;
            scene.seismic.vertical_record = motion.vertical_record;
            scene.seismic.g               = gravity > 0. ? gravity : 9.80665;
            motion_text                   = motion.description;
            drift_text                    = integration_drift(scene.seismic,
                                           motion.processing_report.padding);
          }
        try
          {
            dda = std::make_unique<DdaSystem>(scene, c);
          }
        catch (const InputError &e)
          {
            throw InputError("block file '" + path + "': " + e.what());
          }
        settings.fingerprint = run_fingerprint(dda->system().blocks.size(),
                                               c.time_step,
                                               c.law.normal_penalty,
                                               c.dynamic,
                                               settings.settling_steps,
                                               mode);
      }

      bool
      resumes() const override
      {
        return settings.resume;
      }

      std::vector<std::string>
      warnings() const override
      {
        return dda ? dda->warnings() : std::vector<std::string>();
      }

      void
      run(io::RunContext &context) override
      {
        for (const auto &w : dda->warnings())
          context.log.line("warning: " + w);
        if (!motion_text.empty())
          context.log.line("seismic input: " + motion_text);
        for (const auto &line : drift_text)
          context.log.line(line);
        context.log.line(
          "DDA: " + std::to_string(dda->system().blocks.size())
          + " blocks, penalty "
          + io::format_number(dda->controls().law.normal_penalty, 4)
          + " N/m, time step " + io::format_number(dda->controls().time_step, 4)
          + " s, domain " + io::format_number(dda->domain_size(), 4) + " m");

        io::Table table;
        for (const auto &[n, u] :
             std::vector<std::pair<std::string, std::string>>{
               {"time", "s"},
               {"dt", "s"},
               {"open_close_iterations", "-"},
               {"cuts", "-"},
               {"contacts_open", "-"},
               {"contacts_sliding", "-"},
               {"contacts_locked", "-"},
               {"kinetic_energy", "J/m"},
               {"strain_energy", "J/m"},
               {"contact_energy", "J/m"},
               {"gravity_potential_energy", "J/m"},
               {"fixed_spring_energy", "J/m"},
               {"friction_dissipation", "J/m"},
               {"damping_dissipation", "J/m"},
               {"load_work", "J/m"},
               {"energy_balance", "J/m"},
               {"max_vertex_step_displacement", "m"}})
          table.add_column(n, u);
        const auto &mps = dda->system().measurement_points;
        // The measurement point columns follow the columns above.
        const std::size_t first_point_column = table.n_columns();
        for (std::size_t m = 0; m < mps.size(); ++m)
          {
            const std::string p = "mp" + std::to_string(m + 1) + "_";
            table.add_column(p + "ux", "m");
            table.add_column(p + "uy", "m");
            table.add_column(p + "sigma_x", "Pa");
            table.add_column(p + "sigma_y", "Pa");
            table.add_column(p + "tau_xy", "Pa");
          }
        // The cuts column counts every cut since the previous row (a row
        // may follow several steps); the column sums to time_step_cuts.
        StepReport last;
        auto       add_row = [&](const unsigned long cuts) {
          const StepReport   &r   = last;
          const EnergyLedger  e   = dda->energy();
          std::vector<double> row = {dda->time(),
                                     r.dt,
                                     double(r.iterations),
                                     double(cuts),
                                     double(r.n_open),
                                     double(r.n_sliding),
                                     double(r.n_locked),
                                     e.kinetic,
                                     e.strain,
                                     e.contact,
                                     e.potential,
                                     e.fixed,
                                     e.friction,
                                     e.damping,
                                     e.load_work,
                                     e.balance(),
                                     r.max_displacement};
          for (const auto &m : dda->system().measurement_points)
            {
              const auto  d = m.point - m.initial;
              const auto &s = dda->system().blocks[m.block].stress;
              row.insert(row.end(), {d.x(), d.y(), s[0], s[1], s[2]});
            }
          table.add_row(row);
        };

        RunLoop<DdaSystem> loop(*dda, settings, context, table);
        SnapshotSeries snapshots(context.output, hdf5_snapshots, loop.progress);
        auto           snapshot = [&]() {
          snapshots.write(
            dda->time(),
            [&]() { return blocks_snapshot(*dda); },
            [&]() { return contacts_snapshot(*dda); },
            [&]() { return blocks_vtu(*dda); },
            [&]() { return contacts_vtu(*dda); });
        };
        loop.on_resume = [&]() { snapshots.resume(); };
        if (point_file)
          loop.on_statistics = [&]() {
            context.output.write_with(
              "measurement_points.h5", [&](const std::string &tmp) {
                write_series_hdf5(tmp,
                                  measurement_point_series(table,
                                                           first_point_column,
                                                           dda->system()));
              });
          };
        const auto step = [&](const double target) {
          last
            = dda->run_until(std::min(target, dda->time() + dda->time_step()));
          return last.iterations;
        };
        if (!loop.run(step, add_row, snapshot))
          return;
        // Energy ledger over every accepted step (not only the rows): the
        // balance at the start, the largest gain over it (created energy,
        // > 0 only through the ledger's known inexactness) and the largest
        // energy in play.
        const double balance0       = loop.progress.balance0;
        const double created_max    = loop.progress.created_max;
        const double energy_in_play = loop.progress.energy_in_play;

        auto &s = context.summary;
        s.add("final_time", dda->time(), "s");
        s.add("steps", static_cast<double>(dda->n_steps), "-");
        s.add("time_step_cuts", static_cast<double>(dda->n_cuts), "-");
        s.add("open_close_iterations_per_step",
              static_cast<double>(dda->n_iterations)
                / static_cast<double>(std::max(1ul, dda->n_steps)),
              "-");
        s.add("contact_strength_ratio_max", dda->worst_strength_ratio, "-");
        s.add("linear_solves", static_cast<double>(dda->n_solves), "-");
        s.add("solver_iterations",
              static_cast<double>(dda->n_solver_iterations),
              "-");
        s.add("kinetic_energy", dda->kinetic_energy(), "J/m");
        s.add("strain_energy", dda->strain_energy(), "J/m");
        s.add("energy_balance_change",
              dda->energy().balance() - balance0,
              "J/m");
        s.add("energy_created_max", created_max, "J/m");
        s.add("energy_created_relative",
              energy_in_play > 0. ? created_max / energy_in_play : 0.,
              "-");
        s.add("contacts_final",
              static_cast<double>(dda->contacts().size()),
              "-");
        double max_disp = 0.;
        for (std::size_t b = 0; b < dda->system().blocks.size(); ++b)
          max_disp
            = std::max(max_disp,
                       dda->centroid_displacement(static_cast<int>(b)).norm());
        s.add("max_block_displacement", max_disp, "m");
        for (std::size_t m = 0; m < mps.size(); ++m)
          {
            const auto       &mp = dda->system().measurement_points[m];
            const auto        d  = mp.point - mp.initial;
            const std::string p  = "mp" + std::to_string(m + 1) + "_";
            s.add(p + "ux", d.x(), "m");
            s.add(p + "uy", d.y(), "m");
            s.add(p + "sigma_y",
                  dda->system().blocks[mp.block].stress[1],
                  "Pa");
          }
        const LinearSolver &ls          = dda->linear_solver();
        std::string         solver_text = ls.description();
        if (ls.separator_size() > 0)
          solver_text += ", " + std::to_string(ls.n_threads())
                         + " for detection and state checks";
        context.log.line("linear solver (last step): " + solver_text);
        context.log.line(loop.finished_line());
      }

    private:
      std::unique_ptr<DdaSystem> dda;
      seismic::GroundMotionInput motion;
      /// Log lines on the integration drift of the seismic records.
      std::vector<std::string> drift_text;
      std::string              motion_text;
      /// End time, intervals, Checkpoint interval, Resume, settling steps
      /// and the fingerprint of the run's controls.
      RunSettings settings;
      /// Snapshots as HDF5 + XDMF instead of VTU + PVD (statistics.h5:
      /// RunLoop).
      bool hdf5_snapshots = false;
      /// Write measurement_points.h5.
      bool point_file = false;
    };
  } // namespace



  std::vector<std::unique_ptr<io::Analysis>>
  make_analyses()
  {
    std::vector<std::unique_ptr<io::Analysis>> list;
    list.push_back(std::make_unique<DdaAnalysis>());
    return list;
  }
} // namespace rockdda::dda
