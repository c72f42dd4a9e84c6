/**
 * @file
 * No contact beyond its strength at any accepted step (issues 10 and 12).
 * The engine audits every converged attempt before accepting it
 * (DdaSystem::strength_audit, doc/theory/dda.md "Strength audit"); here
 * every accepted step is also checked from outside, from the contacts'
 * forces alone: a closed contact's tension at most its tensile strength, a
 * locked contact alone on its face at most its Mohr-Coulomb strength, and
 * the resultant shear of the locked contacts of a face at most the sum of
 * their strengths (the face-group rule), each plus 100 force tolerances
 * f (f = 1e-4 of the lighter block's weight): the largest tolerance the
 * open-close iteration may grant a contact (chatter 100 f, holds capped at
 * 100 f). Before commit 4eeeeb3 held contacts of the ratchet's wedge were
 * accepted with shear 100x beyond their strength.
 */
#include <rockdda/dda/engine.h>
#include <rockdda/dda/strength_audit.h>

#include <gtest/gtest.h>

#include "dda_test_scenes.h"
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <map>
#include <string>
#include <vector>

using namespace rockdda;
using namespace rockdda::dda;
using namespace rockdda::dda::test_scenes;

namespace
{
  constexpr double deg = M_PI / 180.;

  /// Runs @p steps steps of @p dda; expects the audit statistic of every
  /// step <= 1 and no excess over strength + 100 f after any of them.
  /// Returns the largest excess (N/m).
  double
  expect_within_strength(DdaSystem &dda, const int steps)
  {
    double         worst_ratio = 0.;
    StrengthExcess worst;
    std::string    at;
    for (int k = 0; k < steps; ++k)
      {
        const StepReport r = dda.step();
        worst_ratio        = std::max(worst_ratio, r.strength_ratio);
        EXPECT_LE(r.strength_ratio, 1.) << "step " << k + 1;
        const StrengthExcess e = strength_excess(dda);
        if (e.value > worst.value)
          {
            worst = e;
            at    = "step " + std::to_string(k + 1);
          }
      }
    EXPECT_LE(dda.worst_strength_ratio, 1.);
    EXPECT_DOUBLE_EQ(dda.worst_strength_ratio, worst_ratio);
    EXPECT_LE(worst.value, 0.) << worst.what << " at " << at;
    std::printf("  %d steps (%lu cuts): audit ratio %.3g, largest excess over "
                "strength + 100 f %.3e N/m (%s, %s)\n",
                steps,
                dda.n_cuts,
                worst_ratio,
                worst.value,
                worst.what.c_str(),
                at.c_str());
    return worst.value;
  }
} // namespace



// Issue 12's scene: a running-bond wall (8 x 10 bricks, cohesionless,
// phi = 35 deg) released from rest with unloaded springs, 120 dynamic steps:
// every contact closes, slips or opens in the first steps.
TEST(DdaStrengthAudit, RunningBondWallFromRest)
{
  Controls c       = controls(1e-3, 1., 1e11);
  c.max_iterations = 100;
  DdaSystem dda(running_bond_wall(8, 10), c);
  expect_within_strength(dda, 120);
}



// A 1 m block on an incline, phi = 30 deg: below the friction angle
// (20 deg) it stays, at it (30 deg) it is at limit equilibrium, where the
// two base contacts (a face group) carry the full strength W cos(a)
// tan(phi) = W sin(a) and the back corner alone is beyond its own strength.
// Dynamic from unloaded springs, then static.
TEST(DdaStrengthAudit, BlockOnInclineAtAndBelowTheFrictionAngle)
{
  for (const double dynamic : {1., 0.})
    for (const double alpha : {20., 30.})
      {
        std::printf("incline %g deg, phi 30 deg, dynamic %g:\n",
                    alpha,
                    dynamic);
        DdaSystem dda(incline_scene(alpha * deg, 30.),
                      controls(1e-3, dynamic, 1e11));
        expect_within_strength(dda, 300);
        // Below the friction angle the block does not slide (the elastic
        // shear of the springs, W sin(a) / (2 p_s) ~ 1e-7 m, is the motion).
        if (alpha < 30.)
          {
            EXPECT_LT(std::abs(along_slope(dda, 1, alpha * deg)), 1e-5);
          }
      }
}



// A 1 m block on a cohesive joint (c = 10 kPa; phi = 10 and 0 deg) pulled
// sideways at its mid-height by 0.95 of its strength c L + W tan(phi),
// static steps (limit equilibrium is a static statement): it holds, the
// joint stays intact, and no contact is beyond its strength.
TEST(DdaStrengthAudit, CohesiveJointPulledNearItsStrength)
{
  const double W = 2700. * g_earth;
  for (const double phi : {10., 0.})
    {
      BlockSystem s        = one_material_scene(2700., 1e10, 0.25, phi);
      s.joints[0].cohesion = 1e4;
      const int base       = add_block(s, rectangle(-2., -1., 5., 1.));
      const int b          = add_block(s, rectangle(0., 0., 1., 1.));
      fix_block(s, base);
      LoadPoint l;
      l.block = b;
      l.point = Point(0.5, 0.5);
      l.force = Point(0.95 * (1e4 * 1. + W * std::tan(phi * deg)), 0.);
      s.load_points.push_back(l);
      std::printf("cohesive joint, phi %g deg, pull %.0f N/m:\n",
                  phi,
                  l.force.x());
      DdaSystem dda(s, controls(1e-3, 0., 1e11));
      expect_within_strength(dda, 300);
      for (const auto &ct : dda.contacts())
        EXPECT_FALSE(ct.broken) << "phi " << phi;
      EXPECT_LT(std::abs(dda.centroid_displacement(b).x()), 1e-5);
    }
}



// The checks themselves (dda::StrengthAudit, both engines), on one contact
// with a Mohr-Coulomb strength of 100 N and tolerances f = 1 N, hold 5 N:
// each excess is measured in units of the tolerance the iteration allowed,
// and only beyond it (ratio > 1) does the audit fail with a diagnosis
// naming the contact, the check and its numbers.
TEST(DdaStrengthAudit, JudgesEachCheckInUnitsOfItsTolerance)
{
  AuditedContact locked;
  locked.state          = ContactState::locked;
  locked.normal_force   = 200.;
  locked.strength       = 100.;
  locked.tolerance      = 1.;
  locked.hold_tolerance = 5.;
  {
    StrengthAudit a;
    locked.locked_shear = 104.;
    EXPECT_TRUE(a.judge_contact(0, locked));
    EXPECT_NEAR(a.ratio(), 0.8, 1e-12);
    EXPECT_TRUE(a.diagnosis(1, 2, "N").empty());
    locked.locked_shear = 110.;
    EXPECT_TRUE(a.judge_contact(3, locked));
    EXPECT_NEAR(a.ratio(), 2., 1e-12);
    EXPECT_EQ(a.worst_contact(), 3);
    const std::string d = a.diagnosis(7, 9, "N");
    EXPECT_NE(d.find("block 7 on block 9"), std::string::npos) << d;
    EXPECT_NE(d.find("shear while locked"), std::string::npos) << d;
  }
  {
    // A locked face-group member beyond its own strength + hold: its group
    // decides (the caller), not the member alone.
    StrengthAudit a;
    locked.in_group = true;
    EXPECT_FALSE(a.judge_contact(0, locked));
    EXPECT_EQ(a.ratio(), 0.);
    locked.in_group = false;
  }
  {
    // Tension: a sliding contact may carry f, a locked one its hold, an
    // intact locked joint its tensile strength on top.
    StrengthAudit  a;
    AuditedContact t = locked;
    t.locked_shear   = 0.;
    t.normal_force   = -4.;
    a.judge_contact(0, t);
    EXPECT_NEAR(a.ratio(), 0.8, 1e-12);
    t.tensile_limit = 10.;
    t.normal_force  = -12.;
    StrengthAudit b;
    b.judge_contact(0, t);
    EXPECT_NEAR(b.ratio(), 0.4, 1e-12);
    t.state         = ContactState::sliding;
    t.tensile_limit = 0.;
    t.normal_force  = -4.;
    t.strength      = 0.;
    StrengthAudit s;
    s.judge_contact(0, t);
    EXPECT_NEAR(s.ratio(), 4., 1e-12);
    EXPECT_NE(s.diagnosis(1, 2, "N").find("tension"), std::string::npos);
  }
  {
    // Sliding: the friction assembled against the strength at the accepted
    // normal force, and a slip against the friction beyond f.
    StrengthAudit  a;
    AuditedContact s     = locked;
    s.state              = ContactState::sliding;
    s.friction_carried   = 103.;
    s.friction_tolerance = 2.;
    a.judge_contact(0, s);
    EXPECT_NEAR(a.ratio(), 1.5, 1e-12);
    EXPECT_NE(a.diagnosis(1, 2, "N/m").find("friction off its strength"),
              std::string::npos);
    StrengthAudit b;
    s.friction_carried = 100.;
    s.slip_against     = 0.5;
    b.judge_contact(0, s);
    EXPECT_NEAR(b.ratio(), 0.5, 1e-12);
    // A frictionless contact has no friction to audit.
    StrengthAudit c;
    s.frictionless     = true;
    s.friction_carried = 0.;
    c.judge_contact(0, s);
    EXPECT_EQ(c.ratio(), 0.);
  }
  {
    // Open: compression up to its open tolerance.
    StrengthAudit  a;
    AuditedContact o;
    o.state          = ContactState::open;
    o.normal_force   = 30.;
    o.open_tolerance = 20.;
    a.judge_contact(0, o);
    EXPECT_NEAR(a.ratio(), 1.5, 1e-12);
    EXPECT_NE(a.diagnosis(1, 2, "N").find("compression while open"),
              std::string::npos);
  }
}
