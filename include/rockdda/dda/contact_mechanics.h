/**
 * @file
 * Contact mechanics shared by the 2D (`dda`) and 3D (`dda3d`) engines: the
 * joint material, the contact states, the penalty springs in series with a
 * joint's stiffness and the Mohr-Coulomb strength. Dimension-generic: the
 * "length" of a 2D contact (m, per m thickness) is the area of a 3D one
 * (m^2), and the functions taking a contact are templates on the contact
 * type (anything with `state` and `broken`).
 */
#ifndef ROCKDDA_DDA_CONTACT_MECHANICS_H
#define ROCKDDA_DDA_CONTACT_MECHANICS_H

#include <algorithm>
#include <cmath>

namespace rockdda::dda
{
  /// Mohr-Coulomb strength and elastic stiffness of a joint (contact)
  /// material.
  struct JointMaterial
  {
    /// Friction angle (deg), in [0, 90).
    double friction_deg = 30.;
    /// Cohesion (Pa), >= 0.
    double cohesion = 0.;
    /// Tensile strength (Pa), >= 0.
    double tensile = 0.;
    /// Physical normal and shear stiffness of the joint (Pa/m: stress per
    /// metre of closure or elastic slip; over a joint length l, per metre
    /// of thickness, a spring of k l N/m), >= 0. A contact's springs are
    /// this stiffness over its contact length in series with the numerical
    /// penalty (contact_springs(), doc/theory/dda.md "Joint stiffness").
    /// 0: a rigid joint, only the penalty acts.
    double normal_stiffness = 0.;
    double shear_stiffness  = 0.;
  };

  /// State of a contact.
  enum class ContactState : int
  {
    open    = 0,
    sliding = 1,
    locked  = 2
  };

  /// The numerical penalty springs (N/m per m thickness), the same for
  /// every contact; a joint's physical stiffness acts in series with them
  /// (contact_springs()).
  struct ContactLaw
  {
    /// Normal penalty p (N/m).
    double normal_penalty = 1e11;
    /// Shear penalty p_s = shear_ratio * p.
    double shear_ratio = 0.4;

    double
    shear_penalty() const
    {
      return shear_ratio * normal_penalty;
    }
  };

  /// The normal and shear spring of one contact (N/m per m thickness).
  struct ContactSprings
  {
    double normal = 0., shear = 0.;
  };

  /**
   * The springs of a contact of length @p length (m, ContactKinematics::
   * length) on @p joint: the joint's stiffness over that length in series
   * with the penalty,
   *   k_n = 1 / (1/p + 1/(k_n,joint l)),  k_s = 1 / (1/p_s + 1/(k_s,joint l)).
   * The penalty alone (exactly p and p_s) where the joint's stiffness is 0
   * (a rigid joint) or the length is 0 (a corner on a face: no joint
   * surface to deform).
   */
  inline ContactSprings
  contact_springs(const ContactLaw    &law,
                  const JointMaterial &joint,
                  const double         length)
  {
    ContactSprings k{law.normal_penalty, law.shear_penalty()};
    if (length > 0.)
      {
        if (joint.normal_stiffness > 0.)
          k.normal
            = 1. / (1. / k.normal + 1. / (joint.normal_stiffness * length));
        if (joint.shear_stiffness > 0.)
          k.shear = 1. / (1. / k.shear + 1. / (joint.shear_stiffness * length));
      }
    return k;
  }

  /// Whether a contact carries no shear at all: no friction and no intact
  /// cohesion.
  template <typename ContactType>
  inline bool
  frictionless(const ContactType &contact, const JointMaterial &joint)
  {
    return joint.friction_deg == 0. && (contact.broken || joint.cohesion == 0.);
  }

  /**
   * Shear strength (N) of a closed contact with normal force @p n
   * (compression positive, N): N tan(phi) + c l while the joint is intact
   * and locked, where a tensile N lowers it (Mohr-Coulomb, floored at 0);
   * max(N, 0) tan(phi) once it is broken or sliding (residual). @p length
   * is the contact's length (2D, m per m thickness) or area (3D, m^2).
   */
  template <typename ContactType>
  double
  shear_strength(const ContactType   &contact,
                 const double         n,
                 const double         length,
                 const JointMaterial &joint)
  {
    // tan() is called per contact and iteration; remember the last angle.
    thread_local double last_deg = 0., last_mu = 0.;
    if (joint.friction_deg != last_deg)
      {
        last_deg = joint.friction_deg;
        last_mu  = std::tan(joint.friction_deg * M_PI / 180.);
      }
    const double mu = last_mu;
    // An intact joint: Mohr-Coulomb with the cohesion, where tension
    // lowers the strength; once broken or sliding: residual friction.
    if (!contact.broken && contact.state != ContactState::sliding)
      return std::max(0., n * mu + joint.cohesion * length);
    return std::max(0., n) * mu;
  }
} // namespace rockdda::dda

#endif
