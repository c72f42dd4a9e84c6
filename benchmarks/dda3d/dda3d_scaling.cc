/**
 * @file
 * Benchmark of the 3D DDA engine (issue 17): wall time per step and
 * block-steps per second for running-bond walls of boxes (bricks 2 x 1 x
 * 1 m) of about 100, 1,000 and 10,000 blocks on a clamped base, static
 * (dynamic control 0) and dynamic (1), medians of 3 runs; the same
 * structure as the 2D benchmark (benchmarks/dda-scaling/dda_scaling.cc).
 *
 *   dda3d_scaling scaling [max_blocks] [steps_10k] [solver] [threads]
 *     > scaling.csv
 *   dda3d_scaling single rows columns dynamic steps [solver] [threads]
 *
 * solver: automatic (default: direct up to 60 blocks, D-ILU CG above),
 * direct or iterative (dda::SolverOptions).
 */
#include <rockdda/dda3d/engine.h>
#include <rockdda/dda3d/generators.h>

#include "../../tests/unit/dda3d_test_scenes.h"
#include "../timing.h"
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <vector>

using namespace rockdda;
using namespace rockdda::dda3d;

namespace
{
  using benchmarks::median;
  using benchmarks::seconds_since;
  using test_scenes::brick_wall;

  /// Controls of the wall cases: dt 1 ms, penalty 1e11 N/m (10 E x 1 m),
  /// @p dynamic control, linear @p solver on @p threads (0: one per core).
  EngineControls
  wall_controls(const double          dynamic,
                const dda::SolverType solver,
                const int             threads)
  {
    EngineControls c;
    c.solver.type        = solver;
    c.solver.threads     = threads;
    c.dt                 = 1e-3;
    c.dynamic            = dynamic;
    c.law.normal_penalty = 1e11;
    return c;
  }

  /// What the timed steps of one run gave.
  struct Timed
  {
    double      seconds_per_step = 0., iterations = 0., cg_iterations = 0.;
    int         cuts     = 0;
    std::size_t contacts = 0;
    double      drift    = 0.;
  };

  /// @p warmup warm-up steps, then @p steps timed steps of a new wall.
  Timed
  timed_run(const int             rows,
            const int             columns,
            const double          dynamic,
            const int             steps,
            const dda::SolverType solver,
            const int             warmup  = 3,
            const int             threads = 0)
  {
    Engine engine(brick_wall(rows, columns),
                  wall_controls(dynamic, solver, threads));
    for (int k = 0; k < warmup; ++k)
      engine.step();
    Timed      out;
    const auto t0 = std::chrono::steady_clock::now();
    int        it = 0, cg = 0;
    for (int k = 0; k < steps; ++k)
      {
        engine.step();
        it += engine.statistics().iterations;
        cg += engine.statistics().solver_iterations;
        out.cuts += engine.statistics().cuts;
      }
    out.seconds_per_step = seconds_since(t0) / steps;
    out.iterations       = double(it) / steps;
    out.cg_iterations    = double(cg) / steps;
    out.contacts         = engine.contacts().size();
    for (std::size_t b = 0; b < engine.scene().blocks.size(); ++b)
      out.drift = std::max(out.drift, engine.displacement(b).norm());
    return out;
  }

  void
  scaling(const int             max_blocks,
          const int             steps_10k,
          const dda::SolverType solver,
          const int             threads)
  {
    std::printf("blocks,mode,ms_per_step,block_steps_per_s,timed_steps,"
                "warmup_steps,iterations_per_step,cuts,contacts,"
                "max_displacement_m,cg_iterations_per_step\n");
    const int sizes[][2] = {{10, 10}, {25, 40}, {80, 125}};
    for (const auto &sz : sizes)
      {
        const int rows = sz[0], columns = sz[1];
        const int n = int(brick_wall(rows, columns).blocks.size());
        if (n > max_blocks)
          continue;
        for (const double dynamic : {0., 1.})
          {
            // 3D steps cost ~15 ms per 100 blocks at 100 and ~1.5 s at
            // 1,000 blocks on the shared machine: 200, 10 and steps_10k
            // timed steps (3, 3 and 1 warm-up) keep a case within minutes.
            const int steps  = n > 5000 ? steps_10k : n > 500 ? 10 : 200;
            const int warmup = n > 5000 ? 1 : 3;
            std::vector<double> times;
            Timed               last;
            for (int repeat = 0; repeat < 3; ++repeat)
              {
                last = timed_run(
                  rows, columns, dynamic, steps, solver, warmup, threads);
                times.push_back(last.seconds_per_step);
              }
            const double t = median(times);
            std::printf("%d,%s,%.4f,%.0f,%d,%d,%.2f,%d,%zu,%.3e,%.1f\n",
                        n,
                        dynamic > 0. ? "dynamic" : "static",
                        1e3 * t,
                        n / t,
                        steps,
                        warmup,
                        last.iterations,
                        last.cuts,
                        last.contacts,
                        last.drift,
                        last.cg_iterations);
            std::fflush(stdout);
          }
      }
  }
} // namespace

int
main(int argc, char **argv)
{
  const std::string what = argc > 1 ? argv[1] : "scaling";
  // The solver: the last argument of either command, if given.
  const auto solver_of = [&](const int at) {
    const std::string s = argc > at ? argv[at] : "automatic";
    return s == "direct"      ? dda::SolverType::direct
           : s == "iterative" ? dda::SolverType::iterative
                              : dda::SolverType::automatic;
  };
  if (what == "scaling")
    scaling(argc > 2 ? std::atoi(argv[2]) : 20000,
            argc > 3 ? std::atoi(argv[3]) : 10,
            solver_of(4),
            argc > 5 ? std::atoi(argv[5]) : 0);
  else if (what == "single" && argc > 5)
    {
      const Timed r = timed_run(std::atoi(argv[2]),
                                std::atoi(argv[3]),
                                std::atof(argv[4]),
                                std::atoi(argv[5]),
                                solver_of(6),
                                3,
                                argc > 7 ? std::atoi(argv[7]) : 0);
      std::printf("%.3f ms/step, %.2f open-close it./step, %.1f CG it./step, "
                  "%d cuts, %zu contacts, largest displacement %.3e m\n",
                  1e3 * r.seconds_per_step,
                  r.iterations,
                  r.cg_iterations,
                  r.cuts,
                  r.contacts,
                  r.drift);
    }
  else
    {
      std::fprintf(
        stderr,
        "usage: dda3d_scaling scaling [max_blocks] [steps_10k] "
        "[solver] [threads] | single rows columns dynamic steps [solver] "
        "[threads]\n"
        "  solver: automatic (default), direct or iterative\n");
      return 2;
    }
  return 0;
}
