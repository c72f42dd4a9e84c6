/**
 * @file
 * The analysis type "compare" (thesis 5.6.2, Fig. 5-19; issue 15, item 3):
 * thermal against seismic displacement rate of Masada Block 1 over a window,
 * and the combined history over seeded Gutenberg-Richter catalogues.
 */
#ifndef ROCKDDA_COUPLING_COMPARE_ANALYSIS_H
#define ROCKDDA_COUPLING_COMPARE_ANALYSIS_H

#include <rockdda/io/analysis.h>

#include <memory>

namespace rockdda::coupling
{
  /// The "compare" analysis, for make_analyses().
  std::unique_ptr<io::Analysis>
  make_compare_analysis();
} // namespace rockdda::coupling

#endif
