/**
 * @file
 * The analysis type "earthquakes" (thesis 5.5.3, Fig. 5-18): Masada Block 1
 * under seeded synthetic earthquakes in DDA and analytically.
 */
#ifndef ROCKDDA_COUPLING_EARTHQUAKES_ANALYSIS_H
#define ROCKDDA_COUPLING_EARTHQUAKES_ANALYSIS_H

#include <rockdda/io/analysis.h>

#include <memory>

namespace rockdda::coupling
{
  /// The "earthquakes" analysis, for make_analyses().
  std::unique_ptr<io::Analysis>
  make_earthquakes_analysis();
} // namespace rockdda::coupling

#endif
