/**
 * @file
 * The adaptive time step of both DDA engines: a step whose open-close
 * iteration fails is cut, an easy step lets the step grow back to the
 * nominal one (Shi 1988, ch. 5; doc/theory/dda.md, "Open-close iteration and
 * time stepping").
 */
#ifndef ROCKDDA_DDA_TIME_STEP_CONTROL_H
#define ROCKDDA_DDA_TIME_STEP_CONTROL_H

#include <algorithm>
#include <cmath>

namespace rockdda::dda
{
  /**
   * The current time step of an engine between the nominal step and a
   * minimum: cut by cut_factor when an attempt fails, grown by growth
   * (never above the nominal step) after a step that took no cut and at
   * most max(2, max_iterations / 2) open-close iterations. An attempt is
   * capped by the time left to an output or the end without shrinking the
   * current step.
   */
  class TimeStepControl
  {
  public:
    TimeStepControl() = default;

    /// Nominal step @p nominal (s, > 0) and the minimum @p minimum (s).
    TimeStepControl(const double nominal,
                    const double minimum,
                    const double cut_factor = 3.,
                    const double growth     = 1.3)
        : nominal_(nominal)
        , minimum_(minimum)
        , cut_factor_(cut_factor)
        , growth_(growth)
        , current_(nominal)
    {}

    /// The nominal step (s).
    double
    nominal() const
    {
      return nominal_;
    }

    /// The current step (s).
    double
    current() const
    {
      return current_;
    }

    /// The smallest step before the run stops (s).
    double
    minimum() const
    {
      return minimum_;
    }

    /// The length of the next attempt (s): the current step, at most
    /// @p max_length (the time to an output or the end).
    double
    attempt(const double max_length) const
    {
      return std::min(current_, max_length);
    }

    /// An attempt of length @p h failed: the step becomes h / cut_factor.
    /// False if that is below the minimum (the run must stop).
    bool
    cut(const double h)
    {
      current_ = h / cut_factor_;
      return !(current_ < minimum_);
    }

    /// A step was accepted after @p cuts cuts and @p iterations open-close
    /// iterations of at most @p max_iterations.
    void
    accept(const unsigned cuts,
           const unsigned iterations,
           const unsigned max_iterations)
    {
      if (cuts == 0 && iterations <= std::max(2u, max_iterations / 2))
        current_ = std::min(nominal_, current_ * growth_);
    }

    /// A new nominal step (s): the minimum scales with it, the current
    /// step is capped by it.
    void
    set_nominal(const double nominal)
    {
      minimum_ *= nominal / nominal_;
      nominal_ = nominal;
      current_ = std::min(current_, nominal);
    }

    /// Back to the nominal step.
    void
    reset()
    {
      current_ = nominal_;
    }

    /// The current step of a checkpoint (s).
    void
    restore(const double current)
    {
      current_ = current;
    }

    /// Whether time @p t (s) is still short of @p t_end (s): by more than
    /// 1e-9 of the nominal step (a remainder below that is round-off of
    /// the sum of the steps, not a step to take).
    bool
    before(const double t, const double t_end) const
    {
      return t < t_end - 1e-9 * nominal_;
    }

    /// The most steps an advance over @p duration (s) may take before the
    /// run stops with a diagnosis: @p max_steps if set, else 100 x the
    /// nominal steps of the duration + 1000.
    unsigned long
    step_limit(const double duration, const unsigned long max_steps) const
    {
      return max_steps > 0
               ? max_steps
               : static_cast<unsigned long>(
                   std::min(1e15, 100. * std::max(0., duration) / nominal_))
                   + 1000ul;
    }

  private:
    double nominal_ = 1., minimum_ = 0., cut_factor_ = 3., growth_ = 1.3;
    double current_ = 1.;
  };
} // namespace rockdda::dda

#endif
