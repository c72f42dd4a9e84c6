/**
 * @file
 * The analysis types of the thermal subsystem ("heat") as the driver sees
 * them.
 */
#ifndef ROCKDDA_THERMAL_ANALYSES_H
#define ROCKDDA_THERMAL_ANALYSES_H

#include <rockdda/io/analysis.h>

#include <memory>
#include <vector>

namespace rockdda::thermal
{
  /// The analyses of this subsystem, for io::all_analyses().
  std::vector<std::unique_ptr<io::Analysis>>
  make_analyses();
} // namespace rockdda::thermal

#endif
