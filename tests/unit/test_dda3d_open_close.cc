/**
 * @file
 * The 3D open-close iteration with the 2D engine's safeguards, written once
 * for both (issue 17): the strength audit of every converged attempt
 * (dda::StrengthAudit), the relaxed friction iteration
 * (dda::FrictionRelaxation) and the inexact solves confirmed by an exact
 * one.
 */
#include <rockdda/dda3d/engine.h>

#include <gtest/gtest.h>

#include "dda3d_test_scenes.h"
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <map>
#include <utility>
#include <vector>

using namespace rockdda;
using namespace rockdda::dda3d;

namespace
{
  constexpr double pi = M_PI;
  constexpr double g  = 9.80665;

  /// The shaking of Dda3dSolvers.IterativeMatchesDirectAndThreadsDoNotMatter:
  /// 0.9 g at 5 Hz along the wall and 0.3 g at 7 Hz across it (loading
  /// mode), on top of gravity.
  EngineControls
  shaken_wall_controls()
  {
    EngineControls c;
    c.dt                  = 1e-3;
    c.law.normal_penalty  = 1e11;
    c.ground_acceleration = [](const double t) {
      return Point(0.9 * g * std::sin(2. * pi * 5. * t),
                   0.3 * g * std::sin(2. * pi * 7. * t),
                   0.);
    };
    return c;
  }

  /// Mass (kg) of a box block of @p s (its bounding box's volume).
  double
  box_mass(const BlockSystem &s, const int b)
  {
    Point lo = Point::Constant(1e300), hi = Point::Constant(-1e300);
    for (const auto &v : s.blocks[b].polyhedron.vertices)
      {
        lo = lo.cwiseMin(v);
        hi = hi.cwiseMax(v);
      }
    return s.materials[s.blocks[b].material].density * (hi - lo).prod();
  }
} // namespace



TEST(Dda3dOpenClose, ShakenWallStaysWithinStrengthAtEveryAcceptedStep)
{
  // A 4 x 4 running-bond wall (cohesionless, phi = 35 deg) shaken for 150
  // steps of 1 ms: its top bricks slide and rock, contacts open, slide and
  // relock. After every accepted step, checked from the contacts' forces
  // alone: no closed contact in tension, no locked contact beyond its
  // Mohr-Coulomb strength (each alone; with face groups sharing their
  // strength, the resultant of a face's locked contacts against the sum of
  // their strengths), each within the largest tolerance the open-close
  // iteration may grant a contact: 1 % of the lighter block's weight
  // (chatter 100 f, holds capped there; the weight with the largest
  // seismic acceleration, |g + a| <= 1.4 g), and the engine's own audit
  // ratio at most 1.
  const BlockSystem wall = test_scenes::brick_wall(4, 4);
  for (const bool groups : {false, true})
    {
      SCOPED_TRACE(groups ? "face groups share their strength"
                          : "each contact alone");
      EngineControls c      = shaken_wall_controls();
      c.face_group_friction = groups;
      Engine       engine(wall, c);
      const auto  &joint = wall.joints[0];
      double       worst = 0., worst_ratio = 0.;
      unsigned     sliding = 0, relocks = 0;
      const double a_max = 1.4 * g;
      for (int k = 0; k < 150; ++k)
        {
          engine.step();
          worst_ratio
            = std::max(worst_ratio, engine.statistics().strength_ratio);
          EXPECT_LE(engine.statistics().strength_ratio, 1.) << "step " << k;
          // Per pair of blocks (a face group): locked shear resultant,
          // strengths and bound.
          std::map<std::pair<int, int>, std::tuple<Point, double, double>>
            faces;
          for (const auto &ct : engine.contacts())
            {
              if (ct.state == dda::ContactState::open)
                continue;
              const int    i = ct.geometry.i, j = ct.geometry.j;
              const double bound
                = 1e-2 * std::min(box_mass(wall, i), box_mass(wall, j)) * a_max;
              worst = std::max(worst, -ct.normal_force / bound);
              sliding += ct.state == dda::ContactState::sliding;
              relocks += ct.state == dda::ContactState::locked
                         && ct.state_at_start == dda::ContactState::sliding;
              if (ct.state != dda::ContactState::locked)
                continue;
              const double strength
                = dda::shear_strength(ct, ct.normal_force, ct.area, joint);
              if (!groups)
                worst
                  = std::max(worst, (ct.shear_force.norm() - strength) / bound);
              else
                {
                  auto &[resultant, sum, allowed]
                    = faces
                        .try_emplace({std::min(i, j), std::max(i, j)},
                                     Point::Zero(),
                                     0.,
                                     0.)
                        .first->second;
                  resultant += (i < j ? 1. : -1.) * ct.shear_force;
                  sum += strength;
                  allowed += bound;
                }
            }
          for (const auto &[pair, f] : faces)
            worst = std::max(worst,
                             (std::get<0>(f).norm() - std::get<1>(f))
                               / std::get<2>(f));
        }
      std::printf("shaken 4 x 4 wall, %s: %u sliding contact-steps, %u "
                  "relocks; largest excess over the strength %.3f of the "
                  "bound (<= 0: within the strength), engine's audit ratio "
                  "%.3f\n",
                  groups ? "face groups" : "contacts alone",
                  sliding,
                  relocks,
                  worst,
                  worst_ratio);
      // The scene exercises the rules: contacts slide and relock.
      EXPECT_GT(sliding, 100u);
      EXPECT_GT(relocks, 0u);
      EXPECT_LE(worst, 1.);
      EXPECT_LE(worst_ratio, 1.);
    }
}



TEST(Dda3dOpenClose, AcceptedStepsDoNotDependOnTheInexactSolves)
{
  // A 4 x 4 running-bond wall released from rest with unloaded springs
  // under gravity, 80 dynamic steps of 1 ms with the D-ILU CG: every
  // contact closes in the first steps and the wall settles on its springs.
  // Solving to 1000 x the solver tolerance while the contact states settle,
  // the settled states confirmed by a solve to the tolerance (inexact
  // Newton, as in 2D:
  // DdaOpenClose.AcceptedStepDoesNotDependOnTheInexactSolves), must accept the
  // physics of exact solves: the settlement within 1 % (the 2D test's bound),
  // every vertex within 1 % of the largest displacement. The paths may differ
  // where a contact near zero force is decided within its tolerance (a state
  // that flips differently moves a brick by up to its elastic slip), so not bit
  // for bit.
  const BlockSystem wall = test_scenes::brick_wall(4, 4);
  auto              run  = [&](const double inexact) {
    EngineControls c         = shaken_wall_controls();
    c.ground_acceleration    = nullptr;
    c.solver.type            = dda::SolverType::iterative;
    c.solver.preconditioner  = dda::Preconditioner::block_dilu;
    c.solver.subdomain_limit = 300;
    c.inexact_factor         = inexact;
    Engine        engine(wall, c);
    unsigned long cg = 0;
    for (int k = 0; k < 80; ++k)
      {
        engine.step();
        cg += engine.statistics().solver_iterations;
      }
    std::vector<Point> vertices;
    for (const auto &b : engine.scene().blocks)
      for (const auto &v : b.polyhedron.vertices)
        vertices.push_back(v);
    double moved = 0.;
    for (std::size_t b = 0; b < wall.blocks.size(); ++b)
      moved = std::max(moved, engine.displacement(b).norm());
    std::printf("inexact factor %g: largest displacement %.5e m, %lu steps, "
                              "%lu cuts, %.2f open-close iterations per step, %lu CG "
                              "iterations, audit ratio %.3f\n",
                inexact,
                moved,
                engine.n_steps,
                engine.n_cuts,
                double(engine.n_iterations) / double(engine.n_steps),
                cg,
                engine.worst_strength_ratio);
    EXPECT_LE(engine.worst_strength_ratio, 1.);
    return std::make_pair(vertices, moved);
  };
  const auto [exact, moved_exact]     = run(1.);
  const auto [inexact, moved_inexact] = run(1000.);
  double d                            = 0.;
  for (std::size_t k = 0; k < exact.size(); ++k)
    d = std::max(d, (exact[k] - inexact[k]).norm());
  std::printf("exact vs inexact solves: max vertex difference %.3e m (%.3f "
              "%% of the largest displacement)\n",
              d,
              100. * d / moved_exact);
  EXPECT_GT(moved_exact, 1e-6); // the wall settles: the test can fail
  EXPECT_NEAR(moved_inexact, moved_exact, 0.01 * moved_exact);
  EXPECT_LE(d, 0.01 * moved_exact);
}
