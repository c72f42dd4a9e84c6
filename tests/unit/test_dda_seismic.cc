/**
 * @file
 * DDA seismic input from a processed record (issue 14, item 6): loading
 * (inertial) mode against the rigid two-way Newmark solution, equivalence of
 * loading and displacement mode, a vertical component changing the normal
 * force, and a baseline-corrected record low-passed at 2.5 Hz (Bakun-Mazor
 * 2011, Sec. 4.7.2) that leaves the foundation at rest.
 */
#include <rockdda/analytical/newmark.h>
#include <rockdda/dda/block_system.h>
#include <rockdda/dda/engine.h>
#include <rockdda/seismic/intensity.h>
#include <rockdda/seismic/processing.h>

#include <gtest/gtest.h>

#include "dda_test_scenes.h"
#include <cmath>
#include <cstdio>

using namespace rockdda;
using namespace rockdda::dda;
using namespace rockdda::dda::test_scenes;

namespace
{
  constexpr double record_dt = 1e-3;

  /// A record of @p n_steps + 1 samples of f(t) (g).
  template <typename F>
  seismic::Record
  sampled(const double dt, const unsigned int n_steps, const F &f)
  {
    seismic::Record r;
    r.name = "test";
    r.dt   = dt;
    for (unsigned int k = 0; k <= n_steps; ++k)
      r.acceleration.push_back(f(k * dt));
    return r;
  }

  /// A 1 m x 0.5 m block (block 1) on a horizontal fixed base 10 m x 1 m
  /// (block 0), friction @p phi (deg); squat enough not to rock below 2 g.
  BlockSystem
  flat_scene(const double phi)
  {
    BlockSystem s    = one_material_scene(2700., 1e10, 0.25, phi);
    const int   base = add_block(s, rectangle(-5., -1., 10., 1.));
    add_block(s, rectangle(-0.5, 0., 1., 0.5));
    fix_block(s, base);
    return s;
  }

  /// Run flat_scene() under the given records (g) in @p mode until @p T,
  /// after 50 static settling steps; returns the DDA system.
  std::unique_ptr<DdaSystem>
  run_flat(const SeismicInput::Mode mode,
           const double             phi,
           const seismic::Record   &horizontal,
           const seismic::Record   &vertical,
           const double             T,
           const double             dt = 1e-3)
  {
    BlockSystem s             = flat_scene(phi);
    s.seismic.mode            = mode;
    s.seismic.g               = g_earth;
    s.seismic.record          = horizontal;
    s.seismic.vertical_record = vertical;
    auto dda = std::make_unique<DdaSystem>(s, controls(dt, 1., 1e11));
    dda->settle(50);
    dda->run_until(T);
    return dda;
  }

  /// Horizontal slip (m) of the block relative to the base.
  double
  relative_slip(const DdaSystem &dda)
  {
    return (dda.centroid_displacement(1) - dda.centroid_displacement(0)).x();
  }
} // namespace

// (1) Loading mode: a block on a horizontal base with friction 20 deg under
// a(t) = 0.5 g (sin(2 pi t) + 0.4 sin(4 pi t + 0.7)) slides both ways (the
// second harmonic makes the two ways unequal: under a pure sine the net
// two-way slip vanishes by symmetry) (ky = tan 20 deg = 0.364 g);
// the rigid two-way Newmark solution (integrated at 1e-4 s) is the
// reference. The block feels -a(t) g, so it slides towards -x by the
// Newmark displacement. The DDA block is elastic and its contact is a
// penalty spring (1e11 N/m): 2 % covers the stick-slip timing at
// dt = 1 ms (measured 0.3 %).
TEST(DdaSeismic, LoadingModeMatchesTwoWayNewmark)
{
  const double phi = 20., A = 0.5, omega = 2. * M_PI, T = 2.;
  const auto   a = sampled(record_dt, 2100, [&](const double t) {
    return A * (std::sin(omega * t) + 0.4 * std::sin(2. * omega * t + 0.7));
  });
  const auto   dda
    = run_flat(SeismicInput::Mode::inertial, phi, a, seismic::Record(), T);

  analytical::NewmarkOptions o;
  o.direction        = analytical::NewmarkOptions::Direction::two_way;
  o.ky               = std::tan(phi * M_PI / 180.);
  o.time_step        = 1e-4;
  o.g                = g_earth;
  const auto   cut   = sampled(record_dt, 2000, [&](const double t) {
    return A * (std::sin(omega * t) + 0.4 * std::sin(2. * omega * t + 0.7));
  });
  const double exact = analytical::newmark_sliding(cut, o).final_displacement;
  const double d     = -relative_slip(*dda);
  std::printf("loading mode: DDA %.6f m, two-way Newmark %.6f m, error "
              "%.3e\n",
              d,
              exact,
              std::abs(d - exact) / std::abs(exact));
  EXPECT_GT(std::abs(exact), 0.05);
  EXPECT_LT(std::abs(d - exact) / std::abs(exact), 0.02);
  // The base stays put in loading mode.
  EXPECT_LT(dda->centroid_displacement(0).norm(), 1e-9);
}

// (2) The same scene in displacement mode: the base follows the double
// integral of a(t) (it drifts away at its mean velocity), and
// the slip relative to it equals the loading mode's: for a rigid base the
// two inputs are the same motion seen from two frames. 2 % (measured
// below 1 %).
TEST(DdaSeismic, DisplacementModeEqualsLoadingMode)
{
  const double phi = 20., A = 0.5, omega = 2. * M_PI, T = 2.;
  const auto   a = sampled(record_dt, 2100, [&](const double t) {
    return A * (std::sin(omega * t) + 0.4 * std::sin(2. * omega * t + 0.7));
  });
  const auto   load
    = run_flat(SeismicInput::Mode::inertial, phi, a, seismic::Record(), T);
  const auto disp
    = run_flat(SeismicInput::Mode::displacement, phi, a, seismic::Record(), T);
  const double d_load = relative_slip(*load), d_disp = relative_slip(*disp);
  std::printf("loading %.6f m, displacement %.6f m (base moved %.4f m), "
              "difference %.3e\n",
              d_load,
              d_disp,
              disp->centroid_displacement(0).x(),
              std::abs(d_disp - d_load) / std::abs(d_load));
  EXPECT_GT(disp->centroid_displacement(0).x(), 1.);
  EXPECT_NEAR(disp->centroid_displacement(0).x(),
              disp->ground_displacement(T).x(),
              1e-6);
  EXPECT_LT(std::abs(d_disp - d_load) / std::abs(d_load), 0.02);
}

// (3) A vertical ground acceleration a_v (positive upward) changes the
// normal force: the yield acceleration is (1 + a_v) tan(phi) g. Under a
// constant horizontal a_h = 0.9 tan(phi) g the block holds; with a_v =
// -0.2 (downward, effective gravity 0.8 g) it slides at (a_h - 0.8
// tan(phi)) g = 0.1 tan(phi) g, i.e. 0.05 tan(phi) g T^2 in T; with a_h =
// 1.1 tan(phi) g and a_v = +0.2 it holds again. Both modes.
TEST(DdaSeismic, VerticalComponentChangesYieldAcceleration)
{
  const double phi = 30., mu = std::tan(phi * M_PI / 180.), T = 1.;
  const auto   constant = [&](const double value) {
    return sampled(record_dt, 1200, [&](double) { return value; });
  };
  const double exact = 0.5 * 0.1 * mu * g_earth * T * T;
  for (const auto mode :
       {SeismicInput::Mode::inertial, SeismicInput::Mode::displacement})
    {
      const char *name
        = mode == SeismicInput::Mode::inertial ? "loading" : "displacement";
      const auto holds
        = run_flat(mode, phi, constant(0.9 * mu), seismic::Record(), T);
      const auto slides
        = run_flat(mode, phi, constant(0.9 * mu), constant(-0.2), T);
      const auto holds_up
        = run_flat(mode, phi, constant(1.1 * mu), constant(0.2), T);
      const double d = -relative_slip(*slides);
      std::printf("%s mode: slip without a_v %.3e m, with a_v = -0.2 g "
                  "%.6f m (exact %.6f m, error %.3e), 1.1 ky with a_v = "
                  "+0.2 g %.3e m\n",
                  name,
                  relative_slip(*holds),
                  d,
                  exact,
                  std::abs(d - exact) / exact,
                  relative_slip(*holds_up));
      EXPECT_LT(std::abs(relative_slip(*holds)), 1e-4) << name;
      EXPECT_LT(std::abs(relative_slip(*holds_up)), 1e-4) << name;
      EXPECT_LT(std::abs(d - exact) / exact, 0.02) << name;
      if (mode == SeismicInput::Mode::displacement)
        // The base follows both components: down by 0.1 g T^2.
        EXPECT_NEAR(slides->centroid_displacement(0).y(),
                    -0.1 * g_earth * T * T,
                    1e-6);
    }
}

// (4) Displacement mode with a record that drifts (a 0.005 g baseline
// offset under a broadband motion): as recorded, the foundation leaves at
// 0.38 m/s when the record ends; after a quadratic baseline correction and
// the acausal 2.5 Hz Butterworth low-pass (order 4, padding kept) it ends
// at rest: the final velocity is 1.5e-4 of the peak ground velocity (bound
// 1e-3; the correction zeroes it, and the filter's response beyond the
// kept padding, cut off, leaves this), and the foundation moves 3e-5 m in
// the second after the record (bound 1e-4 m; 0.38 m unprocessed).
TEST(DdaSeismic, FilteredRecordLeavesFoundationAtRest)
{
  const double T_record = 8.;
  const auto   raw
    = sampled(0.005, static_cast<unsigned>(T_record / 0.005), [](double t) {
        const double envelope = std::sin(M_PI * t / 8.);
        return 0.005
               + envelope
                   * (0.10 * std::sin(2. * M_PI * 0.9 * t)
                      + 0.08 * std::sin(2. * M_PI * 2.1 * t + 0.3)
                      + 0.06 * std::sin(2. * M_PI * 4.3 * t + 1.1)
                      + 0.05 * std::sin(2. * M_PI * 8.7 * t + 2.0));
      });
  seismic::ProcessingOptions options;
  options.baseline_degree         = 2;
  options.low_pass                = 2.5;
  options.order                   = 4;
  options.keep_padding            = true;
  const seismic::Record processed = seismic::process(raw, options);

  const GroundMotionIntegral raw_motion(raw, g_earth),
    motion(processed, g_earth);
  std::printf("final ground velocity: raw %.4e m/s, processed %.4e m/s "
              "(PGV %.4f m/s), drift %.4e m\n",
              raw_motion.final_velocity(),
              motion.final_velocity(),
              motion.peak_velocity(),
              motion.final_displacement());
  EXPECT_GT(std::abs(raw_motion.final_velocity()), 0.3);
  EXPECT_LT(std::abs(motion.final_velocity()), 1e-3 * motion.peak_velocity());

  // The low-pass leaves nothing above 2.5 Hz that the 8.7 Hz component
  // had: its amplitude 0.05 g is cut by (2.5 / 8.7)^4 to below 4e-4 g.
  const double          end    = processed.duration();
  const auto            dda    = run_flat(SeismicInput::Mode::displacement,
                            30.,
                            processed,
                            seismic::Record(),
                            end,
                            2e-3);
  const geometry::Point at_end = dda->centroid_displacement(0);
  dda->run_until(end + 1.);
  const geometry::Point later = dda->centroid_displacement(0);
  std::printf("foundation after the record (%.3f s): moved %.3e m in the "
              "next second; ground %.6f m, foundation %.6f m\n",
              end,
              (later - at_end).norm(),
              dda->ground_displacement(end + 1.).x(),
              later.x());
  EXPECT_LT((later - at_end).norm(), 1e-4);
  EXPECT_NEAR(later.x(), dda->ground_displacement(end + 1.).x(), 1e-6);
}
