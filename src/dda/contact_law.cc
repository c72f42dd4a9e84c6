/**
 * @file
 * Mohr-Coulomb contact states of the open-close iteration (Shi 1988,
 * ch. 4; Shi 1993).
 */
#include <rockdda/dda/block_matrices.h>
#include <rockdda/dda/contact_law.h>
#include <rockdda/dda/state_check.h>

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
    StateCheckSprings k;
    k.normal_stiffness           = kin.normal_stiffness;
    k.shear_stiffness            = kin.shear_stiffness;
    k.force_tolerance            = kin.force_tolerance;
    k.hold_tolerance             = kin.hold_tolerance;
    k.extent                     = kin.length;
    const StateCheckOf<double> c = check_contact_state(
      contact, static_cast<double>(contact.slide_direction), g, s, k, joint);
    StateCheck r;
    r.state        = c.state;
    r.normal_force = c.normal_force;
    // This engine's convention: a locked contact reports its spring force
    // k_s s (also when it starts to slide), a sliding one the friction on
    // block i.
    const bool spring = contact.state == ContactState::locked
                        && c.state != ContactState::open
                        && !frictionless(contact, joint);
    r.shear_force     = spring ? -c.shear_force : c.shear_force;
    r.slide_direction = static_cast<int>(c.direction);
    r.changed         = c.changed;
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
