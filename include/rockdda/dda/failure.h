/**
 * @file
 * The exception of a DDA run that cannot continue, shared by the 2D and the
 * 3D engine (a run failure, not bad input: the driver exits with status 3).
 */
#ifndef ROCKDDA_DDA_FAILURE_H
#define ROCKDDA_DDA_FAILURE_H

#include <stdexcept>
#include <string>

namespace rockdda::dda
{
  /// A run that cannot continue (the message is the diagnosis).
  class DdaFailure : public std::runtime_error
  {
  public:
    explicit DdaFailure(const std::string &message)
        : std::runtime_error(message)
    {}
  };
} // namespace rockdda::dda

#endif
