/**
 * @file
 * The strength audit of a converged attempt, both engines
 * (dda/strength_audit.h).
 */
#include <rockdda/dda/strength_audit.h>
#include <rockdda/io/output.h>

#include <algorithm>
#include <cmath>
#include <limits>

namespace rockdda::dda
{
  void
  StrengthAudit::judge(const int    contact,
                       const char  *what,
                       const double force,
                       const double limit,
                       const double tolerance)
  {
    const double excess = force - limit;
    const double r      = excess <= 0.     ? 0.
                          : tolerance > 0. ? excess / tolerance
                                           : std::numeric_limits<double>::infinity();
    if (r > worst_ratio)
      {
        worst_ratio = r;
        worst       = {contact, what, force, limit, tolerance};
      }
  }



  bool
  StrengthAudit::judge_contact(const int contact, const AuditedContact &a)
  {
    const double n = a.normal_force;
    if (a.state == ContactState::open)
      {
        judge(contact, "compression while open", n, 0., a.open_tolerance);
        return true;
      }
    const bool locked = a.state == ContactState::locked;
    judge(contact,
          "tension",
          -n,
          a.tensile_limit,
          locked ? a.hold_tolerance : a.tolerance);
    if (locked)
      {
        if (a.in_group && a.locked_shear > a.strength + a.hold_tolerance)
          return false;
        judge(contact,
              "shear while locked",
              a.locked_shear,
              a.strength,
              a.hold_tolerance);
        return true;
      }
    if (a.frictionless)
      return true;
    // Sliding: the friction assembled is the strength at the accepted
    // normal force within the friction tolerance of the iteration, and it
    // opposes the slip.
    judge(contact,
          "friction off its strength",
          std::abs(a.friction_carried - a.strength),
          0.,
          a.friction_tolerance);
    judge(
      contact, "slip against its friction", a.slip_against, 0., a.tolerance);
    return true;
  }



  std::string
  StrengthAudit::diagnosis(const int          id_i,
                           const int          id_j,
                           const std::string &unit) const
  {
    if (worst_ratio <= 1.)
      return std::string();
    const auto num = [](const double x) { return io::format_number(x, 3); };
    return "strength audit: the contact of block " + std::to_string(id_i)
           + " on block " + std::to_string(id_j) + " (" + worst.what
           + ") carries " + num(worst.force) + " " + unit
           + " against a limit of " + num(worst.limit) + " " + unit
           + ", beyond its tolerance of " + num(worst.tolerance) + " " + unit
           + " (" + num(worst_ratio) + " x)";
  }
} // namespace rockdda::dda
