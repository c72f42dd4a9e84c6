/**
 * @file
 * The relaxed friction iteration of the open-close iteration, both DDA
 * engines (doc/theory/dda.md, "Open-close iteration and time stepping").
 */
#ifndef ROCKDDA_DDA_FRICTION_RELAXATION_H
#define ROCKDDA_DDA_FRICTION_RELAXATION_H

#include <algorithm>
#include <cstddef>
#include <utility>
#include <vector>

namespace rockdda::dda
{
  /**
   * Aitken's relaxation of the friction iteration (Irons & Tuck 1969;
   * Kuttler & Wall 2008). Once the contact states have settled, the
   * friction of each sliding contact whose force has not converged is
   * assembled with N_a + omega (N - N_a), N_a the normal force it was
   * assembled with and N the force the solve produced; omega follows
   * Aitken's rule over the residuals N - N_a of successive friction-only
   * iterations, within [0.01, 2]. A wedge of small taper couples its
   * friction to its normal force with a gain of about -mu / taper: the
   * plain fixed point (omega = 1) can then oscillate with growing
   * amplitude; the relaxed one converges (omega ~ 1 / (1 + mu / taper)).
   * A state change restarts it from omega = 1.
   */
  class FrictionRelaxation
  {
  public:
    /// For an attempt with @p n contacts, from omega = 1.
    explicit FrictionRelaxation(const std::size_t n)
        : current(n, 0.)
        , previous(n, 0.)
    {}

    /// Contact @p c's residual N - N_a in this iteration (0: not relaxed,
    /// its force converged or it does not slide).
    void
    set_residual(const std::size_t c, const double r)
    {
      current[c] = r;
    }

    /**
     * After an iteration's state check. With @p restart (a state changed,
     * or no friction force changed), or without any residual, omega returns
     * to 1 and nothing is relaxed. Otherwise omega takes Aitken's step over the
     * residuals of this and the previous iteration, and @p relaxed(c, omega x
     * r_c) is called for each contact c with a residual r_c: its normal force
     * for the next assembly is N_a + that.
     */
    template <typename Relaxed>
    void
    relax(bool restart, Relaxed &&relaxed)
    {
      // Nothing to relax (the friction changes were of direction, or of
      // frictionless contacts): a restart too. Recording a zero residual
      // would make the next Aitken step 0 (clamped to 0.01): the friction
      // iteration then all but stalls (the Hoek-Bray wedge of the 3D tests
      // crept at 4e-5 s steps, whose face groups change direction without a
      // force residual).
      if (!restart)
        restart = std::all_of(current.begin(),
                              current.end(),
                              [](const double r) { return r == 0.; });
      if (restart)
        {
          w    = 1.;
          have = false;
          return;
        }
      if (have)
        {
          double dot = 0., den = 0.;
          for (std::size_t c = 0; c < current.size(); ++c)
            {
              const double d = current[c] - previous[c];
              dot += previous[c] * d;
              den += d * d;
            }
          if (den > 0.)
            w = std::clamp(-w * dot / den, 0.01, 2.);
        }
      for (std::size_t c = 0; c < current.size(); ++c)
        if (current[c] != 0.)
          relaxed(c, w * current[c]);
      std::swap(previous, current);
      have = true;
    }

    /// The relaxation factor of the latest relaxed iteration.
    double
    omega() const
    {
      return w;
    }

    /// Whether a residual of a previous iteration is recorded.
    bool
    has_residual() const
    {
      return have;
    }

    /// Contact @p c's residual of the latest relaxed iteration.
    double
    previous_residual(const std::size_t c) const
    {
      return previous[c];
    }

  private:
    std::vector<double> current, previous;
    double              w    = 1.;
    bool                have = false;
  };
} // namespace rockdda::dda

#endif
