#include <rockdda/dda/step_driver.h>
#include <rockdda/io/output.h>

namespace rockdda::dda
{
  std::string
  step_failure_message(const std::string  &engine,
                       const unsigned long step,
                       const double        time,
                       const std::string  &why,
                       const double        minimum,
                       const std::string  &minimum_rule)
  {
    return engine + "step " + std::to_string(step)
           + " at t = " + io::format_number(time, 6) + " s: " + why
           + "; cutting the time step further would go below the minimum "
           + io::format_number(minimum, 6) + " s" + minimum_rule
           + ". Check the penalty, the time step and the geometry.";
  }



  std::string
  step_limit_message(const std::string  &engine,
                     const double        time,
                     const unsigned long limit,
                     const double        current,
                     const double        requested,
                     const std::string  &last_cut)
  {
    return engine + "stopped at t = " + io::format_number(time, 6) + " s after "
           + std::to_string(limit)
           + " steps (step limit): the time step stayed at "
           + io::format_number(current, 6) + " s, far below the requested "
           + io::format_number(requested, 6) + " s"
           + (last_cut.empty() ? std::string()
                               : " (last cut: " + last_cut + ")");
  }
} // namespace rockdda::dda
