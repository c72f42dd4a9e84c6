/**
 * @file
 * Benchmark of the 2D DDA engine (issue 3): per-step wall time and
 * block-steps per second for brick walls of about 100, 1,000 and 10,000
 * blocks, static and dynamic, with each linear solver; and the accuracy
 * against cost of the incline and Newmark cases while sweeping the penalty
 * and the time step.
 *
 *   dda_scaling scaling [max_blocks] > scaling.csv
 *   dda_scaling accuracy > accuracy.csv
 *   dda_scaling tolerance > tolerance.csv
 */
#include <rockdda/analytical/newmark.h>
#include <rockdda/dda/engine.h>
#include <rockdda/dda/hdf5_output.h>
#include <rockdda/dda/vtu_output.h>

#include "../../tests/unit/dda_test_scenes.h"
#include "../timing.h"
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

using namespace rockdda;
using namespace rockdda::dda;
using geometry::Point;
using geometry::Polygon;

namespace
{
  using benchmarks::median;
  using benchmarks::seconds_since;
  using test_scenes::g_earth;
  using test_scenes::rectangle;
  using test_scenes::rotated;

  void
  add_block(BlockSystem &s, const Polygon &p, bool fixed = false)
  {
    Block b;
    b.id       = static_cast<int>(s.blocks.size());
    b.polygon  = p;
    b.material = 0;
    s.blocks.push_back(b);
    if (fixed)
      for (const auto &v : p.vertices)
        {
          FixedPoint f;
          f.block = b.id;
          f.point = v;
          s.fixed_points.push_back(f);
        }
  }

  BlockSystem
  base_scene(double phi)
  {
    BlockSystem s;
    s.materials.push_back({2700., 1e10, 0.25, false});
    JointMaterial j;
    j.friction_deg = phi;
    s.joints.push_back(j);
    return s;
  }

  /// Running-bond brick wall (bricks 2 m x 1 m) of rows x columns on a
  /// fixed base.
  BlockSystem
  brick_wall(int rows, int columns)
  {
    return test_scenes::running_bond_wall(rows, columns);
  }

  /// Controls of the wall cases: dt 1e-3 s, penalty 1e11 N/m, @p dynamic
  /// control, and the solver by name: direct, jacobi (CG + block-Jacobi),
  /// dilu (CG + block D-ILU, one thread), dilu2 (two threads).
  Controls
  wall_controls(const double dynamic, const std::string &name)
  {
    Controls c;
    c.time_step          = 1e-3;
    c.dynamic            = dynamic;
    c.law.normal_penalty = 1e11;
    c.solver.type
      = name == "direct" ? SolverType::direct : SolverType::iterative;
    if (name == "jacobi")
      c.solver.preconditioner = Preconditioner::block_jacobi;
    c.solver.threads = name == "dilu2" ? 2 : 1;
    return c;
  }

  const char *
  solver_label(const std::string &name)
  {
    return name == "direct"   ? "direct"
           : name == "jacobi" ? "cg-block-jacobi"
           : name == "dilu"   ? "cg-block-dilu"
                              : "cg-block-dilu-2-threads";
  }

  void
  scaling(int max_blocks)
  {
    std::printf("blocks,mode,solver,ms_per_step,block_steps_per_s,"
                "iterations_per_step,contacts\n");
    const int sizes[][2] = {{10, 10}, {25, 40}, {80, 125}};
    for (const auto &sz : sizes)
      {
        const int rows = sz[0], columns = sz[1];
        if (rows * columns > max_blocks)
          continue;
        for (double dynamic : {0., 1.})
          for (const std::string name : {"direct", "jacobi", "dilu", "dilu2"})
            {
              const int n
                = static_cast<int>(brick_wall(rows, columns).blocks.size());
              // The simplicial LDL^T takes seconds per step at 10,000
              // blocks; it is measured up to about 1,000. Below 300 blocks
              // the D-ILU runs on one thread anyway.
              if ((name == "direct" && n > 5000)
                  || (name == "dilu2" && n < 300))
                continue;
              const int           steps = n > 5000 ? 10 : n > 500 ? 40 : 200;
              std::vector<double> times;
              double              iterations = 0.;
              std::size_t         contacts   = 0;
              for (int repeat = 0; repeat < 3; ++repeat)
                {
                  DdaSystem dda(brick_wall(rows, columns),
                                wall_controls(dynamic, name));
                  for (int k = 0; k < 3; ++k)
                    dda.step();
                  const auto t0 = std::chrono::steady_clock::now();
                  unsigned   it = 0;
                  for (int k = 0; k < steps; ++k)
                    it += dda.step().iterations;
                  times.push_back(seconds_since(t0) / steps);
                  iterations = double(it) / steps;
                  contacts   = dda.contacts().size();
                }
              const double t = median(times);
              std::printf("%d,%s,%s,%.4f,%.0f,%.2f,%zu\n",
                          n,
                          dynamic > 0. ? "dynamic" : "static",
                          solver_label(name),
                          1e3 * t,
                          n / t,
                          iterations,
                          contacts);
              std::fflush(stdout);
            }
      }
  }

  /// One case: rows x columns wall, dynamic control, solver name (direct,
  /// jacobi, dilu, dilu2), timed steps, optional static settling steps
  /// first; prints ms per step, iteration counts, the simulated time reached
  /// (cuts shorten the steps) and the linear solves of all attempts.
  void
  single(int                rows,
         int                columns,
         double             dynamic,
         const std::string &name,
         int                steps,
         int                settle)
  {
    DdaSystem dda(brick_wall(rows, columns), wall_controls(dynamic, name));
    if (settle > 0)
      dda.settle(settle);
    for (int k = 0; k < 3; ++k)
      dda.step();
    const double start = dda.time();
    const auto   t0    = std::chrono::steady_clock::now();
    unsigned     it = 0, solver_it = 0, cuts = 0;
    for (int k = 0; k < steps; ++k)
      {
        const StepReport r = dda.step();
        it += r.iterations;
        solver_it += r.solver_iterations;
        cuts += r.cuts;
      }
    const double t     = seconds_since(t0) / steps;
    double       drift = 0.;
    for (std::size_t b = 0; b < dda.system().blocks.size(); ++b)
      drift = std::max(drift, dda.centroid_displacement(b).norm());
    std::printf(
      "%zu blocks, %s: %.3f ms/step, %.0f block-steps/s, %.2f "
      "open-close it./step, %.1f solver it./step, %u cuts, "
      "separator %d blocks, largest centroid displacement "
      "%.3e m, simulated time %.6f s, timed from %.6f s, %lu linear solves "
      "since t = 0\n",
      dda.system().blocks.size(),
      solver_label(name),
      1e3 * t,
      dda.system().blocks.size() / t,
      double(it) / steps,
      double(solver_it) / steps,
      cuts,
      dda.linear_solver().separator_size(),
      drift,
      dda.time(),
      start,
      dda.n_solves);
  }

  /// CG tolerance against cost and accuracy: ms and CG iterations per step
  /// on the 1,000-block wall (dynamic), and the largest vertex distance
  /// from the direct solver after 30 dynamic steps of the same wall.
  void
  tolerance()
  {
    std::printf("tolerance,preconditioner,ms_per_step,cg_iterations_per_step,"
                "max_vertex_difference_m\n");
    auto run = [](double         tol,
                  Preconditioner pc,
                  SolverType     type,
                  int            steps,
                  double        &ms,
                  double        &cg) {
      Controls c;
      c.time_step             = 1e-3;
      c.dynamic               = 1.;
      c.law.normal_penalty    = 1e11;
      c.solver.type           = type;
      c.solver.tolerance      = tol;
      c.solver.preconditioner = pc;
      DdaSystem dda(brick_wall(25, 40), c);
      for (int k = 0; k < 3; ++k)
        dda.step();
      const auto t0 = std::chrono::steady_clock::now();
      unsigned   it = 0;
      for (int k = 0; k < steps; ++k)
        it += dda.step().solver_iterations;
      ms = 1e3 * seconds_since(t0) / steps;
      cg = double(it) / steps;
      return dda.system();
    };
    double            ms, cg;
    const BlockSystem direct
      = run(1e-8, Preconditioner::block_dilu, SolverType::direct, 30, ms, cg);
    for (auto pc : {Preconditioner::block_jacobi, Preconditioner::block_dilu})
      for (double tol : {1e-4, 1e-6, 1e-8, 1e-10, 1e-12})
        {
          std::vector<double> times;
          BlockSystem         result;
          for (int repeat = 0; repeat < 3; ++repeat)
            {
              result = run(tol, pc, SolverType::iterative, 30, ms, cg);
              times.push_back(ms);
            }
          std::sort(times.begin(), times.end());
          const double diff
            = test_scenes::max_vertex_difference(result, direct);
          std::printf("%.0e,%s,%.3f,%.1f,%.3e\n",
                      tol,
                      pc == Preconditioner::block_dilu ? "block-dilu"
                                                       : "block-jacobi",
                      times[1],
                      cg,
                      diff);
          std::fflush(stdout);
        }
  }

  void
  accuracy()
  {
    std::printf("case,penalty_N_per_m,dt_s,relative_error,wall_s,steps\n");
    // Incline: 30 deg, friction 20 deg, 1 s.
    const double alpha = M_PI / 6.;
    for (double dt : {1e-2, 1e-3, 1e-4})
      for (double p : {1e8, 1e9, 1e10, 1e11, 1e12})
        {
          BlockSystem s = base_scene(20.);
          add_block(s, rotated(rectangle(-5., -1., 10., 1.), -alpha), true);
          add_block(s, rotated(rectangle(-0.5, 0., 1., 1.), -alpha));
          Controls c;
          c.time_step          = dt;
          c.law.normal_penalty = p;
          const auto t0        = std::chrono::steady_clock::now();
          DdaSystem  dda(s, c);
          dda.run_until(1.);
          const double wall = seconds_since(t0);
          const double d    = dda.centroid_displacement(1).dot(
            Point(std::cos(alpha), -std::sin(alpha)));
          const double exact
            = 0.5 * g_earth
              * (std::sin(alpha)
                 - std::cos(alpha) * std::tan(20. * M_PI / 180.));
          std::printf("incline,%.0e,%.0e,%.3e,%.4f,%lu\n",
                      p,
                      dt,
                      std::abs(d - exact) / exact,
                      wall,
                      dda.n_steps);
        }
    // Newmark: 20 deg plane, friction 30 deg, 0.5 g sin(2 pi t), 2 s.
    for (auto mode :
         {SeismicInput::Mode::inertial, SeismicInput::Mode::displacement})
      for (double dt : {1e-2, 1e-3, 1e-4})
        for (double p : {1e8, 1e9, 1e10, 1e11, 1e12})
          {
            const double a = 20. * M_PI / 180., A = 0.5, w = 2. * M_PI;
            BlockSystem  s = base_scene(30.);
            add_block(s, rotated(rectangle(-5., -1., 10., 1.), a), true);
            add_block(s, rotated(rectangle(-0.5, 0., 1., 1.), a));
            s.seismic.mode      = mode;
            s.seismic.record.dt = 1e-3;
            for (int k = 0; k <= 2001; ++k)
              s.seismic.record.acceleration.push_back(A
                                                      * std::sin(w * k * 1e-3));
            Controls c;
            c.time_step          = dt;
            c.law.normal_penalty = p;
            const auto t0        = std::chrono::steady_clock::now();
            try
              {
                DdaSystem dda(s, c);
                dda.run_until(2.);
                const double wall = seconds_since(t0);
                const Point  down(-std::cos(a), -std::sin(a));
                const double d = (dda.centroid_displacement(1)
                                  - dda.centroid_displacement(0))
                                   .dot(down);
                const double exact
                  = g_earth * (std::cos(a) + std::tan(M_PI / 6.) * std::sin(a))
                    * analytical::harmonic_sliding_displacement(
                      A, w, std::tan(M_PI / 6. - a), 2.);
                std::printf("newmark-%s,%.0e,%.0e,%.3e,%.4f,%lu\n",
                            mode == SeismicInput::Mode::inertial
                              ? "inertial"
                              : "displacement",
                            p,
                            dt,
                            std::abs(d - exact) / exact,
                            wall,
                            dda.n_steps);
              }
            catch (const DdaFailure &e)
              {
                std::printf("newmark,%.0e,%.0e,nan,nan,0\n", p, dt);
              }
            std::fflush(stdout);
          }
  }

  /// Size and write time of one snapshot (blocks and contacts) of a
  /// rows x columns wall after @p steps steps, VTU against HDF5: medians of
  /// @p repeat writes to files in @p folder.
  void
  output(const int rows, const int columns, const int steps, const int repeat)
  {
    DdaSystem dda(brick_wall(rows, columns), wall_controls(1., "dilu2"));
    for (int k = 0; k < steps; ++k)
      dda.step();
    const auto folder
      = std::filesystem::temp_directory_path() / "rockdda-output-benchmark";
    std::filesystem::create_directories(folder);
    const std::string   vtu_b = (folder / "b.vtu").string();
    const std::string   vtu_c = (folder / "c.vtu").string();
    const std::string   h5    = (folder / "s.h5").string();
    std::vector<double> t_vtu, t_h5;
    for (int r = 0; r < repeat; ++r)
      {
        auto t0 = std::chrono::steady_clock::now();
        std::ofstream(vtu_b, std::ios::binary) << blocks_vtu(dda);
        std::ofstream(vtu_c, std::ios::binary) << contacts_vtu(dda);
        t_vtu.push_back(seconds_since(t0));
        t0 = std::chrono::steady_clock::now();
        write_snapshot_hdf5(h5,
                            dda.time(),
                            blocks_snapshot(dda),
                            contacts_snapshot(dda));
        t_h5.push_back(seconds_since(t0));
      }
    const double mib = 1024. * 1024.;
    const double size_vtu
      = (std::filesystem::file_size(vtu_b) + std::filesystem::file_size(vtu_c))
        / mib;
    const double size_h5 = std::filesystem::file_size(h5) / mib;
    std::printf("blocks,contacts,format,MiB,write_s,bytes_per_block\n");
    const double n = static_cast<double>(dda.system().blocks.size());
    std::printf("%zu,%zu,vtu-zlib,%.3f,%.4f,%.1f\n",
                dda.system().blocks.size(),
                dda.contacts().size(),
                size_vtu,
                median(t_vtu),
                size_vtu * mib / n);
    std::printf("%zu,%zu,hdf5,%.3f,%.4f,%.1f\n",
                dda.system().blocks.size(),
                dda.contacts().size(),
                size_h5,
                median(t_h5),
                size_h5 * mib / n);
    std::filesystem::remove_all(folder);
  }
} // namespace

int
main(int argc, char **argv)
{
  const std::string what = argc > 1 ? argv[1] : "scaling";
  if (what == "scaling")
    scaling(argc > 2 ? std::atoi(argv[2]) : 20000);
  else if (what == "accuracy")
    accuracy();
  else if (what == "tolerance")
    tolerance();
  else if (what == "single" && argc > 6)
    single(std::atoi(argv[2]),
           std::atoi(argv[3]),
           std::atof(argv[4]),
           argv[5],
           std::atoi(argv[6]),
           argc > 7 ? std::atoi(argv[7]) : 0);
  else if (what == "output" && argc > 3)
    output(std::atoi(argv[2]),
           std::atoi(argv[3]),
           argc > 4 ? std::atoi(argv[4]) : 2,
           argc > 5 ? std::atoi(argv[5]) : 5);
  else
    {
      std::fprintf(stderr,
                   "usage: dda_scaling scaling [max_blocks] | accuracy | "
                   "tolerance | single "
                   "rows columns dynamic solver steps [settling_steps] | "
                   "output rows columns [steps] [repeat]\n");
      return 2;
    }
  return 0;
}
