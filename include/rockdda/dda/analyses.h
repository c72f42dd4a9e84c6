/**
 * @file
 * The analysis types of the DDA subsystem as the driver sees them.
 */
#ifndef ROCKDDA_DDA_ANALYSES_H
#define ROCKDDA_DDA_ANALYSES_H

#include <rockdda/io/analysis.h>

#include <memory>
#include <vector>

namespace rockdda::dda
{
  /// The analyses of this subsystem ("dda"), for io::all_analyses().
  std::vector<std::unique_ptr<io::Analysis>>
  make_analyses();
} // namespace rockdda::dda

#endif
