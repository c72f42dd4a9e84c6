/**
 * @file
 * Globalisation of the open-close iteration: an exact line search along
 * the Newton direction.
 *
 * With the shear strengths held fixed, the DDA step minimises the convex,
 * piecewise quadratic energy
 *   Pi(x) = 1/2 x^T A x - b^T x
 *           + sum_c [ 1/2 p_c <-g_c(x)>_+^2 + psi_c(s_c(x)) ],
 * A and b the block terms (inertia, elasticity, loads, fixed points), g_c
 * and s_c the linearised gap and shear displacement of contact c, p_c its
 * normal spring and psi_c its elastic-perfectly plastic shear spring (the
 * penalty, in series with the joint's stiffness if it has one). The open-close
 * iteration is Newton's method on grad Pi = 0 with the contact states as the
 * active set (a semismooth Newton method; Hueber & Wohlmuth 2005) and can cycle
 * between active sets when it takes full steps. The line search takes the
 * step x_k + alpha (x_hat - x_k) at which the directional derivative of
 * the energy vanishes, with each contact's force law following the state
 * check exactly (its force tolerances and hold tolerances, the Coulomb
 * strength of a locked contact at the normal force of the point on the
 * line, the friction force of a sliding one as assembled), so that a step
 * shortened by the search ends where some contact changes state. Locked
 * members of face groups slide on their resultant and are left linear.
 * The contact dashpots (ContactDamping, in dynamic steps) are quadratic
 * terms (c / h) (g - g0)^2 - c v (g - g0) of the closed contacts of the
 * iteration's states (the shear one of the locked ones): part of the
 * assembled matrix and load, they are linear along the line and need no
 * correction (a contact's state is decided by its spring force alone).
 */
#include <rockdda/dda/contact_law.h>
#include <rockdda/dda/engine.h>

#include <algorithm>
#include <cmath>

namespace rockdda::dda
{
  double
  DdaSystem::line_search(const std::vector<Contact> &contacts,
                         const Eigen::VectorXd      &x_k,
                         const Eigen::VectorXd      &x_hat,
                         const std::vector<double>  &tolerance_factor,
                         const std::vector<double>  &hold_tolerance)
  {
    const Eigen::VectorXd d = x_hat - x_k;
    Eigen::VectorXd       Kd;
    matrix.vmult(d, Kd);
    const double a = d.dot(Kd);
    if (!(a > 0.) || !std::isfinite(a))
      return 1.;
    // Per contact: the gap and shear displacement at x_k and their change
    // along d, and the terms of the assembled (linearised) system.
    struct Term
    {
      double               g, dg, s, ds;
      double               p, ps; // the contact's normal and shear spring
      bool                 closed, linear_normal;
      double               lin_shear_k, lin_shear_f; // linearised: k s + f
      double               S, o; // true: clip(ps s + o, +-(S(N) + S))
      const Contact       *contact;
      const JointMaterial *joint;
      double               length;
      double               f; // force tolerance of the state check
      double S_sliding;       // friction force used by the assembly (sliding)
      double f_hold;          // closing / sliding threshold of a held contact
      double f_open;          // tension at which it opens
      bool   shear;
      bool   moves; // whether the contact moves along d (else no term)
    };
    // The terms of the contacts are independent: in chunks (the same terms
    // on any number of threads).
    std::vector<Term> terms(contacts.size());
    for_each_chunk(chunks(),
                   contacts.size(),
                   256,
                   [&](const std::size_t lo, const std::size_t hi) {
                     for (std::size_t c = lo; c < hi; ++c)
                       {
                         const Contact       &ct    = contacts[c];
                         const auto          &kin   = assembler.kinematics()[c];
                         const JointMaterial &joint = scene.joints[ct.joint];
                         const int            ci    = static_cast<int>(c);
                         Term                &t     = terms[c];
                         t.g                        = assembler.gap(ci, x_k);
                         t.dg = assembler.gap(ci, x_hat) - t.g;
                         t.s  = assembler.shear_displacement(ci, x_k);
                         t.ds = assembler.shear_displacement(ci, x_hat) - t.s;
                         t.p  = kin.normal_stiffness;
                         t.ps = kin.shear_stiffness;
                         t.closed = ct.state != ContactState::open;
                         t.f = escalated_tolerance(kin, tolerance_factor[c]);
                         t.f_hold = std::max(t.f, hold_tolerance[c]);
                         t.f_open
                           = ct.state == ContactState::locked ? t.f_hold : t.f;
                         // An intact joint with tensile strength is a linear
                         // spring while it holds (breaking is decided by the
                         // state check, not here).
                         t.linear_normal = t.closed && !ct.broken
                                           && ct.state == ContactState::locked
                                           && joint.tensile > 0.;
                         t.contact     = &ct;
                         t.joint       = &joint;
                         t.length      = kin.length;
                         t.lin_shear_k = 0.;
                         t.lin_shear_f = 0.;
                         t.S           = 0.;
                         t.o           = 0.;
                         // The locked members of a face group slide on their
                         // resultant (check_face_groups): left linear here.
                         t.shear = t.closed && !frictionless(ct, joint)
                                   && !(ct.state == ContactState::locked
                                        && assembler.groups()[c] >= 0);
                         if (t.shear)
                           {
                             const double S = shear_strength(ct,
                                                             ct.normal_force,
                                                             kin.length,
                                                             joint);
                             // The state check's rules, with the strength S(N)
                             // of the normal force N at the point of the line
                             // (Coulomb):
                             if (ct.state == ContactState::locked)
                               {
                                 // slides when |p_s s| exceeds S + f;
                                 t.lin_shear_k = t.ps;
                                 t.S           = t.f_hold;
                               }
                             else
                               {
                                 // keeps the friction force S until its slip
                                 // reverses by more than f / p_s, then unloads
                                 // elastically.
                                 t.lin_shear_f = ct.slide_direction * S;
                                 t.o           = ct.slide_direction * t.f;
                                 t.S_sliding   = S;
                               }
                           }
                         t.moves = t.dg != 0. || t.ds != 0.;
                       }
                   });

    // phi'(alpha) = d^T grad Pi(x_k + alpha d): the assembled system gives
    // (alpha - 1) a, corrected by the true minus the linearised contact
    // terms.
    const auto slope = [&](const double alpha) {
      double v = (alpha - 1.) * a;
      for (const Term &t : terms)
        {
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
              const double s = t.s + alpha * t.ds;
              // A locked contact slides on the strength of its normal
              // force at this point; a sliding one keeps the friction
              // force of the assembly (its update is the friction loop).
              const double S = t.lin_shear_k == 0.
                                 ? t.S_sliding
                                 : shear_strength(*t.contact,
                                                  -std::min(p * g, t.f_open),
                                                  t.length,
                                                  *t.joint);
              const double o = t.lin_shear_k == 0.
                                 ? t.o + t.contact->slide_direction * S
                                 : 0.;
              const double f_true
                = std::clamp(t.ps * s + o, -(S + t.S), S + t.S);
              const double f_lin = t.lin_shear_k * s + t.lin_shear_f;
              v += t.ds * (f_true - f_lin);
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
