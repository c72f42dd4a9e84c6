/**
 * @file
 * The open-close iteration on a scene that moves (issue 12): a running-bond
 * wall released from rest with unloaded springs, where every contact is
 * exercised in the first steps. The accepted steps must satisfy the contact
 * conditions (no cohesionless contact in tension beyond the iteration's
 * tolerance), the energy of the step may only be dissipated, and the
 * iteration's accuracy knobs (line search, inexact solves) must not change
 * what is accepted beyond their stated tolerances.
 */
#include <rockdda/dda/block_matrices.h>
#include <rockdda/dda/engine.h>
#include <rockdda/dda/friction_relaxation.h>

#include <gtest/gtest.h>

#include "dda_test_scenes.h"
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <tuple>
#include <utility>
#include <vector>

using namespace rockdda;
using namespace rockdda::dda;
using namespace rockdda::dda::test_scenes;

namespace
{
  /// Weight (N/m) of the lightest block of the wall: a half brick.
  constexpr double half_brick_weight = 2700. * 1. * g_earth;

  /// Mean settlement (m) of the top row of the wall.
  double
  top_settlement(const DdaSystem &dda, const BlockSystem &initial)
  {
    double top = -1e300;
    for (const auto &b : initial.blocks)
      for (const auto &v : b.polygon.vertices)
        top = std::max(top, v.y());
    double sum = 0.;
    int    n   = 0;
    for (std::size_t b = 1; b < initial.blocks.size(); ++b)
      {
        double y_max = -1e300;
        for (const auto &v : initial.blocks[b].polygon.vertices)
          y_max = std::max(y_max, v.y());
        if (y_max < top - 1e-9)
          continue;
        sum -= dda.centroid_displacement(static_cast<int>(b)).y();
        ++n;
      }
    return sum / n;
  }

  Controls
  wall_controls()
  {
    Controls c       = controls(1e-3, 1., 1e11);
    c.max_iterations = 100;
    return c;
  }
} // namespace



/// The no-tension and energy checks at a force tolerance (Contact force
/// tolerance, a fraction of the lighter block's weight).
class DdaOpenCloseTolerance : public ::testing::TestWithParam<double>
{};



TEST_P(DdaOpenCloseTolerance, NoTensionAndNoEnergyCreatedOnAWallFromRest)
{
  // 8 rows x 10 bricks released from rest, 120 dynamic steps of 1 ms. A
  // cohesionless contact accepted as closed may carry a tension of at most
  // the iteration's tolerance: max(1, 1e-2 / fraction) f (f = fraction of
  // the lighter block's weight; chattering contacts: 100 f = 1 % of the
  // weight at the default 1e-4, f itself from 1e-2 up) or, for a held
  // contact, p_s x hold_fraction x the smaller block's size (1e-7 of the
  // size as an elastic displacement). The energy ledger may only lose
  // energy (the time integration dissipates; nothing drives the wall).
  const double      fraction = GetParam();
  const BlockSystem wall     = running_bond_wall(8, 10);
  Controls          c        = wall_controls();
  c.law.force_tolerance      = fraction;
  DdaSystem    dda(wall, c);
  const double hold  = c.law.shear_penalty() * c.hold_fraction * 1.;
  const double cap   = std::max(1e-2, fraction) * half_brick_weight;
  const double bound = std::max(cap, hold) * 1.001;
  const double e0    = dda.energy().balance();
  double       worst = 0., energy_gain = 0.;
  unsigned     held = 0;
  for (int k = 0; k < 120; ++k)
    {
      dda.step();
      for (const auto &ct : dda.contacts())
        if (ct.state != ContactState::open)
          {
            const double tension = -ct.normal_force;
            worst                = std::max(worst, tension);
            if (tension > cap)
              ++held;
          }
      energy_gain = std::max(energy_gain, dda.energy().balance() - e0);
    }
  std::printf("force tolerance %.0e W: largest tension at an accepted step: "
              "%.3e N/m (%.2e of the half-brick weight; bound %.3e), %u "
              "contact-steps above the escalation cap; largest energy gain "
              "%.3e J/m; %lu steps, %lu cuts, %.2f open-close iterations "
              "per step\n",
              fraction,
              worst,
              worst / half_brick_weight,
              bound,
              held,
              energy_gain,
              dda.n_steps,
              dda.n_cuts,
              static_cast<double>(dda.n_iterations) / dda.n_steps);
  EXPECT_LE(worst, bound);
  // Energy: round-off of the ledger's terms, relative to the wall's
  // potential energy change (~ weight x settlement).
  EXPECT_LE(energy_gain, 1e-6 * std::abs(dda.energy().potential) + 1e-6);
}

INSTANTIATE_TEST_SUITE_P(DefaultAndLoose,
                         DdaOpenCloseTolerance,
                         ::testing::Values(1e-4, 1e-2));



TEST(DdaOpenClose, HeldOpenContactsPenetrateNoDeeperThanTheirBound)
{
  // A contact that cycles in the open-close iteration is held: an open one
  // stays open while its penetration is at most hold_fraction x the smaller
  // block's size and its penetration force at most the lighter block's
  // weight (Controls::hold_after; it carries no force, so it hangs no
  // block). Check that bound on the geometry itself: after every accepted
  // step of a 12 x 16 wall released from rest, no vertex of a contact
  // accepted as open lies inside the other block's edge by more than it
  // (plus round-off of 1e-12 of the block's size).
  const BlockSystem wall = running_bond_wall(12, 16);
  const Controls    c    = wall_controls();
  DdaSystem         dda(wall, c);
  const double      k_n   = c.law.normal_penalty;
  double            worst = 0., deepest = 0.;
  unsigned          penetrating = 0;
  for (int k = 0; k < 150; ++k)
    {
      dda.step();
      const auto &blocks = dda.system().blocks;
      for (const auto &ct : dda.contacts())
        {
          if (ct.state != ContactState::open)
            continue;
          const auto &g  = ct.geometry;
          const auto &pi = blocks[g.block_i].polygon;
          const auto &pj = blocks[g.block_j].polygon;
          const Point p  = pi.vertices[g.vertex];
          const Point a  = pj.vertices[g.edge];
          const Point b
            = pj.vertices[(g.edge + 1) % static_cast<int>(pj.vertices.size())];
          const Point  e = b - a;
          const double t = (p - a).dot(e) / e.squaredNorm();
          if (t < 0. || t > 1.)
            continue;
          // Counter-clockwise polygons: inside is to the left of a -> b.
          const double depth
            = (e.x() * (p - a).y() - e.y() * (p - a).x()) / e.norm();
          if (depth <= 0.)
            continue;
          const double size = std::min(block_size(pi), block_size(pj));
          const double weight
            = std::min(pi.area()
                         * wall.materials[blocks[g.block_i].material].density,
                       pj.area()
                         * wall.materials[blocks[g.block_j].material].density)
              * g_earth;
          const double bound
            = std::min(c.hold_fraction * size, weight / k_n) + 1e-12 * size;
          ++penetrating;
          deepest = std::max(deepest, depth);
          worst   = std::max(worst, depth / bound);
        }
    }
  std::printf("open contacts inside the other block after accepted steps: "
              "%u contact-steps, deepest %.3e m, largest depth / bound "
              "%.3f; %lu steps, %lu cuts\n",
              penetrating,
              deepest,
              worst,
              dda.n_steps,
              dda.n_cuts);
  EXPECT_LE(worst, 1.);
}



TEST(DdaOpenClose, AcceptedStepDoesNotDependOnTheInexactSolves)
{
  // Inexact CG while the states settle, confirmed by a solve to the solver
  // tolerance. The states accepted may differ only within the iteration's
  // force tolerance band (100 f, f = 1e-4 of the lighter block's weight),
  // i.e. block positions within 100 f / p after one step; over many steps
  // of the vibrating wall such differences grow, so the settlement after
  // 40 steps is compared to 1 %.
  const BlockSystem wall = running_bond_wall(6, 8);
  auto              run  = [&](const double inexact, const int steps) {
    Controls c       = wall_controls();
    c.inexact_factor = inexact;
    c.solver.type    = SolverType::iterative;
    DdaSystem dda(wall, c);
    for (int k = 0; k < steps; ++k)
      dda.step();
    return std::make_tuple(dda.system(),
                           dda.n_solver_iterations,
                           top_settlement(dda, wall));
  };
  const double band = 100. * 1e-4 * half_brick_weight / 1e11;
  for (const int steps : {1, 40})
    {
      const auto [exact, cg_exact, s_exact]       = run(1., steps);
      const auto [inexact, cg_inexact, s_inexact] = run(1000., steps);
      const double diff = max_vertex_difference(exact, inexact);
      std::printf("%d steps, exact vs inexact solves: max vertex difference "
                  "%.3e m (band %.3e m), settlement %.6e vs %.6e m; CG "
                  "iterations %lu vs %lu\n",
                  steps,
                  diff,
                  band,
                  s_exact,
                  s_inexact,
                  cg_exact,
                  cg_inexact);
      if (steps == 1)
        EXPECT_LT(diff, band);
      else
        EXPECT_NEAR(s_inexact, s_exact, 0.01 * s_exact);
    }
}



TEST(DdaOpenClose, LineSearchKeepsThePhysicsOfFullSteps)
{
  // The line search changes how the iteration reaches the contact states,
  // not the conditions the accepted step satisfies: the settlement of the
  // top row after 0.1 s agrees with that of full open-close steps to within
  // the time discretisation's spread (dt = 1 ms; the settlement at one
  // instant of the undamped vibration moves by a few per cent with the
  // step sequence), and both are close to the static settlement scale.
  const BlockSystem wall = running_bond_wall(6, 8);
  auto              run  = [&](const bool line_search) {
    Controls c    = wall_controls();
    c.line_search = line_search;
    DdaSystem dda(wall, c);
    dda.run_until(0.1);
    std::printf("line search %d: %lu steps, %lu cuts, %.2f iterations per "
                              "step, %lu solves, settlement %.6e m\n",
                line_search ? 1 : 0,
                dda.n_steps,
                dda.n_cuts,
                static_cast<double>(dda.n_iterations) / dda.n_steps,
                dda.n_solves,
                top_settlement(dda, wall));
    return top_settlement(dda, wall);
  };
  const double with    = run(true);
  const double without = run(false);
  EXPECT_GT(with, 0.);
  EXPECT_NEAR(with, without, 0.05 * without);
}



/**
 * A wedge of taper theta slides into a V-notch under its weight W in
 * static steps, until it stops. Exact answer of the rigid wedge at the
 * friction limit (friction up the faces): each face carries
 * N = W / (2 (sin(theta) + mu cos(theta))). The friction iteration couples
 * a sliding face's friction to its normal force with the gain
 * -mu / tan(theta) (vertical equilibrium 2 N_new sin(theta) +
 * 2 mu N_assembled cos(theta) = W, less the step's inertia term), 1.6 to 19
 * here. Tolerance: the friction iteration converges to 1e-3 of the normal
 * force plus the force tolerance (1e-4 W), so 2e-3 N.
 */
class SmallTaperWedge
    : public ::testing::TestWithParam<std::tuple<double, double>>
{};

TEST_P(SmallTaperWedge, SettlesWithTheLimitEquilibriumNormalForce)
{
  const auto [theta_deg, phi_deg] = GetParam();
  const double theta              = theta_deg * M_PI / 180.;
  const double mu                 = std::tan(phi_deg * M_PI / 180.);
  const double H = 2., w0 = 0.5, L = 3., t = std::tan(theta);
  const auto   half = [&](const double y) { return w0 + y * t; };
  BlockSystem  s    = one_material_scene(2700., 1e10, 0.25, phi_deg);
  const int    left = add_block(
    s,
    polygon({Point(-L, 0.), Point(-w0, 0.), Point(-half(H), H), Point(-L, H)}));
  const int right = add_block(
    s, polygon({Point(w0, 0.), Point(L, 0.), Point(L, H), Point(half(H), H)}));
  // The wedge touches both faces from y = 0.5 m up, and stands 0.5 m
  // above the notch.
  const double yb = 0.5, yt = H + 0.5;
  const int    wedge = add_block(s,
                              polygon({Point(-half(yb), yb),
                                          Point(half(yb), yb),
                                          Point(half(yt), yt),
                                          Point(-half(yt), yt)}));
  fix_block(s, left);
  fix_block(s, right);
  const double W = 2700. * g_earth * s.blocks[wedge].polygon.area();

  Controls c       = controls(1e-3, 0., 1e11);
  c.max_iterations = 30;
  DdaSystem dda(s, c);
  // Static steps relax towards the equilibrium (by ~0.7 per step here):
  // until no vertex moves by 1e-12 of the notch's height.
  int steps = 0;
  for (; steps < 1000; ++steps)
    {
      StepReport r;
      ASSERT_NO_THROW(r = dda.step()) << "step " << steps + 1;
      if (r.max_displacement < 1e-12 * H && r.cuts == 0)
        break;
    }
  ASSERT_LT(steps, 1000) << "no equilibrium";

  double n_left = 0., n_right = 0.;
  int    sliding = 0;
  for (const auto &ct : dda.contacts())
    {
      const auto &g = ct.geometry;
      if (ct.state == ContactState::open
          || (g.block_i != wedge && g.block_j != wedge))
        continue;
      const int other = g.block_i == wedge ? g.block_j : g.block_i;
      (other == left ? n_left : n_right) += ct.normal_force;
      sliding += ct.state == ContactState::sliding;
    }
  const double exact = W / (2. * (std::sin(theta) + mu * std::cos(theta)));
  std::printf("theta %.0f deg, phi %.0f deg (gain -%.1f): N left %.6e, right "
              "%.6e, exact %.6e N/m; %d sliding contacts\n",
              theta_deg,
              phi_deg,
              mu / t,
              n_left,
              n_right,
              exact,
              sliding);
  EXPECT_NEAR(n_left, exact, 2e-3 * exact);
  EXPECT_NEAR(n_right, exact, 2e-3 * exact);
  // Friction acts up the faces: the wedge went down.
  EXPECT_LT(dda.centroid_displacement(wedge).y(), 0.);
}

INSTANTIATE_TEST_SUITE_P(GainsFromOneToTwenty,
                         SmallTaperWedge,
                         ::testing::Values(std::make_tuple(20., 30.),
                                           std::make_tuple(10., 35.),
                                           std::make_tuple(5., 30.),
                                           std::make_tuple(3., 45.)));



TEST(DdaOpenClose, RelaxedFrictionIterationConvergesWhereThePlainOneDiverges)
{
  // The friction-normal coupling of a wedge of small taper (the reason for
  // dda::FrictionRelaxation, both engines): the normal force a solve
  // produces from the force its friction was assembled with is
  // N = N* + gain (N_a - N*), gain = -mu / taper. Two contacts with gains
  // -3 and -1.5 (mu = 0.6, tapers 0.2 and 0.4): the plain fixed point
  // (omega = 1) multiplies the error by |gain| >= 1.5 per iteration;
  // Aitken's rule finds the secant factor of the coupled map and converges
  // to N* within round-off in a few iterations. A state change restarts it
  // (omega = 1), and an iteration without residuals relaxes nothing.
  const std::vector<double> target{1000., 400.}, gain{-3., -1.5};
  auto                      iterate = [&](const bool relaxed) {
    std::vector<double> assembled{0., 0.};
    FrictionRelaxation  relaxation(2);
    int                 k = 0;
    for (; k < 60; ++k)
      {
        double              worst = 0.;
        std::vector<double> produced(2);
        for (std::size_t c = 0; c < 2; ++c)
          {
            produced[c] = target[c] + gain[c] * (assembled[c] - target[c]);
            worst = std::max(worst, std::abs(produced[c] - assembled[c]));
            relaxation.set_residual(c, produced[c] - assembled[c]);
          }
        if (worst < 1e-9 * target[0])
          break;
        const std::vector<double> before = assembled;
        assembled                        = produced;
        relaxation.relax(!relaxed, [&](const std::size_t c, const double d) {
          assembled[c] = before[c] + d;
        });
        if (!std::isfinite(assembled[0]) || std::abs(assembled[0]) > 1e12)
          return 1000;
      }
    return k;
  };
  const int plain = iterate(false), aitken = iterate(true);
  std::printf("friction iteration with gains -3 and -1.5: plain fixed point "
              "%s, Aitken converged in %d iterations\n",
              plain >= 60 ? "diverged" : "converged",
              aitken);
  EXPECT_GE(plain, 60);
  EXPECT_LE(aitken, 30);

  // A restart and an iteration without residuals leave omega at 1.
  FrictionRelaxation r(1);
  r.set_residual(0, 5.);
  r.relax(false, [](std::size_t, double) {});
  r.set_residual(0, -10.);
  r.relax(false, [](std::size_t, double) {});
  EXPECT_NE(r.omega(), 1.);
  r.set_residual(0, 0.);
  bool called = false;
  r.relax(false, [&](std::size_t, double) { called = true; });
  EXPECT_FALSE(called);
  EXPECT_EQ(r.omega(), 1.);
  EXPECT_FALSE(r.has_residual());
}
