/**
 * @file
 * The strength audit of every converged attempt, both DDA engines: no
 * contact carries more than its Mohr-Coulomb strength (or tension beyond
 * its tensile strength, or compression while open) by more than the
 * tolerance the open-close iteration allowed it, whatever path (chatter,
 * hold, face group, friction relaxation) accepted it. An attempt that fails
 * is cut like any other (doc/theory/dda.md, "Sanity checks";
 * doc/user-guide-checks.md).
 */
#ifndef ROCKDDA_DDA_STRENGTH_AUDIT_H
#define ROCKDDA_DDA_STRENGTH_AUDIT_H

#include <rockdda/dda/contact_mechanics.h>

#include <string>

namespace rockdda::dda
{
  /**
   * What the audit sees of one contact of the converged attempt, from the
   * accepted increments: forces in N (3D) or N/m (2D).
   */
  struct AuditedContact
  {
    ContactState state = ContactState::open;
    /// The normal force -k_n g (compression positive).
    double normal_force = 0.;
    /// The tension an intact locked joint carries (T x its length or
    /// area), else 0.
    double tensile_limit = 0.;
    /// The iteration's force tolerance f of the contact (chatter-escalated)
    /// and the hold tolerance (>= f) of a locked contact; an open contact
    /// may carry up to open_tolerance in compression.
    double tolerance = 0., hold_tolerance = 0., open_tolerance = 0.;
    /// The contact's Mohr-Coulomb strength at normal_force.
    double strength = 0.;
    /// A locked contact's shear spring force |k_s s|.
    double locked_shear = 0.;
    /// Locked and the member of a face group that shares its strength: a
    /// shear beyond its own strength is judged on the group (the caller).
    bool in_group     = false;
    bool frictionless = false;
    /// A sliding contact: the friction force assembled (from the normal
    /// force of the previous iteration), the tolerance of the friction
    /// iteration on it, and the spring force against its sliding direction
    /// -k_s s . d (a reversal beyond f relocks it).
    double friction_carried = 0., friction_tolerance = 0., slip_against = 0.;
  };

  /**
   * The worst excess over a limit among the contacts of one attempt, in
   * units of the tolerance the open-close iteration allowed it (both
   * engines).
   */
  class StrengthAudit
  {
  public:
    /// Contact @p contact carries @p force against @p limit, with
    /// @p tolerance (the same unit); @p what names the check.
    void
    judge(int         contact,
          const char *what,
          double      force,
          double      limit,
          double      tolerance);

    /**
     * The checks of one contact: compression while open, tension beyond
     * its tensile strength, shear while locked beyond its strength,
     * friction off its strength at the accepted normal force, and slip
     * against its friction. Returns false for a locked group member
     * (AuditedContact::in_group) whose shear exceeds its own strength by
     * more than its hold tolerance: the caller judges its group's resultant
     * (judge()).
     */
    bool
    judge_contact(int contact, const AuditedContact &a);

    /// The worst excess / tolerance so far (0: none; > 1 fails).
    double
    ratio() const
    {
      return worst_ratio;
    }

    /// The contact of the worst check (-1: none).
    int
    worst_contact() const
    {
      return worst.contact;
    }

    /**
     * Empty if ratio() <= 1; otherwise the diagnosis naming the worst
     * contact (of block @p id_i on block @p id_j), its check, force, limit
     * and tolerance in @p unit ("N" or "N/m").
     */
    std::string
    diagnosis(int id_i, int id_j, const std::string &unit) const;

  private:
    struct Worst
    {
      int         contact = -1;
      const char *what    = "";
      double      force = 0., limit = 0., tolerance = 0.;
    } worst;
    double worst_ratio = 0.;
  };
} // namespace rockdda::dda

#endif
