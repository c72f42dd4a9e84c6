/**
 * @file
 * Persistent contact states of 2D DDA (open, sliding, locked) and their
 * transfer from one time step to the next.
 */
#ifndef ROCKDDA_DDA_CONTACT_SET_H
#define ROCKDDA_DDA_CONTACT_SET_H

#include <rockdda/dda/contact_detection.h>
#include <rockdda/dda/contact_history.h>
#include <rockdda/dda/contact_mechanics.h>

#include <cstdint>
#include <functional>
#include <vector>

namespace rockdda::dda
{
  /**
   * One contact during a step: the geometric record plus its state. The
   * shear reference xi_ref is the edge parameter of the point of the edge
   * that the vertex was locked to; the shear displacement is measured from
   * it. normal_force (N/m, compression positive) and slide_direction (+1
   * along the edge, -1 against) come from the latest solve.
   */
  struct Contact
  {
    ContactCandidate geometry;
    ContactState     state           = ContactState::open;
    ContactState     state_at_start  = ContactState::open;
    double           xi_ref          = 0.;
    double           normal_force    = 0.;
    double           shear_force     = 0.;
    int              slide_direction = 0;
    /// Cohesion and tensile strength are lost once an accepted step ends
    /// with the contact sliding or opened (trial states of the open-close
    /// iteration do not break it).
    bool broken = false;
    /// Held across static steps (dynamic control 0): the contact cycled in
    /// the open-close iteration of an accepted static step and was held
    /// there. It keeps the hold in the following static steps, until a
    /// force beyond the hold tolerance changes its state: otherwise a
    /// static step that starts from a held state flips it again, and
    /// successive steps cycle between two equilibria (a contact hysteresis
    /// of the hold force, Controls::hold_fraction; Doolin & Sitar 2004).
    bool held = false;
    /// Joint material index.
    int joint = 0;
    /// Slip rate (m/s) whose friction coefficient the step uses
    /// (friction_coefficient()): the magnitude of the shear displacement
    /// increment of the previous accepted step over its length, 0 for a
    /// new contact (the floor V_min), no_slip_rate in a static step
    /// (dynamic control 0: constant friction).
    double slip_rate = 0.;
  };

  /**
   * The states that persist between steps, keyed by (block i, vertex k,
   * block j, edge e). A contact found again keeps its state, shear reference
   * and normal force; a vertex that passes onto the neighbouring edge of the
   * same block keeps its state with the reference moved to its current
   * projection.
   */
  class ContactSet
  {
  public:
    /**
     * Turn this step's candidates into contacts, with the states transferred
     * from the previous step. New contacts start locked if their gap is
     * at most closed_gap(candidate) (m, the round-off of that contact),
     * open otherwise; they are intact joints
     * (cohesion and tensile strength) only if @p intact (the first
     * detection of a run), otherwise contacts that formed by motion.
     */
    std::vector<Contact>
    transfer(const std::vector<ContactCandidate>                   &candidates,
             const std::function<double(const ContactCandidate &)> &closed_gap,
             const bool intact) const;

    /// Store the states at the end of an accepted step.
    void
    store(const std::vector<Contact> &contacts);

    /// Number of stored contacts.
    std::size_t
    size() const
    {
      return stored.size();
    }

  private:
    static std::uint64_t
    key(int i, int k, int j, int e);
    static std::uint64_t
    vertex_key(int i, int k, int j);
    /// The stored contacts, and which of them a new contact continues.
    std::vector<Contact>                         stored;
    ContactHistory<std::uint64_t, std::uint64_t> history;
  };
} // namespace rockdda::dda

#endif
