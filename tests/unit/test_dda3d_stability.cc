/**
 * @file
 * Stability of 3D DDA at the extremes (issue 17): the 2D engine's table
 * (penalty 1e-3 to 1e3 x E L, time step 1e-6 to 1e-1 s, friction 0 to 89
 * deg, size 1 mm to 100 m, aspect ratio to 1:1000) on a box on an incline,
 * one axis at a time about a nominal case, plus the corners. Every case
 * either completes with a finite state, no energy created and the exact
 * answer (slides by 1/2 g (sin a - cos a tan phi) t^2 below the friction
 * angle, stays above it) within a tolerance from the penalty and the
 * block's compliance, or stops with a dda::DdaFailure whose message is a
 * diagnosis; never NaN, never a hang. Each case prints a row
 * "stability3d|case|outcome|error|tolerance|steps|cuts|wall" that
 * benchmarks/dda3d/stability_table.py turns into the README's table.
 */
#include <rockdda/dda3d/engine.h>

#include <gtest/gtest.h>

#include "dda3d_test_scenes.h"
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <string>

using namespace rockdda;
using namespace rockdda::dda3d;

namespace
{
  constexpr double g_earth = 9.80665;

  /// One row of the table.
  struct ExtremeCase
  {
    const char *name;
    /// Normal penalty over E L (-), L the slider's longest edge.
    double penalty_over_EL;
    /// Time step (s).
    double dt;
    /// Friction angle and slope angle (deg).
    double phi_deg, alpha_deg;
    /// Longest edge L of the slider (m).
    double size;
    /// Aspect ratio width / height (-): > 1 a plate L x L x L / aspect,
    /// < 1 a column L aspect x L aspect x L.
    double aspect;
  };

  std::ostream &
  operator<<(std::ostream &out, const ExtremeCase &c)
  {
    return out << c.name;
  }

  /// What a run gave.
  struct ExtremeResult
  {
    bool        finished = false;
    std::string outcome;
    /// Slide down the slope (m), its exact value and the tolerance (m).
    double slide = 0., exact = 0., tolerance = 0.;
    /// Largest energy created (balance above its start, J) and the energy
    /// scale m g L (J).
    double created = 0., energy_scale = 0.;
    bool   finite = true;
    int    steps = 0, cuts = 0;
    double wall = 0.;
  };

  /**
   * The slider on a clamped base 3 L_x long, 3 L_y wide and L_z' = max of
   * the slider's edges / 3 thick; run for 1000 time steps, or until the
   * frictionless slide would be 10 % of the slider's length (so that it
   * stays on the base), or until it would fall 10 % of its height on a
   * level base, whichever is first. At most 5000 steps (a guard: a
   * blocked run is a failure of the test, not a hang).
   */
  ExtremeResult
  run_extreme(const ExtremeCase &c)
  {
    const double E = 1e10, rho = 2700.;
    const double L     = c.size;
    const double lx    = c.aspect >= 1. ? L : L * c.aspect;
    const double lz    = c.aspect >= 1. ? L / c.aspect : L;
    const double ly    = lx;
    const double th    = std::max(lx, lz) / 3.;
    const auto   sc    = test_scenes::incline_scene(c.alpha_deg,
                                               c.phi_deg,
                                               Point(-1.5 * lx, -1.5 * ly, -th),
                                               Point(1.5 * lx, 1.5 * ly, 0.),
                                               Point(-lx, -0.5 * ly, 0.),
                                               Point(0., 0.5 * ly, lz),
                                               {rho, E, 0.25, 1});
    const double alpha = c.alpha_deg * M_PI / 180.;
    const double phi   = c.phi_deg * M_PI / 180.;
    const double t_cap
      = c.alpha_deg > 0.
          ? std::sqrt(2. * 0.1 * lx / (g_earth * std::sin(alpha)))
          : std::sqrt(2. * 0.1 * lz / g_earth);
    const double t_end = std::min(1000. * c.dt, t_cap);
    const double mass  = rho * lx * ly * lz;
    const double W     = mass * g_earth;

    EngineControls ctrl;
    ctrl.dt                 = c.dt;
    ctrl.law.normal_penalty = c.penalty_over_EL * E * L;
    ctrl.max_steps          = 5000;

    ExtremeResult r;
    r.energy_scale = W * L;
    // Exact: the rigid block slides with a = g (sin a - cos a tan phi) if
    // positive, else stays.
    const double accel
      = std::max(0.,
                 g_earth * (std::sin(alpha) - std::cos(alpha) * std::tan(phi)));
    r.exact = 0.5 * accel * t_end * t_end;
    // Tolerance (m): 1 % of the slide (the bound at 1 s) plus the
    // displacements the method allows besides the rigid solution: the
    // normal spring's compression W / p (the block starts on uncompressed
    // springs; the friction of the bounce that follows changes the slide
    // by tan phi times its amplitude, at most this), the shear springs'
    // stretch W / p_s of a contact that locks, and the block's elastic
    // shortening under its weight rho g lz^2 / E, each twice (the undamped
    // overshoot of a load applied at once).
    const double ps = ctrl.law.shear_penalty();
    r.tolerance     = 0.01 * r.exact
                  + 2.
                      * (W / ctrl.law.normal_penalty + W / ps
                         + rho * g_earth * lz * lz / E);

    const auto start = std::chrono::steady_clock::now();
    try
      {
        Engine       engine(sc.system, ctrl);
        const double b0 = engine.energy().balance();
        while (engine.time() < t_end - 1e-9 * c.dt && r.steps < 5000)
          {
            engine.advance_to(std::min(t_end, engine.time() + c.dt));
            ++r.steps;
            r.cuts += engine.statistics().cuts;
            r.created = std::max(r.created, engine.energy().balance() - b0);
          }
        r.finished = engine.time() >= t_end - 1e-9 * c.dt;
        for (const auto &b : engine.scene().blocks)
          {
            for (const auto &v : b.polyhedron.vertices)
              r.finite = r.finite && v.allFinite();
            r.finite
              = r.finite && b.velocity.allFinite() && b.stress.allFinite();
          }
        r.slide   = engine.displacement(1).dot(sc.frame.col(0));
        r.outcome = r.finished ? "completed" : "step guard reached";
      }
    catch (const dda::DdaFailure &e)
      {
        r.outcome = std::string("stopped: ") + e.what();
      }
    r.wall
      = std::chrono::duration<double>(std::chrono::steady_clock::now() - start)
          .count();
    return r;
  }
} // namespace



class Dda3dStability : public testing::TestWithParam<ExtremeCase>
{};

TEST_P(Dda3dStability, FiniteAndExactOrDiagnosed)
{
  const ExtremeCase  &c = GetParam();
  const ExtremeResult r = run_extreme(c);
  std::printf("stability3d|%s|%s|%.3e|%.3e|%.3e|%.3e|%d|%d|%.3f\n",
              c.name,
              r.outcome.c_str(),
              r.slide,
              r.exact,
              std::abs(r.slide - r.exact),
              r.tolerance,
              r.steps,
              r.cuts,
              r.wall);
  std::printf("  energy created %.3e J (%.2e m g L)\n",
              r.created,
              r.created / r.energy_scale);
  if (r.outcome.rfind("stopped: ", 0) == 0)
    {
      // A diagnosis: names the cause, with the time reached.
      EXPECT_NE(r.outcome.find("time step"), std::string::npos) << r.outcome;
      EXPECT_NE(r.outcome.find("t = "), std::string::npos) << r.outcome;
      return;
    }
  ASSERT_TRUE(r.finished) << r.outcome << " after " << r.steps << " steps";
  EXPECT_TRUE(r.finite);
  EXPECT_LE(std::abs(r.slide - r.exact), r.tolerance)
    << "slide " << r.slide << " m, exact " << r.exact << " m";
  // Shi's scheme and friction only dissipate: the energy balance may not
  // rise beyond round-off of the energy in play.
  EXPECT_LE(r.created, 1e-9 * r.energy_scale);
}

// Nominal: a 1 m cube, E = 10 GPa, penalty 10 E L, dt 1 ms, 30 deg slope,
// 20 deg friction (slides). Then one axis at a time, then the corners.
INSTANTIATE_TEST_SUITE_P(
  Table,
  Dda3dStability,
  testing::Values(
    ExtremeCase{"nominal", 10., 1e-3, 20., 30., 1., 1.},
    ExtremeCase{"penalty_1e-3_EL", 1e-3, 1e-3, 20., 30., 1., 1.},
    ExtremeCase{"penalty_1e3_EL", 1e3, 1e-3, 20., 30., 1., 1.},
    ExtremeCase{"dt_1e-6_s", 10., 1e-6, 20., 30., 1., 1.},
    ExtremeCase{"dt_1e-1_s", 10., 1e-1, 20., 30., 1., 1.},
    ExtremeCase{"friction_0_deg", 10., 1e-3, 0., 30., 1., 1.},
    ExtremeCase{"friction_40_deg_stays", 10., 1e-3, 40., 30., 1., 1.},
    ExtremeCase{"friction_89_deg_stays", 10., 1e-3, 89., 30., 1., 1.},
    ExtremeCase{"size_1_mm", 10., 1e-3, 20., 30., 1e-3, 1.},
    ExtremeCase{"size_100_m", 10., 1e-3, 20., 30., 100., 1.},
    ExtremeCase{"plate_1000_to_1", 10., 1e-3, 20., 30., 1., 1000.},
    ExtremeCase{"column_1_to_1000_level", 10., 1e-3, 20., 0., 1., 1e-3},
    // The same column with the penalty 10 E x its 1 mm footprint.
    ExtremeCase{"column_1_to_1000_level_soft", 1e-2, 1e-3, 20., 0., 1., 1e-3},
    ExtremeCase{"stiff_long_step", 1e3, 1e-1, 20., 30., 1., 1.},
    ExtremeCase{"soft_short_step", 1e-3, 1e-6, 20., 30., 1., 1.},
    ExtremeCase{"all_large", 1e3, 1e-1, 89., 30., 100., 1000.},
    ExtremeCase{"all_small", 1e-3, 1e-6, 0., 30., 1e-3, 1.},
    ExtremeCase{"small_stiff_long_step", 1e3, 1e-1, 0., 30., 1e-3, 1.}),
  [](const testing::TestParamInfo<ExtremeCase> &info) {
    std::string n = info.param.name;
    std::replace(n.begin(), n.end(), '-', 'm');
    std::replace(n.begin(), n.end(), '.', 'p');
    return n;
  });
