/**
 * @file
 * Calibration of DDA's numerical control on Masada Block 1 without infill
 * (thesis 5.5.2, issue 15 item 1): at the calibrated penalty and time step
 * (500 GN/m, 0.005 s) DDA reproduces the analytical sliding block (Newmark
 * 'plane' model: 19 deg dip, 41 deg friction, horizontal input) under a
 * 0.5 g sinusoid and under the scaled El Centro record, in loading and in
 * displacement mode; bad grid values are rejected naming the key.
 */
#include <rockdda/coupling/block1_seismic.h>
#include <rockdda/io/error.h>

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

using namespace rockdda;
using namespace rockdda::coupling;

namespace
{
  constexpr double calibrated_penalty = 5e11;  // N/m
  constexpr double calibrated_dt      = 0.005; // s

  double
  relative_error(const double dda, const double exact)
  {
    return std::abs(dda - exact) / std::abs(exact);
  }
} // namespace

// The yield acceleration of 19 deg / 41 deg (thesis 5.5.3: 0.404 g).
TEST(Calibrate, YieldAcceleration)
{
  EXPECT_NEAR(block1_yield_acceleration(Block1Geometry(), Block1Materials()),
              0.404,
              5e-4);
}

// 0.5 g at 1.3 and 3.8 Hz for 5 s at the calibrated pair (the thesis'
// 500 GN/m, 0.005 s): the final slip is within 15 % of the analytical one
// (measured 7.4 % at 1.3 Hz and 1.7 % at 3.8 Hz; between 100 and 1000
// GN/m the grid of benchmarks/seismic-calibration scatters between 0.7 and
// 16 %: the stick-slip timing within a step and the step cuts of the stiff
// contact, not a trend, so 15 % is twice the measured error, not a tuned
// bound).
TEST(Calibrate, SinusoidAtCalibratedPair)
{
  const Block1Geometry  g;
  const Block1Materials m;
  for (const double f : {1.3, 3.8})
    {
      const auto   rec   = sinusoid_record(0.5, f, 5., 1e-3);
      const double exact = block1_analytical_slip(g, m, rec, 5.);
      const auto   r     = run_block1_dda(g,
                                    m,
                                    rec,
                                    dda::SeismicInput::Mode::inertial,
                                    calibrated_penalty,
                                    calibrated_dt,
                                    5.);
      std::printf("%.1f Hz: DDA %.5f m, analytical %.5f m, error %.2f %%, "
                  "rotation %.2e rad, %.3f s\n",
                  f,
                  r.slip,
                  exact,
                  100. * relative_error(r.slip, exact),
                  r.max_rotation,
                  r.wall_time);
      EXPECT_GT(exact, 0.01);
      EXPECT_LT(relative_error(r.slip, exact), 0.15) << f << " Hz";
    }
}

// El Centro 1940 (ELC-180, PGA 0.313 g) scaled to PGA 0.8 g (factor 2.56,
// about twice the yield acceleration, so that the block slides in several
// pulses), all 39.5 s: loading and displacement mode within 10 % of the
// analytical slip (measured 0.27 % in loading and 0.60 % in displacement
// mode).
TEST(Calibrate, ElCentroBothModes)
{
  auto rec = seismic::read_record(
    ROCKDDA_SHARED_DATA
    "/ground-motions/slammer/Imperial_Valley_1940_ELC-180.txt",
    0.01);
  ASSERT_NEAR(rec.peak(), 0.313, 1e-3);
  seismic::scale_to_pga(rec, 0.8);
  const Block1Geometry  g;
  const Block1Materials m;
  const double          T     = rec.duration();
  const double          exact = block1_analytical_slip(g, m, rec, T);
  EXPECT_GT(exact, 0.03);
  for (const auto mode : {dda::SeismicInput::Mode::inertial,
                          dda::SeismicInput::Mode::displacement})
    {
      const auto r
        = run_block1_dda(g, m, rec, mode, calibrated_penalty, calibrated_dt, T);
      const char *name = mode == dda::SeismicInput::Mode::inertial
                           ? "loading"
                           : "displacement";
      std::printf("El Centro x 2.56, %s mode: DDA %.5f m, analytical %.5f m, "
                  "error %.2f %%, %.3f s\n",
                  name,
                  r.slip,
                  exact,
                  100. * relative_error(r.slip, exact),
                  r.wall_time);
      EXPECT_LT(relative_error(r.slip, exact), 0.10) << name;
    }
}

// A penalty or a time step <= 0 is an InputError naming the key.
TEST(Calibrate, BadGridValues)
{
  const auto rec = sinusoid_record(0.5, 1.3, 0.1, 1e-3);
  const auto run = [&](const double k, const double dt) {
    run_block1_dda(Block1Geometry(),
                   Block1Materials(),
                   rec,
                   dda::SeismicInput::Mode::inertial,
                   k,
                   dt,
                   0.1);
  };
  try
    {
      run(0., 0.005);
      FAIL() << "no error for a zero penalty";
    }
  catch (const InputError &e)
    {
      EXPECT_NE(std::string(e.what()).find("'Calibration/Penalties'"),
                std::string::npos)
        << e.what();
    }
  try
    {
      run(5e11, -0.005);
      FAIL() << "no error for a negative time step";
    }
  catch (const InputError &e)
    {
      EXPECT_NE(std::string(e.what()).find("'Calibration/Time steps'"),
                std::string::npos)
        << e.what();
    }
}
