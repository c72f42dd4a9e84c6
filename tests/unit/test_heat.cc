/**
 * @file
 * Tests of the thermal subsystem: periodic half-space (Carslaw & Jaeger
 * 1959, Sec. 2.6), thesis skin depth (Eq. 5.1), manufactured solutions
 * (orders in space and time), energy balance, block moments, bad input.
 */
#include <rockdda/io/error.h>
#include <rockdda/thermal/boundary_data.h>
#include <rockdda/thermal/heat_cycles.h>
#include <rockdda/thermal/heat_solver.h>
#include <rockdda/thermal/verification.h>

#include <gtest/gtest.h>

#include "heat_test_scenes.h"
#include <chrono>
#include <cmath>
#include <complex>
#include <cstdio>
#include <fstream>

using namespace rockdda;
using namespace rockdda::thermal;

namespace
{
  const double day  = 86400.;
  const double year = 365.25 * day;

  Block
  rectangle(const double                    x0,
            const double                    y0,
            const double                    x1,
            const double                    y1,
            const std::vector<std::string> &tags)
  {
    Block b;
    b.name      = "rectangle";
    b.vertices  = {{{x0, y0}}, {{x1, y0}}, {{x1, y1}}, {{x0, y1}}};
    b.edge_tags = tags; // bottom, right, top, left
    return b;
  }

  BoundaryCondition
  constant_flux(const std::string &tag, const double q)
  {
    BoundaryCondition bc;
    bc.tag   = tag;
    bc.type  = BoundaryCondition::Type::flux;
    bc.value = [q](double, double, double) { return q; };
    return bc;
  }

  /// Convective exchange (h = 10 W/(m^2 K)) on tag 'exposed' with air at
  /// 25 + 8 sin(2 pi t / period) deg C.
  BoundaryCondition
  sinusoidal_air(const double period)
  {
    BoundaryCondition air;
    air.tag                       = "exposed";
    air.type                      = BoundaryCondition::Type::convective;
    air.heat_transfer_coefficient = 10.;
    air.value                     = [period](double, double, double t) {
      return 25. + 8. * std::sin(2. * M_PI * t / period);
    };
    return air;
  }

  double
  order(const double e_coarse, const double e_fine, const double ratio)
  {
    return std::log(e_coarse / e_fine) / std::log(ratio);
  }

  /// Probe temperatures sampled daily over one year.
  struct YearOfSamples
  {
    std::vector<double>              t;
    std::vector<std::vector<double>> values; ///< per depth
  };

  /// Add probes at x = @p x and the given depths below y = 0, spin up for
  /// 12 years, then sample them daily over the 13th year.
  YearOfSamples
  sample_thirteenth_year(HeatSolver                &solver,
                         const double               x,
                         const std::vector<double> &depths)
  {
    for (const double z : depths)
      solver.add_probe(x, -z);
    solver.advance_to(12. * year);
    YearOfSamples s;
    s.values.resize(depths.size());
    for (unsigned int i = 0; i < 365; ++i)
      {
        solver.advance_to(12. * year + (i + 1) * year / 365.);
        s.t.push_back(solver.time());
        for (unsigned int k = 0; k < depths.size(); ++k)
          s.values[k].push_back(solver.probe_value(k));
      }
    return s;
  }
} // namespace



// The periodic half-space: T(z, t) = Tm + A exp(-z/d) sin(w t - z/d),
// d = sqrt(2 kappa / w) (Carslaw & Jaeger 1959, Sec. 2.6). A column 30 m
// deep (> 10 d, so the adiabatic bottom changes the field at 5 m by
// ~exp(-2 (30 - 5) / d) ~ 1e-8), FE_Q(2) with 0.25 m cells (8 nodes per
// d) and Crank-Nicolson with dt = 1/365 year (w dt = 0.017, phase error
// ~ (w dt)^2 / 12 ~ 3e-5 rad). 12 years of spin-up from the mean: the
// start-up transient decays like t^(-3/2) to well below 0.1 % of A.
TEST(Heat, PeriodicHalfSpaceAmplitudeAndLag)
{
  const double   A = 10., Tm = 20.;
  const double   w = 2. * M_PI / year;
  HeatParameters p;
  p.materials        = {masada_dolomite()};
  p.blocks           = {rectangle(
    0., -30., 0.25, 0., {"far field", "adiabatic", "exposed", "adiabatic"})};
  p.degree           = 2;
  p.coarse_cell_size = 0.25;
  BoundaryCondition surface;
  surface.tag  = "exposed";
  surface.type = BoundaryCondition::Type::temperature;
  surface.value
    = [=](double, double, double t) { return Tm + A * std::sin(w * t); };
  p.boundary_conditions = {surface, constant_flux("far field", 0.)};
  p.stepper             = TimeStepper::crank_nicolson;
  p.time_step           = year / 365.;
  p.initial_temperature = Tm;

  HeatSolver                solver(p);
  const std::vector<double> depths = {0.5, 1., 2.5, 5.};
  const YearOfSamples       s = sample_thirteenth_year(solver, 0.125, depths);
  const double d = periodic_skin_depth(masada_dolomite().diffusivity(), year);
  EXPECT_NEAR(d, 2.847, 0.001);
  for (unsigned int k = 0; k < depths.size(); ++k)
    {
      const SinusoidFit fit       = fit_sinusoid(s.t, s.values[k], w);
      const double      z         = depths[k];
      const double      lag_days  = -fit.phase / w / day;
      const double      lag_exact = z / d / w / day;
      std::printf("z = %4.1f m: amplitude %.4f (exact %.4f) K, lag %.2f "
                  "(exact %.2f) days, mean %.4f\n",
                  z,
                  fit.amplitude,
                  A * std::exp(-z / d),
                  lag_days,
                  lag_exact,
                  fit.mean);
      EXPECT_NEAR(fit.amplitude, A * std::exp(-z / d), 0.01 * A);
      EXPECT_NEAR(lag_days, lag_exact, 1.);
      EXPECT_NEAR(fit.mean, Tm, 0.01 * A);
    }
}



// The harmonic periodic solution (HeatSolver::harmonic_block_means) of a
// slab of depth L under air Re(e^{i w t}) with h at its top, adiabatic
// elsewhere: Theta(z) = A cosh(q (L - z)), q = sqrt(i w / kappa), A = h /
// (lambda q sinh(qL) + h cosh(qL)) (Carslaw & Jaeger 1959, Sec. 2.6 with a
// convective surface), block mean A sinh(qL) / (qL). Two slabs on top of
// each other (blocks 0-2 m and 2-6 m below the surface, conforming) check
// the block means of a layered response: the mean over [z0, z1] is
// A (sinh(q (L - z0)) - sinh(q (L - z1))) / (q (z1 - z0)). FE_Q(2) with
// 0.25 m cells (d = 2.85 m: 11 cells per skin depth, a spatial error
// ~(h/d)^3 ~ 1e-3 of the amplitude): asserted 2e-3 of the 1 K amplitude, in
// both the real (in phase) and imaginary (lagging) parts. The time-stepped
// solver's periodic state after spin-up agrees with it to Crank-Nicolson's
// (w dt)^2 / 12 ~ 3e-5 plus the spin-up's remainder.
TEST(Heat, HarmonicPeriodicSlabMatchesTheExactResponse)
{
  using Complex       = std::complex<double>;
  const double   L    = 6.;
  const double   h    = 10.;
  const double   w    = 2. * M_PI / year;
  const auto     rock = masada_dolomite();
  HeatParameters p;
  p.materials = {rock};
  p.blocks
    = {rectangle(
         0., -2., 0.5, 0., {"interior", "adiabatic", "exposed", "adiabatic"}),
       rectangle(0.,
                 -L,
                 0.5,
                 -2.,
                 {"adiabatic", "adiabatic", "interior", "adiabatic"})};
  p.degree           = 2;
  p.coarse_cell_size = 0.25;
  p.joint_contact    = HeatParameters::JointContact::perfect;
  BoundaryCondition air;
  air.tag                       = "exposed";
  air.type                      = BoundaryCondition::Type::convective;
  air.heat_transfer_coefficient = h;
  air.uniform                   = true;
  air.value = [w](double, double, double t) { return std::sin(w * t); };
  p.boundary_conditions = {air, constant_flux("adiabatic", 0.)};
  p.stepper             = TimeStepper::crank_nicolson;
  p.time_step           = year / 365.;
  p.initial_temperature = 0.;

  const double  lambda = rock.conductivity;
  const Complex q      = std::sqrt(Complex(0., w / rock.diffusivity()));
  const Complex A = h / (lambda * q * std::sinh(q * L) + h * std::cosh(q * L));
  const auto    exact_mean = [&](const double z0, const double z1) {
    return A * (std::sinh(q * (L - z0)) - std::sinh(q * (L - z1)))
           / (q * (z1 - z0));
  };
  const std::vector<Complex> exact = {exact_mean(0., 2.), exact_mean(2., L)};

  HeatSolver solver(p);
  const auto means = solver.harmonic_block_means(w);
  ASSERT_EQ(means.size(), 2u);
  for (std::size_t b = 0; b < 2; ++b)
    {
      std::printf("block %zu: harmonic (%.5f, %.5f), exact (%.5f, %.5f)\n",
                  b,
                  means[b].real(),
                  means[b].imag(),
                  exact[b].real(),
                  exact[b].imag());
      EXPECT_NEAR(means[b].real(), exact[b].real(), 2e-3);
      EXPECT_NEAR(means[b].imag(), exact[b].imag(), 2e-3);
    }
  // The time-stepped solver from 0 K after 8 years: the block means follow
  // Re(-i m e^{i w t}) (the air is sin(w t) = Re(-i e^{i w t})).
  solver.advance_to(8. * year);
  for (int k = 1; k <= 4; ++k)
    {
      solver.advance_to(8. * year + k * year / 4.);
      const auto   m  = solver.block_moments();
      const double wt = w * solver.time();
      for (std::size_t b = 0; b < 2; ++b)
        EXPECT_NEAR(m[b].mean,
                    std::real(Complex(0., -1.) * means[b] * std::polar(1., wt)),
                    1e-3)
          << b << " " << k;
    }
}



// Thesis Eq. 5.1, S_d = sqrt(kappa t_exp / 2), t_exp = 180 days: "2.5 m".
TEST(Heat, ThesisSkinDepth)
{
  const double sd
    = thesis_skin_depth(masada_dolomite().diffusivity(), 180. * day);
  EXPECT_NEAR(sd, 2.5, 0.05);
  EXPECT_NEAR(masada_dolomite().diffusivity(), 8.072e-7, 1e-10);
}



// Space: T = (1 + t) sin(2x + 0.3) cos(1.5y) is linear in time, which the
// theta scheme integrates exactly, so the error is spatial: O(h^(p+1)).
TEST(Heat, ManufacturedSpaceConvergence)
{
  const double a = 2., b = 1.5;
  auto         exact = [=](double x, double y, double t) {
    return (1. + t) * std::sin(a * x + 0.3) * std::cos(b * y);
  };
  auto dx = [=](double x, double y, double t) {
    return (1. + t) * a * std::cos(a * x + 0.3) * std::cos(b * y);
  };
  auto dy = [=](double x, double y, double t) {
    return -(1. + t) * b * std::sin(a * x + 0.3) * std::sin(b * y);
  };
  auto source = [=](double x, double y, double t) {
    return std::sin(a * x + 0.3) * std::cos(b * y)
           * (1. + (a * a + b * b) * (1. + t));
  };
  for (unsigned int p = 1; p <= 3; ++p)
    {
      std::vector<double> errors;
      const double        h0 = p == 3 ? 0.5 : 0.25;
      for (unsigned int level = 0; level < 3; ++level)
        {
          const double h = h0 / (1 << level);
          HeatSolver   solver(manufactured_problem(
            p, h, 0.1, TimeStepper::crank_nicolson, exact, dx, dy, source));
          solver.advance_to(0.5);
          errors.push_back(solver.l2_error(exact));
        }
      const double observed = order(errors[1], errors[2], 2.);
      std::printf("FE_Q(%u): L2 errors %.3e %.3e %.3e, order %.2f\n",
                  p,
                  errors[0],
                  errors[1],
                  errors[2],
                  observed);
      EXPECT_NEAR(observed, p + 1., 0.2) << "degree " << p;
    }
}



// Time: T = (1 + x^2 + x y + y^2 / 2)(1 + sin 2t) lies in Q2 at every
// time, so the Q2 semi-discrete solution is exact and the error is the
// time-stepping error: order 2 (CN, with its two backward-Euler start-up
// steps) and 1 (BE).
TEST(Heat, ManufacturedTimeConvergence)
{
  auto P = [](double x, double y) { return 1. + x * x + x * y + 0.5 * y * y; };
  auto exact = [=](double x, double y, double t) {
    return P(x, y) * (1. + std::sin(2. * t));
  };
  auto dx = [=](double x, double y, double t) {
    return (2. * x + y) * (1. + std::sin(2. * t));
  };
  auto dy = [=](double x, double y, double t) {
    return (x + y) * (1. + std::sin(2. * t));
  };
  auto source = [=](double x, double y, double t) {
    // rho c dT/dt - lambda Laplace T, Laplace P = 2 + 1.
    return P(x, y) * 2. * std::cos(2. * t) - 3. * (1. + std::sin(2. * t));
  };
  for (const auto stepper :
       {TimeStepper::crank_nicolson, TimeStepper::backward_euler})
    {
      std::vector<double> errors;
      for (const double dt : {1. / 16., 1. / 32., 1. / 64.})
        {
          HeatSolver solver(
            manufactured_problem(2, 0.25, dt, stepper, exact, dx, dy, source));
          solver.advance_to(1.);
          errors.push_back(solver.l2_error(exact));
          const auto st = solver.statistics();
          EXPECT_EQ(st.oscillation_steps, 0u);
          EXPECT_EQ(st.n_factorizations,
                    1u + (stepper == TimeStepper::crank_nicolson));
        }
      const double observed = order(errors[1], errors[2], 2.);
      const double expected = stepper == TimeStepper::crank_nicolson ? 2. : 1.;
      std::printf("%s: L2 errors %.3e %.3e %.3e, order %.2f\n",
                  stepper == TimeStepper::crank_nicolson ? "CN" : "BE",
                  errors[0],
                  errors[1],
                  errors[2],
                  observed);
      EXPECT_NEAR(observed, expected, 0.2);
    }
}



// ARKODE with adaptive error control on the same problem: the error
// follows the tolerance.
TEST(Heat, ArkodeAdaptive)
{
  auto P = [](double x, double y) { return 1. + x * x + x * y + 0.5 * y * y; };
  auto exact = [=](double x, double y, double t) {
    return P(x, y) * (1. + std::sin(2. * t));
  };
  auto dx = [=](double x, double y, double t) {
    return (2. * x + y) * (1. + std::sin(2. * t));
  };
  auto dy = [=](double x, double y, double t) {
    return (x + y) * (1. + std::sin(2. * t));
  };
  auto source = [=](double x, double y, double t) {
    return P(x, y) * 2. * std::cos(2. * t) - 3. * (1. + std::sin(2. * t));
  };
  HeatParameters p = manufactured_problem(
    2, 0.25, 0.01, TimeStepper::arkode, exact, dx, dy, source);
  p.arkode_relative_tolerance = 1e-7;
  p.arkode_absolute_tolerance = 1e-9;
  HeatSolver solver(p);
  solver.advance_to(1.);
  const double error = solver.l2_error(exact);
  std::printf("ARKODE: L2 error %.3e after %lu steps (%s)\n",
              error,
              solver.statistics().n_steps,
              solver.method_description().c_str());
  EXPECT_LT(error, 1e-4);
  EXPECT_GT(solver.statistics().n_steps, 0u);
}



// A closed domain (convective and flux boundaries only): two blocks of
// different materials, an L-shaped one (ear clipping) and a refinement
// band (hanging nodes). The stored heat change equals the boundary heat
// input integrated with the scheme's own theta weights, to round-off.
TEST(Heat, EnergyBalanceClosedDomain)
{
  for (const auto stepper :
       {TimeStepper::crank_nicolson, TimeStepper::backward_euler})
    {
      HeatParameters p;
      Material       soft = masada_dolomite();
      soft.name           = "soft";
      soft.conductivity   = 0.8;
      soft.density        = 2200.;
      p.materials         = {masada_dolomite(), soft};
      Block l;
      l.name     = "L";
      l.vertices = {
        {{0., 0.}}, {{4., 0.}}, {{4., 2.}}, {{2., 2.}}, {{2., 4.}}, {{0., 4.}}};
      l.edge_tags
        = {"base", "joint", "joint", "exposed", "exposed", "adiabatic"};
      Block r;
      r.name                = "R";
      r.vertices            = {{{4., 0.}}, {{6., 0.}}, {{6., 2.}}, {{4., 2.}}};
      r.edge_tags           = {"base", "exposed", "exposed", "joint"};
      r.material            = 1;
      p.blocks              = {l, r};
      p.degree              = 2;
      p.coarse_cell_size    = 1.;
      p.refine_near_tags    = {"exposed"};
      p.band_width          = 0.5;
      p.band_cell_size      = 0.25;
      p.time_step           = day;
      p.stepper             = stepper;
      p.initial_temperature = 15.;
      const BoundaryCondition air = sinusoidal_air(20. * day);
      p.boundary_conditions
        = {air, constant_flux("base", 5.), constant_flux("joint", 0.)};
      HeatSolver   solver(p);
      const double e0 = solver.stored_heat();
      solver.advance_to(60. * day);
      const double stored = solver.stored_heat() - e0;
      const double input  = solver.boundary_heat_in();
      std::printf("stored %.6e J/m, boundary input %.6e J/m, cells %u, "
                  "relative mismatch %.2e\n",
                  stored,
                  input,
                  solver.statistics().n_cells,
                  std::abs(stored - input) / std::abs(input));
      EXPECT_GT(std::abs(input), 1e6);
      EXPECT_LT(std::abs(stored - input), 1e-6 * std::abs(input));
    }
}



// Per-block mean and linear trend of a linear field are exact.
namespace
{
  /// The steady linear field 10 + 2 x + 3 y degC on the 3 m x 2 m
  /// rectangle [1, 4] x [-2, 0] (held on its whole boundary, also the
  /// initial field), FE_Q(1) on 0.5 m cells.
  double
  linear(const double x, const double y, const double = 0.)
  {
    return 10. + 2. * x + 3. * y;
  }

  HeatParameters
  linear_field_scene()
  {
    HeatParameters p;
    p.blocks = {rectangle(1., -2., 4., 0., {"a", "a", "a", "a"})};
    BoundaryCondition bc;
    bc.tag     = "a";
    bc.type    = BoundaryCondition::Type::temperature;
    bc.value   = [](double x, double y, double) { return linear(x, y); };
    bc.uniform = false;
    p.boundary_conditions = {bc};
    p.initial_field       = [](double x, double y) { return linear(x, y); };
    p.coarse_cell_size    = 0.5;
    p.degree              = 1;
    return p;
  }
} // namespace



TEST(Heat, BlockMomentsOfLinearField)
{
  const HeatParameters p = linear_field_scene();
  HeatSolver           solver(p);
  solver.advance_to(10. * day);
  const auto m = solver.block_moments();
  ASSERT_EQ(m.size(), 1u);
  EXPECT_NEAR(m[0].area, 6., 1e-12);
  EXPECT_NEAR(m[0].centroid_x, 2.5, 1e-12);
  EXPECT_NEAR(m[0].centroid_y, -1., 1e-12);
  EXPECT_NEAR(m[0].mean, 10. + 5. - 3., 1e-9);
  EXPECT_NEAR(m[0].gradient_x, 2., 1e-9);
  EXPECT_NEAR(m[0].gradient_y, 3., 1e-9);
  EXPECT_NEAR(solver.value(2., -1.), linear(2., -1., 0.), 1e-9);
}



// The block moments sampled at equal intervals (thermal::sample_block_moments,
// what the coupling reads): a steady linear field gives the same moments at
// every sample; a non-finite field is an error naming the block and ending
// with the caller's advice.
TEST(Heat, SampledBlockMomentsNameTheBlock)
{
  const HeatParameters p = linear_field_scene();
  HeatSolver           solver(p);
  const auto           samples = sample_block_moments(solver, p, day, day, 3);
  ASSERT_EQ(samples.size(), 3u);
  EXPECT_DOUBLE_EQ(solver.time(), 3. * day);
  for (const auto &row : samples)
    {
      ASSERT_EQ(row.size(), 1u);
      // The linear field is the steady solution: the CG tolerance bounds
      // the drift of the mean (12 degC) and of the gradients (2, 3 K/m).
      EXPECT_NEAR(row[0].mean, 12., 1e-9);
      EXPECT_NEAR(row[0].gradient_x, 2., 1e-9);
      EXPECT_NEAR(row[0].gradient_y, 3., 1e-9);
    }

  HeatParameters broken = p;
  broken.blocks[0].name = "Block 7";
  broken.initial_field  = [](double, double) { return std::nan(""); };
  HeatSolver nan_solver(broken);
  try
    {
      sample_block_moments(nan_solver, broken, 0., day, 2, "check the mesh");
      FAIL() << "a non-finite block mean was sampled";
    }
  catch (const InputError &e)
    {
      const std::string what = e.what();
      EXPECT_NE(what.find("block 'Block 7'"), std::string::npos) << what;
      EXPECT_NE(what.find("not finite at t = 0 s"), std::string::npos) << what;
      EXPECT_NE(what.find(": check the mesh"), std::string::npos) << what;
    }
}



// Bad input: each gets an InputError with a clear message.
TEST(Heat, BadInput)
{
  HeatParameters p;
  p.blocks = {rectangle(0., 0., 1., 1., {"a", "a", "exposed", "a"})};
  p.boundary_conditions
    = {constant_flux("a", 0.), constant_flux("exposed", 0.)};

  HeatParameters negative            = p;
  negative.materials[0].conductivity = -1.7;
  try
    {
      HeatSolver solver(negative);
      FAIL() << "negative conductivity accepted";
    }
  catch (const InputError &e)
    {
      EXPECT_NE(std::string(e.what()).find("conductivity"), std::string::npos)
        << e.what();
      EXPECT_NE(std::string(e.what()).find("-1.7"), std::string::npos);
    }

  HeatParameters unknown = p;
  unknown.boundary_conditions.push_back(constant_flux("tension crack", 1.));
  try
    {
      HeatSolver solver(unknown);
      FAIL() << "unknown tag accepted";
    }
  catch (const InputError &e)
    {
      EXPECT_NE(std::string(e.what()).find("'tension crack'"),
                std::string::npos)
        << e.what();
    }

  HeatParameters missing = p;
  missing.boundary_conditions.pop_back();
  EXPECT_THROW(HeatSolver solver(missing), InputError);

  // A CSV temperature record with a bad value on line 4, and one whose time
  // goes backwards on line 3.
  const std::string file = ::testing::TempDir() + "heat_bad.csv";
  {
    std::ofstream out(file);
    out << "time_day,temperature_C\n0, 10\n1, 12\n2, twelve\n";
  }
  try
    {
      read_time_series(file, 86400.);
      FAIL() << "bad CSV accepted";
    }
  catch (const InputError &e)
    {
      EXPECT_NE(std::string(e.what()).find(file + ":4"), std::string::npos)
        << e.what();
    }
  {
    std::ofstream out(file);
    out << "# air temperature\n0, 10\n0, 12\n";
  }
  try
    {
      read_time_series(file, 86400.);
      FAIL() << "non-increasing CSV accepted";
    }
  catch (const InputError &e)
    {
      EXPECT_NE(std::string(e.what()).find(file + ":3"), std::string::npos)
        << e.what();
    }
  EXPECT_THROW(read_time_series(file + ".missing"), InputError);
  std::remove(file.c_str());

  // A good record interpolates linearly, in seconds.
  {
    std::ofstream out(file);
    out << "time_day,temperature_C\n0, 10\n1, 12\n";
  }
  const TimeSeries s = read_time_series(file, 86400.);
  EXPECT_DOUBLE_EQ(s(43200.), 11.);
  EXPECT_THROW(s(2. * 86400.), std::runtime_error);
  std::remove(file.c_str());

  EXPECT_THROW(parse_sinusoids("9, 0, 0", "x"), InputError);
  EXPECT_EQ(parse_sinusoids("9, 31557600, 0; 5, 86400, 1.5", "x").size(), 2u);
}



// Extremes: dt from 1 s to 1 year, diffusivity 1e-8 to 1e-4 m^2/s, a
// 50 K surface amplitude switched on at t = 0 (a 50 K jump against the
// initial field: the hardest case for Crank-Nicolson). Every run stays
// finite and within the maximum-principle bounds [10, 60] K (up to 1 %);
// the default Rannacher start-up (2 backward-Euler steps) damps the CN
// oscillation, and without it the oscillation is detected and reported.
TEST(Heat, StabilityAtExtremes)
{
  for (const double kappa : {1e-8, 1e-4})
    for (const double dt : {1., year})
      for (const unsigned int variant : {0u, 1u, 2u})
        {
          // 0: CN with start-up, 1: BE, 2: CN without start-up.
          HeatParameters p;
          Material       m = masada_dolomite();
          m.conductivity   = kappa * m.density * m.heat_capacity;
          p.materials      = {m};
          p.blocks = {rectangle(0., -10., 1., 0., {"a", "a", "exposed", "a"})};
          BoundaryCondition s;
          s.tag   = "exposed";
          s.type  = BoundaryCondition::Type::temperature;
          s.value = [](double, double, double t) {
            return 10. + 50. * std::cos(2. * M_PI * t / year);
          };
          p.boundary_conditions  = {s, constant_flux("a", 0.)};
          p.coarse_cell_size     = 0.5;
          p.degree               = 2;
          p.time_step            = dt;
          p.stepper              = variant == 1 ? TimeStepper::backward_euler
                                                : TimeStepper::crank_nicolson;
          p.rannacher_steps      = variant == 2 ? 0 : 2;
          p.oscillation_fallback = variant != 2;
          p.initial_temperature  = 10.;
          HeatSolver solver(p);
          solver.add_probe(0.5, -1.);
          const double end = dt < 10. ? 2000. : 5. * year;
          solver.advance_to(end);
          const auto   st = solver.statistics();
          const double v  = solver.probe_value(0);
          EXPECT_TRUE(std::isfinite(v));
          std::printf("kappa %.0e dt %.0e %s: T(1 m) = %.4f, stiffness "
                      "ratio %.2e, oscillating steps %lu, fallback to BE "
                      "at %.3g s\n",
                      kappa,
                      dt,
                      variant == 0   ? "CN+startup"
                      : variant == 1 ? "BE"
                                     : "CN (no startup)",
                      v,
                      st.stiffness_ratio,
                      st.oscillation_steps,
                      st.fallback_time);
          if (variant == 2 && st.stiffness_ratio > 1e3)
            {
              // The undamped CN oscillation is detected.
              EXPECT_GT(st.oscillation_steps, 0u);
            }
          else
            {
              EXPECT_GE(v, 10. - 0.5);
              EXPECT_LE(v, 60. + 0.5);
              // BE never oscillates; CN with start-up flags at most the
              // step that triggers the fallback and the first BE step
              // that damps it (then it continues as BE, reported).
              EXPECT_LE(st.oscillation_steps, variant == 1 ? 0u : 2u);
              if (st.oscillation_steps > 0)
                {
                  EXPECT_FALSE(std::isnan(st.fallback_time));
                }
            }
        }
}



namespace
{
  /// Two blocks side by side in a slab [0, L1 + L2] x [0, H]: block 1
  /// (lambda1) on the left, block 2 (lambda2) on the right, T = @p tl on
  /// the left end and @p tr on the right end, top and bottom adiabatic.
  HeatParameters
  two_block_slab(const double                       l1,
                 const double                       l2,
                 const double                       lambda1,
                 const double                       lambda2,
                 const double                       tl,
                 const double                       tr,
                 const HeatParameters::JointContact contact,
                 const double                       hj)
  {
    HeatParameters p;
    Material       m1 = masada_dolomite(), m2 = masada_dolomite();
    m1.name         = "left";
    m1.conductivity = lambda1;
    m2.name         = "right";
    m2.conductivity = lambda2;
    p.materials     = {m1, m2};
    Block b1        = rectangle(
      0., 0., l1, 1., {"adiabatic", "joint", "adiabatic", "left end"});
    Block b2 = rectangle(
      l1, 0., l1 + l2, 1., {"adiabatic", "right end", "adiabatic", "joint"});
    b1.name               = "left block";
    b2.name               = "right block";
    b2.material           = 1;
    p.blocks              = {b1, b2};
    p.boundary_conditions = test_scenes::fixed_end_temperatures(tl, tr);
    p.boundary_conditions.push_back(constant_flux("joint", 0.));
    p.joint_contact       = contact;
    p.joint_conductance   = hj;
    p.degree              = 2;
    p.coarse_cell_size    = 0.25;
    p.initial_temperature = 0.5 * (tl + tr);
    return p;
  }
} // namespace



// Contact conductance h_j across a joint (series resistances): at steady
// state q = (T_L - T_R) / (L1/lambda1 + 1/h_j + L2/lambda2), each block
// carries a linear profile (gradient -q/lambda) and the joint a jump q/h_j.
// The linear profile lies in FE_Q, so the FE steady state is exact up to
// round-off; backward Euler with dt = one diffusion time L^2/kappa_min
// damps the slowest mode (rate >= pi^2 kappa / (4 L^2), a block held on one
// side and insulated on the other) by at least (1 + pi^2/4)^-1 ~ 0.3 per
// step, so after 60 steps the transient is below 1e-30 of the initial
// error. What remains is round-off amplified by the condition number
// (~1e4 for these meshes): the tolerance 1e-8 of T_L - T_R leaves a
// margin. Block means and gradients are checked (they determine the
// jump). Large h_j tends to perfect contact, small h_j to insulated
// joints.
TEST(Heat, JointConductanceSteadyState)
{
  const double l1 = 1., l2 = 1.5, lambda1 = 1.7, lambda2 = 0.8;
  const double tl = 30., tr = 10.;
  const double kappa = masada_dolomite().diffusivity();
  const double t_diff
    = (l1 + l2) * (l1 + l2) / (kappa * std::min(lambda1, lambda2) / 1.7);
  const auto steady
    = [&](const HeatParameters::JointContact contact, const double hj) {
        HeatParameters p
          = two_block_slab(l1, l2, lambda1, lambda2, tl, tr, contact, hj);
        p.stepper   = TimeStepper::backward_euler;
        p.time_step = t_diff;
        HeatSolver solver(p);
        solver.advance_to(59. * t_diff);
        const auto before = solver.block_moments();
        solver.advance_to(60. * t_diff);
        const auto after = solver.block_moments();
        // The transient has decayed: one more step changes nothing.
        for (unsigned int b = 0; b < 2; ++b)
          EXPECT_NEAR(after[b].mean, before[b].mean, 1e-10 * (tl - tr));
        return after;
      };
  for (const double hj : {0.5, 2., 50.})
    {
      const double q   = (tl - tr) / (l1 / lambda1 + 1. / hj + l2 / lambda2);
      const auto   m   = steady(HeatParameters::JointContact::conductance, hj);
      const double t1  = tl - q * l1 / lambda1; // left side of the joint
      const double t2  = t1 - q / hj;           // right side of the joint
      const double tol = 1e-8 * (tl - tr);
      std::printf("h_j = %5.1f W/m^2/K: q = %.6f W/m^2, jump %.6f K "
                  "(FE: %.6f K), block mean errors %.1e %.1e K\n",
                  hj,
                  q,
                  q / hj,
                  (m[0].mean + m[0].gradient_x * 0.5 * l1)
                    - (m[1].mean - m[1].gradient_x * 0.5 * l2),
                  m[0].mean - 0.5 * (tl + t1),
                  m[1].mean - 0.5 * (t2 + tr));
      EXPECT_NEAR(m[0].mean, 0.5 * (tl + t1), tol);
      EXPECT_NEAR(m[1].mean, 0.5 * (t2 + tr), tol);
      EXPECT_NEAR(m[0].gradient_x, -q / lambda1, tol / l1);
      EXPECT_NEAR(m[1].gradient_x, -q / lambda2, tol / l2);
      EXPECT_NEAR(m[0].gradient_y, 0., tol / l1);
      // Jump at the joint from the two linear profiles.
      EXPECT_NEAR((m[0].mean + m[0].gradient_x * 0.5 * l1)
                    - (m[1].mean - m[1].gradient_x * 0.5 * l2),
                  q / hj,
                  4. * tol);
    }

  // Limits: h_j = 1e9 W/(m^2 K) differs from perfect contact by the joint
  // resistance 1e-9 against L/lambda ~ 2.5 m^2 K/W (relative 4e-10);
  // h_j = 1e-9 differs from insulated joints by q ~ 1e-9 (T_L - T_R).
  const auto perfect   = steady(HeatParameters::JointContact::perfect, 1.);
  const auto stiff     = steady(HeatParameters::JointContact::conductance, 1e9);
  const auto insulated = steady(HeatParameters::JointContact::insulated, 1.);
  const auto loose = steady(HeatParameters::JointContact::conductance, 1e-9);
  std::printf("limits: |h_j = 1e9 - perfect| = %.1e K, |h_j = 1e-9 - "
              "insulated| = %.1e K\n",
              std::abs(stiff[0].mean - perfect[0].mean),
              std::abs(loose[0].mean - insulated[0].mean));
  for (unsigned int b = 0; b < 2; ++b)
    {
      EXPECT_NEAR(stiff[b].mean, perfect[b].mean, 1e-7 * (tl - tr));
      EXPECT_NEAR(loose[b].mean, insulated[b].mean, 1e-7 * (tl - tr));
    }
  EXPECT_NEAR(insulated[0].mean, tl, 1e-8 * (tl - tr));
  EXPECT_NEAR(insulated[1].mean, tr, 1e-8 * (tl - tr));
}



// The joint term is conservative: in a closed domain (convective and flux
// boundaries only) with a contact conductance, non-matching meshes on the
// two sides of the joint (block 2 is refined near its exposed face, block
// 1 is not) and Crank-Nicolson, the stored heat change equals the boundary
// input to round-off.
TEST(Heat, JointConductanceEnergyBalance)
{
  HeatParameters p = two_block_slab(
    1., 1.5, 1.7, 0.8, 30., 10., HeatParameters::JointContact::conductance, 5.);
  p.blocks[1].edge_tags       = {"adiabatic", "exposed", "adiabatic", "joint"};
  p.blocks[0].edge_tags       = {"adiabatic", "joint", "adiabatic", "base"};
  const BoundaryCondition air = sinusoidal_air(5. * day);
  p.boundary_conditions       = {air, constant_flux("base", 3.)};
  p.refine_near_tags          = {"exposed"};
  p.band_width                = 1.2;
  p.band_cell_size            = 0.07;
  p.time_step                 = day / 4.;
  p.initial_temperature       = 15.;
  HeatSolver   solver(p);
  const double e0 = solver.stored_heat();
  solver.advance_to(20. * day);
  const double stored = solver.stored_heat() - e0;
  const double input  = solver.boundary_heat_in();
  const auto   m      = solver.block_moments();
  std::printf("joint conductance: stored %.6e J/m, input %.6e J/m, "
              "mismatch %.2e, block means %.4f %.4f\n",
              stored,
              input,
              std::abs(stored - input) / std::abs(input),
              m[0].mean,
              m[1].mean);
  EXPECT_GT(std::abs(input), 1e5);
  EXPECT_LT(std::abs(stored - input), 1e-8 * std::abs(input));
  // The run did something: block 1 moved from its initial 15 degC.
  EXPECT_GT(std::abs(m[0].mean - 15.), 1e-3);
}



namespace
{
  /// The periodic half-space in a 2 m wide, 30 m deep column with FE_Q(1),
  /// Crank-Nicolson with daily steps; amplitude and lag errors at z = 0.5,
  /// 1, 2.5, 5 m over the 13th year (fractions of A, days).
  struct HalfSpaceRun
  {
    double         amplitude_error = 0.;
    double         lag_error       = 0.;
    HeatStatistics statistics;
  };

  HalfSpaceRun
  run_half_space_column(const double cell_size, const bool adaptive)
  {
    const double   A = 10., Tm = 20., w = 2. * M_PI / year;
    HeatParameters p         = half_space_column(2., 1, cell_size, A, Tm);
    p.adaptive_refinement    = adaptive;
    p.adaptive_interval      = 10;
    p.refine_fraction        = 0.3;
    p.coarsen_fraction       = 0.03;
    p.adaptive_min_cell_size = 0.5;
    HeatSolver                solver(p);
    const std::vector<double> depths = {0.5, 1., 2.5, 5.};
    const YearOfSamples       s = sample_thirteenth_year(solver, 1., depths);
    const double d = periodic_skin_depth(masada_dolomite().diffusivity(), year);
    HalfSpaceRun r;
    for (unsigned int k = 0; k < depths.size(); ++k)
      {
        const SinusoidFit fit = fit_sinusoid(s.t, s.values[k], w);
        const double      z   = depths[k];
        r.amplitude_error
          = std::max(r.amplitude_error,
                     std::abs(fit.amplitude - A * std::exp(-z / d)) / A);
        r.lag_error
          = std::max(r.lag_error, std::abs(-fit.phase / w - z / d / w) / day);
      }
    r.statistics = solver.statistics();
    return r;
  }
} // namespace



// Kelly-estimator adaptivity (refine/coarsen every 10 steps, solution
// transfer) on the periodic half-space: starting from 2 m cells and
// refining to at most 0.5 m cells where the estimator asks, it meets the
// same targets as the uniform 0.5 m mesh (amplitude within 1 % of A, lag
// within 1 day; the uniform FE_Q(1) 0.5 m mesh gives ~1e-3 A, see
// benchmarks/heat-halfspace) with at most 40 % of its cells at any time,
// and the column below the skin depths keeps its 2 m cells.
TEST(Heat, AdaptiveHalfSpaceMeetsUniformAccuracy)
{
  const HalfSpaceRun uniform  = run_half_space_column(0.5, false);
  const HalfSpaceRun adaptive = run_half_space_column(2., true);
  std::printf("uniform 0.5 m: %u cells, amplitude error %.2e A, lag error "
              "%.3f d\nadaptive 2 m -> 0.5 m: at most %u cells (%u at the "
              "end, %lu adaptations), amplitude error %.2e A, lag error "
              "%.3f d, largest cell %.2f m\n",
              uniform.statistics.n_cells,
              uniform.amplitude_error,
              uniform.lag_error,
              adaptive.statistics.max_n_cells,
              adaptive.statistics.n_cells,
              adaptive.statistics.n_adaptations,
              adaptive.amplitude_error,
              adaptive.lag_error,
              adaptive.statistics.max_cell_size);
  EXPECT_LT(uniform.amplitude_error, 0.01);
  EXPECT_LT(adaptive.amplitude_error, 0.01);
  EXPECT_LT(adaptive.lag_error, 1.);
  EXPECT_GT(adaptive.statistics.n_adaptations, 100u);
  EXPECT_LT(adaptive.statistics.max_n_cells, 0.4 * uniform.statistics.n_cells);
  EXPECT_GE(adaptive.statistics.max_cell_size, 2. * std::sqrt(2.) - 1e-9);
  EXPECT_GE(adaptive.statistics.min_cell_size, 0.5 * std::sqrt(2.) - 1e-9);
}



// Adaptivity keeps the energy bookkeeping closed: in a closed domain the
// stored heat change equals the boundary input plus the heat added by
// the (non-conservative) interpolation onto new meshes, to round-off; the
// probes and block moments follow the mesh.
TEST(Heat, AdaptiveEnergyBalanceAndMoments)
{
  HeatParameters p;
  p.materials = {masada_dolomite()};
  p.blocks = {rectangle(0., 0., 4., 2., {"base", "exposed", "exposed", "a"})};
  const BoundaryCondition air = sinusoidal_air(2. * day);
  p.boundary_conditions
    = {air, constant_flux("base", 5.), constant_flux("a", 0.)};
  p.degree                 = 2;
  p.coarse_cell_size       = 1.;
  p.time_step              = day / 24.;
  p.initial_temperature    = 15.;
  p.adaptive_refinement    = true;
  p.adaptive_interval      = 6;
  p.adaptive_min_cell_size = 0.0625;
  HeatSolver solver(p);
  solver.add_probe(3.9, 1.9);
  const double e0 = solver.stored_heat();
  solver.advance_to(4. * day);
  const auto   st     = solver.statistics();
  const double stored = solver.stored_heat() - e0;
  const double input  = solver.boundary_heat_in() + st.mesh_transfer_heat;
  std::printf("adaptive closed domain: %lu adaptations, %u cells, stored "
              "%.6e J/m, boundary input %.6e J/m, transfer %.3e J/m, "
              "mismatch %.2e\n",
              st.n_adaptations,
              st.n_cells,
              stored,
              solver.boundary_heat_in(),
              st.mesh_transfer_heat,
              std::abs(stored - input) / std::abs(input));
  EXPECT_GT(st.n_adaptations, 0u);
  EXPECT_GT(st.max_n_cells, 8u);
  EXPECT_LT(std::abs(stored - input), 1e-9 * std::abs(input));
  // The probe follows the mesh: it equals the field value at its point.
  EXPECT_NEAR(solver.probe_value(0), solver.value(3.9, 1.9), 1e-10);

  // The block moments are rebuilt with the mesh: the block mean times
  // rho c_p A is the stored heat.
  const auto m   = solver.block_moments();
  const auto mat = masada_dolomite();
  EXPECT_NEAR(m[0].area, 8., 1e-10); // sum of ~1e4 quadrature terms
  EXPECT_NEAR(m[0].mean * m[0].area * mat.density * mat.heat_capacity,
              solver.stored_heat(),
              1e-12 * solver.stored_heat());
}
