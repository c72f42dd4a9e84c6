/**
 * @file
 * Mohr-Coulomb contact states of the open-close iteration (Shi 1988,
 * ch. 4; Shi 1993).
 */
#include <rockdda/dda/block_matrices.h>
#include <rockdda/dda/contact_law.h>

#include <algorithm>
#include <cmath>

namespace rockdda::dda
{
  StateCheck
  check_state(const Contact           &contact,
              const ContactKinematics &kin,
              const double             g,
              const double             s,
              const JointMaterial     &joint)
  {
    StateCheck r;
    r.state           = contact.state;
    r.slide_direction = contact.slide_direction;
    r.normal_force    = 0.;
    r.shear_force     = 0.;
    // The contact's springs: the penalty, in series with the joint's
    // stiffness over the contact length if it has one.
    const double p      = kin.normal_stiffness;
    const double ps     = kin.shear_stiffness;
    const double f      = kin.force_tolerance;
    const double f_hold = std::max(f, kin.hold_tolerance);

    if (contact.state == ContactState::open)
      {
        const double n = -p * g;
        if (n > f_hold)
          {
            // Closing: lock it, or let it slide at once if the shear spring
            // would already exceed the strength (saves an iteration).
            Contact locked = contact;
            locked.state   = ContactState::locked;
            r.state        = ContactState::locked;
            if (std::abs(ps * s)
                > shear_strength(locked, n, kin.length, joint) + f)
              {
                r.state           = ContactState::sliding;
                r.slide_direction = s > 0. ? 1 : -1;
              }
            r.normal_force = n;
          }
      }
    else
      {
        const double tension_limit
          = !contact.broken && contact.state == ContactState::locked
              ? joint.tensile * kin.length
              : 0.;
        const double n = -p * g;
        // A held locked contact opens only above the hold tolerance.
        if (-n > tension_limit
                   + (contact.state == ContactState::locked ? f_hold : f))
          r.state = ContactState::open;
        else
          {
            const double strength
              = shear_strength(contact, n, kin.length, joint);
            r.normal_force = n;
            if (frictionless(contact, joint))
              {
                r.state           = ContactState::sliding;
                r.slide_direction = s >= 0. ? 1 : -1;
              }
            else if (contact.state == ContactState::locked)
              {
                if (std::abs(ps * s) > strength + f_hold)
                  {
                    r.state           = ContactState::sliding;
                    r.slide_direction = s > 0. ? 1 : -1;
                  }
                r.shear_force = ps * s;
              }
            else if (contact.slide_direction == 0)
              r.state = ContactState::locked;
            else // sliding
              {
                if (ps * s * contact.slide_direction < -f)
                  r.state = ContactState::locked;
                r.shear_force = -strength * contact.slide_direction;
              }
          }
      }
    r.changed = r.state != contact.state;
    return r;
  }


  double
  automatic_penalty(const BlockSystem &scene, const double g)
  {
    double p = 0.;
    for (const auto &m : scene.materials)
      p = std::max(p, 10. * m.young * 1.);
    for (const auto &b : scene.blocks)
      {
        const double weight
          = scene.materials[b.material].density * b.polygon.area() * g;
        p = std::max(p, weight / (1e-4 * block_size(b.polygon)));
      }
    return p;
  }
} // namespace rockdda::dda
