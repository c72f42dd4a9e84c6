/**
 * @file
 * Viscous dashpots in parallel with a closed contact's penalty springs in
 * Shi's time integration, written for any engine (doc/theory/dda3d.md,
 * "Contact damping").
 */
#ifndef ROCKDDA_DDA_CONTACT_DAMPING_H
#define ROCKDDA_DDA_CONTACT_DAMPING_H

#include <algorithm>
#include <cmath>

namespace rockdda::dda
{
  /**
   * Dashpots of a closed contact: in parallel with each spring of stiffness
   * k (N/m) a dashpot
   *   c = 2 zeta sqrt(k m) + beta k h / 2,
   * acting on the relative velocity across the spring (the normal dashpot on
   * the gap rate, the shear dashpot of a locked contact on the shear rate;
   * a sliding contact's shear is friction alone). zeta (-) is the ratio of
   * critical of that spring with the mass m (kg) of the lighter free block
   * of the pair: a physical dashpot. beta (-) is a numerical one, relative
   * to the step h (s): a contact mode resolved by the step (omega h << 1)
   * gets the damping ratio beta omega h / 4 (vanishing as h -> 0, as Shi's
   * own numerical damping omega h / 4), a stiff one (omega h >> 1) the
   * velocity amplification -1 / (1 + beta) per step instead of Shi's -1
   * (0 at beta = 1; doc/theory/dda3d.md, "Contact damping").
   * In Shi's step the end-of-step velocity is v' = 2 d / h - v (d the step
   * displacement, v the velocity at the start, times the dynamic control):
   * the dashpot force -c v' adds 2 c / h to the spring's stiffness and c v
   * to its load. Its work in the step, c v' . d, is the energy it
   * dissipates (J), which the energy ledger books. The contact's state
   * (open, friction strength) is that of its spring force alone: the
   * dashpot neither holds a contact closed nor adds friction. Only in
   * dynamic steps.
   */
  class ContactDamping
  {
  public:
    /// @p ratio zeta (-, >= 0), @p step_ratio beta (-, >= 0), @p h the
    /// step (s), @p dynamic the dynamic control parameter of the step (-).
    ContactDamping(const double ratio,
                   const double step_ratio,
                   const double h,
                   const double dynamic)
        : ratio_(dynamic > 0. ? ratio : 0.)
        , step_ratio_(dynamic > 0. ? step_ratio : 0.)
        , h_(h)
    {}

    /// Whether the step is damped.
    bool
    active() const
    {
      return ratio_ > 0. || step_ratio_ > 0.;
    }

    /// The dashpot (N s/m) of a spring @p k (N/m) between blocks of masses
    /// @p m_i, @p m_j (kg; a clamped block's as infinite). Between two
    /// clamped blocks (no free block: both masses infinite) the ratio's
    /// part is 0, as the contact moves no free block.
    double
    dashpot(const double k, const double m_i, const double m_j) const
    {
      const double m = std::min(m_i, m_j);
      return (ratio_ > 0. && std::isfinite(m) ? 2. * ratio_ * std::sqrt(k * m)
                                              : 0.)
             + 0.5 * step_ratio_ * k * h_;
    }

    /// 2 c / h (N/m): the stiffness the dashpot @p c (N s/m) adds.
    double
    stiffness(const double c) const
    {
      return 2. * c / h_;
    }

  private:
    double ratio_, step_ratio_, h_;
  };
} // namespace rockdda::dda

#endif
