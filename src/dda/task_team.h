/**
 * @file
 * Internal to the dda subsystem: the threads of a DDA run, a TBB task
 * arena of a fixed size (Intel oneTBB, which deal.II brings).
 */
#ifndef ROCKDDA_DDA_TASK_TEAM_H
#define ROCKDDA_DDA_TASK_TEAM_H

#include <cstddef>
#include <functional>
#include <memory>

namespace rockdda::dda::internal
{
  /**
   * A fixed number of threads for the DDA's parallel loops: contact
   * detection, contact kinematics and state checks, in chunks of an index
   * range. Work is split in the same way for every thread count and each
   * chunk writes its own data, so results do not depend on the number of
   * threads. (The D-ILU sweeps use ThreadPair: see thread_pair.h.)
   */
  class TaskTeam
  {
  public:
    /// @p n_threads threads (0: one per core); with one, no arena.
    explicit TaskTeam(const unsigned int n_threads);
    ~TaskTeam();
    TaskTeam(const TaskTeam &) = delete;
    TaskTeam &
    operator=(const TaskTeam &)
      = delete;

    /// Number of threads.
    unsigned int
    n_threads() const
    {
      return threads;
    }

    /// Run f(lo, hi) for the chunks [k g, min(n, (k + 1) g)) of [0, n),
    /// g = @p grain, concurrently with two threads or more.
    void
    for_chunks(const std::size_t                                    n,
               const std::size_t                                    grain,
               const std::function<void(std::size_t, std::size_t)> &f);

  private:
    struct Arena;
    unsigned int           threads = 1;
    std::unique_ptr<Arena> arena;
  };
} // namespace rockdda::dda::internal

#endif
