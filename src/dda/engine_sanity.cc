/**
 * @file
 * Physical sanity of a DDA run (issue 11): warnings for parameters outside
 * the plausible range for rock, and the checks of every attempted step
 * (energy, penetration, strain, speed) that cut the step, or stop the run
 * with a diagnosis, instead of accepting a physically impossible state; and
 * the strength audit of every converged attempt (no contact beyond its
 * strength by more than the tolerance the open-close iteration allowed).
 * The checks and what the user sees are listed in doc/user-guide-checks.md.
 */
#include <rockdda/dda/block_matrices.h>
#include <rockdda/dda/engine.h>
#include <rockdda/dda/strength_audit.h>
#include <rockdda/io/output.h>

#include <algorithm>
#include <cmath>
#include <functional>
#include <limits>
#include <tuple>
#include <utility>
#include <vector>

namespace rockdda::dda
{
  namespace
  {
    std::string
    num(const double x)
    {
      return io::format_number(x, 3);
    }
  } // namespace



  void
  DdaSystem::add_plausibility_warnings()
  {
    const double g = scene.gravity.norm();
    for (std::size_t m = 0; m < scene.materials.size(); ++m)
      {
        const auto &mat = scene.materials[m];
        // Intact rock: E from ~0.1 GPa (weak chalk, marl) to ~200 GPa;
        // density 1,000-6,000 kg/m^3 (pumice to ore).
        if (mat.young < 1e8 || mat.young > 2e11)
          warning_list.push_back(
            "material " + std::to_string(m + 1) + ": Young's modulus "
            + num(mat.young)
            + " Pa is outside the range of rock (1e8 to 2e11 Pa); check "
              "the units (Pa, not MPa or GPa)");
        if (mat.density < 1000. || mat.density > 6000.)
          warning_list.push_back(
            "material " + std::to_string(m + 1) + ": density "
            + num(mat.density)
            + " kg/m^3 is outside the range of rock (1000 to 6000 kg/m^3)");
      }
    if (scene.seismic.mode != SeismicInput::Mode::none)
      {
        const double pga = scene.seismic.record.peak();
        if (pga > 2.)
          warning_list.push_back(
            "seismic record '" + scene.seismic.record.name + "': PGA "
            + num(pga)
            + " g is above any recorded earthquake (~4 g); if the record is "
              "in cm/s^2 it is "
            + num(pga / 100. * scene.seismic.g / 9.80665)
            + " m/s^2 = " + num(pga / 100. / 9.80665) + " g (check Units)");
      }
    // Both ends of the penalty against each block's weight W, in one pass:
    // - too soft: the heaviest block resting on one contact under its own
    //   weight sinks by W / p, against 1e-3 of its size;
    // - too stiff: the force of a round-off gap (round_off_tolerance(), 1e-12
    //   of a free block's size) exceeds 1 % of W. Its contact states are then
    //   decided by round-off: the tolerances of the open-close iteration
    //   cannot grow in units of its weight (an infill wedge hung on one
    //   contact at 40 x its strength before they were floored instead of
    //   multiplied).
    struct Worst
    {
      double ratio = 0., need = 0.;
      int    block = -1;
      void
      note(const double r, const int b, const double n)
      {
        if (r > ratio)
          {
            ratio = r;
            block = b;
            need  = n;
          }
      }
    } soft, stiff;
    const double penalty = ctrl.law.normal_penalty;
    for (std::size_t b = 0; b < scene.blocks.size(); ++b)
      {
        const auto  &blk = scene.blocks[b];
        const double weight
          = scene.materials[blk.material].density * blk.polygon.area() * g;
        const int i = static_cast<int>(b);
        soft.note(weight / penalty / block_size[b],
                  i,
                  weight / (1e-3 * block_size[b]));
        const double round_off = round_off_tolerance(block_size[b],
                                                     geometry::Point::Zero(),
                                                     geometry::Point::Zero());
        if (!clamped_block[b] && weight > 0.)
          stiff.note(penalty * round_off / weight,
                     i,
                     1e-2 * weight / round_off);
      }
    if (soft.block >= 0 && soft.ratio > 1e-3)
      warning_list.push_back(
        "contact penalty " + num(penalty) + " N/m lets block "
        + std::to_string(scene.blocks[soft.block].id) + " sink "
        + num(soft.ratio * 100.)
        + " % of its size into a contact under its own weight; use at "
          "least "
        + num(soft.need) + " N/m (10 to 100 x E is usual)");
    if (stiff.block >= 0 && stiff.ratio > 1e-2)
      warning_list.push_back(
        "contact penalty " + num(penalty)
        + " N/m resolves the contact forces of block "
        + std::to_string(scene.blocks[stiff.block].id) + " only to "
        + num(stiff.ratio * 100.)
        + " % of its weight (the force of a round-off gap, 1e-12 x its "
          "size): its contact states are decided by round-off; use at most "
        + num(stiff.need) + " N/m");
    // Joint stiffness against the penalty in series with it: the penalty
    // adds k l / (p + k l) to a contact's compliance. A contact's length is
    // at most the smaller of its two blocks' sizes, so at most the second
    // largest block size (the largest if there is one block).
    std::vector<double> sizes = block_size;
    std::sort(sizes.begin(), sizes.end(), std::greater<double>());
    const double largest = sizes.size() > 1 ? sizes[1] : sizes[0];
    for (std::size_t j = 0; j < scene.joints.size(); ++j)
      for (const auto &[what, k, p] : {std::tuple<const char *, double, double>{
                                         "normal",
                                         scene.joints[j].normal_stiffness,
                                         ctrl.law.normal_penalty},
                                       {"shear",
                                        scene.joints[j].shear_stiffness,
                                        ctrl.law.shear_penalty()}})
        {
          const double kl = k * largest;
          if (kl > 0.01 * p)
            warning_list.push_back(
              "joint material " + std::to_string(j + 1) + ": its " + what
              + " stiffness " + num(k) + " Pa/m over " + num(largest)
              + " m (the largest possible contact length) is " + num(kl)
              + " N/m; the penalty in series with it (" + num(p)
              + " N/m) adds up to " + num(100. * kl / (p + kl))
              + " % to the joint's compliance: for the joint's own "
                "stiffness within 1 %, raise 'DDA/Contact penalty' (or the "
                "shear penalty ratio) until the penalty is at least 100 x "
                "that (doc/theory/dda.md, Joint stiffness)");
        }
    // Speed bound: initial block speeds and the ground velocity.
    speed_bound = 0.;
    for (const auto &b : scene.blocks)
      speed_bound = std::max(speed_bound, b.velocity.head<2>().norm());
    if (scene.seismic.mode != SeismicInput::Mode::none)
      speed_bound += ground.peak_velocity();
  }



  std::string
  DdaSystem::implausible_state(const double energy_before,
                               double      &balance) const
  {
    // (dda::implausible_state(), the check of both engines.)
    PlausibilityInput in;
    in.time        = t;
    in.energy_unit = "J/m";
    if (scene.seismic.mode != SeismicInput::Mode::displacement)
      {
        const EnergyLedger e = energy();
        balance              = e.balance();
        in.check_energy      = true;
        in.energy_gain       = balance - energy_before;
        in.energy_scale      = e.scale();
      }
    in.normal_penalty = ctrl.law.normal_penalty;
    in.motion_bound   = scene.gravity.norm() * t + speed_bound
                      + 2. * eigenstrain_motion / attempt_length;
    in.speed_floor = 1e-9 * domain / ctrl.time_step;
    in.blocks.reserve(scene.blocks.size());
    for (const auto &blk : scene.blocks)
      {
        const double m
          = scene.materials[blk.material].density * blk.polygon.area();
        const double v = blk.velocity.head<2>().norm();
        in.blocks.push_back({blk.id,
                             0.5 * m * blk.velocity.head<2>().squaredNorm(),
                             v,
                             blk.strain.cwiseAbs().maxCoeff(),
                             scene.materials[blk.material].young});
      }
    for (const auto &c : current_contacts)
      if (c.state != ContactState::open)
        {
          const int i = c.geometry.block_i;
          const int j = c.geometry.block_j;
          in.contacts.push_back({scene.blocks[i].id,
                                 scene.blocks[j].id,
                                 c.normal_force,
                                 std::min(block_size[i], block_size[j])});
        }
    return dda::implausible_state(ctrl.plausibility, in);
  }
} // namespace rockdda::dda



namespace rockdda::dda
{
  std::string
  DdaSystem::strength_audit(const std::vector<Contact> &contacts,
                            const Eigen::VectorXd      &x,
                            const std::vector<double>  &factor,
                            const std::vector<double>  &hold,
                            const std::vector<double>  &assembled_normal,
                            const double                mean_normal,
                            double                     &ratio) const
  {
    const auto   &kinematics = assembler.kinematics();
    const auto   &group      = assembler.groups();
    StrengthAudit audit;
    // The iteration's tolerances of contact c (check_state): f escalated by
    // its chatter factor for a sliding contact, max(that, its hold) for an
    // open or a locked one; never more than max_tolerance_factor() x the
    // weight tolerance (ContactLaw::force_tolerance of the lighter block's
    // weight), or f if that is larger (the round-off
    // floor: escalated_tolerance).
    const auto tolerances = [&](const int c) {
      const double cap
        = escalated_tolerance(kinematics[c], max_tolerance_factor());
      const double fc
        = std::min(escalated_tolerance(kinematics[c], factor[c]), cap);
      return std::make_pair(fc, std::min(std::max(fc, hold[c]), cap));
    };
    // Face groups with a locked member beyond its own strength: judged on
    // their resultant below.
    std::vector<int> suspect;
    for (std::size_t k = 0; k < contacts.size(); ++k)
      {
        const int                c     = static_cast<int>(k);
        const Contact           &ct    = contacts[k];
        const ContactKinematics &kin   = kinematics[k];
        const JointMaterial     &joint = scene.joints[ct.joint];
        const auto [f, f_hold]         = tolerances(c);
        const double n = -kin.normal_stiffness * assembler.gap(c, x);
        // (StrengthAudit::judge_contact(), the checks of both engines.) A
        // held open contact may carry up to its penetration bound, capped
        // at the lighter block's weight rather than at 1 % of it
        // (update_factors in try_step).
        AuditedContact a;
        a.state          = ct.state;
        a.normal_force   = n;
        a.tolerance      = f;
        a.hold_tolerance = f_hold;
        a.open_tolerance = std::max(f_hold, hold[c]);
        if (ct.state != ContactState::open)
          {
            const bool locked = ct.state == ContactState::locked;
            a.tensile_limit
              = locked && !ct.broken ? joint.tensile * kin.length : 0.;
            a.strength     = shear_strength(ct, n, kin.length, joint);
            const double s = assembler.shear_displacement(c, x);
            a.locked_shear = std::abs(kin.shear_stiffness * s);
            a.in_group     = group[k] >= 0;
            a.frictionless = frictionless(ct, joint);
            if (!locked && !a.frictionless)
              {
                // The friction assembled from the normal force of the
                // previous iteration.
                a.friction_carried
                  = shear_strength(ct, assembled_normal[k], kin.length, joint);
                a.friction_tolerance
                  = friction_coefficient(joint, ct.slip_rate)
                    * friction_tolerance(n, mean_normal, kin.force_tolerance);
                a.slip_against = -kin.shear_stiffness * s * ct.slide_direction;
              }
          }
        if (!audit.judge_contact(c, a))
          suspect.push_back(group[k]);
      }
    std::sort(suspect.begin(), suspect.end());
    suspect.erase(std::unique(suspect.begin(), suspect.end()), suspect.end());
    const auto         &start  = assembler.group_start();
    const auto         &member = assembler.group_members();
    std::vector<int>    members;
    std::vector<double> sense;
    for (const int g : suspect)
      {
        // The group's locked members, as check_face_groups() takes them.
        members.clear();
        for (int k = start[g]; k < start[g + 1]; ++k)
          if (contacts[member[k]].state == ContactState::locked
              && !frictionless(contacts[member[k]],
                               scene.joints[contacts[member[k]].joint]))
            members.push_back(member[k]);
        const auto normal = [&](const int c) {
          return -kinematics[c].normal_stiffness * assembler.gap(c, x);
        };
        const GroupShear gs
          = group_shear(contacts, x, members, normal, hold, sense);
        // A stretched face is not locked as a group (its members slip on
        // their own): each member is judged alone.
        if (members.size() < 2 || gs.stretched)
          for (const int c : members)
            {
              const auto &kin = kinematics[c];
              audit.judge(c,
                          "shear while locked",
                          std::abs(kin.shear_stiffness
                                   * assembler.shear_displacement(c, x)),
                          shear_strength(contacts[c],
                                         normal(c),
                                         kin.length,
                                         scene.joints[contacts[c].joint]),
                          tolerances(c).second);
            }
        else
          audit.judge(members[0],
                      "resultant shear of its locked face group",
                      std::abs(gs.resultant),
                      gs.strength,
                      gs.tolerance);
      }
    ratio = audit.ratio();
    if (audit.worst_contact() < 0)
      return std::string();
    const auto &g = contacts[audit.worst_contact()].geometry;
    return audit.diagnosis(scene.blocks[g.block_i].id,
                           scene.blocks[g.block_j].id,
                           "N/m");
  }
} // namespace rockdda::dda
