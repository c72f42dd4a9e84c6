/**
 * @file
 * The analysis type "calibrate" (thesis 5.5.2, Fig. 5-16): DDA's penalty
 * and time step on Masada Block 1 against the analytical sliding block.
 */
#ifndef ROCKDDA_COUPLING_CALIBRATE_ANALYSIS_H
#define ROCKDDA_COUPLING_CALIBRATE_ANALYSIS_H

#include <rockdda/io/analysis.h>

#include <memory>

namespace rockdda::coupling
{
  /// The "calibrate" analysis, for make_analyses().
  std::unique_ptr<io::Analysis>
  make_calibrate_analysis();
} // namespace rockdda::coupling

#endif
