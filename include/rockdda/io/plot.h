/**
 * @file
 * Plots of a run: run one of the project's Python scripts (scripts/) on
 * the run's output folder.
 */
#ifndef ROCKDDA_IO_PLOT_H
#define ROCKDDA_IO_PLOT_H

#include <rockdda/io/output.h>

#include <string>
#include <vector>

namespace rockdda::io
{
  /**
   * Run scripts/@p script with /usr/bin/python3 (Debian's
   * python3-matplotlib) on the folder of @p output with the extra command
   * line @p arguments; the @p pngs it writes are owned by the run. Logs
   * which plots were written, or why not (no interpreter or script, or the
   * script failed); never throws for a failed plot.
   */
  void
  run_plot_script(const OutputDirectory          &output,
                  Log                            &log,
                  const std::string              &script,
                  const std::vector<std::string> &pngs,
                  const std::string              &arguments = "");
} // namespace rockdda::io

#endif
