/**
 * @file
 * The analysis types of the seismic subsystem as the driver sees them.
 */
#ifndef ROCKDDA_SEISMIC_ANALYSES_H
#define ROCKDDA_SEISMIC_ANALYSES_H

#include <rockdda/io/analysis.h>

#include <memory>
#include <vector>

namespace rockdda::seismic
{
  /// The analyses of this subsystem ('record'), for io::all_analyses().
  std::vector<std::unique_ptr<io::Analysis>>
  make_analyses();

  namespace internal
  {
    /// Factory of the 'record' analysis (record_analysis.cc).
    std::unique_ptr<io::Analysis>
    make_record_analysis();
  } // namespace internal
} // namespace rockdda::seismic

#endif
