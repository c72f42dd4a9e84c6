/**
 * @file
 * The contact law of 2D DDA: penalty normal and shear springs, Mohr-Coulomb
 * strength with friction, cohesion and tensile strength, and the state
 * check of the open-close iteration.
 */
#ifndef ROCKDDA_DDA_CONTACT_LAW_H
#define ROCKDDA_DDA_CONTACT_LAW_H

#include <rockdda/dda/block_system.h>
#include <rockdda/dda/contact_set.h>

namespace rockdda::dda
{
  /// Spring stiffnesses (N/m per m thickness).
  struct ContactLaw
  {
    /// Normal penalty p (N/m).
    double normal_penalty = 1e11;
    /// Shear spring = shear_ratio * p.
    double shear_ratio = 0.4;

    double
    shear_penalty() const
    {
      return shear_ratio * normal_penalty;
    }
  };

  /**
   * The linearised kinematics of one contact: normal gap
   * g = g0 + e_n . D_i + h_n . D_j and shear displacement
   * s = s0 + e_s . D_i + h_s . D_j (m), with e = T_i(P)^T n,
   * h = -T_j(P0)^T n (P the vertex, P0 its projection on the edge; the
   * shear uses the edge tangent and the locked reference point), and the
   * contact length l (m) over which cohesion and tensile strength act.
   */
  struct ContactKinematics
  {
    double  g0 = 0., s0 = 0., length = 0.;
    Vector6 en, hn, es, hs;
    /// Unit tangent of the edge (m/m) and the edge's length (m).
    geometry::Point tangent;
    double          edge_length = 0.;
    /// Gap and shear displacements below this are round-off (m).
    double tolerance = 0.;
    /// Hysteresis of the state switches (m): a sliding contact locks only
    /// when its shear displacement reverses by more than this, and an open
    /// contact closes only when it penetrates by more than this. Smaller
    /// changes are noise (lagged friction, contacts at zero force) that
    /// would make the open-close iteration chatter.
    double reversal_tolerance = 0.;
  };

  /**
   * The result of checking one contact after a solve: the new state, the
   * normal force (compression positive) and shear force (N/m), and whether
   * it changed.
   */
  struct StateCheck
  {
    ContactState state;
    double       normal_force, shear_force;
    int          slide_direction;
    bool         changed;
  };

  /**
   * Mohr-Coulomb check of the open-close iteration for a contact whose
   * latest gap is @p g and shear displacement @p s (m):
   * - open -> locked when the vertex penetrates (g < -reversal tolerance);
   * - closed -> open when the tensile force p g exceeds T l;
   * - locked -> sliding when |p_s s| > N tan(phi) + c l (direction of s);
   * - sliding -> locked when the shear displacement reverses against the
   *   assumed sliding direction.
   */
  StateCheck
  check_state(const Contact           &contact,
              const ContactKinematics &kinematics,
              const double             g,
              const double             s,
              const ContactLaw        &law,
              const JointMaterial     &joint);

  /// Shear strength (N/m) of a closed contact with normal force @p n.
  double
  shear_strength(const Contact       &contact,
                 const double         n,
                 const double         length,
                 const JointMaterial &joint);
} // namespace rockdda::dda

#endif
