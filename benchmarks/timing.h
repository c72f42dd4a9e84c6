/**
 * @file
 * Wall-clock helpers shared by the benchmark executables
 * (benchmarks/dda-scaling/dda_scaling.cc, benchmarks/dda3d/dda3d_scaling.cc).
 */
#ifndef ROCKDDA_BENCHMARKS_TIMING_H
#define ROCKDDA_BENCHMARKS_TIMING_H

#include <algorithm>
#include <chrono>
#include <vector>

namespace rockdda::benchmarks
{
  /// Wall time (s) since @p t0.
  inline double
  seconds_since(const std::chrono::steady_clock::time_point t0)
  {
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0)
      .count();
  }

  /// The median of @p v (the upper of the two middle values if the count is
  /// even); @p v must not be empty.
  inline double
  median(std::vector<double> v)
  {
    std::sort(v.begin(), v.end());
    return v[v.size() / 2];
  }
} // namespace rockdda::benchmarks

#endif
