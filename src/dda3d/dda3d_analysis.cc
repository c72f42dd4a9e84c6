/**
 * @file
 * Analysis type "dda3d": 3D discontinuous deformation analysis of a scene
 * of polyhedral blocks read from a block file
 * (doc/block-file-format-dda3d.md), with optional seismic input in the
 * thesis's loading or displacement mode (Bakun-Mazor 2011, Sec. 4.6-4.7).
 */
#include <rockdda/dda/analysis_parameters.h>
#include <rockdda/dda/block_system.h>
#include <rockdda/dda/hdf5_output.h>
#include <rockdda/dda/run_loop.h>
#include <rockdda/dda/snapshot_series.h>
#include <rockdda/dda/vtu_output.h>
#include <rockdda/dda3d/analyses.h>
#include <rockdda/dda3d/block_file.h>
#include <rockdda/dda3d/engine.h>
#include <rockdda/dda3d/vtu_output.h>
#include <rockdda/io/error.h>
#include <rockdda/io/parameters.h>
#include <rockdda/io/time_expression.h>
#include <rockdda/seismic/ground_motion.h>

#include <deal.II/base/parameter_handler.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <map>
#include <memory>

namespace rockdda::dda3d
{
  namespace
  {
    using dealii::Patterns::Bool;
    using dealii::Patterns::Double;
    using dealii::Patterns::Integer;
    using dealii::Patterns::Selection;

    /// The "dda3d" analysis.
    class Dda3dAnalysis : public io::Analysis
    {
    public:
      std::string
      name() const override
      {
        return "dda3d";
      }

      std::string
      description() const override
      {
        return "3D discontinuous deformation analysis (DDA) of polyhedral "
               "blocks";
      }

      void
      declare_parameters(dealii::ParameterHandler &prm) const override
      {
        seismic::GroundMotionInput::declare_parameters(prm);
        prm.enter_subsection(dda::AnalysisParameters<3>::section());
        dda::AnalysisParameters<3>::declare_parameters(prm);
        io::declare(prm,
                    "Minimum time step ratio",
                    "1e-6",
                    io::DoubleInterval(0., true, 1., false),
                    "-",
                    "The run stops with a diagnosis when a step must be cut "
                    "below this fraction of the Time step; 0 < ratio <= 1.");
        io::declare(prm,
                    "Contact penalty",
                    "1e10",
                    io::DoubleInterval::positive(),
                    "N/m",
                    "Normal penalty spring of a contact, > 0 (in series with "
                    "a joint's stiffness over the contact area, if the joint "
                    "has one). A block of weight W on n contacts sinks by "
                    "W / (n p).");
        io::declare(prm,
                    "Stiff mode velocity",
                    "false",
                    Bool(),
                    "-",
                    "false: Shi's end-of-step velocity v' = 2 D / dt - v, "
                    "whose modes stiff for the step (omega dt >> 1: contact "
                    "springs, fixed points, block elasticity at a large "
                    "penalty or E) keep a velocity that changes sign every "
                    "step. true: the velocity solve (2 M / dt^2 + K) v'' = "
                    "(2 M / dt^2) v' + K D / dt gives each stiff mode its "
                    "mean rate over the step (an inelastic contact, "
                    "amplification ~1.4 / (omega dt)) and leaves resolved "
                    "ones (omega dt << 1) Shi's to O((omega dt)^2); the "
                    "foundation moves with the exact ground velocity. The "
                    "kinetic energy removed is booked as damping "
                    "(doc/theory/dda3d.md, Velocity of the stiff modes).");
        io::declare(prm,
                    "Line search",
                    "false",
                    Bool(),
                    "-",
                    "Globalise the open-close iteration with the 2D engine's "
                    "exact line search on the convex energy of the step "
                    "(dda/line_search.h, written once for both). Off by "
                    "default in 3D: its scenes converge without it, and with "
                    "it the velocity-weakening run-out of the shaking-table "
                    "wedge is 3.4 % from sliding3d instead of 1.5 % "
                    "(doc/theory/dda3d.md).");
        io::declare(prm,
                    "Face group shared strength",
                    "false",
                    Bool(),
                    "-",
                    "false: every contact starts to slide when its shear "
                    "spring force (N) exceeds its own Mohr-Coulomb strength "
                    "(N). true: the closed contacts between two faces that "
                    "face each other (a face group: one statically "
                    "indeterminate interface) share their strength: none of "
                    "its locked members starts to slide while the sum of "
                    "their shear spring forces (N) is within the sum of their "
                    "strengths (N); opening (tension) and relocking stay each "
                    "contact's own (doc/theory/dda3d.md, Face groups: shared "
                    "strength).");
        io::declare(prm,
                    "Seismic input",
                    "none",
                    Selection("none|loading|inertial|displacement"),
                    "-",
                    "'loading' or 'inertial' (the thesis's loading mode, as "
                    "in dda): every block is "
                    "loaded by the inertial body force -rho V a_g(t) at the "
                    "middle of each step, the foundation stays put (the "
                    "scene is seen in the ground's frame); 'displacement': "
                    "the clamped blocks (the foundation) are moved by the "
                    "ground displacement u_g(t), the double integral of "
                    "a_g from rest, and fixed points follow it (low-pass "
                    "and baseline-correct a record first: 'Ground "
                    "motion/Processing'; the thesis used a 2.5 Hz "
                    "Butterworth).");
        io::declare(prm,
                    "Seismic source",
                    "expression",
                    Selection("expression|ground motion"),
                    "-",
                    "'expression': a_g(t) from 'Ground acceleration'; "
                    "'ground motion': the 'Ground motion' section's record "
                    "or harmonic (with its ramp and processing), "
                    "horizontal along 'Ground motion azimuth', its "
                    "'Transverse record file' 90 deg clockwise from it and "
                    "its 'Vertical record file' upward.");
        io::declare(prm,
                    "Ground acceleration",
                    "0; 0; 0",
                    dealii::Patterns::Anything(),
                    "g",
                    "Ground acceleration a_g(t) (not the resultant on the "
                    "block: that is gravity - a_g): three expressions of t "
                    "(s) for x (east), y (north), z (up), separated by ';'. "
                    "Thesis Fig. 4-2A, r = [0.5 sin 10t, 0, -1] g, is "
                    "'-0.5*sin(10*t); 0; 0'. A ramp is written into the "
                    "expression, e.g. 'min(t/5,1)*0.21*sin(4*pi*t); 0; 0'.");
        io::RunCheckpoint::declare_parameters(
          prm,
          "at multiples of this interval (steps land on them, as on output "
          "times) and at the End time");
        io::declare(prm,
                    "Ground motion azimuth",
                    "90",
                    Double(0., 360.),
                    "deg",
                    "Direction (clockwise from north, 0 to 360) of the "
                    "horizontal record of the Ground motion section.");
        dda::SolverParameters<3>::declare_parameters(prm);
        prm.leave_subsection();
      }

      void
      parse_parameters(dealii::ParameterHandler &prm,
                       const std::string        &prm_file) override
      {
        prm.enter_subsection(dda::AnalysisParameters<3>::section());
        dda::AnalysisParameters<3> shared;
        shared.parse_parameters(prm, prm_file);
        c.min_dt_ratio        = prm.get_double("Minimum time step ratio");
        c.law.normal_penalty  = prm.get_double("Contact penalty");
        c.stiff_velocity      = prm.get_bool("Stiff mode velocity");
        c.face_group_friction = prm.get_bool("Face group shared strength");
        c.line_search         = prm.get_bool("Line search");
        settings              = dda::run_settings(shared, prm);
        const std::string seismic_mode = prm.get("Seismic input");
        c.solver = dda::SolverParameters<3>::parse_parameters(prm, prm_file);
        prm.leave_subsection();
        c.dt                             = shared.time_step;
        c.dynamic                        = shared.dynamic;
        c.strain_damping                 = shared.strain_damping;
        c.contact_damping                = shared.contact_damping;
        c.contact_step_damping           = shared.contact_step_damping;
        c.max_open_close                 = shared.max_open_close;
        c.inexact_factor                 = shared.inexact_factor;
        c.plausibility.penetration_ratio = shared.penetration_ratio;
        c.max_displacement_ratio         = shared.max_displacement_ratio;
        c.law.shear_ratio                = shared.shear_ratio;
        c.law.fixed_shear_penalty        = shared.shear_penalty;
        c.law.force_tolerance            = shared.force_tolerance;
        c.fixed_penalty                  = shared.fixed_penalty;
        const double      gravity        = shared.gravity;
        const std::string s              = shared.section() + "/";
        io::require(c.min_dt_ratio > 0. && c.min_dt_ratio <= 1.,
                    prm_file,
                    s + "Minimum time step ratio",
                    c.min_dt_ratio,
                    "0 < ratio <= 1");
        io::require(c.law.normal_penalty > 0.,
                    prm_file,
                    s + "Contact penalty",
                    c.law.normal_penalty,
                    "> 0 N/m");
        const std::string &path  = shared.block_file;
        BlockSystem        scene = read_block_file(path);
        scene.gravity            = Point(0., 0., -gravity);
        shared.apply_friction_law(scene.joints);
        seismic = parse_seismic_input(prm,
                                      prm_file,
                                      settings.end_time,
                                      c.dt,
                                      gravity > 0. ? gravity : 9.80665);
        if (seismic.mode == SeismicInput3d::Mode::loading)
          c.ground_acceleration = seismic.acceleration;
        else if (seismic.mode == SeismicInput3d::Mode::displacement)
          c.ground_displacement = seismic.displacement;
        try
          {
            engine = std::make_unique<Engine>(scene, c);
          }
        catch (const InputError &e)
          {
            throw InputError("block file '" + path + "': " + e.what());
          }
        settings.fingerprint
          = dda::run_fingerprint(engine->scene().blocks.size(),
                                 c.dt,
                                 c.law.normal_penalty,
                                 c.dynamic,
                                 settings.settling_steps,
                                 seismic_mode);
      }

      bool
      resumes() const override
      {
        return settings.resume;
      }

      void
      run(io::RunContext &context) override
      {
        if (!seismic.description.empty())
          context.log.line("seismic input: " + seismic.description);
        const auto &sys = engine->scene();
        context.log.line(
          "DDA 3d: " + std::to_string(sys.blocks.size()) + " blocks, penalty "
          + io::format_number(c.law.normal_penalty, 4) + " N/m, time step "
          + io::format_number(c.dt, 4) + " s");
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
               {"kinetic_energy", "J"},
               {"strain_energy", "J"},
               {"contact_energy", "J"},
               {"gravity_potential_energy", "J"},
               {"fixed_spring_energy", "J"},
               {"friction_dissipation", "J"},
               {"damping_dissipation", "J"},
               {"load_work", "J"},
               {"energy_balance", "J"}})
          table.add_column(n, u);
        const bool ground = seismic.mode == SeismicInput3d::Mode::displacement;
        if (ground)
          for (const char *n : {"ground_ux", "ground_uy", "ground_uz"})
            table.add_column(n, "m");
        const std::size_t n_mp = sys.measurement_points.size();
        for (std::size_t m = 0; m < n_mp; ++m)
          {
            const std::string p = "mp" + std::to_string(m + 1) + "_";
            for (const char *x : {"ux", "uy", "uz"})
              table.add_column(p + x, "m");
            for (const char *x : {"sigma_x", "sigma_y", "sigma_z"})
              table.add_column(p + x, "Pa");
          }
        auto mp_displacement = [&](const std::size_t m) {
          const auto &mp = engine->scene().measurement_points[m];
          return Point(mp.point - mp.initial);
        };
        auto add_row = [&](const unsigned long cuts) {
          const auto         &st = engine->statistics();
          const Energy        e  = engine->energy();
          std::vector<double> row{engine->time(),
                                  st.dt,
                                  double(st.iterations),
                                  double(cuts),
                                  double(st.open),
                                  double(st.sliding),
                                  double(st.locked),
                                  e.kinetic,
                                  e.strain,
                                  e.contact,
                                  e.potential,
                                  e.fixed,
                                  e.friction,
                                  e.damping,
                                  e.load_work,
                                  e.balance()};
          if (ground)
            {
              const Point u = seismic.displacement(engine->time());
              row.insert(row.end(), {u.x(), u.y(), u.z()});
            }
          for (std::size_t m = 0; m < n_mp; ++m)
            {
              const Point d = mp_displacement(m);
              const auto &b
                = engine->scene()
                    .blocks[engine->scene().measurement_points[m].block];
              row.insert(
                row.end(),
                {d.x(), d.y(), d.z(), b.stress[0], b.stress[1], b.stress[2]});
            }
          table.add_row(row);
        };
        dda::RunLoop<Engine> loop(*engine, settings, context, table);
        dda::SnapshotSeries  snapshots(context.output,
                                      settings.statistics_hdf5,
                                      loop.progress);
        auto                 snapshot = [&]() {
          snapshots.write(
            engine->time(),
            [&]() {
              return blocks_snapshot(engine->scene(), engine->origin());
            },
            [&]() { return contacts_snapshot(*engine); },
            [&]() { return blocks_vtu(engine->scene(), engine->origin()); },
            [&]() { return contacts_vtu(*engine); });
        };
        loop.on_resume = [&]() { snapshots.resume(); };
        // One step (the last before an output or checkpoint time
        // shortened to land on it).
        const auto step = [&](const double target) {
          const unsigned long before = engine->n_iterations;
          engine->advance_to(std::min(target, engine->time() + c.dt));
          return static_cast<unsigned int>(engine->n_iterations - before);
        };
        if (!loop.run(step, add_row, snapshot))
          return;
        const double balance0    = loop.progress.balance0;
        const double created_max = loop.progress.created_max;
        auto        &sm          = context.summary;
        sm.add("final_time", engine->time(), "s");
        sm.add("steps", double(engine->n_steps), "-");
        sm.add("time_step_cuts", double(engine->n_cuts), "-");
        sm.add("open_close_iterations_per_step",
               double(engine->n_iterations)
                 / double(std::max(1ul, engine->n_steps)),
               "-");
        const Energy e = engine->energy();
        sm.add("kinetic_energy", e.kinetic, "J");
        sm.add("friction_dissipation", e.friction, "J");
        sm.add("damping_dissipation", e.damping, "J");
        sm.add("energy_balance_change", e.balance() - balance0, "J");
        sm.add("energy_created_max", created_max, "J");
        sm.add("energy_created_relative",
               loop.progress.energy_in_play > 0.
                 ? created_max / loop.progress.energy_in_play
                 : 0.,
               "-");
        sm.add("contact_strength_ratio_max", engine->worst_strength_ratio, "-");
        sm.add("contacts_final", double(engine->contacts().size()), "-");
        double max_disp = 0.;
        for (std::size_t b = 0; b < sys.blocks.size(); ++b)
          max_disp = std::max(max_disp, engine->displacement(b).norm());
        sm.add("max_block_displacement", max_disp, "m");
        for (std::size_t m = 0; m < n_mp; ++m)
          {
            const Point       d = mp_displacement(m);
            const std::string p = "mp" + std::to_string(m + 1) + "_";
            sm.add(p + "ux", d.x(), "m");
            sm.add(p + "uy", d.y(), "m");
            sm.add(p + "uz", d.z(), "m");
          }
        if (ground)
          {
            const Point u = seismic.displacement(engine->time());
            sm.add("ground_ux", u.x(), "m");
            sm.add("ground_uy", u.y(), "m");
            sm.add("ground_uz", u.z(), "m");
          }
        sm.add("wall_time", loop.wall, "s");
        context.log.line("linear solver (last step): "
                         + engine->linear_solver().description());
        context.log.line(loop.finished_line());
      }

    private:
      std::unique_ptr<Engine> engine;
      EngineControls          c;
      SeismicInput3d          seismic;
      /// End time, intervals, Checkpoint interval, Resume, settling steps
      /// and the fingerprint of the run's controls.
      dda::RunSettings settings;
    };
  } // namespace



  SeismicInput3d
  parse_seismic_input(dealii::ParameterHandler &prm,
                      const std::string        &prm_file,
                      const double              end_time,
                      const double              time_step,
                      const double              g)
  {
    SeismicInput3d in;
    prm.enter_subsection("DDA 3d");
    const std::string mode    = prm.get("Seismic input");
    const std::string source  = prm.get("Seismic source");
    const std::string expr    = prm.get("Ground acceleration");
    const double      azimuth = prm.get_double("Ground motion azimuth");
    prm.leave_subsection();
    if (mode == "none")
      return in;
    in.mode = mode == "loading" || mode == "inertial"
                ? SeismicInput3d::Mode::loading
                : SeismicInput3d::Mode::displacement;
    // The three components as records (g): x, y, z.
    std::array<seismic::Record, 3> records;
    if (source == "expression")
      {
        const auto a   = io::parse_time_expressions(expr,
                                                  prm_file,
                                                  "DDA 3d/Ground acceleration",
                                                  "-0.5*sin(10*t); 0; 0");
        in.description = "a_g(t) = [" + expr + "] g, " + mode + " mode";
        if (in.mode == SeismicInput3d::Mode::loading)
          {
            in.acceleration
              = [a, g](const double t) { return Point(g * a(t)); };
            return in;
          }
        // Sampled at dt / 20 for the exact piecewise-linear integral.
        const double      h = time_step / 20.;
        const std::size_t n
          = static_cast<std::size_t>(std::ceil(end_time / h)) + 2;
        for (auto &r : records)
          {
            r.name = "expression";
            r.dt   = h;
            r.acceleration.resize(n);
          }
        for (std::size_t k = 0; k < n; ++k)
          {
            const Point v = a(k * h);
            for (int d = 0; d < 3; ++d)
              records[d].acceleration[k] = v[d];
          }
        in.description += " (sampled at " + io::format_number(h, 4) + " s)";
      }
    else
      {
        seismic::GroundMotionInput motion;
        motion.parse_parameters(prm, prm_file);
        const double sign = motion.single_polarity_sign(prm_file, "dda3d");
        const double a    = azimuth * M_PI / 180.;
        const Point  e1   = sign * Point(std::sin(a), std::cos(a), 0.);
        const Point  e2   = sign * Point(std::cos(a), -std::sin(a), 0.);
        const auto add = [&](const seismic::Record &r, const Point &direction) {
          if (r.acceleration.empty())
            return;
          for (int d = 0; d < 3; ++d)
            if (direction[d] != 0.)
              {
                // Resample the component onto the record's own
                // grid: every component shares it (add in place).
                seismic::Record &out = records[d];
                if (out.acceleration.empty())
                  {
                    out.dt = r.dt;
                    out.acceleration.assign(r.acceleration.size(), 0.);
                  }
                const std::size_t n
                  = std::max(out.acceleration.size(),
                             static_cast<std::size_t>(
                               std::ceil(r.duration() / out.dt))
                               + 1);
                out.acceleration.resize(n, 0.);
                for (std::size_t k = 0; k < n; ++k)
                  out.acceleration[k] += direction[d] * r.at(k * out.dt);
              }
        };
        add(motion.record, e1);
        add(motion.transverse_record, e2);
        add(motion.vertical_record, Point::UnitZ());
        in.description = motion.description + ", azimuth "
                         + io::format_number(azimuth, 6) + " deg, " + mode
                         + " mode";
        if (in.mode == SeismicInput3d::Mode::loading)
          {
            auto rec
              = std::make_shared<std::array<seismic::Record, 3>>(records);
            in.acceleration = [rec, g](const double t) {
              return Point(g * (*rec)[0].at(t),
                           g * (*rec)[1].at(t),
                           g * (*rec)[2].at(t));
            };
            return in;
          }
      }
    auto integrals
      = std::make_shared<std::array<dda::GroundMotionIntegral, 3>>();
    for (int d = 0; d < 3; ++d)
      if (!records[d].acceleration.empty())
        (*integrals)[d] = dda::GroundMotionIntegral(records[d], g);
    in.displacement = [integrals](const double t) {
      return Point((*integrals)[0].displacement(t),
                   (*integrals)[1].displacement(t),
                   (*integrals)[2].displacement(t));
    };
    return in;
  }



  std::vector<std::unique_ptr<io::Analysis>>
  make_analyses()
  {
    std::vector<std::unique_ptr<io::Analysis>> list;
    list.push_back(std::make_unique<Dda3dAnalysis>());
    return list;
  }
} // namespace rockdda::dda3d
