/**
 * @file
 * The analysis type "synthetic-motion": seeded realisations of the
 * stochastic point-source method (Boore 2003) for one earthquake scenario,
 * with an optional site amplification, compared with BJF97 and with their
 * target Fourier spectrum.
 */
#ifndef ROCKDDA_SEISMIC_SYNTHETIC_ANALYSIS_H
#define ROCKDDA_SEISMIC_SYNTHETIC_ANALYSIS_H

#include <rockdda/io/analysis.h>

#include <memory>

namespace rockdda::seismic
{
  /// Factory of the 'synthetic-motion' analysis (synthetic_analysis.cc).
  std::unique_ptr<io::Analysis>
  make_synthetic_analysis();
} // namespace rockdda::seismic

#endif
