/**
 * @file
 * Internal to the dda subsystem: a caller thread and at most one worker
 * thread that run the two halves of a parallel phase (the two subdomains
 * of the linear solver's D-ILU sweeps, two phases per CG iteration).
 * Phases are short (tens to hundreds of microseconds), so the worker waits
 * by spinning, then yields, then sleeps. Measured against TBB for these
 * phases (benchmarks/dda-scaling, wall-25x40 from rest, 2 threads, back to
 * back): TBB's parallel_invoke in a task arena was 8-10 % slower at 1,000
 * blocks (its workers sleep between phases) and equal at 4,000; every
 * coarser phase (detection, kinematics, state checks) runs on TBB
 * (task_team.h).
 */
#ifndef ROCKDDA_DDA_THREAD_PAIR_H
#define ROCKDDA_DDA_THREAD_PAIR_H

#include <atomic>
#include <condition_variable>
#include <mutex>
#include <thread>

namespace rockdda::dda::internal
{
  /**
   * Runs f(0) on the calling thread and f(1) on a worker thread, or both on
   * the calling thread (in the order 0, 1) when built with one thread. The
   * two calls must touch disjoint data; the results are then the same for
   * one and two threads.
   */
  class ThreadPair
  {
  public:
    /// With @p two_threads false no worker is started.
    explicit ThreadPair(const bool two_threads);
    ~ThreadPair();
    ThreadPair(const ThreadPair &) = delete;
    ThreadPair &
    operator=(const ThreadPair &)
      = delete;

    /// Number of threads (1 or 2).
    unsigned int
    n_threads() const
    {
      return worker.joinable() ? 2 : 1;
    }

    /// Run f(0) and f(1) and return when both are done.
    template <typename F>
    void
    run(F &f)
    {
      if (!worker.joinable())
        {
          f(0);
          f(1);
          return;
        }
      task    = [](void *c, int part) { (*static_cast<F *>(c))(part); };
      context = &f;
      post();
      f(0);
      wait();
    }

    /// Let the worker sleep at once instead of spinning (call after the
    /// last phase of a solve, so that it does not hold a core while other
    /// threads, e.g. TBB's, do the work between solves).
    void
    rest();

  private:
    void
    post();
    void
    wait();
    void
    loop();

    void (*task)(void *, int)       = nullptr;
    void                   *context = nullptr;
    std::atomic<unsigned>   generation{0}, finished{0};
    std::atomic<bool>       sleeping{false}, stop{false}, resting{false};
    std::mutex              mutex;
    std::condition_variable wake;
    std::thread             worker;
  };
} // namespace rockdda::dda::internal

#endif
