/**
 * @file
 * The Mohr-Coulomb state check of the open-close iteration, written once
 * for both engines over the type of the shear: a scalar along the edge
 * (2D) or a 2-vector in the contact plane (3D). Shi 1988, ch. 4; Shi 2001;
 * doc/theory/dda.md, "Open-close iteration and time stepping".
 */
#ifndef ROCKDDA_DDA_STATE_CHECK_H
#define ROCKDDA_DDA_STATE_CHECK_H

#include <rockdda/dda/contact_mechanics.h>

#include <Eigen/Core>

#include <algorithm>
#include <cmath>

namespace rockdda::dda
{
  /**
   * @name The shear as a scalar (2D) or a 2-vector (3D)
   * The operations the state check needs: its magnitude, its projection on
   * a sliding direction, and the direction it slides along.
   */
  /// @{
  inline double
  shear_magnitude(const double s)
  {
    return std::abs(s);
  }

  inline double
  shear_magnitude(const Eigen::Vector2d &s)
  {
    return s.norm();
  }

  inline double
  shear_along(const double s, const double direction)
  {
    return s * direction;
  }

  inline double
  shear_along(const Eigen::Vector2d &s, const Eigen::Vector2d &direction)
  {
    return s.dot(direction);
  }

  /// Whether @p direction is none (a sliding contact without one locks).
  inline bool
  no_direction(const double direction)
  {
    return direction == 0.;
  }

  inline bool
  no_direction(const Eigen::Vector2d &direction)
  {
    return direction.squaredNorm() == 0.;
  }

  /// A zero shear of the type of @p s.
  inline double
  zero_shear(const double)
  {
    return 0.;
  }

  inline Eigen::Vector2d
  zero_shear(const Eigen::Vector2d &)
  {
    return Eigen::Vector2d::Zero();
  }

  /// The sense of @p s along the edge (+1 for s = 0).
  inline double
  slide_direction_of(const double s, const double /*fallback*/)
  {
    return s >= 0. ? 1. : -1.;
  }

  /// The unit vector of @p s, or @p fallback if s is zero.
  inline Eigen::Vector2d
  slide_direction_of(const Eigen::Vector2d &s, const Eigen::Vector2d &fallback)
  {
    const double l = s.norm();
    return l > 0. ? Eigen::Vector2d(s / l) : fallback;
  }
  /// @}

  /**
   * The largest factor by which a chattering contact's force tolerance
   * may grow (escalated_tolerance()): the tolerance stays at most 1 % of
   * the lighter block's weight, @p weight_fraction being the weight part's
   * fraction of it (ContactLaw::force_tolerance, 1e-4 by default: 100).
   */
  inline double
  max_chatter_factor(const double weight_fraction)
  {
    return std::max(1., 1e-2 / weight_fraction);
  }

  /**
   * The factor by which the force tolerance of a contact that has changed
   * state @p changes times within the step grows (chatter, doc/theory/
   * dda.md): 1 until two changes, then 10^(changes - 1) (10 after two,
   * 100 after three), at most max_chatter_factor(@p weight_fraction).
   */
  inline double
  chatter_factor(const int changes, const double weight_fraction)
  {
    return changes >= 2 ? std::min(std::pow(10., changes - 1),
                                   max_chatter_factor(weight_fraction))
                        : 1.;
  }

  /**
   * The result of checking one contact after a solve: the new state, the
   * normal force (N, compression positive; N/m in 2D), the shear force on
   * block i (the locked spring's -k_s s, or the friction -S d of a sliding
   * contact), the sliding direction, and whether the state changed.
   */
  template <typename Shear>
  struct StateCheckOf
  {
    ContactState state        = ContactState::open;
    double       normal_force = 0.;
    Shear        shear_force  = zero_shear(Shear());
    Shear        direction    = zero_shear(Shear());
    bool         changed      = false;
  };

  /**
   * The springs and tolerances of one check: the contact's normal and shear
   * springs k_n, k_s (N/m), its force tolerance f (N; escalated for a
   * chattering contact), the hold tolerance (>= f) that a held contact must
   * exceed to close or to start sliding, and the length (2D, m) or area
   * (3D, m^2) over which cohesion and tensile strength act.
   */
  struct StateCheckSprings
  {
    double normal_stiffness = 0., shear_stiffness = 0.;
    double force_tolerance = 0., hold_tolerance = 0.;
    double extent = 0.;
  };

  /**
   * Mohr-Coulomb check of the open-close iteration for a contact whose
   * latest gap is @p g (m) and shear displacement @p s (m), sliding (if it
   * slides) along @p direction, with force criteria (f the force tolerance,
   * h the hold tolerance):
   * - open -> locked when the compression -k_n g exceeds h; sliding at once
   *   if the locked spring |k_s s| would exceed the strength + f, or if the
   *   contact is frictionless;
   * - closed -> open when the tension k_n g exceeds T A + h (locked) or
   *   + f (sliding); T only while the joint is intact and locked;
   * - a frictionless contact is sliding whenever closed (along s);
   * - locked -> sliding when |k_s s| > strength + h, along s;
   * - sliding -> locked when the slip reverses against the sliding
   *   direction by more than f / k_s (the direction is not changed here:
   *   the engines set it from the face group's resultant).
   * @p contact needs the members state, broken and slip_rate
   * (shear_strength()).
   */
  template <typename ContactType, typename Shear>
  StateCheckOf<Shear>
  check_contact_state(const ContactType       &contact,
                      const Shear             &direction,
                      const double             g,
                      const Shear             &s,
                      const StateCheckSprings &k,
                      const JointMaterial     &joint)
  {
    StateCheckOf<Shear> r;
    r.state        = contact.state;
    r.direction    = direction;
    r.shear_force  = zero_shear(s);
    const double n = -k.normal_stiffness * g;
    const double f = k.force_tolerance;
    const double h = std::max(f, k.hold_tolerance);
    // The locked spring's force k_s s and its magnitude.
    const Shear  spring = k.shear_stiffness * s;
    const double fs     = shear_magnitude(spring);
    if (contact.state == ContactState::open)
      {
        if (n > h)
          {
            ContactType locked = contact;
            locked.state       = ContactState::locked;
            r.state            = ContactState::locked;
            r.normal_force     = n;
            if (frictionless(locked, joint)
                || fs > shear_strength(locked, n, k.extent, joint) + f)
              {
                r.state     = ContactState::sliding;
                r.direction = slide_direction_of(s, direction);
              }
          }
        r.changed = r.state != contact.state;
        return r;
      }
    const bool   locked = contact.state == ContactState::locked;
    const double tension_limit
      = !contact.broken && locked ? joint.tensile * k.extent : 0.;
    if (-n > tension_limit + (locked ? h : f))
      {
        r.state   = ContactState::open;
        r.changed = true;
        return r;
      }
    const double strength = shear_strength(contact, n, k.extent, joint);
    r.normal_force        = n;
    if (frictionless(contact, joint))
      {
        r.state     = ContactState::sliding;
        r.direction = slide_direction_of(s, direction);
      }
    else if (locked)
      {
        r.shear_force = -spring;
        if (fs > strength + h)
          {
            r.state     = ContactState::sliding;
            r.direction = slide_direction_of(s, direction);
          }
      }
    else if (no_direction(direction))
      r.state = ContactState::locked;
    else // sliding
      {
        if (k.shear_stiffness * shear_along(s, direction) < -f)
          r.state = ContactState::locked;
        r.shear_force = -strength * direction;
      }
    r.changed = r.state != contact.state;
    return r;
  }
} // namespace rockdda::dda

#endif
