/**
 * @file
 * A progress bar for long runs.
 */
#ifndef ROCKDDA_IO_PROGRESS_H
#define ROCKDDA_IO_PROGRESS_H

#include <chrono>
#include <string>

namespace rockdda::io
{
  /**
   * Shows step, simulated time, rate and ETA on stderr for a run that has
   * lasted longer than a second, and only when stderr is a terminal (silent
   * in pipes, files and CI). Redraws at most five times a second, so calling
   * update() every step is cheap.
   */
  class ProgressBar
  {
  public:
    /// @p end_time (s) is the simulated time at which the run ends.
    ProgressBar(const std::string &label, const double end_time);
    ~ProgressBar();

    /// Report that step @p step reached simulated time @p time (s).
    void
    update(const unsigned long step, const double time)
    {
      if (enabled && (++calls & 0x3ff) == 0)
        draw(step, time, false);
    }

    /// Clear the line (called by the destructor too).
    void
    finish();

  private:
    void
    draw(const unsigned long step, const double time, const bool force);

    std::string                           label;
    double                                end_time;
    bool                                  enabled;
    bool                                  drawn = false;
    unsigned long                         calls = 0;
    std::chrono::steady_clock::time_point start, last;
  };
} // namespace rockdda::io

#endif
