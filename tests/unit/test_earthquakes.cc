/**
 * @file
 * Masada Block 1 under earthquakes (issue 15, item 2): the physics the
 * `earthquakes` analysis rests on.
 */
#include <rockdda/coupling/block1_seismic.h>
#include <rockdda/coupling/concurrent_runs.h>
#include <rockdda/coupling/earthquakes.h>
#include <rockdda/io/error.h>
#include <rockdda/io/interrupt.h>

#include <gtest/gtest.h>

#include <cmath>
#include <csignal>

using namespace rockdda;
using namespace rockdda::coupling;

// Yield acceleration of Block 1 (19 deg bedding, 41 deg friction):
// tan(41 - 19) = 0.404 g, the thesis' value.
TEST(Earthquakes, YieldAccelerationOfBlock1)
{
  EXPECT_NEAR(block1_yield_acceleration(Block1Geometry(), Block1Materials()),
              std::tan(22. * M_PI / 180.),
              1e-12);
  EXPECT_NEAR(block1_yield_acceleration(Block1Geometry(), Block1Materials()),
              0.404,
              5e-4);
}

// A motion whose peak stays below the yield acceleration moves the block by
// no more than the elastic compliance of its contact (the rigid solution is
// exactly 0): a 0.3 g sinusoid (ky = 0.404 g) for 3 s at the calibrated
// penalty (100 GN/m) gives a slip below 1e-4 m (the penalty deflection
// of 0.3 g x the block's weight, ~2.5e6 N/m / 1e11 N/m = 2.5e-5 m, plus its
// vibration), while 0.6 g, beyond the yield, slides the block by
// centimetres in both DDA and the rigid solution, within 10 % of each other
// (the calibration's errors at this pair are 1-7 %). Measured: 5.3e-6 m at
// 0.3 g; 0.2048 m against 0.2041 m at 0.6 g.
TEST(Earthquakes, NoSlidingBelowTheYieldAcceleration)
{
  const Block1Geometry  g;
  const Block1Materials m;
  for (const double a : {0.3, 0.6})
    {
      const seismic::Record r   = sinusoid_record(a, 1.3, 3., 0.005);
      const Block1Run       run = run_block1_dda(
        g, m, r, dda::SeismicInput::Mode::inertial, 1e11, 0.005, 3.);
      const double exact = block1_analytical_slip(g, m, r, 3.);
      std::printf("%.1f g: DDA %.4e m, rigid block %.4e m\n",
                  a,
                  run.slip,
                  exact);
      if (a < 0.404)
        {
          EXPECT_EQ(exact, 0.);
          EXPECT_LT(std::abs(run.slip), 1e-4);
        }
      else
        {
          EXPECT_GT(exact, 1e-2);
          EXPECT_NEAR(run.slip / exact, 1., 0.1);
        }
    }
}

// The trigger distance is where the median PGA of the seeds falls to the
// yield acceleration: just inside it the median still reaches ky, just
// outside (beyond the bisection tolerance) it does not.
TEST(Earthquakes, TriggerDistanceIsWherePgaEqualsYield)
{
  const auto   motion = EarthquakeOptions::default_motion();
  const double ky     = 0.404;
  const double d      = trigger_distance(motion, 7., ky, 5, 1, 3e5, 10.);
  ASSERT_GT(d, 0.);
  EXPECT_GE(median_pga(motion, 7., d - 20., 5, 1), ky);
  EXPECT_LT(median_pga(motion, 7., d + 20., 5, 1), ky);
}

// Rates: one bin per magnitude, 1/T_i - 1/T_{i+1} events a year; a
// recurrence interval <= 0 or intervals that do not grow are errors naming
// the key.
TEST(Earthquakes, RatesFromRecurrenceIntervals)
{
  const auto bins
    = displacement_rate({6., 7.}, {0.001, 0.1}, {100., 1000.}, "key");
  ASSERT_EQ(bins.size(), 2u);
  EXPECT_NEAR(bins[0].annual_rate, 1. / 100. - 1. / 1000., 1e-15);
  EXPECT_NEAR(bins[1].annual_rate, 1. / 1000., 1e-15);
  EXPECT_NEAR(bins[0].rate + bins[1].rate,
              1e3 * (0.009 * 0.001 + 0.001 * 0.1),
              1e-12);
  for (const std::vector<double> &bad :
       {std::vector<double>{0., 1000.}, std::vector<double>{1000., 100.}})
    {
      try
        {
          displacement_rate({6., 7.}, {0.001, 0.1}, bad, "key");
          ADD_FAILURE() << "no error";
        }
      catch (const InputError &e)
        {
          EXPECT_NE(std::string(e.what()).find("key"), std::string::npos)
            << e.what();
        }
    }
}

// The shared runner of independent runs: every index runs exactly once
// whatever the number of threads.
TEST(ConcurrentRuns, EveryRunOnce)
{
  for (const unsigned int threads : {1u, 2u, 0u})
    {
      std::vector<int> count(57, 0);
      const auto       runs
        = run_concurrently(count.size(), threads, [&](const std::size_t i) {
            ++count[i];
          });
      EXPECT_EQ(runs.n_done(), count.size());
      EXPECT_EQ(runs.signal, 0);
      for (const int c : count)
        EXPECT_EQ(c, 1);
    }
}

// After SIGINT no further run starts: the runs done are kept and flagged,
// the others are not started.
TEST(ConcurrentRuns, InterruptStopsBetweenRuns)
{
  io::InterruptGuard guard;
  std::vector<int>   count(20, 0);
  const auto runs = run_concurrently(count.size(), 1, [&](const std::size_t i) {
    ++count[i];
    if (i == 4)
      std::raise(SIGINT);
  });
  io::clear_interrupt();
  EXPECT_EQ(runs.signal, SIGINT);
  EXPECT_EQ(runs.n_done(), 5u);
  for (std::size_t i = 0; i < count.size(); ++i)
    {
      EXPECT_EQ(count[i], i < 5 ? 1 : 0);
      EXPECT_EQ(runs.done[i], i < 5);
    }
}

// The events of run_earthquakes() are independent runs: on one and on two
// threads every number is the same to the bit (each DDA run uses one
// linear-solver thread and its own scene; the motions are made serially).
TEST(Earthquakes, SameResultsOnOneAndTwoThreads)
{
  EarthquakeOptions o;
  o.magnitudes   = {6.5, 7.};
  o.realisations = 2;
  std::vector<EarthquakeEvent> results[2];
  for (const unsigned int threads : {1u, 2u})
    {
      o.threads         = threads;
      unsigned int used = 0;
      results[threads - 1]
        = run_earthquakes(Block1Geometry(), Block1Materials(), o, &used);
      EXPECT_EQ(used, threads);
    }
  ASSERT_EQ(results[0].size(), 4u);
  ASSERT_EQ(results[1].size(), 4u);
  for (std::size_t j = 0; j < 4; ++j)
    {
      const auto &a = results[0][j], &b = results[1][j];
      EXPECT_TRUE(a.failure.empty()) << a.failure;
      EXPECT_EQ(a.seed, b.seed);
      EXPECT_EQ(a.pga, b.pga);
      EXPECT_EQ(a.dda, b.dda);
      EXPECT_EQ(a.analytical, b.analytical);
      EXPECT_EQ(a.max_rotation, b.max_rotation);
      EXPECT_EQ(a.steps, b.steps);
    }
}

// The key names of the one Block 1 runner are parameters: the earthquake
// analysis' errors name its own keys.
TEST(Earthquakes, RunnerNamesTheCallersKeys)
{
  Block1RunControls c;
  c.penalty       = -1.;
  c.penalty_key   = "Earthquakes/Penalty";
  c.time_step_key = "Earthquakes/Time step";
  c.section       = "Earthquakes";
  const auto rec  = sinusoid_record(0.5, 1.3, 0.1, 1e-3);
  try
    {
      run_block1_dda(Block1Geometry(), Block1Materials(), rec, c, 0.1);
      ADD_FAILURE() << "no error";
    }
  catch (const InputError &e)
    {
      EXPECT_NE(std::string(e.what()).find("Earthquakes/Penalty"),
                std::string::npos)
        << e.what();
    }
  Block1Geometry g;
  g.height  = 1.;
  c.penalty = 1e11;
  try
    {
      run_block1_dda(g, Block1Materials(), rec, c, 0.1);
      ADD_FAILURE() << "no error";
    }
  catch (const InputError &e)
    {
      EXPECT_NE(std::string(e.what()).find("Earthquakes/Block height"),
                std::string::npos)
        << e.what();
    }
}

// Pseudo-static rocking about the toe: Block 1 (L_B 7 m, H 15 m on 19 deg)
// tips at 0.42 g, just above its yield acceleration 0.404 g; a squat block
// (H 4 m) only at 1.19 g, a slender one (H 25 m) already at 0.26 g. (The
// centroids by hand: (3.602, 5.675) m for H 15 m; toe at (7, -2.410) m.)
TEST(Earthquakes, RockingAcceleration)
{
  Block1Geometry g;
  EXPECT_NEAR(block1_rocking_acceleration(g),
              (7. - 3.602) / (5.675 + 7. * std::tan(19. * M_PI / 180.)),
              1e-3);
  EXPECT_GT(block1_rocking_acceleration(g),
            block1_yield_acceleration(g, Block1Materials()));
  g.height = 4.;
  EXPECT_NEAR(block1_rocking_acceleration(g), 1.191, 1e-3);
  g.height = 25.;
  EXPECT_NEAR(block1_rocking_acceleration(g), 0.263, 1e-3);
}

// Why DDA and the rigid sliding block part at Mw >= 7 (issue 15, item 2):
// Block 1's rocking acceleration (0.42 g) is barely above its yield
// acceleration (0.404 g), and the strong pulses of Mw 7.5 at 1 km (PGA
// 0.9-1.0 g) make it rock as it slides: the heel lifts (rotations of
// 1e-3-5e-3 rad) and the slide-rock motion slides further than pure
// sliding (+39 % and +49 % on these two motions), a mode the rigid sliding
// block excludes. The same motions on a squat block (H = 4 m, rocking
// acceleration 1.19 g, everything else equal: the rigid solution does not
// depend on the block's shape) do not rock (rotation ~1e-6 rad) and DDA
// matches the rigid block within 1 % (measured 0.1-0.5 % over 12 Mw 7-7.5
// motions; the calibration's 1-7 % was for stick-slip of a block near
// yield). So the gap is physical, not a defect of DDA's contacts or time
// step: 10x the penalty or dt / 5 leave it (29-46 % and 51-116 % on these
// motions).
TEST(Earthquakes, GapAtLargeMagnitudesIsRocking)
{
  auto motion      = EarthquakeOptions::default_motion();
  motion.magnitude = 7.5;
  motion.distance  = 1e3;
  for (const std::uint64_t seed : {5u, 6u})
    {
      const seismic::Record rec = seismic::simulate(motion, seed, true);
      const double          T   = rec.duration();
      Block1Geometry        g;
      const Block1Materials m;
      const double          rigid = block1_analytical_slip(g, m, rec, T);
      Block1RunControls     c;
      const Block1Run       block1 = run_block1_dda(g, m, rec, c, T);
      g.height                     = 4.;
      const Block1Run squat        = run_block1_dda(g, m, rec, c, T);
      std::printf("Mw 7.5 seed %d: rigid %.4f m; Block 1 %.4f m (rotation "
                  "%.1e rad); squat %.4f m (rotation %.1e rad)\n",
                  static_cast<int>(seed),
                  rigid,
                  block1.slip,
                  block1.max_rotation,
                  squat.slip,
                  squat.max_rotation);
      EXPECT_GT(rigid, 0.05);
      EXPECT_NEAR(squat.slip / rigid, 1., 0.01);
      EXPECT_LT(squat.max_rotation, 1e-5);
      EXPECT_GT(block1.max_rotation, 1e-3);
      EXPECT_GT(block1.slip / rigid, 1.2);
    }
}
