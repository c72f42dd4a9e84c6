/**
 * @file
 * The time loop of the DDA analyses, written once for the 2D engine
 * (dda::DdaSystem) and the 3D one (dda3d::Engine): settling, steps that
 * land on output, statistics and checkpoint times, rows of statistics.csv,
 * the VTU (or HDF5) series, checkpoints and Resume, stopping on SIGINT /
 * SIGTERM, and the energy ledger over every accepted step.
 */
#ifndef ROCKDDA_DDA_RUN_LOOP_H
#define ROCKDDA_DDA_RUN_LOOP_H

#include <rockdda/dda/failure.h>
#include <rockdda/dda/hdf5_output.h>
#include <rockdda/io/analysis.h>
#include <rockdda/io/binary_stream.h>
#include <rockdda/io/checkpoint.h>
#include <rockdda/io/interrupt.h>
#include <rockdda/io/output.h>
#include <rockdda/io/progress.h>

#include <deal.II/base/parameter_handler.h>

#include <algorithm>
#include <cctype>
#include <chrono>
#include <functional>
#include <limits>
#include <string>
#include <utility>
#include <vector>

namespace rockdda::dda
{
  /// Controls of the time loop of a DDA analysis.
  struct RunSettings
  {
    /// The parameter subsection ("DDA", "DDA 3d"): the name of the run in
    /// log lines, messages and the checkpoint's header.
    std::string section;
    /// Label of the progress bar ("dda", "dda3d").
    std::string progress_label;
    /// End time (s), requested time step (s), output, statistics and
    /// checkpoint intervals (s; 0 = output and checkpoints off, a row
    /// after every step).
    double end_time = 1., time_step = 1e-3, output_interval = 0.,
           statistics_interval = 0., checkpoint_interval = 0.;
    /// Static steps before t = 0 (not when resuming).
    unsigned int settling_steps = 0;
    /// Continue from checkpoint.bin.
    bool resume = false;
    /// Also write the table as statistics.h5 (write_table_hdf5()) wherever
    /// statistics.csv is written ('Snapshot format' = hdf5).
    bool statistics_hdf5 = false;
    /// The controls a resumed run must share (io::RunCheckpoint).
    std::string fingerprint;
  };

  /**
   * The settings of a run from the keys the 2D and 3D analyses share
   * (@p shared, an AnalysisParameters<dim>) and 'Checkpoint interval' and
   * 'Resume' (io::RunCheckpoint::declare_parameters()) of the current
   * subsection of @p prm; the fingerprint is left to the analysis
   * (run_fingerprint()).
   */
  template <typename Shared>
  RunSettings
  run_settings(const Shared &shared, const dealii::ParameterHandler &prm)
  {
    RunSettings s;
    s.section = Shared::section();
    for (const char ch : s.section)
      if (ch != ' ')
        s.progress_label += static_cast<char>(std::tolower(ch));
    s.end_time            = shared.end_time;
    s.time_step           = shared.time_step;
    s.output_interval     = shared.output_interval;
    s.statistics_interval = shared.statistics_interval;
    s.settling_steps      = shared.settling_steps;
    s.statistics_hdf5     = shared.hdf5_output;
    s.checkpoint_interval = prm.get_double("Checkpoint interval");
    s.resume              = prm.get_bool("Resume");
    return s;
  }

  /**
   * The fingerprint of a run's controls that a checkpoint must share with
   * the run resuming it (End time excluded: a run can be extended).
   */
  std::string
  run_fingerprint(const std::size_t  n_blocks,
                  const double       time_step,
                  const double       penalty,
                  const double       dynamic,
                  const unsigned int settling_steps,
                  const std::string &seismic_input);

  /**
   * A run's progress beyond the engine's state, saved in its checkpoint:
   * the snapshot series, the next output, row and checkpoint times, the
   * counters of the rows and the energy ledger over every accepted step.
   */
  struct RunProgress
  {
    /// (time, file) of the block and contact snapshots so far.
    std::vector<std::pair<double, std::string>> block_files, contact_files;
    double next_output = 0., next_row = 0., next_checkpoint = 0.;
    /// Largest and total open-close iterations of the steps.
    unsigned int  max_iterations   = 0;
    unsigned long iterations_total = 0;
    /// The engine's cuts counted by the rows so far (the cuts column
    /// counts every cut since the previous row).
    unsigned long cuts_reported = 0;
    /// The ledger's balance at the start (J or J/m), the largest gain over
    /// it (created energy) and the largest energy in play.
    double balance0 = 0., created_max = 0., energy_in_play = 0.;

    /// Append to @p w (the format of the 2D run's checkpoint).
    void
    put(io::BinaryWriter &w) const;

    /// Read what put() wrote.
    void
    get(io::BinaryReader &r);
  };

  /**
   * The time loop of a DDA analysis over the engine type @p EngineType,
   * which provides time(), time_step() (the current step length, s),
   * n_steps and n_cuts, energy() (with balance() and scale()),
   * settle(n, after_step), checkpoint() and restore(bytes, source). The
   * analysis provides the engine-specific parts as functions: one step,
   * a row of the table, a snapshot.
   */
  template <typename EngineType>
  class RunLoop
  {
  public:
    /// One step towards @p target (s), not beyond it; returns the step's
    /// open-close iterations.
    using Step = std::function<unsigned int(const double target)>;
    /// Append a row to the table; @p cuts: the cuts since the last row.
    using AddRow = std::function<void(const unsigned long cuts)>;

    RunLoop(EngineType        &engine,
            const RunSettings &settings,
            io::RunContext    &context,
            io::Table         &table)
        : engine(engine)
        , settings(settings)
        , context(context)
        , table(table)
        , checkpoint_file(context.output,
                          settings.section,
                          settings.fingerprint,
                          settings.section)
    {}

    /**
     * Settle (unless resuming), then resume from the checkpoint or write
     * the first row and snapshot (@p snapshot, if the output interval is
     * > 0), and step to the End time. Writes statistics.csv and the
     * checkpoints; sets the context's stopped_early on SIGINT / SIGTERM;
     * logs and rethrows a dda::DdaFailure. Returns false if stopped while
     * settling (nothing else written).
     */
    bool
    run(const Step                  &step,
        const AddRow                &add_row,
        const std::function<void()> &snapshot);

    /// Called after a checkpoint has been loaded (e.g. to reopen a series).
    std::function<void()> on_resume;

    /// Called wherever statistics.csv is written (each checkpoint, before
    /// checkpoint.bin, and the end of the run), after statistics.h5 (if
    /// RunSettings::statistics_hdf5), to write other files of the table
    /// (e.g. measurement_points.h5) at the same cadence.
    std::function<void()> on_statistics;

    /// The run's progress (after run(): at its end).
    RunProgress progress;
    /// Nonzero if stopped by this signal.
    int interrupted = 0;
    /// Wall time of the time loop (s).
    double wall = 0.;

    /// The log's last line: steps, cuts and wall time.
    std::string
    finished_line() const
    {
      return settings.section
             + (interrupted != 0 ? " stopped early: " : " finished: ")
             + std::to_string(engine.n_steps) + " steps, "
             + std::to_string(engine.n_cuts) + " cuts, "
             + io::format_number(wall, 3) + " s wall";
    }

  private:
    void
    save_checkpoint();

    void
    load_checkpoint();

    /// The files of the table beside statistics.csv: statistics.h5 and
    /// those of on_statistics.
    void
    write_table_files();

    /// A row, with the cuts since the previous one.
    void
    row(const AddRow &add_row)
    {
      const unsigned long cuts = engine.n_cuts - progress.cuts_reported;
      progress.cuts_reported   = engine.n_cuts;
      add_row(cuts);
    }

    EngineType             &engine;
    const RunSettings       settings;
    io::RunContext         &context;
    io::Table              &table;
    const io::RunCheckpoint checkpoint_file;
    /// Time of the last checkpoint written.
    double saved_at = std::numeric_limits<double>::quiet_NaN();
  };



  template <typename EngineType>
  void
  RunLoop<EngineType>::save_checkpoint()
  {
    io::BinaryWriter w = checkpoint_file.begin();
    w.put_string(engine.checkpoint());
    io::RunCheckpoint::put_rows(w, table);
    progress.put(w);
    write_table_files();
    checkpoint_file.write(w, table);
    saved_at = engine.time();
  }



  template <typename EngineType>
  void
  RunLoop<EngineType>::write_table_files()
  {
    if (settings.statistics_hdf5)
      write_table_hdf5(context.output, "statistics.h5", table);
    if (on_statistics)
      on_statistics();
  }



  template <typename EngineType>
  void
  RunLoop<EngineType>::load_checkpoint()
  {
    const std::string bytes = checkpoint_file.read();
    io::BinaryReader  r     = checkpoint_file.reader(bytes);
    engine.restore(r.get_string(), checkpoint_file.file());
    io::RunCheckpoint::get_rows(r, table);
    progress.get(r);
    if (!r.at_end())
      throw InputError(checkpoint_file.file() + ": trailing data");
    context.log.line("resumed from " + checkpoint_file.file()
                     + " at t = " + io::format_number(engine.time(), 8)
                     + " s (step " + std::to_string(engine.n_steps) + ")");
    if (on_resume)
      on_resume();
  }



  template <typename EngineType>
  bool
  RunLoop<EngineType>::run(const Step                  &step,
                           const AddRow                &add_row,
                           const std::function<void()> &snapshot)
  {
    const RunSettings &s = settings;
    const unsigned int n = s.settling_steps;
    if (n > 0 && !s.resume)
      {
        // Static steps before t = 0, with progress, stopped by SIGINT /
        // SIGTERM like the time loop.
        unsigned int done = 0;
        {
          io::ProgressBar bar(s.progress_label + " settling", 0., double(n), n);
          engine.settle(n, [&](const unsigned int k) {
            done = k;
            bar.update(k, double(k));
            return io::interrupt_signal() == 0;
          });
        }
        if (done < n)
          {
            context.stopped_early = true;
            context.stopped_note
              = s.section + " stopped while settling, after "
                + std::to_string(done) + " of " + std::to_string(n)
                + " static steps (before t = 0: there is no time series to "
                  "keep; run again to settle)";
            context.log.line(context.stopped_note);
            return false;
          }
        context.log.line("settled with " + std::to_string(n) + " static steps");
      }

    RunProgress &p     = progress;
    p.next_output      = s.output_interval;
    p.next_row         = s.statistics_interval;
    p.next_checkpoint  = s.checkpoint_interval;
    const auto ledger0 = engine.energy();
    p.balance0         = ledger0.balance();
    p.energy_in_play   = ledger0.scale();
    if (s.resume)
      load_checkpoint();
    else
      {
        row(add_row);
        if (s.output_interval > 0.)
          snapshot();
      }
    std::string         failure;
    const auto          start = std::chrono::steady_clock::now();
    const unsigned long step_limit
      = static_cast<unsigned long>(100. * s.end_time / s.time_step) + 1000;
    {
      io::ProgressBar bar(s.progress_label,
                          engine.time(),
                          s.end_time,
                          engine.n_steps
                            + static_cast<unsigned long>(io::planned_steps(
                              engine.time(), s.end_time, s.time_step)));
      try
        {
          while (engine.time() < s.end_time - 1e-9 * s.time_step
                 && (interrupted = io::interrupt_signal()) == 0)
            {
              // One step, landing exactly on output and checkpoint times.
              double target = s.end_time;
              if (s.output_interval > 0.)
                target = std::min(target, p.next_output);
              if (s.checkpoint_interval > 0.)
                target = std::min(target, p.next_checkpoint);
              const unsigned int iterations = step(target);
              if (engine.n_steps > step_limit)
                throw DdaFailure(
                  "stopped at t = " + io::format_number(engine.time(), 6)
                  + " s after " + std::to_string(step_limit)
                  + " steps (100 x End time / Time step + 1000): the time "
                    "step stayed far below the requested one (now "
                  + io::format_number(engine.time_step(), 4) + " s)");
              p.max_iterations = std::max(p.max_iterations, iterations);
              p.iterations_total += iterations;
              {
                const auto e = engine.energy();
                p.created_max
                  = std::max(p.created_max, e.balance() - p.balance0);
                p.energy_in_play = std::max(p.energy_in_play, e.scale());
              }
              if (s.statistics_interval <= 0.
                  || engine.time() >= p.next_row - 1e-12)
                {
                  row(add_row);
                  while (s.statistics_interval > 0.
                         && p.next_row <= engine.time() + 1e-12)
                    p.next_row += s.statistics_interval;
                }
              if (s.output_interval > 0.
                  && engine.time() >= p.next_output - 1e-12)
                {
                  snapshot();
                  p.next_output += s.output_interval;
                }
              if (s.checkpoint_interval > 0.
                  && engine.time() >= p.next_checkpoint - 1e-12)
                {
                  while (p.next_checkpoint <= engine.time() + 1e-12)
                    p.next_checkpoint += s.checkpoint_interval;
                  save_checkpoint();
                }
              bar.update(engine.n_steps, engine.time());
            }
        }
      catch (const DdaFailure &e)
        {
          failure = e.what();
        }
    }
    wall
      = std::chrono::duration<double>(std::chrono::steady_clock::now() - start)
          .count();
    // At the End time, unless just taken there (the run can be extended);
    // a checkpoint writes statistics.csv too. An interrupted run always
    // writes a checkpoint (Resume = true continues it bit for bit), with
    // statistics.csv so far.
    if ((s.checkpoint_interval > 0. || interrupted != 0) && failure.empty()
        && saved_at != engine.time())
      save_checkpoint();
    else if ((s.checkpoint_interval <= 0. && interrupted == 0)
             || !failure.empty())
      {
        write_table_files();
        context.output.write("statistics.csv", table.csv());
      }
    if (interrupted != 0 && failure.empty())
      {
        // statistics.csv has the rows reported so far; the state reached is
        // in the summary and the checkpoint.
        context.stopped_early = true;
        context.stopped_note
          = s.section + " stopped at t = " + io::format_number(engine.time(), 8)
            + " s of " + io::format_number(s.end_time, 8) + " s (step "
            + std::to_string(engine.n_steps)
            + "); statistics.csv so far and checkpoint.bin written (set '"
            + s.section + "/Resume' = true to continue).";
        context.log.line(context.stopped_note);
      }
    if (!failure.empty())
      {
        context.log.line(s.section + " stopped: " + failure);
        throw DdaFailure(failure);
      }
    return true;
  }
} // namespace rockdda::dda

#endif
