/**
 * @file
 * What both DDA engines do around a step attempt, written once: the
 * attempt-restore-cut loop of one step, the run to an end time under a step
 * limit, and static (settling) steps that restore the dynamic controls
 * whatever happens (doc/theory/dda.md, "Open-close iteration and time
 * stepping").
 */
#ifndef ROCKDDA_DDA_STEP_DRIVER_H
#define ROCKDDA_DDA_STEP_DRIVER_H

#include <rockdda/dda/failure.h>
#include <rockdda/dda/time_step_control.h>

#include <functional>
#include <string>

namespace rockdda::dda
{
  /// The diagnosis of a step that cannot be cut further.
  std::string
  step_failure_message(const std::string  &engine,
                       const unsigned long step,
                       const double        time,
                       const std::string  &why,
                       const double        minimum,
                       const std::string  &minimum_rule);

  /// The diagnosis of a run that reached its step limit.
  std::string
  step_limit_message(const std::string  &engine,
                     const double        time,
                     const unsigned long limit,
                     const double        current,
                     const double        requested,
                     const std::string  &last_cut);

  /**
   * One step of at most @p max_length (s): try_step(h, iterations) attempts
   * a step of length h (true: accepted, with its open-close iterations);
   * after a failed attempt failed() undoes what it changed and the step is
   * cut, until an attempt is accepted. When a cut would go below the
   * minimum, DdaFailure with step_failure_message() (the reason is
   * @p why, read when thrown). Returns the cuts; @p control is told the
   * accepted step.
   */
  template <typename Try, typename Failed>
  unsigned
  take_step(TimeStepControl    &control,
            const double        max_length,
            const unsigned      max_iterations,
            Try               &&try_step,
            Failed            &&failed,
            const std::string  &engine,
            const unsigned long step,
            const double        time,
            const std::string  &why,
            const std::string  &minimum_rule)
  {
    unsigned cuts = 0, iterations = 0;
    for (;;)
      {
        const double h = control.attempt(max_length);
        if (try_step(h, iterations))
          break;
        failed();
        ++cuts;
        if (!control.cut(h))
          throw DdaFailure(step_failure_message(
            engine, step, time, why, control.minimum(), minimum_rule));
      }
    control.accept(cuts, iterations, max_iterations);
    return cuts;
  }

  /**
   * Steps advance(max_length) until @p time (the engine's clock, s) reaches
   * @p end (s); DdaFailure with step_limit_message() after the step limit
   * of @p control for @p max_steps.
   */
  template <typename Advance>
  void
  run_to(const TimeStepControl &control,
         const double          &time,
         const double           end,
         const unsigned long    max_steps,
         const double           requested,
         Advance              &&advance,
         const std::string     &engine,
         const std::string     &last_cut)
  {
    const unsigned long limit = control.step_limit(end - time, max_steps);
    unsigned long       steps = 0;
    while (control.before(time, end))
      {
        if (++steps > limit)
          throw DdaFailure(step_limit_message(
            engine, time, limit, control.current(), requested, last_cut));
        advance(end - time);
      }
  }

  /**
   * @p n static steps step(), after each of which @p after_step(k) may stop
   * them (false); restore() puts the dynamic controls back after the steps,
   * also when a step throws.
   */
  template <typename Step, typename Restore>
  void
  static_steps(const unsigned int                             n,
               const std::function<bool(const unsigned int)> &after_step,
               Step                                         &&step,
               Restore                                      &&restore)
  {
    try
      {
        for (unsigned int k = 0; k < n; ++k)
          {
            step();
            if (after_step && !after_step(k + 1))
              break;
          }
      }
    catch (...)
      {
        restore();
        throw;
      }
    restore();
  }
} // namespace rockdda::dda

#endif
