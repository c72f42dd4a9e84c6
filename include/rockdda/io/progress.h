/**
 * @file
 * A progress line for long runs.
 */
#ifndef ROCKDDA_IO_PROGRESS_H
#define ROCKDDA_IO_PROGRESS_H

#include <chrono>
#include <string>

namespace rockdda::io
{
  /**
   * Shows the step against the planned step count, the simulated time, the
   * fraction done and the ETA on one line of stderr ("dda  step 1200/3000
   * t = 1.2 s of 3 s  40.0 %  ETA 12 s"), rewritten in place with '\r' at
   * most four times a second, for a run that has lasted longer than a
   * second, and only when stderr is a terminal: nothing goes to pipes,
   * files, logs or CI. update() reads the clock only every few calls
   * (the stride adapts to the step rate), so calling it every step is
   * cheap. The line is cleared when the bar is finished or destroyed.
   */
  class ProgressBar
  {
  public:
    /// @p end_time (s) is the simulated time at which the run ends; the
    /// run starts at 0 and no step count is planned.
    ProgressBar(const std::string &label, const double end_time);

    /**
     * A run from @p start_time to @p end_time (s) in about @p planned_steps
     * steps in all (0: not known, e.g. adaptive time stepping).
     */
    ProgressBar(const std::string  &label,
                const double        start_time,
                const double        end_time,
                const unsigned long planned_steps);

    ~ProgressBar();

    /// Report that step @p step reached simulated time @p time (s).
    void
    update(const unsigned long step, const double time)
    {
      if (enabled && ++calls >= next_check)
        check(step, time);
    }

    /// Clear the line (called by the destructor too).
    void
    finish();

    /// The line that would be drawn after @p elapsed seconds of wall time
    /// (for tests).
    std::string
    text(const unsigned long step,
         const double        time,
         const double        elapsed) const;

  private:
    void
    check(const unsigned long step, const double time);

    std::string                           label;
    double                                start_time, end_time;
    unsigned long                         planned_steps;
    bool                                  enabled;
    bool                                  drawn      = false;
    unsigned long                         calls      = 0;
    unsigned long                         next_check = 1;
    unsigned long                         stride     = 1;
    std::chrono::steady_clock::time_point start, last_check, last_draw;
  };

  /**
   * The time steps a run from @p start_time to @p end_time with step
   * @p time_step plans: (end_time - start_time) / time_step, rounded up
   * (as a double: it may be absurdly large).
   */
  double
  planned_steps(const double start_time,
                const double end_time,
                const double time_step);

  /// The largest planned step count a run accepts.
  constexpr double max_planned_steps = 1e8;
} // namespace rockdda::io

#endif
