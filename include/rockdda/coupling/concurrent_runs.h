/**
 * @file
 * Independent runs (the calibration grid, the earthquake events, the
 * catalogues of the comparison) spread over threads with TBB, each run
 * once, stopped between runs by SIGINT / SIGTERM.
 */
#ifndef ROCKDDA_COUPLING_CONCURRENT_RUNS_H
#define ROCKDDA_COUPLING_CONCURRENT_RUNS_H

#include <cstddef>
#include <functional>
#include <vector>

namespace rockdda::coupling
{
  /// What run_concurrently() did.
  struct ConcurrentRuns
  {
    /// Threads used (>= 1).
    unsigned int threads = 1;
    /// Per run: true if it was started (and so finished).
    std::vector<bool> done;
    /// The signal that stopped the remaining runs (0: none).
    int signal = 0;
    /// Runs started.
    std::size_t
    n_done() const;
  };

  /**
   * Call @p run(i) once for every i in [0, @p n), on at most @p threads
   * threads (0: one per core, capped at @p n), with tbb::parallel_for in a
   * task arena of that size, one run per task. The runs must be
   * independent and write only their own results: then the results do not
   * depend on the number of threads or on the order of the runs. After
   * io::interrupt_signal() becomes nonzero no further run starts; those
   * already running finish. An exception thrown by a run is passed on after
   * the other runs have finished or been skipped.
   */
  ConcurrentRuns
  run_concurrently(const std::size_t                       n,
                   const unsigned int                      threads,
                   const std::function<void(std::size_t)> &run);
} // namespace rockdda::coupling

#endif
