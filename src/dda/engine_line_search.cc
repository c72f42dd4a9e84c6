/**
 * @file
 * The 2D engine's terms of the exact line search of the open-close
 * iteration (dda/line_search.h, shared with 3D).
 */
#include <rockdda/dda/contact_law.h>
#include <rockdda/dda/engine.h>
#include <rockdda/dda/line_search.h>

#include <algorithm>
#include <cmath>

namespace rockdda::dda
{
  double
  DdaSystem::line_search(const std::vector<Contact> &contacts,
                         const Eigen::VectorXd      &x_k,
                         const Eigen::VectorXd      &x_hat,
                         const std::vector<double>  &tolerance_factor,
                         const std::vector<double>  &hold_tolerance)
  {
    const Eigen::VectorXd d = x_hat - x_k;
    Eigen::VectorXd       Kd;
    matrix.vmult(d, Kd);
    const double a = d.dot(Kd);
    if (!(a > 0.) || !std::isfinite(a))
      return 1.;
    // The terms of the contacts are independent: in chunks (the same terms
    // on any number of threads).
    std::vector<LineSearchTerm<double>> terms(contacts.size());
    for_each_chunk(
      chunks(),
      contacts.size(),
      256,
      [&](const std::size_t lo, const std::size_t hi) {
        for (std::size_t c = lo; c < hi; ++c)
          {
            const Contact       &ct    = contacts[c];
            const auto          &kin   = assembler.kinematics()[c];
            const JointMaterial &joint = scene.joints[ct.joint];
            const int            ci    = static_cast<int>(c);
            auto                &t     = terms[c];
            t.g                        = assembler.gap(ci, x_k);
            t.dg                       = assembler.gap(ci, x_hat) - t.g;
            t.s                        = assembler.shear_displacement(ci, x_k);
            t.ds           = assembler.shear_displacement(ci, x_hat) - t.s;
            t.p            = kin.normal_stiffness;
            t.ps           = kin.shear_stiffness;
            t.closed       = ct.state != ContactState::open;
            const double f = escalated_tolerance(kin, tolerance_factor[c]);
            t.f_hold       = std::max(f, hold_tolerance[c]);
            t.f_open       = ct.state == ContactState::locked ? t.f_hold : f;
            // An intact joint with tensile strength is a linear
            // spring while it holds (breaking is decided by the
            // state check, not here).
            t.linear_normal = t.closed && !ct.broken
                              && ct.state == ContactState::locked
                              && joint.tensile > 0.;
            // The locked members of a face group slide on their
            // resultant (check_face_groups): left linear here.
            t.shear = t.closed && !frictionless(ct, joint)
                      && !(ct.state == ContactState::locked
                           && assembler.groups()[c] >= 0);
            if (t.shear)
              set_line_search_shear(
                t,
                ct.state,
                f,
                static_cast<double>(ct.slide_direction),
                shear_strength(ct, ct.normal_force, kin.length, joint));
            t.moves = t.dg != 0. || t.ds != 0.;
          }
      });
    return exact_line_search(
      terms, a, [&](const std::size_t c, const double n) {
        return shear_strength(contacts[c],
                              n,
                              assembler.kinematics()[c].length,
                              scene.joints[contacts[c].joint]);
      });
  }
} // namespace rockdda::dda
