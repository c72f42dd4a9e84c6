#include <rockdda/io/plot.h>

#include <cstdlib>
#include <fstream>

namespace rockdda::io
{
  void
  run_plot_script(const OutputDirectory          &output,
                  Log                            &log,
                  const std::string              &script,
                  const std::vector<std::string> &pngs,
                  const std::string              &arguments)
  {
    const std::string path
      = std::string(ROCKDDA_SOURCE_DIR) + "/scripts/" + script;
    const std::string python = "/usr/bin/python3";
    std::string       names;
    for (const auto &png : pngs)
      {
        output.own(png);
        names += (names.empty() ? "" : ", ") + png;
      }
    if (!std::ifstream(python) || !std::ifstream(path))
      {
        log.line("note: no plots (" + python + " or " + path + " missing)");
        return;
      }
    const std::string command = python + " '" + path + "' '" + output.path()
                                + "'" + arguments + " > /dev/null 2>&1";
    if (std::system(command.c_str()) == 0)
      log.line("plots: " + names);
    else
      log.line("note: plotting failed (" + command
               + "); is python3-matplotlib installed?");
  }
} // namespace rockdda::io
