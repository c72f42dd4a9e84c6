/**
 * @file
 * The contact law of 2D DDA: normal and shear springs (the numerical
 * penalty in series with the joint's physical stiffness), Mohr-Coulomb
 * strength with friction, cohesion and tensile strength, and the state
 * check of the open-close iteration.
 */
#ifndef ROCKDDA_DDA_CONTACT_LAW_H
#define ROCKDDA_DDA_CONTACT_LAW_H

#include <rockdda/dda/block_system.h>
#include <rockdda/dda/contact_mechanics.h>
#include <rockdda/dda/contact_set.h>

#include <limits>
#include <vector>

namespace rockdda::dda
{
  /// Whether any joint of @p joints has a physical stiffness (otherwise
  /// every contact spring is the penalty).
  inline bool
  any_joint_stiffness(const std::vector<JointMaterial> &joints)
  {
    for (const auto &j : joints)
      if (j.normal_stiffness > 0. || j.shear_stiffness > 0.)
        return true;
    return false;
  }

  /**
   * The linearised kinematics of one contact: normal gap
   * g = g0 + e_n . D_i + h_n . D_j and shear displacement
   * s = s0 + e_s . D_i + h_s . D_j (m), with e = T_i(P)^T n,
   * h = -T_j(P0)^T n (P the vertex, P0 its projection on the edge; the
   * shear uses the edge tangent and the locked reference point), the
   * contact length l (m) over which cohesion, tensile strength and the
   * joint's stiffness act, and the contact's springs.
   */
  struct ContactKinematics
  {
    double  g0 = 0., s0 = 0., length = 0.;
    Vector6 en, hn, es, hs;
    /// Normal and shear spring of the contact (N/m): contact_springs() of
    /// its joint and length; the normal force is -normal_stiffness g, the
    /// shear force of a locked contact shear_stiffness s.
    double normal_stiffness = 0., shear_stiffness = 0.;
    /// Unit tangent of the edge (m/m) and the edge's length (m).
    geometry::Point tangent;
    double          edge_length = 0.;
    /// Gap and shear displacements below this are round-off (m): 1e-12 of
    /// the smaller block's size plus the round-off of the vertex's local
    /// coordinates.
    double tolerance = 0.;
    /// Force below which a state change is noise (N/m): 1e-4 of the
    /// weight of the lighter block (its mass times the body acceleration),
    /// and at least the normal spring times the round-off tolerance. A contact
    /// closes when it would carry more than this in compression, opens
    /// when its tension exceeds the tensile strength by more than this,
    /// slides when the shear force exceeds the strength by more than this,
    /// and a sliding contact locks when reversing its slip would change
    /// the shear spring force by more than this.
    double force_tolerance = 0.;
    /// 1e-4 of the weight of the lighter block (N/m): the unit in which a
    /// chattering or held contact's tolerance grows (escalated_tolerance()).
    /// The round-off part of force_tolerance is a floor, never multiplied:
    /// at a penalty where p x tolerance exceeds the weight of a light block
    /// (an infill wedge), 100 x force_tolerance let such a block hang on
    /// one contact with 40 x its Mohr-Coulomb strength.
    double weight_tolerance = 0.;
    /// Held contact (one that cycles in the open-close iteration): an
    /// open contact closes only above this compression, a locked one
    /// slides only when its shear force exceeds the strength by more than
    /// this (N/m; 0: force_tolerance). Neither rule can create energy.
    double hold_tolerance = 0.;
    /// Dashpots in parallel with the normal and the shear spring (N s/m;
    /// ContactDamping; 0 without contact damping or in static steps).
    double normal_dashpot = 0., shear_dashpot = 0.;
    /// Gap rate and shear rate at the start of the step (m/s), e_n . v_i +
    /// h_n . v_j and e_s . v_i + h_s . v_j of the blocks' velocities times
    /// the dynamic control (set only with dashpots).
    double normal_rate = 0., shear_rate = 0.;
  };

  /**
   * The force tolerance of a contact whose state check is relaxed by
   * @p factor (>= 1; chatter or hold): @p factor x the weight tolerance (1e-4
   * by default) of the lighter block's weight, and at least the contact's
   * force_tolerance (its round-off floor).
   */
  inline double
  escalated_tolerance(const ContactKinematics &k, const double factor)
  {
    return escalated_tolerance(k.weight_tolerance, k.force_tolerance, factor);
  }

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
   * The state check of the open-close iteration
   * (dda::check_contact_state(), the one implementation of both engines)
   * for a contact whose latest gap is @p g and shear displacement @p s (m)
   * along the edge, with the force and hold tolerances of @p kinematics. A
   * locked contact reports its spring force k_s s as shear_force (this
   * engine's convention), a sliding one its friction on block i.
   */
  StateCheck
  check_state(const Contact           &contact,
              const ContactKinematics &kinematics,
              const double             g,
              const double             s,
              const JointMaterial     &joint);

  /**
   * Automatic normal penalty (N/m) for @p scene under gravity @p g (m/s^2):
   * the larger of 10 x the largest Young's modulus x 1 m (the usual DDA
   * choice, Shi 1993) and the stiffness with which the heaviest block,
   * resting on one contact under its own weight, sinks by at most 1e-4 of
   * its size.
   */
  double
  automatic_penalty(const BlockSystem &scene, const double g);

} // namespace rockdda::dda

#endif
