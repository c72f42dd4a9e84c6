/**
 * @file
 * Heat half-space benchmark. (1) The periodic half-space with the Masada
 * properties: error of the amplitude (fraction of A) and of the phase lag
 * (days) at z = 0.5, 1, 2.5, 5 m against cell size, degree, time stepper and
 * time step, with wall times (sweep.csv). (2) The timing of 1,000 annual
 * cycles of a 15 m x 7 m block (Masada Block 1) with annual + daily forcing
 * (block.csv). Usage: heat_halfspace FOLDER [CYCLES [DEGREE COARSE_CELL
 * BAND_WIDTH BAND_CELL DT_HOURS]]; with CYCLES the sweep is skipped.
 */
#include <rockdda/thermal/heat_solver.h>
#include <rockdda/thermal/verification.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <string>

using namespace rockdda::thermal;

namespace
{
  const double day  = 86400.;
  const double year = 365.25 * day;

  double
  seconds_since(const std::chrono::steady_clock::time_point &t0)
  {
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0)
      .count();
  }

  struct HalfSpaceResult
  {
    double        amplitude_error = 0.; ///< max over depths, fraction of A
    double        lag_error       = 0.; ///< max over depths, days
    double        wall            = 0.;
    unsigned int  dofs            = 0;
    unsigned long steps           = 0;
  };

  HalfSpaceResult
  half_space(const unsigned int degree,
             const double       h,
             const double       dt,
             const TimeStepper  stepper,
             const double       tolerance)
  {
    const auto     t0 = std::chrono::steady_clock::now();
    const double   A = 10., Tm = 20., w = 2. * M_PI / year;
    HeatParameters p;
    p.materials = {masada_dolomite()};
    Block b;
    b.name             = "column";
    b.vertices         = {{{0., -30.}}, {{h, -30.}}, {{h, 0.}}, {{0., 0.}}};
    b.edge_tags        = {"adiabatic", "adiabatic", "exposed", "adiabatic"};
    p.blocks           = {b};
    p.degree           = degree;
    p.coarse_cell_size = h;
    BoundaryCondition surface;
    surface.tag  = "exposed";
    surface.type = BoundaryCondition::Type::temperature;
    surface.value
      = [=](double, double, double t) { return Tm + A * std::sin(w * t); };
    p.boundary_conditions       = {surface};
    p.stepper                   = stepper;
    p.time_step                 = dt;
    p.arkode_relative_tolerance = tolerance;
    p.arkode_absolute_tolerance = tolerance * A;
    p.initial_temperature       = Tm;
    HeatSolver   solver(p);
    const double depths[] = {0.5, 1., 2.5, 5.};
    for (const double z : depths)
      solver.add_probe(0.5 * h, -z);
    // Spin-up of 12 years (transient < 0.1 % of A), then daily samples
    // over one year (sampling independent of dt: advance_to() ends a step
    // exactly at each sample for the theta scheme, or interpolates ARKODE).
    solver.advance_to(12. * year);
    const unsigned int  n = 73; // every 5 days
    std::vector<double> t, v[4];
    for (unsigned int i = 0; i < n; ++i)
      {
        solver.advance_to(12. * year + (i + 1) * year / n);
        t.push_back(solver.time());
        for (unsigned int k = 0; k < 4; ++k)
          v[k].push_back(solver.probe_value(k));
      }
    HalfSpaceResult r;
    const double d = periodic_skin_depth(masada_dolomite().diffusivity(), year);
    for (unsigned int k = 0; k < 4; ++k)
      {
        const SinusoidFit fit  = fit_sinusoid(t, v[k], w);
        double            lag  = -fit.phase / w;
        const double      lag0 = depths[k] / d / w;
        while (lag < lag0 - 0.5 * year)
          lag += year;
        while (lag > lag0 + 0.5 * year)
          lag -= year;
        r.amplitude_error
          = std::max(r.amplitude_error,
                     std::abs(fit.amplitude - A * std::exp(-depths[k] / d))
                       / A);
        r.lag_error = std::max(r.lag_error, std::abs(lag - lag0) / day);
      }
    r.wall  = seconds_since(t0);
    r.dofs  = solver.statistics().n_dofs;
    r.steps = solver.statistics().n_steps;
    return r;
  }
} // namespace

int
main(int argc, char **argv)
{
  const std::string folder = argc > 1 ? argv[1] : ".";

  if (argc <= 2) // the sweep only in the full run
    {
      std::ofstream out(folder + "/sweep.csv");
      out << "stepper,degree,h_m,dt_s,tolerance,dofs,steps,amplitude_error,"
             "lag_error_day,wall_time_s\n";
      const auto report = [&](const char            *name,
                              unsigned int           p,
                              double                 h,
                              double                 dt,
                              double                 tol,
                              const HalfSpaceResult &r) {
        out << name << ',' << p << ',' << h << ',' << dt << ',' << tol << ','
            << r.dofs << ',' << r.steps << ',' << r.amplitude_error << ','
            << r.lag_error << ',' << r.wall << '\n';
        std::printf("%-6s p=%u h=%5.3f dt=%5.1f d tol=%.0e dofs=%4u "
                    "amp.err=%.2e lag.err=%.2e d wall=%.3f s\n",
                    name,
                    p,
                    h,
                    dt / day,
                    tol,
                    r.dofs,
                    r.amplitude_error,
                    r.lag_error,
                    r.wall);
      };
      for (const unsigned int p : {1u, 2u, 3u})
        for (const double h : {2., 1., 0.5, 0.25})
          for (const double steps_per_year : {12., 52., 365.})
            for (const auto stepper :
                 {TimeStepper::crank_nicolson, TimeStepper::backward_euler})
              {
                const double dt = year / steps_per_year;
                report(stepper == TimeStepper::crank_nicolson ? "CN" : "BE",
                       p,
                       h,
                       dt,
                       0.,
                       half_space(p, h, dt, stepper, 0.));
              }
      for (const unsigned int p : {1u, 2u, 3u})
        for (const double h : {1., 0.5})
          for (const double tol : {1e-3, 1e-4, 1e-5})
            report("ARKODE",
                   p,
                   h,
                   year / 52.,
                   tol,
                   half_space(p, h, year / 52., TimeStepper::arkode, tol));
    }

  // Adaptive (Kelly) against uniform meshes: a 2 m wide column (square
  // cells, so the mesh can refine near the surface and stay coarse below),
  // FE_Q(p), CN with daily steps; error vs cells vs wall time.
  if (argc <= 2)
    {
      std::ofstream out(folder + "/adaptive.csv");
      out << "mesh,degree,coarse_cell_m,min_cell_m,max_cells,final_cells,"
             "max_dofs,adaptations,amplitude_error,lag_error_day,"
             "wall_time_s\n";
      const auto run = [&](const unsigned int p,
                           const double       coarse,
                           const double       min_cell,
                           const bool         adaptive) {
        const auto     t0 = std::chrono::steady_clock::now();
        const double   A = 10., Tm = 20., w = 2. * M_PI / year;
        HeatParameters prm         = half_space_column(2., p, coarse, A, Tm);
        prm.adaptive_refinement    = adaptive;
        prm.adaptive_interval      = 10;
        prm.refine_fraction        = 0.3;
        prm.coarsen_fraction       = 0.03;
        prm.adaptive_min_cell_size = min_cell;
        HeatSolver   solver(prm);
        const double depths[] = {0.5, 1., 2.5, 5.};
        for (const double z : depths)
          solver.add_probe(1., -z);
        solver.advance_to(12. * year);
        std::vector<double> t, v[4];
        unsigned int        max_dofs = solver.statistics().n_dofs;
        for (unsigned int i = 0; i < 73; ++i)
          {
            solver.advance_to(12. * year + (i + 1) * year / 73.);
            t.push_back(solver.time());
            max_dofs = std::max(max_dofs, solver.statistics().n_dofs);
            for (unsigned int k = 0; k < 4; ++k)
              v[k].push_back(solver.probe_value(k));
          }
        const double d
          = periodic_skin_depth(masada_dolomite().diffusivity(), year);
        double ea = 0., el = 0.;
        for (unsigned int k = 0; k < 4; ++k)
          {
            const SinusoidFit fit = fit_sinusoid(t, v[k], w);
            ea                    = std::max(ea,
                          std::abs(fit.amplitude - A * std::exp(-depths[k] / d))
                            / A);
            el                    = std::max(el,
                          std::abs(-fit.phase / w - depths[k] / d / w) / day);
          }
        const auto st = solver.statistics();
        out << (adaptive ? "adaptive" : "uniform") << ',' << p << ',' << coarse
            << ',' << (adaptive ? min_cell : coarse) << ',' << st.max_n_cells
            << ',' << st.n_cells << ',' << max_dofs << ',' << st.n_adaptations
            << ',' << ea << ',' << el << ',' << seconds_since(t0) << '\n';
        std::printf("%s p=%u coarse=%g min=%g: %u cells (max), amp.err=%.2e "
                    "lag.err=%.2f d\n",
                    adaptive ? "adaptive" : "uniform",
                    p,
                    coarse,
                    min_cell,
                    st.max_n_cells,
                    ea,
                    el);
      };
      for (const double h : {2., 1., 0.5, 0.25})
        run(1, h, 0., false);
      run(1, 2., 0.5, true);
      run(1, 2., 0.25, true);
      for (const double h : {2., 1., 0.5})
        run(2, h, 0., false);
      run(2, 2., 1., true);
      run(2, 2., 0.5, true);
    }

  // 1,000 annual cycles of Masada Block 1 (15 m x 7 m): the top and the
  // slope face (right) exchange heat with air at 20 + 9 sin(annual) + 5
  // sin(daily) deg C (h = 10 W/m^2/K), the base and the tension-crack side
  // are adiabatic. Default (chosen by the block-accuracy study in
  // README.md): FE_Q(2), 1.75 m cells, no band, CN, dt = 3 h.
  // Optional arguments 3..7: degree, coarse cell (m), band width (m), band
  // cell (m), dt (h).
  {
    const unsigned int n_cycles
      = argc > 2 ? std::max(1, std::atoi(argv[2])) : 1000;
    const auto arg = [&](const int i, const double fallback) {
      return argc > i ? std::atof(argv[i]) : fallback;
    };
    HeatParameters p;
    p.materials = {masada_dolomite()};
    Block b;
    b.name             = "Masada Block 1";
    b.vertices         = {{{0., 0.}}, {{15., 0.}}, {{15., 7.}}, {{0., 7.}}};
    b.edge_tags        = {"adiabatic", "exposed", "exposed", "adiabatic"};
    p.blocks           = {b};
    p.degree           = static_cast<unsigned int>(arg(3, 2.));
    p.coarse_cell_size = arg(4, 1.75);
    p.refine_near_tags = {"exposed"};
    p.band_width       = arg(5, 0.);
    p.band_cell_size   = arg(6, 0.);
    BoundaryCondition air;
    air.tag                       = "exposed";
    air.type                      = BoundaryCondition::Type::convective;
    air.heat_transfer_coefficient = 10.;
    air.value                     = [](double, double, double t) {
      return 20. + 9. * std::sin(2. * M_PI * t / year)
             + 5. * std::sin(2. * M_PI * t / day);
    };
    p.boundary_conditions = {air};
    p.time_step           = arg(7, 3.) * 3600.;
    p.stepper             = TimeStepper::crank_nicolson;
    p.initial_temperature = 20.;
    const auto t0         = std::chrono::steady_clock::now();
    HeatSolver solver(p);
    solver.add_probe(7.5, 3.5);
    std::ofstream out(folder + "/block.csv");
    out << "cycle,time_s,block_mean_degC,gradient_x_K_m,gradient_y_K_m,"
           "centre_degC\n";
    std::ofstream last(folder + "/block_last_cycle.csv");
    last << "time_s,block_mean_degC,gradient_x_K_m,gradient_y_K_m\n";
    for (unsigned int c = 1; c <= n_cycles; ++c)
      {
        if (c == n_cycles)
          for (unsigned int w = 1; w < 52; ++w)
            {
              solver.advance_to((c - 1) * year + w * year / 52.);
              const auto m = solver.block_moments()[0];
              last << solver.time() << ',' << m.mean << ',' << m.gradient_x
                   << ',' << m.gradient_y << '\n';
            }
        solver.advance_to(c * year);
        const auto m = solver.block_moments()[0];
        out << c << ',' << solver.time() << ',' << m.mean << ',' << m.gradient_x
            << ',' << m.gradient_y << ',' << solver.probe_value(0) << '\n';
      }
    const double  wall = seconds_since(t0);
    const auto    st   = solver.statistics();
    std::ofstream timing(folder + "/block_timing.csv");
    timing << "cycles,cells,dofs,steps,wall_time_s,steps_per_s\n"
           << n_cycles << ',' << st.n_cells << ',' << st.n_dofs << ','
           << st.n_steps << ',' << wall << ',' << st.n_steps / wall << '\n';
    std::printf("Block 1: %u cycles, %u cells, %u dofs, %lu steps, %.2f s "
                "(%.0f steps/s)\n%s",
                n_cycles,
                st.n_cells,
                st.n_dofs,
                st.n_steps,
                wall,
                st.n_steps / wall,
                solver.timing_summary().c_str());
  }
  return 0;
}
