/**
 * @file
 * The two-thread team of the DDA linear solver.
 */
#include "thread_pair.h"

#include <algorithm>

#if defined(__x86_64__) || defined(__i386__)
#  include <immintrin.h>
#endif

namespace rockdda::dda::internal
{
  namespace
  {
    inline void
    cpu_relax()
    {
#if defined(__x86_64__) || defined(__i386__)
      _mm_pause();
#endif
    }
  } // namespace



  ThreadPair::ThreadPair(const bool two_threads)
  {
    if (two_threads)
      worker = std::thread([this]() { loop(); });
  }



  ThreadPair::~ThreadPair()
  {
    if (!worker.joinable())
      return;
    stop.store(true);
    post();
    worker.join();
  }



  void
  ThreadPair::rest()
  {
    resting.store(true);
  }



  void
  ThreadPair::post()
  {
    resting.store(false);
    generation.fetch_add(1); // sequentially consistent, pairs with sleeping
    if (sleeping.load())
      {
        std::lock_guard<std::mutex> lock(mutex);
        wake.notify_one();
      }
  }



  void
  ThreadPair::wait()
  {
    const unsigned target = generation.load(std::memory_order_relaxed);
    for (unsigned spins = 0; finished.load(std::memory_order_acquire) != target;
         ++spins)
      if (spins < 20000)
        cpu_relax();
      else
        std::this_thread::yield();
  }



  void
  ThreadPair::late_phase(const std::chrono::steady_clock::duration own,
                         const std::chrono::steady_clock::duration waited)
  {
    const bool is_late
      = waited > 4 * own && waited > std::chrono::microseconds(50);
    late = is_late ? late + 1 : 0;
    if (late >= 8)
      {
        late          = 0;
        serial_phases = 4096;
        rest();
      }
  }



  void
  ThreadPair::loop()
  {
    unsigned seen = 0;
    for (;;)
      {
        // Spin (~0.1 ms), then yield (a loaded machine), then sleep until
        // the next phase (the worker is idle between time steps).
        unsigned spins = 0;
        unsigned g;
        while ((g = generation.load(std::memory_order_acquire)) == seen)
          {
            ++spins;
            if (resting.load(std::memory_order_relaxed))
              spins = std::max(spins, 22000u);
            if (spins < 20000)
              cpu_relax();
            else if (spins < 22000)
              std::this_thread::yield();
            else
              {
                std::unique_lock<std::mutex> lock(mutex);
                sleeping.store(true);
                wake.wait(lock, [&]() { return generation.load() != seen; });
                sleeping.store(false);
              }
          }
        seen = g;
        if (stop.load())
          return;
        task(context, 1);
        finished.store(g, std::memory_order_release);
      }
  }
} // namespace rockdda::dda::internal
