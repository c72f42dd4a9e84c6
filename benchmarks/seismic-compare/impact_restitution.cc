/**
 * @file
 * benchmarks/seismic-compare: the coefficient of restitution of a DDA
 * penalty contact in Shi's time integration. A block of Block 1's mass
 * (7 m x 13.8 m, 2600 kg/m^3) falls flat onto a fixed base with the speed
 * V (no gravity, frictionless); its rebound speed over V is the
 * restitution e of the impact, which the rigid sliding block takes as 0
 * (it never leaves the plane). A linear spring integrated exactly rebounds
 * with e = 1; Shi's scheme damps a contact mode of frequency omega at the
 * step h by the ratio about omega h / 4 (omega h < 2), so e grows towards
 * 1 as h shrinks.
 *   impact_restitution drop PENALTY DT...
 *   impact_restitution rock PENALTY DT...
 * drop: as above; prints per step omega h with omega = sqrt(2 PENALTY / m)
 * (the two corner springs), the rebound speed ratio and the contact time.
 * rock: the same block under gravity on the base (friction 41 deg),
 * released at rest tilted by 1e-3 rad about one corner, rocks freely for
 * 1 s (dda::test_scenes::free_rocking(), as unit-dda_rocking); prints the
 * successive peak tilts and their mean ratio, against Housner's (1963) rigid
 * block on a rigid base, which loses angular velocity at every impact by the
 * factor 1 - 3/2 sin^2 alpha (tan alpha = width / height) and never leaves the
 * base: the peak tilts (small against alpha) fall by (1 - 3/2 sin^2 alpha)^2
 * per impact. PENALTY: normal penalty (N/m); DT: time steps (s).
 */
#include <rockdda/dda/engine.h>

#include "../../tests/unit/dda_test_scenes.h"
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <vector>

using namespace rockdda;
using geometry::Point;

int
main(int argc, char **argv)
{
  if (argc < 4)
    {
      std::fprintf(stderr, "usage: %s drop|rock PENALTY DT...\n", argv[0]);
      return 2;
    }
  const bool   rock    = std::string(argv[1]) == "rock";
  const double penalty = std::atof(argv[2]);
  const double L = 7., H = 13.8, rho = 2600., V = 0.1, gap = 1e-3;
  const double m = rho * L * H;
  for (int a = 3; a < argc; ++a)
    {
      const double dt = std::atof(argv[a]);
      if (rock)
        {
          // tests/unit/dda_test_scenes.h (the unit test's scene).
          const auto r
            = dda::test_scenes::free_rocking(L, H, rho, 1e-3, penalty, dt, 1.);
          const double alpha = std::atan(L / H);
          const double e_h   = 1. - 1.5 * std::sin(alpha) * std::sin(alpha);
          std::printf("k %.1e N/m, dt %.4e s: peak tilts (mrad)", penalty, dt);
          for (std::size_t k = 0; k < r.peaks.size() && k < 6; ++k)
            std::printf(" %.3f", 1e3 * r.peaks[k]);
          const double ratio
            = r.peaks.size() >= 3 ? std::sqrt(r.peaks[2] / r.peaks[0]) : 0.;
          std::printf("; ratio per impact %.3f (Housner %.3f), %zu impacts "
                      "in 1 s, %lu steps in the air\n",
                      ratio,
                      e_h * e_h,
                      r.peaks.size(),
                      r.airborne);
          continue;
        }
      dda::BlockSystem s;
      s.materials.push_back(dda::BlockMaterial{rho, 4e10, 0.2, true, -1});
      dda::JointMaterial joint;
      joint.friction_deg = 0.;
      s.joints.push_back(joint);
      s.gravity = Point(0., 0.);
      dda::Block base;
      base.id               = 0;
      base.material         = 0;
      base.polygon.vertices = {Point(-5., -3.),
                               Point(L + 5., -3.),
                               Point(L + 5., 0.),
                               Point(-5., 0.)};
      s.blocks.push_back(base);
      for (int k = 0; k < 3; ++k)
        {
          dda::FixedPoint f;
          f.block = 0;
          f.point = base.polygon.vertices[k];
          s.fixed_points.push_back(f);
        }
      dda::Block b;
      b.id               = 1;
      b.material         = 0;
      b.polygon.vertices = {Point(0., gap),
                            Point(L, gap),
                            Point(L, gap + H),
                            Point(0., gap + H)};
      b.velocity[1]      = -V;
      s.blocks.push_back(b);
      dda::Controls c;
      c.time_step          = dt;
      c.dynamic            = 1.;
      c.law.normal_penalty = penalty;
      c.solver.threads     = 1;
      dda::DdaSystem d(s, c);
      bool           touched = false;
      double         t_in = 0., t_out = -1., v_out = 0.;
      while (d.time() < 0.5)
        {
          const dda::StepReport r      = d.step();
          const bool            closed = r.n_sliding + r.n_locked > 0;
          if (closed && !touched)
            {
              touched = true;
              t_in    = r.time;
            }
          if (touched && !closed)
            {
              t_out = r.time;
              v_out = d.system().blocks[1].velocity[1];
              break;
            }
        }
      const double omega = std::sqrt(2. * penalty / m);
      std::printf("k %.1e N/m, dt %.4e s: omega h = %.3f, e = %.3f, contact "
                  "%.2f ms (pi / omega = %.2f ms)%s\n",
                  penalty,
                  dt,
                  omega * dt,
                  t_out > 0. ? v_out / V : 0.,
                  t_out > 0. ? 1e3 * (t_out - t_in) : 0.,
                  1e3 * 3.14159265358979 / omega,
                  t_out > 0. ? "" : " (stays on the base)");
    }
  return 0;
}
