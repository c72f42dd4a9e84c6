/**
 * @file
 * Internal to the dda subsystem: a caller thread and at most one worker
 * thread that run the two halves of a parallel phase (the two subdomains
 * of the linear solver's D-ILU sweeps, two phases per CG iteration).
 * Phases are short (tens to hundreds of microseconds), so the worker waits
 * by spinning, then yields, then sleeps; when the machine's cores are
 * taken by other processes the phases fall back to the calling thread
 * (late_phase()). Measured against TBB for these
 * phases (benchmarks/dda-scaling, wall-25x40 from rest, 2 threads, back to
 * back): TBB's parallel_invoke in a task arena was 8-10 % slower at 1,000
 * blocks (its workers sleep between phases) and equal at 4,000; every
 * coarser phase (detection, kinematics, state checks) runs on TBB
 * (task_team.h).
 */
#ifndef ROCKDDA_DDA_THREAD_PAIR_H
#define ROCKDDA_DDA_THREAD_PAIR_H

#include <atomic>
#include <chrono>
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
      if (serial_phases > 0)
        {
          // The machine's cores are taken (see late_phase()): both halves
          // here, in the order of one thread.
          --serial_phases;
          f(0);
          f(1);
          return;
        }
      task    = [](void *c, int part) { (*static_cast<F *>(c))(part); };
      context = &f;
      post();
      const auto start = std::chrono::steady_clock::now();
      f(0);
      const auto own = std::chrono::steady_clock::now();
      wait();
      late_phase(own - start, std::chrono::steady_clock::now() - own);
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
    /**
     * Called after each parallel phase with the caller's own work and how
     * long it then waited for the worker. A worker that keeps arriving much
     * later than the caller's half took (8 phases in a row, each waiting
     * more than 4x its own work and 50 us) is not being scheduled: other
     * processes hold the cores, and every phase would pay a scheduler
     * time slice. The next 4096 phases then run on the calling thread,
     * after which two threads are tried again. Results are the same either
     * way (the halves touch disjoint data and run in the order 0, 1).
     * Measured: benchmarks/dda-scaling, section 15.
     */
    void
                 late_phase(const std::chrono::steady_clock::duration own,
                            const std::chrono::steady_clock::duration waited);
    unsigned int late = 0, serial_phases = 0;

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
