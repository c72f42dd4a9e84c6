/**
 * @file
 * The exception type for bad user input.
 */
#ifndef ROCKDDA_IO_ERROR_H
#define ROCKDDA_IO_ERROR_H

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
} // namespace rockdda

#endif
