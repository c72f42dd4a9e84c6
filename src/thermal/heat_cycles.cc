/**
 * @file
 * Running the heat solver under a periodic forcing (see heat_cycles.h):
 * the spin-up cycles in chunks that can be interrupted, and the block
 * moments sampled at equal intervals.
 */
#include <rockdda/io/error.h>
#include <rockdda/io/output.h>
#include <rockdda/thermal/heat_cycles.h>

#include <algorithm>
#include <cmath>

namespace rockdda::thermal
{
  bool
  spin_up(HeatSolver            &solver,
          const HeatParameters  &parameters,
          const SpinUp          &spin_up,
          unsigned int          &done,
          const SpinUpCallbacks &callbacks)
  {
    const auto stop     = [&]() { return callbacks.stop && callbacks.stop(); };
    const auto progress = [&]() {
      if (callbacks.progress)
        callbacks.progress();
    };
    const unsigned int steps_per_chunk
      = parameters.stepper == TimeStepper::arkode
          ? 1u
          : static_cast<unsigned int>(
            std::max(1.,
                     std::floor(spin_up.period / parameters.time_step / 100.)));
    const double chunk = parameters.time_step * steps_per_chunk;
    while (done < spin_up.cycles)
      {
        if (stop())
          return false;
        const double cycle_start = spin_up.start + done * spin_up.period;
        const double cycle_end   = cycle_start + spin_up.period;
        for (unsigned int j = 1;
             steps_per_chunk > 1
             && cycle_start + j * chunk < cycle_end - 0.5 * chunk;
             ++j)
          {
            if (stop())
              return false;
            if (cycle_start + j * chunk > solver.time())
              solver.advance_to(cycle_start + j * chunk);
            progress();
          }
        solver.advance_to(cycle_end);
        ++done;
        progress();
        if (done < spin_up.cycles && callbacks.cycle_done)
          callbacks.cycle_done();
      }
    return true;
  }



  std::vector<std::vector<BlockMoments>>
  sample_block_moments(HeatSolver           &solver,
                       const HeatParameters &parameters,
                       const double          start,
                       const double          interval,
                       const unsigned int    n,
                       const std::string    &advice)
  {
    const auto block_name = [&](const std::size_t b) {
      return b < parameters.blocks.size() && !parameters.blocks[b].name.empty()
               ? "'" + parameters.blocks[b].name + "'"
               : std::to_string(b + 1);
    };
    std::vector<std::vector<BlockMoments>> samples(n);
    for (unsigned int k = 0; k < n; ++k)
      {
        solver.advance_to(start + k * interval);
        samples[k] = solver.block_moments();
        for (std::size_t b = 0; b < samples[k].size(); ++b)
          if (!std::isfinite(samples[k][b].mean))
            throw InputError("the heat solution of block " + block_name(b)
                             + " is not finite at t = "
                             + io::format_number(solver.time(), 10) + " s"
                             + (advice.empty() ? "" : ": " + advice));
      }
    return samples;
  }
} // namespace rockdda::thermal
