#include <rockdda/io/progress.h>

#include <cstdio>
#include <unistd.h>

namespace rockdda::io
{
  ProgressBar::ProgressBar(const std::string &label, const double end_time)
      : label(label)
      , end_time(end_time)
      , enabled(::isatty(STDERR_FILENO) == 1)
      , start(std::chrono::steady_clock::now())
      , last(start)
  {}



  ProgressBar::~ProgressBar()
  {
    finish();
  }



  void
  ProgressBar::draw(const unsigned long step, const double time, const bool)
  {
    const auto   now     = std::chrono::steady_clock::now();
    const double elapsed = std::chrono::duration<double>(now - start).count();
    if (elapsed < 1. || std::chrono::duration<double>(now - last).count() < 0.2)
      return;
    last                = now;
    const double frac   = end_time > 0. ? std::min(1., time / end_time) : 0.;
    const double rate   = step / elapsed;
    const double eta    = frac > 0. ? elapsed * (1. - frac) / frac : 0.;
    const int    width  = 30;
    const int    filled = static_cast<int>(frac * width);
    std::string  bar(filled, '#');
    bar += std::string(width - filled, '.');
    std::fprintf(stderr,
                 "\r%s [%s] %5.1f%%  step %lu  t = %.4g s  %.3g steps/s  "
                 "ETA %.0f s   ",
                 label.c_str(),
                 bar.c_str(),
                 100. * frac,
                 step,
                 time,
                 rate,
                 eta);
    std::fflush(stderr);
    drawn = true;
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
} // namespace rockdda::io
