/**
 * @file
 * Heat convergence benchmark: L2 error of manufactured solutions against
 * cell size (FE_Q 1..3), time step (Crank-Nicolson, backward Euler) and
 * ARKODE tolerance, with wall times. Writes space.csv and time.csv into the
 * folder given as argument. See README.md.
 */
#include <rockdda/io/output.h>
#include <rockdda/thermal/heat_solver.h>
#include <rockdda/thermal/verification.h>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <functional>
#include <string>

using namespace rockdda::thermal;

namespace
{
  using F = std::function<double(double, double, double)>;

  double
  seconds_since(const std::chrono::steady_clock::time_point &t0)
  {
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0)
      .count();
  }
} // namespace

int
main(int argc, char **argv)
{
  const std::string folder = argc > 1 ? argv[1] : ".";

  // Space: T = (1 + t) sin(2x + 0.3) cos(1.5y), linear in t (no time
  // error with the theta scheme), to t = 0.5 with CN, dt = 0.1.
  {
    const double a = 2., b = 1.5;
    F            exact = [=](double x, double y, double t) {
      return (1. + t) * std::sin(a * x + 0.3) * std::cos(b * y);
    };
    F dx = [=](double x, double y, double t) {
      return (1. + t) * a * std::cos(a * x + 0.3) * std::cos(b * y);
    };
    F dy = [=](double x, double y, double t) {
      return -(1. + t) * b * std::sin(a * x + 0.3) * std::sin(b * y);
    };
    F source = [=](double x, double y, double t) {
      return std::sin(a * x + 0.3) * std::cos(b * y)
             * (1. + (a * a + b * b) * (1. + t));
    };
    rockdda::io::CsvWriter out;
    out.record({"degree", "h_m", "cells", "dofs", "l2_error", "wall_time_s"});
    for (unsigned int p = 1; p <= 3; ++p)
      for (unsigned int level = 0; level < 6; ++level)
        {
          const double h  = 0.5 / (1 << level);
          const auto   t0 = std::chrono::steady_clock::now();
          HeatSolver   solver(manufactured_problem(
            p, h, 0.1, TimeStepper::crank_nicolson, exact, dx, dy, source));
          solver.advance_to(0.5);
          const double e    = solver.l2_error(exact);
          const double wall = seconds_since(t0);
          const auto   st   = solver.statistics();
          out.number(p).number(h).number(st.n_cells).number(st.n_dofs);
          out.number(e).number(wall).end_record();
          std::printf("space p=%u h=%.5f dofs=%u error=%.3e wall=%.3f s\n",
                      p,
                      h,
                      st.n_dofs,
                      e,
                      wall);
        }
    rockdda::io::OutputDirectory(folder).write("space.csv", out.text());
  }

  // Time: T = (1 + x^2 + xy + y^2/2)(1 + sin 2t) is in Q2 at every time,
  // so Q2 has no space error; to t = 1.
  {
    auto P
      = [](double x, double y) { return 1. + x * x + x * y + 0.5 * y * y; };
    F exact = [=](double x, double y, double t) {
      return P(x, y) * (1. + std::sin(2. * t));
    };
    F dx = [=](double x, double y, double t) {
      return (2. * x + y) * (1. + std::sin(2. * t));
    };
    F dy = [=](double x, double y, double t) {
      return (x + y) * (1. + std::sin(2. * t));
    };
    F source = [=](double x, double y, double t) {
      return P(x, y) * 2. * std::cos(2. * t) - 3. * (1. + std::sin(2. * t));
    };
    rockdda::io::CsvWriter out;
    out.record(
      {"stepper", "dt_s", "tolerance", "steps", "l2_error", "wall_time_s"});
    for (const auto stepper :
         {TimeStepper::crank_nicolson, TimeStepper::backward_euler})
      for (unsigned int level = 0; level < 8; ++level)
        {
          const double dt = 0.25 / (1 << level);
          const auto   t0 = std::chrono::steady_clock::now();
          HeatSolver   solver(
            manufactured_problem(2, 0.25, dt, stepper, exact, dx, dy, source));
          solver.advance_to(1.);
          const double e    = solver.l2_error(exact);
          const double wall = seconds_since(t0);
          const char  *name
            = stepper == TimeStepper::crank_nicolson ? "CN" : "BE";
          out.field(name).number(dt).number(0.);
          out.number(solver.statistics().n_steps).number(e).number(wall);
          out.end_record();
          std::printf(
            "time %s dt=%.5f error=%.3e wall=%.4f s\n", name, dt, e, wall);
        }
    for (unsigned int level = 0; level < 7; ++level)
      {
        const double   tol = std::pow(10., -2. - level);
        const auto     t0  = std::chrono::steady_clock::now();
        HeatParameters p   = manufactured_problem(
          2, 0.25, 0.01, TimeStepper::arkode, exact, dx, dy, source);
        p.arkode_relative_tolerance = tol;
        p.arkode_absolute_tolerance = tol;
        HeatSolver solver(p);
        solver.advance_to(1.);
        const double e     = solver.l2_error(exact);
        const double wall  = seconds_since(t0);
        const auto   steps = solver.statistics().n_steps;
        out.field("ARKODE").number(1. / steps).number(tol).number(steps);
        out.number(e).number(wall).end_record();
        std::printf("time ARKODE tol=%.0e steps=%lu error=%.3e wall=%.4f s\n",
                    tol,
                    steps,
                    e,
                    wall);
      }
    rockdda::io::OutputDirectory(folder).write("time.csv", out.text());
  }
  return 0;
}
