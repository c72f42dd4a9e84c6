/**
 * @file
 * Running the heat solver under a periodic forcing: the spin-up cycles
 * that make the field periodic (the transient of the initial condition
 * decays), and the block moments sampled at equal intervals, as the heat
 * analysis and the coupled thermo-mechanical analyses use them. deal.II-free
 * like heat_solver.h.
 */
#ifndef ROCKDDA_THERMAL_HEAT_CYCLES_H
#define ROCKDDA_THERMAL_HEAT_CYCLES_H

#include <rockdda/thermal/heat_solver.h>

#include <functional>
#include <string>
#include <vector>

namespace rockdda::thermal
{
  /// Whole cycles of a periodic forcing, run before anything is recorded.
  struct SpinUp
  {
    unsigned int cycles = 0;  ///< number of cycles
    double       period = 0.; ///< length of one cycle, s
    double       start  = 0.; ///< start of the first cycle, s

    /// The end of the spin-up (start + cycles period), s.
    double
    end() const
    {
      return start + cycles * period;
    }
  };

  /// What spin_up() asks and tells its caller.
  struct SpinUpCallbacks
  {
    /// Asked before every chunk and cycle: true stops the spin-up (e.g.
    /// on a signal; must answer alike on all MPI ranks).
    std::function<bool()> stop;
    /// Told after every chunk and cycle (e.g. a progress bar).
    std::function<void()> progress;
    /// Told after every completed cycle but the last (e.g. a checkpoint).
    std::function<void()> cycle_done;
  };

  /**
   * Advance @p solver through the cycles of @p spin_up from cycle @p done
   * on (counted in @p done, so that a resumed run continues where it
   * stopped). A theta-scheme cycle advances in chunks of whole time steps
   * counted from the cycle's start, about 100 per cycle (the solver takes
   * the same steps as in one call), so that @p callbacks.stop is asked
   * often; ARKODE, whose steps adapt, advances one cycle per call. The
   * time step and stepper are those of @p parameters, the solver's.
   * Returns false if stopped before the last cycle.
   */
  bool
  spin_up(HeatSolver            &solver,
          const HeatParameters  &parameters,
          const SpinUp          &spin_up,
          unsigned int          &done,
          const SpinUpCallbacks &callbacks = SpinUpCallbacks());

  /**
   * The block moments at the @p n times @p start + k @p interval (k = 0 to
   * n - 1, from the solver's time on): one sample per row, one entry per
   * block of @p parameters (the solver's). Throws InputError naming the
   * block (its name in @p parameters, or its number if it has none) if a
   * mean is not finite, followed by @p advice if that is not empty.
   */
  std::vector<std::vector<BlockMoments>>
  sample_block_moments(HeatSolver           &solver,
                       const HeatParameters &parameters,
                       const double          start,
                       const double          interval,
                       const unsigned int    n,
                       const std::string    &advice = "");
} // namespace rockdda::thermal

#endif
