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
   * The hold tolerance (N; N/m in 2D) of a contact that cycles in the
   * open-close iteration (it changed state the engine's hold_after times
   * in the attempt), both engines: it then keeps its state while the force
   * it would take to change is at most k_s x @p hold_fraction x @p size
   * (an elastic slip or penetration of that fraction of the smaller
   * block's size @p size, m) and at most 1 % of the lighter block's weight
   * (the largest chatter escalation of its @p weight_tolerance, whose
   * fraction of the weight is @p weight_fraction; @p force_tolerance is its
   * round-off floor). An @p open contact carries no force, so holding it
   * open hangs no block: it stays open up to a penetration of
   * hold_fraction x size and at most the lighter block's weight in force
   * (the compression its own weight gives one contact spring), not capped
   * at 1 % of the weight. With that cap the lightly loaded end of a face
   * contact that rocks (0.01-0.06 of a brick's weight when closed) opened
   * and closed until the step was cut: 29 of the 53 cuts of wall-25x40
   * from rest (benchmarks/dda-scaling, section 10).
   */
  inline double
  hold_tolerance(const bool   open,
                 const double normal_stiffness,
                 const double shear_stiffness,
                 const double hold_fraction,
                 const double size,
                 const double weight_tolerance,
                 const double force_tolerance,
                 const double weight_fraction)
  {
    double hold
      = std::min(shear_stiffness * hold_fraction * size,
                 escalated_tolerance(weight_tolerance,
                                     force_tolerance,
                                     max_chatter_factor(weight_fraction)));
    if (open)
      hold = std::max(hold,
                      std::min(normal_stiffness * hold_fraction * size,
                               escalated_tolerance(weight_tolerance,
                                                   force_tolerance,
                                                   1. / weight_fraction)));
    return hold;
  }

  /**
   * Whether a contact that has changed state @p changes times in this
   * attempt is held (hold_tolerance()), both engines: from @p hold_after
   * changes on, or if it was @p held at the step's start (a hold carried
   * across static steps).
   */
  inline bool
  is_held(const int changes, const unsigned hold_after, const bool held)
  {
    return changes >= static_cast<int>(hold_after) || held;
  }

  /**
   * Whether an accepted step leaves a contact held for the next step, both
   * engines: only in static steps (@p dynamic control 0: an iteration
   * towards equilibrium; dynamic steps carry their history in the
   * velocities), if it cycled in this step (@p changes >= @p hold_after)
   * or was @p held and kept its state (@p kept_state: its state at the end
   * equals its state at the start).
   */
  inline bool
  stays_held(const double   dynamic,
             const int      changes,
             const unsigned hold_after,
             const bool     held,
             const bool     kept_state)
  {
    return dynamic == 0.
           && (changes >= static_cast<int>(hold_after) || (held && kept_state));
  }

  /**
   * The normal-force tolerance of the friction iteration, both engines: a
   * sliding contact's friction has converged when the normal force N of
   * the solve differs from the one its friction was assembled with by at
   * most 1e-3 (|N| + @p mean_normal) + @p f (@p mean_normal the mean
   * normal force of the closed contacts, @p f the contact's force
   * tolerance). The strength audit allows the friction the same, times
   * the friction coefficient.
   */
  inline double
  friction_tolerance(const double normal,
                     const double mean_normal,
                     const double f)
  {
    return 1e-3 * (std::abs(normal) + mean_normal) + f;
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
  /**
   * Where the shear spring of a contact that locks during the open-close
   * iteration is anchored (force continuity at lock, both engines;
   * doc/theory/dda.md, "Force continuity at lock"):
   * - start_spring: the spring and anchor of the step's start;
   * - start_friction: anchored so that the spring carries the friction
   *   force the contact carried at the step's start;
   * - current_friction: anchored so that the spring carries the friction
   *   force of the iteration in which it locks;
   * - here: anchored where it touches now (no force).
   */
  enum class LockAnchor
  {
    start_spring,
    start_friction,
    current_friction,
    here
  };

  /**
   * The LockAnchor of a contact that locks in the open-close iteration,
   * whose state at the step's start was @p at_start and in the iteration
   * before it locks @p before (both engines). The iterations of a step are
   * not time, so the spring is the one of the step's start: a contact that
   * was locked then takes back its start spring (start_spring), one that
   * was sliding the friction force it carried then (start_friction), one
   * that was open starts where it touches (here). Rebasing on the friction
   * force of the current iteration pre-stretches the spring by the change
   * of the normal force within the step, energy that no work paid for
   * (+864 J/m in one step of a 2D ratchet earthquake episode).
   *
   * Without @p start_forces (the 3D engine) a contact that slid in the
   * iteration before it locks takes the current iteration's friction force
   * (current_friction), and any other starts where it touches (here).
   * With the start spring, a block on a shaken plane at the onset of
   * sliding returns exactly to an earlier iterate (slides, reverses,
   * relocks on the same spring) and the step is cut below its minimum (6
   * of the 3D tests; 5 with the line search, EngineControls::line_search);
   * with the start friction force
   * the velocity-weakening run-out of the shaking-table wedge moves from
   * 1.5 % to 3.4 % of sliding3d; with the start spring only after an
   * opening, the shaken stack of test
   * Dda3dContacts.ShakenStackNeverGainsEnergyAtRelock gains 5.4e-3 of the
   * energy in play in a step, against 6.7e-5 with this rule (doc/theory/
   * dda3d.md, "Force continuity at lock").
   */
  inline LockAnchor
  lock_anchor(const ContactState at_start,
              const ContactState before,
              const bool         start_forces)
  {
    if (!start_forces)
      return before == ContactState::sliding ? LockAnchor::current_friction
                                             : LockAnchor::here;
    return at_start == ContactState::locked    ? LockAnchor::start_spring
           : at_start == ContactState::sliding ? LockAnchor::start_friction
                                               : LockAnchor::here;
  }
} // namespace rockdda::dda

#endif
