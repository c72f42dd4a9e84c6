#include <rockdda/coupling/concurrent_runs.h>
#include <rockdda/io/interrupt.h>

#include <algorithm>
#include <atomic>
#include <exception>
#include <mutex>
#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <tbb/partitioner.h>
#include <tbb/task_arena.h>
#include <thread>

namespace rockdda::coupling
{
  std::size_t
  ConcurrentRuns::n_done() const
  {
    return static_cast<std::size_t>(std::count(done.begin(), done.end(), true));
  }



  ConcurrentRuns
  run_concurrently(const std::size_t                       n,
                   const unsigned int                      threads,
                   const std::function<void(std::size_t)> &run)
  {
    ConcurrentRuns     result;
    const unsigned int cores
      = std::max(1u, std::thread::hardware_concurrency());
    result.threads = static_cast<unsigned int>(std::max<std::size_t>(
      1, std::min<std::size_t>(threads > 0 ? threads : cores, n)));
    // std::vector<bool> packs bits: each run writes its own char.
    std::vector<char>  started(n, 0);
    std::exception_ptr error;
    std::mutex         error_mutex;
    std::atomic<bool>  failed{false};
    const auto         one = [&](const std::size_t i) {
      if (failed.load() || io::interrupt_signal() != 0)
        return;
      started[i] = 1;
      try
        {
          run(i);
        }
      catch (...)
        {
          const std::lock_guard<std::mutex> lock(error_mutex);
          if (!error)
            error = std::current_exception();
          failed.store(true);
        }
    };
    if (result.threads == 1)
      for (std::size_t i = 0; i < n; ++i)
        one(i);
    else
      {
        tbb::task_arena arena(static_cast<int>(result.threads));
        arena.execute([&]() {
          tbb::parallel_for(
            tbb::blocked_range<std::size_t>(0, n, 1),
            [&](const tbb::blocked_range<std::size_t> &r) {
              for (std::size_t i = r.begin(); i != r.end(); ++i)
                one(i);
            },
            tbb::simple_partitioner());
        });
      }
    if (error)
      std::rethrow_exception(error);
    result.done.assign(started.begin(), started.end());
    result.signal = io::interrupt_signal();
    return result;
  }
} // namespace rockdda::coupling
