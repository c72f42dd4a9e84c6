#include <rockdda/dda/plausibility.h>
#include <rockdda/io/output.h>

#include <algorithm>

namespace rockdda::dda
{
  std::string
  implausible_state(const PlausibilityLimits &limits,
                    const PlausibilityInput  &in)
  {
    const auto num = [](const double x) { return io::format_number(x, 3); };
    const std::string at = " at t = " + num(in.time) + " s";
    // Energy: the ledger may only lose energy (the time integration
    // dissipates); a gain beyond the tolerance is energy created by the
    // contact treatment (a penalty spring fired from a deep penetration,
    // a sliver, a time step too long for the contact stiffness).
    if (in.check_energy)
      {
        const double allow = limits.energy_tolerance * in.energy_scale;
        if (in.energy_gain > allow && in.energy_gain > 0.)
          {
            // The block that gained most kinetic energy.
            int    block = 0;
            double most  = -1.;
            for (const auto &b : in.blocks)
              if (b.kinetic > most)
                {
                  most  = b.kinetic;
                  block = b.id;
                }
            return "the energy ledger gained " + num(in.energy_gain) + " "
                   + in.energy_unit + at + " (allowed " + num(allow) + " "
                   + in.energy_unit + "), fastest block "
                   + std::to_string(block)
                   + ": energy created by the contacts (penalty too low or "
                     "too high for the time step, or a sliver block)";
          }
      }
    // Penetration of closed contacts: only the numerical part of the
    // closure, N / p. With a joint stiffness the penalty is in series with
    // the joint and carries the same force N; the joint's share is the
    // physical closure of the joint, not a penetration.
    for (const auto &c : in.contacts)
      {
        const double depth = std::max(0., c.normal_force) / in.normal_penalty;
        if (depth > limits.penetration_ratio * c.size)
          return "block " + std::to_string(c.block_i) + " penetrates block "
                 + std::to_string(c.block_j) + " by " + num(depth) + " m" + at
                 + ", more than " + num(limits.penetration_ratio)
                 + " x the block size " + num(c.size)
                 + " m: the contact penalty " + num(in.normal_penalty)
                 + " N/m is too low for the load (raise Contact penalty, "
                   "or accept the overlap with Penetration limit)";
      }
    // Strain (DDA blocks are small-strain).
    for (const auto &b : in.blocks)
      if (b.strain > limits.strain_limit)
        return "block " + std::to_string(b.id) + " is strained by "
               + num(b.strain) + at + ", beyond the small strains of DDA ("
               + num(limits.strain_limit) + "): Young's modulus " + num(b.young)
               + " Pa is too low for the load (check its units)";
    // Speed.
    const double bound = limits.speed_factor * in.motion_bound + in.speed_floor;
    for (const auto &b : in.blocks)
      if (b.speed > bound)
        return "block " + std::to_string(b.id) + " moves at " + num(b.speed)
               + " m/s" + at + ", faster than anything the scene can produce ("
               + num(bound)
               + " m/s: free fall since t = 0, the ground velocity, the "
                 "initial speeds and the eigenstrain change): a contact "
                 "released energy";
    return "";
  }
} // namespace rockdda::dda
