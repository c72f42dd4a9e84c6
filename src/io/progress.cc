#include <rockdda/io/progress.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <unistd.h>

namespace rockdda::io
{
  ProgressBar::ProgressBar(const std::string &label, const double end_time)
      : ProgressBar(label, 0., end_time, 0)
  {}



  ProgressBar::ProgressBar(const std::string  &label,
                           const double        start_time,
                           const double        end_time,
                           const unsigned long planned_steps)
      : label(label)
      , start_time(start_time)
      , end_time(end_time)
      , planned_steps(planned_steps)
      , enabled(::isatty(STDERR_FILENO) == 1)
      , start(std::chrono::steady_clock::now())
      , last_check(start)
      , last_draw(start)
  {}



  ProgressBar::~ProgressBar()
  {
    finish();
  }



  void
  ProgressBar::check(const unsigned long step, const double time)
  {
    const auto   now = std::chrono::steady_clock::now();
    const double since
      = std::chrono::duration<double>(now - last_check).count();
    last_check = now;
    // Read the clock about every 10 ms, whatever a step costs.
    if (since < 0.005 && stride < (1ul << 20))
      stride *= 2;
    else if (since > 0.05 && stride > 1)
      stride /= 2;
    next_check           = calls + stride;
    const double elapsed = std::chrono::duration<double>(now - start).count();
    if (elapsed < 1.
        || std::chrono::duration<double>(now - last_draw).count() < 0.25)
      return;
    last_draw = now;
    std::fprintf(stderr, "\r%s", text(step, time, elapsed).c_str());
    std::fflush(stderr);
    drawn = true;
  }



  std::string
  ProgressBar::text(const unsigned long step,
                    const double        time,
                    const double        elapsed) const
  {
    const double span = end_time - start_time;
    const double frac
      = span > 0. ? std::clamp((time - start_time) / span, 0., 1.) : 0.;
    char buffer[256];
    int  n = std::snprintf(
      buffer, sizeof(buffer), "%s  step %lu", label.c_str(), step);
    if (planned_steps > 0)
      n += std::snprintf(buffer + n, sizeof(buffer) - n, "/%lu", planned_steps);
    n += std::snprintf(buffer + n,
                       sizeof(buffer) - n,
                       "  t = %.4g s of %.4g s  %5.1f %%",
                       time,
                       end_time,
                       100. * frac);
    if (frac > 0.)
      std::snprintf(buffer + n,
                    sizeof(buffer) - n,
                    "  ETA %.0f s   ",
                    elapsed * (1. - frac) / frac);
    else
      std::snprintf(buffer + n, sizeof(buffer) - n, "  ETA -   ");
    return buffer;
  }



  void
  ProgressBar::finish()
  {
    if (drawn)
      {
        std::fprintf(stderr, "\r%*s\r", 100, "");
        std::fflush(stderr);
        drawn = false;
      }
  }



  double
  planned_steps(const double start_time,
                const double end_time,
                const double time_step)
  {
    if (!(time_step > 0.) || !(end_time > start_time))
      return 0.;
    const double n = (end_time - start_time) / time_step;
    // A last partial step counts; round-off (1e-9 of a step) does not.
    return std::ceil(n * (1. - 1e-12) - 1e-9);
  }
} // namespace rockdda::io
