/**
 * @file
 * The exception type for bad user input.
 */
#ifndef ROCKDDA_IO_ERROR_H
#define ROCKDDA_IO_ERROR_H

#include <cmath>
#include <sstream>
#include <stdexcept>
#include <string>

namespace rockdda
{
  /**
   * Thrown for any bad user input: an unknown key, a value out of range, a
   * malformed data file, a degenerate geometry. The message is complete and
   * meant for the user as it stands: it names the file, the line or key, and
   * the valid range. The driver prints it and exits non-zero.
   */
  class InputError : public std::runtime_error
  {
  public:
    explicit InputError(const std::string &message)
        : std::runtime_error(message)
    {}
  };

  /**
   * Throw an InputError "KEY = VALUE is out of range; valid: RANGE" unless
   * @p ok holds and @p value is finite.
   */
  inline void
  require_in_range(const bool         ok,
                   const std::string &key,
                   const double       value,
                   const std::string &range)
  {
    if (ok && std::isfinite(value))
      return;
    std::ostringstream message;
    message << "key '" << key << "' = " << value
            << " is out of range; valid: " << range;
    throw InputError(message.str());
  }
} // namespace rockdda

#endif
