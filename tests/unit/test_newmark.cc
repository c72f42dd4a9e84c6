/**
 * @file
 * Tests of the 1D rigid-block Newmark analysis: SLAMMER reference results,
 * the closed-form harmonic solution, model equivalences and bad input.
 */
#include <rockdda/analytical/newmark.h>
#include <rockdda/io/error.h>
#include <rockdda/io/output.h>
#include <rockdda/seismic/record.h>

#include <gtest/gtest.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <map>
#include <sstream>
#include <string>
#include <vector>

#ifndef ROCKDDA_SHARED_DATA
#  error "ROCKDDA_SHARED_DATA must name the shared data folder"
#endif

using namespace rockdda;
using namespace rockdda::analytical;

namespace
{
  const double g_std = 9.80665; // m/s^2, as in SLAMMER

  const std::string slammer_dir
    = std::string(ROCKDDA_SHARED_DATA) + "/ground-motions/slammer/";


  /// Rows of a CSV file (header skipped).
  std::vector<std::vector<std::string>>
  read_csv(const std::string &file_name)
  {
    std::ifstream in(file_name);
    EXPECT_TRUE(in.good()) << "cannot open " << file_name;
    std::vector<std::vector<std::string>> rows;
    std::string                           line;
    std::getline(in, line);
    while (std::getline(in, line))
      if (!line.empty())
        rows.push_back(io::split_csv_record(line));
    return rows;
  }

  /// A record of A sin(omega t) (g) sampled at dt for [0, duration].
  seismic::Record
  sine_record(const double amplitude,
              const double omega,
              const double dt,
              const double duration)
  {
    seismic::Record record;
    record.name  = "sine";
    record.dt    = dt;
    const auto n = static_cast<std::size_t>(std::llround(duration / dt));
    for (std::size_t i = 0; i <= n; ++i)
      record.acceleration.push_back(amplitude * std::sin(omega * i * dt));
    return record;
  }

  /// A record of constant value (g).
  seismic::Record
  constant_record(const double value, const double dt, const std::size_t n)
  {
    seismic::Record record;
    record.name = "constant";
    record.dt   = dt;
    record.acceleration.assign(n, value);
    return record;
  }
} // namespace



namespace
{
  /// One SLAMMER case: record, scaling and reference displacements (cm).
  struct SlammerCase
  {
    std::string name;
    double      target_pga, ky, normal_cm, inverse_cm;
  };

  /// The 90 reference cases and their (unscaled) records.
  void
  read_slammer(std::vector<SlammerCase>               &cases,
               std::map<std::string, seismic::Record> &records)
  {
    std::map<std::string, double> dt_of;
    for (const auto &row : read_csv(slammer_dir + "records.csv"))
      dt_of[row.at(0)] = std::stod(row.at(9));
    for (const auto &row :
         read_csv(slammer_dir + "rigid_newmark_reference.csv"))
      {
        cases.push_back({row.at(0),
                         std::stod(row.at(1)),
                         std::stod(row.at(2)),
                         std::stod(row.at(3)),
                         std::stod(row.at(4))});
        if (records.count(row[0]) == 0)
          records[row[0]]
            = seismic::read_record(slammer_dir + row[0], dt_of.at(row[0]));
      }
  }

  /// Displacements (cm) of all 180 runs (90 cases x 2 polarities) and
  /// what they are compared with.
  struct SlammerRuns
  {
    std::vector<std::string> names;
    std::vector<double>      displacement_cm, slammer_cm;
    double                   seconds = 0.;
  };

  /**
   * Run all 90 cases in both polarities with @p options (ky set per case;
   * time_step = dt / substeps).
   */
  SlammerRuns
  run_slammer_cases(NewmarkOptions options, const unsigned int substeps)
  {
    std::vector<SlammerCase>               cases;
    std::map<std::string, seismic::Record> records;
    read_slammer(cases, records);
    EXPECT_EQ(cases.size(), 90u);
    SlammerRuns out;
    for (const auto &c : cases)
      for (const int polarity : {+1, -1})
        {
          seismic::Record record = records.at(c.name);
          seismic::scale_to_pga(record, c.target_pga);
          if (polarity < 0)
            seismic::scale(record, -1.);
          options.ky        = c.ky;
          options.time_step = substeps > 1 ? record.dt / substeps : 0.;

          const auto start  = std::chrono::steady_clock::now();
          const auto result = newmark_sliding(record, options);
          out.seconds += std::chrono::duration<double>(
                           std::chrono::steady_clock::now() - start)
                           .count();
          out.displacement_cm.push_back(100. * result.final_displacement);
          out.slammer_cm.push_back(polarity > 0 ? c.normal_cm : c.inverse_cm);
          out.names.push_back(c.name + " pga="
                              + std::to_string(c.target_pga).substr(0, 4)
                              + " ky=" + std::to_string(c.ky).substr(0, 4)
                              + (polarity > 0 ? " normal" : " inverse"));
        }
    return out;
  }

  /// Discrepancy of a set of runs with respect to reference values.
  struct Discrepancy
  {
    double      worst_rel = 0., worst_abs = 0.;
    std::string worst_rel_case, worst_abs_case;
    unsigned    n_runs = 0, n_out = 0;
  };

  /**
   * Compare @p values with @p reference (cm), run by run, with the tolerance
   * max(2 % of the reference, 0.05 cm); each run outside it is a test
   * failure when @p fail. The worst relative discrepancy is taken over
   * references > 0.05 cm (below, the absolute tolerance applies).
   */
  Discrepancy
  compare(const SlammerRuns         &runs,
          const std::vector<double> &reference,
          const bool                 fail)
  {
    Discrepancy out;
    for (std::size_t i = 0; i < reference.size(); ++i)
      {
        const double d = runs.displacement_cm[i], ref = reference[i];
        const double err = std::abs(d - ref);
        ++out.n_runs;
        if (err > std::max(0.02 * ref, 0.05))
          {
            ++out.n_out;
            if (fail)
              ADD_FAILURE()
                << runs.names[i] << ": " << d << " cm vs " << ref << " cm";
          }
        if (ref > 0.05 && err / ref > out.worst_rel)
          {
            out.worst_rel      = err / ref;
            out.worst_rel_case = runs.names[i];
          }
        if (err > out.worst_abs)
          {
            out.worst_abs      = err;
            out.worst_abs_case = runs.names[i];
          }
      }
    return out;
  }

  /// Print a Discrepancy.
  void
  print(const char *label, const Discrepancy &d)
  {
    std::printf("%s: %u outside max(2 %%, 0.05 cm) of %u; worst relative "
                "%.3f %% (%s), worst absolute %.4f cm (%s)\n",
                label,
                d.n_out,
                d.n_runs,
                100. * d.worst_rel,
                d.worst_rel_case.c_str(),
                d.worst_abs,
                d.worst_abs_case.c_str());
  }
} // namespace



// All 90 SLAMMER rigid-block cases, normal and inverse polarity, with the
// events placed at the samples as SLAMMER does (EventLocation::at_samples).
// Tolerance max(2 % of the reference, 0.05 cm), as required. The remaining
// differences (< 1.8 %) are a per-record factor, the same for both
// polarities and for all ky/PGA (e.g. Coalinga +1.2 %, Cape Mendocino
// -0.7 %), i.e. a difference in the input samples or their scaling inside
// SLAMMER, not in the integration.
TEST(Newmark, SlammerReference)
{
  NewmarkOptions options;
  options.event_location = NewmarkOptions::EventLocation::at_samples;
  const auto runs        = run_slammer_cases(options, 1);
  const auto d           = compare(runs, runs.slammer_cm, true);
  print("SLAMMER vs this code (events at samples, as SLAMMER)", d);
  std::printf("  180 runs in %.3f s\n", runs.seconds);
  EXPECT_EQ(d.n_runs, 180u);
  EXPECT_EQ(d.n_out, 0u);
  // Performance requirement: the whole suite well under a second (it takes
  // a few tens of milliseconds; 1 s leaves room for a loaded machine).
  EXPECT_LT(runs.seconds, 1.);
}



// The default event location on the SLAMMER cases. SLAMMER starts sliding
// up to one step early (at the previous sample, with zero relative
// acceleration there) and stops up to one step late: an O(dt) bias per slip
// event, which matters for short slips (small displacements, high ky/PGA,
// dt = 0.02 s records). The default places both events within the step and
// integrates the velocity and displacement exactly for a relative
// acceleration linear across the step, so for a (piecewise-linear) record it
// is exact: sub-stepping (dt/5, the record linearly interpolated) must give
// the same displacements to round-off (1e-9 relative + 1e-9 cm). The
// SLAMMER-style placement converges to the same answer (within max(2 %,
// 0.05 cm) at dt/5). The comparison of the default with SLAMMER is printed,
// not asserted: it measures SLAMMER's own discretization error.
TEST(Newmark, SlammerCasesWithinStepIsExactForTheRecord)
{
  NewmarkOptions options;
  const auto     native   = run_slammer_cases(options, 1);
  const auto     sub      = run_slammer_cases(options, 5);
  options.event_location  = NewmarkOptions::EventLocation::at_samples;
  const auto at_samples_5 = run_slammer_cases(options, 5);

  print("SLAMMER vs default (within step)",
        compare(native, native.slammer_cm, false));
  for (std::size_t i = 0; i < native.displacement_cm.size(); ++i)
    EXPECT_NEAR(native.displacement_cm[i],
                sub.displacement_cm[i],
                1e-9 * sub.displacement_cm[i] + 1e-9)
      << native.names[i];
  print("default dt vs default dt/5",
        compare(native, sub.displacement_cm, true));
  print("at samples dt/5 vs default",
        compare(at_samples_5, sub.displacement_cm, true));
}



// The closed form itself: t_start, v(t_stop) = 0 and the displacement per
// cycle against a brute-force quadrature of v(t) (composite Simpson, 2e5
// intervals: error ~1e-15 relative), for several ky/A.
TEST(Newmark, HarmonicClosedFormIsConsistent)
{
  const double amplitude = 0.5, omega = 10.;
  for (const double ratio : {0., 0.1, 0.3, 0.5, 0.8, 0.99})
    {
      const double ky    = ratio * amplitude;
      const auto   cycle = harmonic_sliding_cycle(amplitude, omega, ky);
      EXPECT_NEAR(cycle.t_start, std::asin(ratio) / omega, 1e-15);
      const auto v = [&](const double t) {
        return amplitude / omega
                 * (std::cos(omega * cycle.t_start) - std::cos(omega * t))
               - ky * (t - cycle.t_start);
      };
      // The root to machine precision: |v| ~ a few ulps of A/omega.
      EXPECT_LT(std::abs(v(cycle.t_stop)), 1e-14);
      EXPECT_GT(cycle.t_stop, M_PI / omega - cycle.t_start);
      EXPECT_LE(cycle.t_stop, cycle.t_start + 2. * M_PI / omega + 1e-15);

      const unsigned int n        = 200000;
      const double       h        = (cycle.t_stop - cycle.t_start) / n;
      double             integral = v(cycle.t_start) + v(cycle.t_stop);
      for (unsigned int i = 1; i < n; ++i)
        integral += (i % 2 ? 4. : 2.) * v(cycle.t_start + i * h);
      integral *= h / 3.;
      EXPECT_NEAR(cycle.displacement_per_cycle,
                  integral,
                  1e-10 * integral + 1e-16);
      // Displacement at any time: continuous, cycles add up.
      const double period = 2. * M_PI / omega;
      EXPECT_NEAR(
        harmonic_sliding_displacement(amplitude, omega, ky, 3.5 * period),
        (ratio == 0. ? 3.5 : 3.) * cycle.displacement_per_cycle
          + (ratio == 0. ? 0.
                         : harmonic_sliding_displacement(
                           amplitude, omega, ky, 0.5 * period)),
        1e-12 * cycle.displacement_per_cycle);
    }
  // No sliding when ky >= A.
  EXPECT_EQ(harmonic_sliding_cycle(0.5, 10., 0.5).displacement_per_cycle, 0.);
  EXPECT_EQ(harmonic_sliding_displacement(0.5, 10., 0.6, 100.), 0.);
  EXPECT_THROW(harmonic_sliding_cycle(0., 10., 0.1), InputError);
  EXPECT_THROW(harmonic_sliding_cycle(0.5, -1., 0.1), InputError);
  EXPECT_THROW(harmonic_sliding_cycle(0.5, 10., -0.1), InputError);
}



// Numerical integration of a(t) = 0.5 g sin(10 t) against the closed form
// after 5.25 cycles (t = 3.30 s), dt = 0.001 s (628 samples per period). The
// sampled record is linearly interpolated (error ~ A (omega dt)^2 / 8 =
// 1.25e-5 A) and the interpolant is integrated exactly, so the error (~1e-4
// at most, for ky/A = 0.8 whose short slips are most sensitive) is far below
// the required 0.5 %.
TEST(Newmark, HarmonicMatchesClosedForm)
{
  const double amplitude = 0.5, omega = 10., period = 2. * M_PI / omega;
  const double t_end = 5.25 * period;
  for (const double ratio : {0.1, 0.3, 0.5, 0.8})
    {
      const double   ky     = ratio * amplitude;
      const double   dt     = 0.001;
      auto           record = sine_record(amplitude, omega, dt, t_end);
      NewmarkOptions options;
      options.ky          = ky;
      const auto   res    = newmark_sliding(record, options);
      const double t_last = res.time.back();
      const double exact
        = g_std * harmonic_sliding_displacement(amplitude, omega, ky, t_last);
      const double rel = std::abs(res.final_displacement - exact) / exact;
      std::printf("harmonic ky/A = %.1f, dt = %g s: numerical %.6f m, exact "
                  "%.6f m, relative error %.2e\n",
                  ratio,
                  dt,
                  res.final_displacement,
                  exact,
                  rel);
      EXPECT_LT(rel, 0.005);
      // Also along the history (sampled every 0.1 s), relative to the final
      // displacement.
      for (std::size_t i = 0; i < res.time.size(); i += 100)
        EXPECT_NEAR(
          res.displacement[i],
          g_std
            * harmonic_sliding_displacement(amplitude, omega, ky, res.time[i]),
          0.005 * exact);
      // One slip event per cycle: 6 starts within 5.25 cycles.
      EXPECT_EQ(res.n_slip_events, 6u);
    }
}



// Convergence: halving dt (of the sampled record itself) must reduce the
// error. The integration is exact for the linearly interpolated record, so
// the error is that of the interpolation of the sine, O(dt^2): each halving
// should gain close to a factor 4 (we require > 3 to allow for the irregular
// position of the events relative to the samples). The SLAMMER-style event
// placement is printed for comparison (first order).
TEST(Newmark, HarmonicConvergence)
{
  const double amplitude = 0.5, omega = 10., period = 2. * M_PI / omega;
  const double t_end = 5. * period;
  for (const double ratio : {0.1, 0.3, 0.5, 0.8})
    {
      const double ky = ratio * amplitude;
      const double exact
        = g_std * harmonic_sliding_displacement(amplitude, omega, ky, t_end);
      std::vector<double> errors;
      for (const double dt : {0.02, 0.01, 0.005, 0.0025})
        {
          // dt does not divide t_end; compare at the last sample.
          auto record
            = sine_record(amplitude, omega, dt, std::floor(t_end / dt) * dt);
          NewmarkOptions options;
          options.ky       = ky;
          const auto   res = newmark_sliding(record, options);
          const double ex  = g_std
                            * harmonic_sliding_displacement(amplitude,
                                                            omega,
                                                            ky,
                                                            res.time.back());
          errors.push_back(std::abs(res.final_displacement - ex) / exact);
          // The linear interpolant of the samples has, as fundamental, a
          // sine of amplitude A sinc^2(omega dt / 2) (transfer function of
          // linear interpolation); the closed form for that amplitude
          // accounts for the whole error: the rest (< 5e-5) comes from the
          // interpolant's higher harmonics, and shows that the integration
          // itself adds nothing at this level.
          const double half  = 0.5 * omega * dt;
          const double sinc2 = std::pow(std::sin(half) / half, 2);
          const double ex_interpolated
            = g_std
              * harmonic_sliding_displacement(amplitude * sinc2,
                                              omega,
                                              ky,
                                              res.time.back());
          EXPECT_NEAR(res.final_displacement, ex_interpolated, 5e-5 * exact);
          options.event_location = NewmarkOptions::EventLocation::at_samples;
          const double slammer_like
            = std::abs(newmark_sliding(record, options).final_displacement - ex)
              / exact;
          std::printf("  ky/A = %.1f dt = %-7g relative error %.3e (events "
                      "at samples, as SLAMMER: %.3e)\n",
                      ratio,
                      dt,
                      errors.back(),
                      slammer_like);
        }
      for (std::size_t i = 1; i < errors.size(); ++i)
        EXPECT_LT(errors[i], errors[i - 1] / 3.)
          << "ky/A = " << ratio << " refinement " << i;
    }
}



// Sub-stepping a coarse record: with time_step < dt the record is linearly
// interpolated, and the default scheme is exact for a relative acceleration
// linear across each step, so the result equals the native-step result to
// round-off (1e-10 relative). Output every 0.1 s.
TEST(Newmark, SubSteppingAndOutputInterval)
{
  auto           record = sine_record(0.5, 10., 0.01, 3.);
  NewmarkOptions options;
  options.ky              = 0.15;
  const auto native       = newmark_sliding(record, options);
  options.time_step       = 0.001;
  options.output_interval = 0.1;
  const auto fine         = newmark_sliding(record, options);
  EXPECT_NEAR(fine.final_displacement,
              native.final_displacement,
              1e-10 * native.final_displacement);
  EXPECT_EQ(fine.n_steps, 3000u);
  EXPECT_EQ(native.n_steps, 300u);
  ASSERT_EQ(native.time.size(), 301u);
  // Output every 0.1 s: t = 0, 0.1, ..., 3.0.
  ASSERT_EQ(fine.time.size(), 31u);
  EXPECT_NEAR(fine.time[7], 0.7, 1e-12);
  EXPECT_NEAR(fine.time.back(), 3., 1e-12);
  EXPECT_EQ(fine.displacement.back(), fine.final_displacement);
  EXPECT_NEAR(fine.displacement[10], native.displacement[100], 1e-10);
}



// Two-way sliding, symmetric yield: a positive half-sine pulse, a rest long
// enough for the block to stop, then the same pulse negated. The block slides
// down by D, then up by exactly D (same equations mirrored): net zero to
// round-off (1e-12 of D). Mirroring the whole record mirrors the history.
TEST(Newmark, TwoWaySymmetry)
{
  const double    dt = 0.005, omega = 2. * M_PI;
  seismic::Record record;
  record.name = "pulses";
  record.dt   = dt;
  for (int i = 0; i <= 100; ++i) // half sine, 0.5 s
    record.acceleration.push_back(0.4 * std::sin(omega * i * dt));
  record.acceleration.resize(record.acceleration.size() + 200, 0.); // 1 s rest
  const std::size_t n = record.acceleration.size();
  for (std::size_t i = 0; i < 101; ++i)
    record.acceleration.push_back(-record.acceleration[i]);
  record.acceleration.resize(record.acceleration.size() + 200, 0.);

  NewmarkOptions options;
  options.ky        = 0.1;
  options.direction = NewmarkOptions::Direction::two_way;
  const auto   res  = newmark_sliding(record, options);
  const double down = res.displacement[n - 1];
  EXPECT_GT(down, 0.01);
  EXPECT_NEAR(res.final_displacement, 0., 1e-12 * down);
  EXPECT_EQ(res.n_slip_events, 2u);
  EXPECT_EQ(*std::min_element(res.state.begin(), res.state.end()), -1);

  // Downslope only: the second pulse does nothing.
  options.direction = NewmarkOptions::Direction::downslope;
  EXPECT_NEAR(newmark_sliding(record, options).final_displacement,
              down,
              1e-12 * down);

  // Mirrored record, two-way: mirrored history, step by step.
  options.direction = NewmarkOptions::Direction::two_way;
  auto mirrored     = record;
  seismic::scale(mirrored, -1.);
  const auto res_m = newmark_sliding(mirrored, options);
  ASSERT_EQ(res_m.displacement.size(), res.displacement.size());
  for (std::size_t i = 0; i < res.displacement.size(); ++i)
    {
      EXPECT_EQ(res_m.displacement[i], -res.displacement[i]);
      EXPECT_EQ(res_m.state[i], -res.state[i]);
    }
}



// A ky table with a constant value is the constant model (identical
// arithmetic: equal to 1e-14 relative). A table that drops from 0.2 to 0.1 g
// over the first centimetres gives a displacement between the two constant
// cases.
TEST(Newmark, TableModel)
{
  auto record
    = seismic::read_record(slammer_dir + "Imperial_Valley_1940_ELC-180.txt",
                           0.01);
  NewmarkOptions constant;
  constant.ky        = 0.15;
  const double   d_c = newmark_sliding(record, constant).final_displacement;
  NewmarkOptions table;
  table.yield_model        = NewmarkOptions::YieldModel::table;
  table.table_displacement = {0., 0.5};
  table.table_ky           = {0.15, 0.15};
  EXPECT_NEAR(newmark_sliding(record, table).final_displacement,
              d_c,
              1e-14 * d_c);
  EXPECT_GT(d_c, 0.);

  table.table_displacement = {0.001, 0.02};
  table.table_ky           = {0.2, 0.1};
  const double d_t         = newmark_sliding(record, table).final_displacement;
  constant.ky              = 0.2;
  const double d_hi = newmark_sliding(record, constant).final_displacement;
  constant.ky       = 0.1;
  const double d_lo = newmark_sliding(record, constant).final_displacement;
  EXPECT_GT(d_t, d_hi);
  EXPECT_LT(d_t, d_lo);
}



// Plane model with Coulomb friction (phi = 30, alpha = 20 deg). The start
// condition g(sin a + k cos a) > tan(phi) g (cos a - k sin a) is exactly
// k > tan(phi - alpha); when sliding, the relative acceleration is
// g (cos a + tan(phi) sin a) (k - tan(phi - alpha)), so the along-plane
// displacement is cos(phi - alpha) / cos(phi) times the Newmark displacement
// with ky = tan(phi - alpha) (same arithmetic up to round-off: 1e-10).
TEST(Newmark, PlaneCoulombReducesToConstantKy)
{
  const double phi = 30., alpha = 20.;
  const double ky_eff = std::tan((phi - alpha) * M_PI / 180.);

  NewmarkOptions plane;
  plane.yield_model = NewmarkOptions::YieldModel::plane;
  plane.dip_deg     = alpha;
  plane.friction    = FrictionLaw::coulomb_deg(phi);

  // Start threshold: a constant input just above / below tan(phi - alpha).
  const auto above
    = newmark_sliding(constant_record(ky_eff * (1. + 1e-9), 0.01, 101), plane);
  EXPECT_EQ(above.n_slip_events, 1u);
  EXPECT_GT(above.final_displacement, 0.);
  const auto below
    = newmark_sliding(constant_record(ky_eff * (1. - 1e-9), 0.01, 101), plane);
  EXPECT_EQ(below.n_slip_events, 0u);
  EXPECT_EQ(below.final_displacement, 0.);

  // Equivalence on the thesis case (Figure 4-2A): 0.5 g sin(10 t), 10
  // cycles, dt = 0.001 s.
  const auto     record = sine_record(0.5, 10., 0.001, 2. * M_PI);
  NewmarkOptions constant;
  constant.ky = ky_eff;
  const double factor
    = std::cos((phi - alpha) * M_PI / 180.) / std::cos(phi * M_PI / 180.);
  const double d_plane = newmark_sliding(record, plane).final_displacement;
  const double d_const = newmark_sliding(record, constant).final_displacement;
  EXPECT_NEAR(d_plane, factor * d_const, 1e-10 * d_plane);
  // And against the closed form (0.5 %, as in the harmonic test).
  const double exact
    = factor * g_std
      * harmonic_sliding_displacement(0.5, 10., ky_eff, record.duration());
  EXPECT_NEAR(d_plane, exact, 0.005 * exact);
  std::printf("plane alpha=20 phi=30, 0.5 g sin(10t), 10 cycles: %.5f m "
              "(closed form %.5f m)\n",
              d_plane,
              exact);
}



// Gravity alone on a plane steeper than the friction angle (alpha = 35,
// phi = 25 deg): constant relative acceleration g (sin a - cos a tan phi),
// x = 1/2 g (sin a - cos a tan phi) t^2. The trapezoidal rule is exact for
// constant acceleration: agreement to round-off (1e-12 relative).
TEST(Newmark, PlaneGravityAlone)
{
  const double   alpha = 35. * M_PI / 180., phi = 25. * M_PI / 180.;
  NewmarkOptions plane;
  plane.yield_model = NewmarkOptions::YieldModel::plane;
  plane.dip_deg     = 35.;
  plane.friction    = FrictionLaw::coulomb_deg(25.);
  const auto   res  = newmark_sliding(constant_record(0., 0.01, 201), plane);
  const double acc
    = g_std * (std::sin(alpha) - std::cos(alpha) * std::tan(phi));
  for (std::size_t i = 0; i < res.time.size(); i += 20)
    EXPECT_NEAR(res.displacement[i],
                0.5 * acc * res.time[i] * res.time[i],
                1e-12 * 0.5 * acc * 4.);
  EXPECT_NEAR(res.final_displacement, 0.5 * acc * 4., 1e-12 * 2. * acc);
  EXPECT_NEAR(res.max_velocity, acc * 2., 1e-12 * acc * 2.);
  EXPECT_EQ(res.n_slip_events, 1u);
  EXPECT_NEAR(res.sliding_duration, 2., 1e-12);
}



// Plane model, two-way: upslope sliding starts at k < -tan(phi + alpha).
// A constant input just beyond that threshold slides upslope, just inside it
// does not.
TEST(Newmark, PlaneUpslopeThreshold)
{
  NewmarkOptions plane;
  plane.yield_model = NewmarkOptions::YieldModel::plane;
  plane.dip_deg     = 20.;
  plane.friction    = FrictionLaw::coulomb_deg(30.);
  plane.direction   = NewmarkOptions::Direction::two_way;
  const double k_up = -std::tan(50. * M_PI / 180.);
  const auto   beyond
    = newmark_sliding(constant_record(k_up * (1. + 1e-9), 0.01, 11), plane);
  EXPECT_LT(beyond.final_displacement, 0.);
  EXPECT_EQ(beyond.state.back(), -1);
  const auto inside
    = newmark_sliding(constant_record(k_up * (1. - 1e-9), 0.01, 11), plane);
  EXPECT_EQ(inside.final_displacement, 0.);
}



// Rate-dependent friction mu(V) = mu0 + (A - B) ln(V / V0), V0 = cutoff, so
// the static coefficient is mu0: A - B = 0 is Coulomb (to round-off);
// velocity strengthening (A - B > 0) gives less displacement than Coulomb,
// weakening more. The implicit update converges: halving the step changes
// the result by < 0.5 % (the second-order scheme at dt = 1e-3 s).
TEST(Newmark, PlaneRateDependentFriction)
{
  const auto     record = sine_record(0.5, 10., 0.001, 2. * M_PI);
  NewmarkOptions plane;
  plane.yield_model      = NewmarkOptions::YieldModel::plane;
  plane.dip_deg          = 20.;
  plane.friction         = FrictionLaw::coulomb_deg(30.);
  const double d_coulomb = newmark_sliding(record, plane).final_displacement;

  FrictionLaw law = plane.friction;
  law.type        = FrictionLaw::Type::steady_state;
  law.v0          = 1e-6;
  law.v_cutoff    = 1e-6;
  law.a_minus_b   = 0.;
  plane.friction  = law;
  EXPECT_NEAR(newmark_sliding(record, plane).final_displacement,
              d_coulomb,
              1e-12 * d_coulomb);

  double d[2] = {0., 0.};
  for (const int i : {0, 1})
    {
      plane.friction.a_minus_b = i == 0 ? 0.005 : -0.005;
      d[i]                = newmark_sliding(record, plane).final_displacement;
      plane.time_step     = 0.0005;
      const double d_fine = newmark_sliding(record, plane).final_displacement;
      plane.time_step     = 0.;
      EXPECT_NEAR(d_fine, d[i], 0.005 * d[i]);
      EXPECT_TRUE(std::isfinite(d[i]));
    }
  std::printf("rate dependence: strengthening %.5f m < Coulomb %.5f m < "
              "weakening %.5f m\n",
              d[0],
              d_coulomb,
              d[1]);
  EXPECT_LT(d[0], d_coulomb);
  EXPECT_GT(d[1], d_coulomb);
}



// Lift-off: a horizontal input beyond cot(alpha) makes the normal force
// negative; the analysis must stop with an error, not produce NaN.
TEST(Newmark, PlaneLiftOffIsAnError)
{
  NewmarkOptions plane;
  plane.yield_model = NewmarkOptions::YieldModel::plane;
  plane.dip_deg     = 30.;
  plane.friction    = FrictionLaw::coulomb_deg(35.);
  EXPECT_THROW(newmark_sliding(constant_record(2., 0.01, 11), plane),
               std::runtime_error);
}



// Bad input is an InputError naming the quantity.
TEST(Newmark, BadInput)
{
  const auto record = sine_record(0.5, 10., 0.01, 1.);
  const auto throws = [&](const NewmarkOptions &o, const std::string &word) {
    try
      {
        newmark_sliding(record, o);
        ADD_FAILURE() << "no InputError for " << word;
      }
    catch (const InputError &e)
      {
        EXPECT_NE(std::string(e.what()).find(word), std::string::npos)
          << e.what();
      }
  };
  NewmarkOptions o;
  o.time_step = -0.01;
  throws(o, "time step");
  o                 = NewmarkOptions();
  o.output_interval = -1.;
  throws(o, "output interval");
  o    = NewmarkOptions();
  o.ky = -0.1;
  throws(o, "ky");
  o.ky = std::nan("");
  throws(o, "ky");

  o                    = NewmarkOptions();
  o.yield_model        = NewmarkOptions::YieldModel::table;
  o.table_displacement = {0., 0.1, 0.1};
  o.table_ky           = {0.1, 0.1, 0.1};
  throws(o, "increasing");
  o.table_displacement = {0., 0.1};
  throws(o, "same number");
  o.table_displacement = {0., 0.1, 0.2};
  o.table_ky           = {0.1, -0.1, 0.1};
  throws(o, ">= 0 g");

  o             = NewmarkOptions();
  o.yield_model = NewmarkOptions::YieldModel::plane;
  o.dip_deg     = 90.;
  throws(o, "[0, 90)");
  o.dip_deg = -1.;
  throws(o, "[0, 90)");
  o.dip_deg  = 20.;
  o.friction = FrictionLaw::coulomb_deg(90.); // tan(pi/2) = 1.6e16
  throws(o, "friction angle");
  o.friction = FrictionLaw::coulomb_deg(100.); // negative coefficient
  throws(o, "friction angle");
  o.friction.mu0 = std::numeric_limits<double>::infinity();
  throws(o, "friction angle");
  o.friction      = FrictionLaw::coulomb_deg(30.);
  o.friction.type = FrictionLaw::Type::steady_state;
  o.friction.v0   = 0.;
  throws(o, "V0");

  // A record with a zero or negative time step.
  auto bad_dt = record;
  bad_dt.dt   = 0.;
  EXPECT_THROW(newmark_sliding(bad_dt, NewmarkOptions()), InputError);
  bad_dt.dt = -0.01;
  EXPECT_THROW(newmark_sliding(bad_dt, NewmarkOptions()), InputError);
  auto bad_value            = record;
  bad_value.acceleration[3] = std::nan("");
  EXPECT_THROW(newmark_sliding(bad_value, NewmarkOptions()), InputError);
}



// A record file with a non-numeric line: InputError naming the line.
TEST(Newmark, RecordFileWithJunkNamesTheLine)
{
  const std::string file_name
    = ::testing::TempDir() + "rockdda_newmark_bad_record.txt";
  {
    std::ofstream out(file_name);
    out << "0.01\n0.02\n-0.01\n0.0x3\n0.04\n";
  }
  try
    {
      seismic::read_record(file_name, 0.01);
      ADD_FAILURE() << "no InputError";
    }
  catch (const InputError &e)
    {
      const std::string message = e.what();
      EXPECT_NE(message.find(":4:"), std::string::npos) << message;
      EXPECT_NE(message.find("0.0x3"), std::string::npos) << message;
    }
  std::remove(file_name.c_str());
}
