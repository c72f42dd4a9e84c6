/**
 * @file
 * Globalisation of the open-close iteration, both engines: an exact line
 * search along the Newton direction, written once over the type of the
 * shear (a scalar along the edge in 2D, a 2-vector in the contact plane in
 * 3D).
 *
 * With the shear strengths held fixed, the DDA step minimises the convex,
 * piecewise quadratic energy
 *   Pi(x) = 1/2 x^T A x - b^T x
 *           + sum_c [ 1/2 p_c <-g_c(x)>_+^2 + psi_c(s_c(x)) ],
 * A and b the block terms (inertia, elasticity, loads, fixed points), g_c
 * and s_c the linearised gap and shear displacement of contact c, p_c its
 * normal spring and psi_c its elastic-perfectly plastic shear spring (the
 * penalty, in series with the joint's stiffness if it has one). The
 * open-close iteration is Newton's method on grad Pi = 0 with the contact
 * states as the active set (a semismooth Newton method; Hueber & Wohlmuth
 * 2005) and can cycle between active sets when it takes full steps. The line
 * search takes the step x_k + alpha (x_hat - x_k) at which the directional
 * derivative of the energy vanishes, with each contact's force law
 * following the state check exactly (its force tolerances and hold
 * tolerances, the Coulomb strength of a locked contact at the normal force
 * of the point on the line, the friction force of a sliding one as
 * assembled), so that a step shortened by the search ends where some
 * contact changes state. Locked members of face groups slide on their
 * resultant and are left linear. The contact dashpots (ContactDamping, in
 * dynamic steps) are quadratic terms of the closed contacts of the
 * iteration's states: part of the assembled matrix and load, they are
 * linear along the line and need no correction.
 */
#ifndef ROCKDDA_DDA_LINE_SEARCH_H
#define ROCKDDA_DDA_LINE_SEARCH_H

#include <rockdda/dda/state_check.h>

#include <algorithm>
#include <cmath>
#include <vector>

namespace rockdda::dda
{
  /// The spring force @p f clipped to the magnitude @p limit: clamp in 2D,
  /// the radial projection onto the disc of that radius in 3D.
  inline double
  clip_shear(const double f, const double limit)
  {
    return std::clamp(f, -limit, limit);
  }

  inline Eigen::Vector2d
  clip_shear(const Eigen::Vector2d &f, const double limit)
  {
    const double n = f.norm();
    return n > limit ? Eigen::Vector2d(f * (limit / n)) : f;
  }

  /**
   * One contact's part of the line search: its gap g and shear
   * displacement s at x_k and their changes dg, ds along the direction
   * (m), its normal and shear springs p, p_s (N/m), and how its force law
   * differs from the assembled (linearised) one.
   */
  template <typename Shear>
  struct LineSearchTerm
  {
    double g = 0., dg = 0.;
    Shear  s = zero_shear(Shear()), ds = zero_shear(Shear());
    double p = 0., ps = 0.;
    /// Closed in the iteration's states; a locked intact joint with tensile
    /// strength (a linear spring while it holds).
    bool closed = false, linear_normal = false;
    /// The assembled shear force: lin_shear_k s + lin_shear_f.
    double lin_shear_k = 0.;
    Shear  lin_shear_f = zero_shear(Shear());
    /// True shear force: clip(p_s s + o, S(N) + S_extra); for a sliding
    /// contact o = slide_direction (S_sliding + f).
    double S_extra = 0.;
    Shear  o       = zero_shear(Shear());
    /// The friction force the assembly used (sliding) and its direction.
    double S_sliding       = 0.;
    Shear  slide_direction = zero_shear(Shear());
    /// The tension at which the contact opens, and the compression at which
    /// an open one closes (its hold tolerance, at least f).
    double f_open = 0., f_hold = 0.;
    /// Whether it has a shear term, and whether it moves along the line.
    bool shear = false, moves = false;
  };

  /**
   * Fills the shear part of term @p t of a closed contact with friction
   * in state @p state (locked or sliding), force tolerance @p f (N), hold
   * tolerance @p f_hold, sliding along @p direction with the assembled
   * friction force @p S (N), the state check's rules: a locked contact
   * slides when |p_s s| exceeds S(N) + f_hold, a sliding one keeps the
   * friction force S until its slip reverses by more than f / p_s, then
   * unloads elastically.
   */
  template <typename Shear>
  void
  set_line_search_shear(LineSearchTerm<Shear> &t,
                        const ContactState     state,
                        const double           f,
                        const Shear           &direction,
                        const double           S)
  {
    if (state == ContactState::locked)
      {
        t.lin_shear_k = t.ps;
        t.S_extra     = t.f_hold;
      }
    else
      {
        t.lin_shear_f     = direction * S;
        t.o               = direction * f;
        t.S_sliding       = S;
        t.slide_direction = direction;
      }
  }

  /**
   * The exact line search: the step length alpha in [1e-3, 1] along
   * d = x_hat - x_k at which the directional derivative of the step's
   * energy vanishes; @p a = d^T K d (K the assembled matrix), @p terms
   * the contacts' parts, and @p strength(c, N) the Coulomb strength (N) of
   * contact c at the normal force N. Returns 1 (the full step) when the
   * energy is not convex along d, when d is not a descent direction (state
   * hysteresis) or when the full step does not overshoot.
   */
  template <typename Shear, typename Strength>
  double
  exact_line_search(const std::vector<LineSearchTerm<Shear>> &terms,
                    const double                              a,
                    const Strength                           &strength)
  {
    if (!(a > 0.) || !std::isfinite(a))
      return 1.;
    // phi'(alpha) = d^T grad Pi(x_k + alpha d): the assembled system gives
    // (alpha - 1) a, corrected by the true minus the linearised contact
    // terms.
    const auto slope = [&](const double alpha) {
      double v = (alpha - 1.) * a;
      for (std::size_t c = 0; c < terms.size(); ++c)
        {
          const LineSearchTerm<Shear> &t = terms[c];
          if (!t.moves)
            continue;
          const double g = t.g + alpha * t.dg;
          const double p = t.p;
          if (!t.linear_normal)
            {
              // With the state check's tolerance: a closed contact opens
              // above the tension f, an open one closes above the
              // compression f.
              const double n_true = t.closed ? std::min(p * g, t.f_open)
                                             : std::min(p * g + t.f_hold, 0.);
              const double n_lin  = t.closed ? p * g : 0.;
              v += t.dg * (n_true - n_lin);
            }
          if (t.shear)
            {
              const Shear s = t.s + alpha * t.ds;
              // A locked contact slides on the strength of its normal
              // force at this point; a sliding one keeps the friction
              // force of the assembly (its update is the friction loop).
              const double S = t.lin_shear_k == 0.
                                 ? t.S_sliding
                                 : strength(c, -std::min(p * g, t.f_open));
              const Shear  o = t.lin_shear_k == 0.
                                 ? Shear(t.o + t.slide_direction * S)
                                 : zero_shear(s);
              const Shear  f_true
                = clip_shear(Shear(t.ps * s + o), S + t.S_extra);
              const Shear f_lin = t.lin_shear_k * s + t.lin_shear_f;
              v += shear_along(t.ds, Shear(f_true - f_lin));
            }
        }
      return v;
    };
    const double s1 = slope(1.);
    if (!(s1 > 0.))
      return 1.;
    const double s0 = slope(0.);
    if (!(s0 < 0.))
      return 1.; // not a descent direction (state hysteresis): plain step
    // phi' is increasing and piecewise linear: regula falsi (Illinois).
    double lo = 0., hi = 1., flo = s0, fhi = s1;
    int    side  = 0;
    double alpha = 1.;
    for (int k = 0; k < 40; ++k)
      {
        alpha          = (lo * fhi - hi * flo) / (fhi - flo);
        const double f = slope(alpha);
        if (std::abs(f) <= 1e-10 * a || hi - lo < 1e-6)
          break;
        if (f < 0.)
          {
            lo = alpha, flo = f;
            if (side == -1)
              fhi *= 0.5;
            side = -1;
          }
        else
          {
            hi = alpha, fhi = f;
            if (side == 1)
              flo *= 0.5;
            side = 1;
          }
      }
    return std::clamp(alpha, 1e-3, 1.);
  }
} // namespace rockdda::dda

#endif
