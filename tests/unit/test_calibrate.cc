/**
 * @file
 * Calibration of DDA's numerical control on Masada Block 1 without infill
 * (thesis 5.5.2, issue 15 item 1): at the thesis' calibrated penalty and
 * time step (500 GN/m, 0.005 s) DDA reproduces the analytical sliding block
 * (Newmark 'plane' model: 19 deg dip, 41 deg friction, horizontal input)
 * under a 0.5 g sinusoid, and at that pair and at rockdda's own (100 GN/m,
 * 0.005 s: the pair of 'earthquakes' and 'compare') under the scaled El
 * Centro record, in loading and in displacement mode; bad grid values are
 * rejected naming the key.
 */
#include <rockdda/coupling/block1_seismic.h>
#include <rockdda/io/error.h>

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <utility>

using namespace rockdda;
using namespace rockdda::coupling;

namespace
{
  // The thesis' pair (Table 5-2).
  constexpr double calibrated_penalty = 5e11;  // N/m
  constexpr double calibrated_dt      = 0.005; // s
  // rockdda's pair, that of 'earthquakes' and 'compare': 100 GN/m is the
  // best penalty of the El Centro grid of benchmarks/seismic-calibration
  // (and of the sinusoid grid when it was first run).
  constexpr double rockdda_penalty = 1e11;  // N/m
  constexpr double rockdda_dt      = 0.005; // s

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
// (measured 0.97 % at 1.3 Hz and 1.85 % at 3.8 Hz; between 100 and 1000
// GN/m the grid of benchmarks/seismic-calibration scatters between 0.5 and
// 4.8 %, and scattered between 0.7 and 16 % before the DDA engine changes
// since commit 89b5630: the stick-slip timing within a step and the step cuts
// of the stiff contact, not a trend, so 15 % covers that floor as the contact
// algorithm moves it, not a tuned bound).
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
// pulses), all 39.5 s, at the thesis' pair (500 GN/m, 0.005 s) and at
// rockdda's (100 GN/m, 0.005 s): loading and displacement mode within 10 %
// of the analytical slip, issue 15's bound for DDA at the calibrated pair
// on a real record (measured at 500 GN/m: 1.62 % in loading and 1.91 % in
// displacement mode; at 100 GN/m: 1.99 % and 2.27 %). The bound is not
// tuned to these figures: at k >= 100 GN/m the El Centro grid of
// benchmarks/seismic-calibration spans 0.05-2.3 % and the sinusoid grid
// 0.5-4.8 % (0.7-16 % before the DDA engine changes since commit 89b5630), set
// by the stick-slip timing within a step, so the 10 % of issue 15 leaves room
// for that floor to move with the contact algorithm.
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
  const std::pair<double, double> pairs[]
    = {{calibrated_penalty, calibrated_dt}, {rockdda_penalty, rockdda_dt}};
  for (const auto &[k, dt] : pairs)
    for (const auto mode : {dda::SeismicInput::Mode::inertial,
                            dda::SeismicInput::Mode::displacement})
      {
        const auto  r    = run_block1_dda(g, m, rec, mode, k, dt, T);
        const char *name = mode == dda::SeismicInput::Mode::inertial
                             ? "loading"
                             : "displacement";
        std::printf("El Centro x 2.56, %g GN/m, dt = %g s, %s mode: DDA "
                    "%.5f m, analytical %.5f m, error %.2f %%, %.3f s\n",
                    k / 1e9,
                    dt,
                    name,
                    r.slip,
                    exact,
                    100. * relative_error(r.slip, exact),
                    r.wall_time);
        EXPECT_LT(relative_error(r.slip, exact), 0.10)
          << name << " mode, k = " << k << " N/m, dt = " << dt << " s";
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
