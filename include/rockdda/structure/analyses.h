/**
 * @file
 * The analysis types of the structure subsystem ("cut": generate a rock
 * structure, cut it into blocks, write blocks and structure statistics).
 */
#ifndef ROCKDDA_STRUCTURE_ANALYSES_H
#define ROCKDDA_STRUCTURE_ANALYSES_H

#include <rockdda/io/analysis.h>

#include <memory>
#include <vector>

namespace rockdda::structure
{
  /// The analyses of this subsystem, for io::all_analyses().
  std::vector<std::unique_ptr<io::Analysis>>
  make_analyses();
} // namespace rockdda::structure

#endif
