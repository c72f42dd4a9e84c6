/**
 * @file
 * Analysis type "newmark": rigid-block sliding under one acceleration
 * component (Newmark 1965), driven by the "Ground motion" and "Newmark"
 * sections.
 */
#include <rockdda/analytical/analyses.h>
#include <rockdda/analytical/newmark.h>
#include <rockdda/io/data_file.h>
#include <rockdda/io/error.h>
#include <rockdda/io/parameters.h>
#include <rockdda/io/progress.h>
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
        return "1D rigid-block (Newmark) sliding under an acceleration record";
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
        prm.leave_subsection();

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
      seismic::GroundMotionInput motion;
      NewmarkOptions             options;
    };
  } // namespace



  std::unique_ptr<io::Analysis>
  internal::make_newmark_analysis()
  {
    return std::make_unique<NewmarkAnalysis>();
  }
} // namespace rockdda::analytical
