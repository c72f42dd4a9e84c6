/**
 * @file
 * The analysis type "heat": transient conduction in the rock blocks. It
 * builds the solver from the parameters read by heat_analysis_input.cc,
 * spins up (thermal::spin_up()), records probes, block moments and the
 * heat balance at the output times, writes VTU files and checkpoints
 * (resumable, interruptible), and reports the statistics, the energy
 * balance and the periodic half-space check.
 */
#include "heat_analysis.h"

#include <rockdda/io/checkpoint.h>
#include <rockdda/io/error.h>
#include <rockdda/io/interrupt.h>
#include <rockdda/io/progress.h>
#include <rockdda/thermal/analyses.h>
#include <rockdda/thermal/heat_cycles.h>

#include <deal.II/base/mpi.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <limits>
#include <memory>
#include <sstream>

namespace rockdda::thermal::internal
{
  void
  HeatAnalysis::run(io::RunContext &context)
  {
    const auto wall_start = std::chrono::steady_clock::now();
    HeatSolver solver(parameters);
    const auto st0 = solver.statistics();
    context.log.line("heat: " + solver.method_description());
    context.log.line("mesh: " + std::to_string(st0.n_cells) + " cells, "
                     + std::to_string(st0.n_dofs) + " dofs, cell size "
                     + io::format_number(st0.min_cell_size, 4) + " to "
                     + io::format_number(st0.max_cell_size, 4) + " m");
    for (const auto &d : bc_descriptions)
      context.log.line("boundary " + d);
    const Material &m0 = parameters.materials[0];
    const double    sd = thesis_skin_depth(m0.diffusivity(), 180. * 86400.);
    context.log.line("material '" + m0.name + "': diffusivity "
                     + io::format_number(m0.diffusivity(), 4)
                     + " m^2/s, seasonal skin depth (thesis Eq. 5.1, 180 "
                       "days) "
                     + io::format_number(sd, 4) + " m");
    context.summary.add_text("method", solver.method_description());
    context.summary.add("cells", st0.n_cells, "-");
    context.summary.add("dofs", st0.n_dofs, "-");
    context.summary.add("skin_depth_eq_5_1", sd, "m");

    for (const auto &q : probes)
      solver.add_probe(q[0], q[1]);
    const double record_start
      = parameters.start_time + spin_up_cycles * spin_up_period;

    io::Table table;
    table.add_column("time", "s");
    for (std::size_t k = 0; k < probes.size(); ++k)
      table.add_column("probe" + std::to_string(k + 1), "degC");
    const auto n_blocks = parameters.blocks.size();
    for (std::size_t b = 0; b < n_blocks; ++b)
      {
        const std::string s = "block" + std::to_string(b + 1);
        table.add_column(s + "_mean", "degC");
        table.add_column(s + "_gradient_x", "K/m");
        table.add_column(s + "_gradient_y", "K/m");
      }
    table.add_column("stored_heat_change", "J/m");
    table.add_column("boundary_heat_in", "J/m");
    if (parameters.adaptive_refinement)
      table.add_column("cells", "-");

    // Progress of the run (all of it is in a checkpoint).
    unsigned int                     spin_up_done = 0;
    bool                             recording    = false;
    unsigned long                    n_records    = 0;
    double                           e0 = 0., q0 = 0.;
    std::vector<std::vector<double>> samples(probes.size());
    std::vector<double>              sample_times;
    std::vector<double>              vtu_pending = vtu_times;
    std::sort(vtu_pending.begin(), vtu_pending.end());
    std::string  pvd = "<?xml version=\"1.0\"?>\n<VTKFile type=\"Collection\" "
                       "version=\"0.1\">\n<Collection>\n";
    unsigned int n_vtu           = 0;
    double       next_checkpoint = parameters.start_time + checkpoint_interval;

    const auto record = [&]() {
      std::vector<double> row{solver.time()};
      for (std::size_t k = 0; k < probes.size(); ++k)
        {
          row.push_back(solver.probe_value(k));
          samples[k].push_back(row.back());
        }
      sample_times.push_back(solver.time());
      for (const auto &bm : solver.block_moments())
        {
          row.push_back(bm.mean);
          row.push_back(bm.gradient_x);
          row.push_back(bm.gradient_y);
        }
      row.push_back(solver.stored_heat() - e0);
      row.push_back(solver.boundary_heat_in() - q0);
      if (parameters.adaptive_refinement)
        row.push_back(solver.statistics().n_cells);
      for (const double v : row)
        if (!std::isfinite(v))
          throw std::runtime_error("heat: non-finite result at t = "
                                   + io::format_number(solver.time(), 10)
                                   + " s");
      table.add_row(row);
    };
    const auto write_vtu = [&]() {
      char name[64];
      std::snprintf(name, sizeof(name), "temperature-%04u", n_vtu++);
      // One .vtu (serial), or a .pvtu with one piece per MPI rank.
      const auto files = solver.vtu_files(name);
      for (const auto &f : files)
        context.output.write(f.first, f.second);
      if (!files.empty())
        pvd += "<DataSet timestep=\"" + io::format_number(solver.time())
               + "\" file=\"" + files.front().first + "\"/>\n";
    };

    // Checkpoints: the solver's state and the run's progress.
    std::ostringstream fingerprint_text;
    fingerprint_text.precision(17);
    fingerprint_text << solver.method_description() << "; " << st0.n_cells
                     << " cells; start " << parameters.start_time
                     << " s; spin-up " << spin_up_cycles << " x "
                     << spin_up_period << " s; output every " << output_interval
                     << " s";
    const std::string       fingerprint = fingerprint_text.str();
    const io::RunCheckpoint checkpoint_file(context.output,
                                            "heat",
                                            fingerprint,
                                            "Heat/Time stepping");
    // The distributed solver's mesh and field (p4est files).
    const std::string mesh_files = context.output.file("checkpoint-mesh");
    double            saved_at   = std::numeric_limits<double>::quiet_NaN();
    const auto        save_checkpoint = [&]() {
      io::BinaryWriter w = checkpoint_file.begin();
      context.output.own("checkpoint-mesh*");
      w.put_string(solver.checkpoint(mesh_files));
      w.put<std::uint32_t>(spin_up_done);
      w.put<std::uint8_t>(recording ? 1 : 0);
      w.put<std::uint64_t>(n_records);
      w.put(e0);
      w.put(q0);
      io::RunCheckpoint::put_rows(w, table);
      for (const auto &series : samples)
        w.put_doubles(series);
      w.put_doubles(sample_times);
      w.put_doubles(vtu_pending);
      w.put<std::uint32_t>(n_vtu);
      w.put_string(pvd);
      w.put(next_checkpoint);
      checkpoint_file.write(w, table);
      saved_at = solver.time();
    };
    const auto checkpoint_if_due = [&]() {
      if (checkpoint_interval > 0. && solver.time() >= next_checkpoint - 1e-9)
        {
          while (next_checkpoint <= solver.time() + 1e-9)
            next_checkpoint += checkpoint_interval;
          save_checkpoint();
        }
    };
    if (resume)
      {
        const std::string bytes = checkpoint_file.read();
        io::BinaryReader  r     = checkpoint_file.reader(bytes);
        solver.restore(r.get_string(), checkpoint_file.file());
        spin_up_done = r.get<std::uint32_t>();
        recording    = r.get<std::uint8_t>() != 0;
        n_records    = r.get<std::uint64_t>();
        e0           = r.get<double>();
        q0           = r.get<double>();
        io::RunCheckpoint::get_rows(r, table);
        for (auto &series : samples)
          series = r.get_doubles();
        sample_times    = r.get_doubles();
        vtu_pending     = r.get_doubles();
        n_vtu           = r.get<std::uint32_t>();
        pvd             = r.get_string();
        next_checkpoint = r.get<double>();
        if (!r.at_end())
          throw InputError(checkpoint_file.file() + ": trailing data");
        context.log.line("resumed from " + checkpoint_file.file() + " at t = "
                         + io::format_number(solver.time(), 10) + " s");
      }

    // Planned steps from the current time to @p end (0: adaptive).
    const auto planned_to = [&](const double end) -> unsigned long {
      if (parameters.stepper == TimeStepper::arkode)
        return 0;
      return solver.statistics().n_steps
             + static_cast<unsigned long>(
               io::planned_steps(solver.time(), end, parameters.time_step));
    };
    // Stopped early by SIGINT / SIGTERM, polled (on every MPI rank alike)
    // about 100 times per spin-up cycle (see thermal::spin_up()) and
    // between output times.
    int interrupted = 0;
    {
      io::ProgressBar progress("heat spin-up",
                               solver.time(),
                               record_start,
                               planned_to(record_start));
      SpinUpCallbacks callbacks;
      callbacks.stop = [&]() {
        return (interrupted = io::interrupt_signal_all_ranks()) != 0;
      };
      callbacks.progress = [&]() {
        progress.update(solver.statistics().n_steps, solver.time());
      };
      callbacks.cycle_done = checkpoint_if_due;
      thermal::spin_up(solver,
                       parameters,
                       SpinUp{spin_up_cycles,
                              spin_up_period,
                              parameters.start_time},
                       spin_up_done,
                       callbacks);
    }
    if (spin_up_cycles > 0 && !resume && interrupted == 0)
      context.log.line("spin-up: " + std::to_string(spin_up_cycles)
                       + " cycles of " + io::format_number(spin_up_period, 8)
                       + " s");
    if (!recording && interrupted == 0)
      {
        e0        = solver.stored_heat();
        q0        = solver.boundary_heat_in();
        recording = true;
        record();
        checkpoint_if_due();
      }
    if (interrupted == 0)
      {
        io::ProgressBar progress("heat",
                                 solver.time(),
                                 end_time,
                                 planned_to(end_time));
        while (solver.time() < end_time - 1e-9 * output_interval
               && (interrupted = io::interrupt_signal_all_ranks()) == 0)
          {
            double next
              = std::min(end_time,
                         record_start + (n_records + 1) * output_interval);
            ++n_records;
            while (!vtu_pending.empty() && vtu_pending.front() <= next)
              {
                if (vtu_pending.front() > solver.time())
                  solver.advance_to(vtu_pending.front());
                if (vtu_pending.front() >= record_start - 1e-9)
                  write_vtu();
                vtu_pending.erase(vtu_pending.begin());
              }
            solver.advance_to(next);
            record();
            progress.update(solver.statistics().n_steps, solver.time());
            checkpoint_if_due();
          }
      }
    // At the End time, unless just taken there (the run can be
    // extended); a checkpoint writes statistics.csv too. An interrupted
    // run always writes one (Resume = true continues it bit for bit).
    if ((checkpoint_interval > 0. || interrupted != 0)
        && saved_at != solver.time())
      save_checkpoint();
    else if (checkpoint_interval <= 0. && interrupted == 0)
      context.output.write("statistics.csv", table.csv());
    if (interrupted != 0)
      {
        context.stopped_early = true;
        context.stopped_note
          = "heat stopped at t = " + io::format_number(solver.time(), 10)
            + " s of " + io::format_number(end_time, 10) + " s"
            + (spin_up_done < spin_up_cycles
                 ? " (spin-up cycle " + std::to_string(spin_up_done) + " of "
                     + std::to_string(spin_up_cycles) + ")"
                 : std::string())
            + "; statistics.csv so far and checkpoint.bin written (set "
              "'Heat/Time stepping/Resume' = true to continue).";
        context.log.line(context.stopped_note);
      }
    if (n_vtu > 0)
      context.output.write("temperature.pvd",
                           pvd + "</Collection>\n</VTKFile>\n");

    const auto st = solver.statistics();
    if (parameters.adaptive_refinement)
      {
        context.summary.add("adaptations", st.n_adaptations, "-");
        context.summary.add("final_cells", st.n_cells, "-");
        context.summary.add("max_cells", st.max_n_cells, "-");
        context.summary.add("mesh_transfer_heat", st.mesh_transfer_heat, "J/m");
        context.log.line("adaptive mesh: " + std::to_string(st.n_adaptations)
                         + " adaptations, " + std::to_string(st.n_cells)
                         + " cells at the end (at most "
                         + std::to_string(st.max_n_cells) + ")");
      }
    context.summary.add("time_steps", st.n_steps, "-");
    context.summary.add("factorizations", st.n_factorizations, "-");
    context.summary.add("stiffness_ratio", st.stiffness_ratio, "-");
    context.summary.add("oscillation_steps", st.oscillation_steps, "-");
    if (st.oscillation_steps > 0)
      context.log.line(
        "WARNING: Crank-Nicolson oscillation detected in "
        + std::to_string(st.oscillation_steps) + " steps (dt kappa / h^2 = "
        + io::format_number(st.stiffness_ratio, 3) + ")"
        + (std::isnan(st.fallback_time)
             ? std::string("; consider backward-euler or a smaller time step")
             : "; continued with backward Euler from t = "
                 + io::format_number(st.fallback_time, 8) + " s"));
    for (std::size_t k = 0; k < probes.size(); ++k)
      context.summary.add("final_probe" + std::to_string(k + 1),
                          solver.probe_value(k),
                          "degC");
    const auto moments = solver.block_moments();
    for (std::size_t b = 0; b < moments.size(); ++b)
      context.summary.add("final_block" + std::to_string(b + 1) + "_mean",
                          moments[b].mean,
                          "degC");
    bool closed = true;
    for (const auto &bc : parameters.boundary_conditions)
      closed = closed && bc.type != BoundaryCondition::Type::temperature;
    if (closed && recording && parameters.stepper != TimeStepper::arkode)
      {
        // Heat added by the (non-conservative) field transfer onto
        // adapted meshes counts as input.
        const double stored = solver.stored_heat() - e0;
        const double input  = solver.boundary_heat_in() - q0
                             + st.mesh_transfer_heat - st0.mesh_transfer_heat;
        const double rel
          = std::abs(stored - input) / std::max(std::abs(input), 1e-300);
        context.summary.add("energy_balance_relative_error", rel, "-");
        context.log.line(
          "energy balance: stored " + io::format_number(stored, 8)
          + " J/m, boundary "
            "input "
          + io::format_number(input, 8) + " J/m, relative mismatch "
          + io::format_number(rel, 3));
      }

    if (halfspace_check && interrupted == 0)
      {
        // Fit over the last whole period of the recorded samples.
        const double omega = 2. * M_PI / halfspace_period;
        const double d
          = periodic_skin_depth(m0.diffusivity(), halfspace_period);
        std::vector<double> t;
        std::size_t         first = 0;
        while (first < sample_times.size()
               && sample_times[first] < end_time - halfspace_period + 1e-6)
          ++first;
        // Skip the duplicate end point of a whole period.
        for (std::size_t i = first; i < sample_times.size(); ++i)
          t.push_back(sample_times[i]);
        double worst_amplitude = 0., worst_lag = 0.;
        context.log.line("periodic half-space check: d = sqrt(2 kappa / "
                         "omega) = "
                         + io::format_number(d, 5) + " m");
        for (std::size_t k = 0; k < probes.size(); ++k)
          {
            const std::vector<double> v(samples[k].begin() + first,
                                        samples[k].end());
            const SinusoidFit         fit = fit_sinusoid(t, v, omega);
            const double              z   = surface_elevation - probes[k][1];
            const double amp  = halfspace_amplitude * std::exp(-z / d);
            double       lag  = -fit.phase / omega;
            const double lag0 = z / d / omega;
            // Unwrap the phase to the branch nearest the exact lag.
            while (lag < lag0 - 0.5 * halfspace_period)
              lag += halfspace_period;
            while (lag > lag0 + 0.5 * halfspace_period)
              lag -= halfspace_period;
            const double ea
              = std::abs(fit.amplitude - amp) / std::abs(halfspace_amplitude);
            const double el = std::abs(lag - lag0) / 86400.;
            worst_amplitude = std::max(worst_amplitude, ea);
            worst_lag       = std::max(worst_lag, el);
            context.log.line(
              "  z = " + io::format_number(z, 4) + " m: amplitude "
              + io::format_number(fit.amplitude, 6) + " (exact "
              + io::format_number(amp, 6) + "), lag "
              + io::format_number(lag / 86400., 5) + " days (exact "
              + io::format_number(lag0 / 86400., 5) + ")");
            context.summary.add("amplitude_probe" + std::to_string(k + 1),
                                fit.amplitude,
                                "K");
            context.summary.add("lag_probe" + std::to_string(k + 1),
                                lag / 86400.,
                                "day");
          }
        context.summary.add("halfspace_skin_depth", d, "m");
        context.summary.add("max_amplitude_error_fraction_of_A",
                            worst_amplitude,
                            "-");
        context.summary.add("max_lag_error", worst_lag, "day");
      }
    context.summary.add("solver_wall_time",
                        std::chrono::duration<double>(
                          std::chrono::steady_clock::now() - wall_start)
                          .count(),
                        "s");
    context.output.write("timing.txt", solver.timing_summary());
  }
} // namespace rockdda::thermal::internal



namespace rockdda::thermal
{
  std::vector<std::unique_ptr<io::Analysis>>
  make_analyses()
  {
    std::vector<std::unique_ptr<io::Analysis>> list;
    list.push_back(std::make_unique<internal::HeatAnalysis>());
    return list;
  }
} // namespace rockdda::thermal
