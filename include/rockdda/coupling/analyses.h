/**
 * @file
 * The analysis types of the coupling subsystem (the coupled
 * thermo-mechanical ratchet) as the driver sees them.
 */
#ifndef ROCKDDA_COUPLING_ANALYSES_H
#define ROCKDDA_COUPLING_ANALYSES_H

#include <rockdda/io/analysis.h>

#include <memory>
#include <vector>

namespace rockdda::coupling
{
  /// The analyses of this subsystem, for io::all_analyses().
  std::vector<std::unique_ptr<io::Analysis>>
  make_analyses();
} // namespace rockdda::coupling

#endif
