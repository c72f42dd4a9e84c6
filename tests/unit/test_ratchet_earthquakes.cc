/**
 * @file
 * Earthquakes inside the coupled ratchet (issue 15, item 3): an episode
 * runs on the same DDA state as the thermal cycles
 * (RatchetRun::run_episode()). Without events the combined history is the
 * thermal run bit for bit; a motion below the yield acceleration leaves the
 * block where it was (up to the bedding joint's elastic give); a strong one
 * slides it downslope without the energy ledger gaining energy, opens the
 * crack, and the infill drops into the opening; bad input names the key.
 */
#include <rockdda/coupling/block1_seismic.h>
#include <rockdda/coupling/ratchet_earthquakes.h>
#include <rockdda/io/error.h>

#include <gtest/gtest.h>

#include "ratchet_test_helpers.h"
#include <cmath>
#include <string>
#include <vector>

using namespace rockdda;
using namespace rockdda::coupling;
using test_helpers::cheap_heat;
using test_helpers::expect_error_naming;

namespace
{
  constexpr double pi = 3.14159265358979323846;

  /// Block 1's horizontal yield acceleration (g) for the scene's
  /// materials: tan(phi - eta).
  double
  yield_acceleration(const RatchetGeometry &g, const RatchetMaterials &m)
  {
    return std::tan((m.bedding_friction_deg - g.block.slope_deg) * pi / 180.);
  }

  /// One scene, its heat solution and controls, shared by the tests.
  struct Fixture
  {
    RatchetGeometry          geometry;
    RatchetMaterials         materials;
    SeasonalForcing          forcing;
    RatchetScene             scene;
    PeriodicBlockTemperature temperature;
    RatchetControls          controls;

    Fixture()
        : scene(make_ratchet_scene(geometry, materials))
        , temperature(scene.heat_blocks, forcing, cheap_heat())
    {
      controls.threads = 1;
    }

    RatchetRun
    run() const
    {
      return RatchetRun(scene, temperature, forcing, 8e-6, controls);
    }
  };

  const Fixture &
  fixture()
  {
    static const Fixture f;
    return f;
  }

} // namespace



// A catalogue without events (a recurrence far beyond the window): the
// coupled history (run_ratchet_earthquakes(), its own RatchetRun) is the
// thermal run alone, bit for bit, year by year.
TEST(RatchetEarthquakes, NoEventsIsTheThermalRunBitForBit)
{
  const Fixture      &f       = fixture();
  const unsigned      cycles  = 2;
  RatchetRun          thermal = f.run();
  std::vector<double> yearly;
  for (unsigned k = 0; k < cycles; ++k)
    yearly.push_back(thermal.run_cycle().displacement);

  RatchetEarthquakeOptions o;
  o.catalogues      = 1;
  o.gr.recurrence   = 1e12;
  o.quakes_on_scene = false;
  Block1Geometry b1;
  static_cast<analytical::Block1Section &>(b1) = f.geometry.block;
  Block1Materials               b1m;
  const RatchetEarthquakeResult r = run_ratchet_earthquakes(
    f.scene, f.temperature, f.forcing, 8e-6, f.controls, cycles, b1, b1m, o);
  ASSERT_EQ(r.histories.size(), 1u);
  EXPECT_EQ(r.histories[0].events, 0u);
  EXPECT_TRUE(r.histories[0].failure.empty()) << r.histories[0].failure;
  EXPECT_EQ(r.histories[0].coupled, thermal.displacement());
  ASSERT_EQ(r.histories[0].yearly.size(), cycles);
  for (unsigned k = 0; k < cycles; ++k)
    EXPECT_EQ(r.histories[0].yearly[k], yearly[k]) << "year " << k + 1;
}



// Below the yield acceleration (half of k_y = tan(41 - 19 deg) = 0.404 g,
// 2 Hz, 3 s) the rigid block cannot slide: DDA moves it by the bedding
// joint's elastic give only. Its estimate: 0.2 g on Block 1's 2.5e5 kg/m
// over a 7 m joint of 1 GPa/m shear stiffness, 7e-5 m while shaken, less
// after; the bound is 1e-5 of the block's height (1.5e-4 m), twice that.
// Measured: 4.3e-6 m.
TEST(RatchetEarthquakes, BelowYieldTheBlockStays)
{
  const Fixture &f   = fixture();
  RatchetRun     run = f.run();
  run.run_cycle();
  const double          ky = yield_acceleration(f.geometry, f.materials);
  const seismic::Record a  = sinusoid_record(0.5 * ky, 2., 3., 0.005);
  EpisodeControls       ec;
  const EpisodeRecord   e = run.run_episode(a, ec);
  EXPECT_LT(std::abs(e.slip), 1e-5 * f.geometry.block.height) << e.slip;
  EXPECT_LT(std::abs(e.dynamic_slip), 1e-5 * f.geometry.block.height);
  // The thermal cycling resumes from the state the episode left.
  const CycleRecord c = run.run_cycle();
  EXPECT_EQ(c.cycle, 2u);
  EXPECT_EQ(run.cycles(), 2u);
}



// Well above the yield acceleration (0.8 g at 1.3 Hz, 2 s) the block slides
// down the bedding plane: the slip is positive, the time integration
// (Newmark beta = 1/2, gamma = 1) only dissipates, so the energy ledger's
// balance over the dynamic steps may not grow beyond 1e-6 of the energy in
// play (round-off of the ledger's sums; a spurious gain from, e.g., starting
// the dynamic steps with the static steps' velocities is of the order of
// the kinetic energy). The crack opens at the top (the block moves away
// from the cliff) and the infill, held by friction between the faces,
// drops into the opening; the supply rule then applies as after a cycle.
TEST(RatchetEarthquakes, StrongEventSlidesOpensTheCrackAndTheInfillDrops)
{
  const Fixture &f   = fixture();
  RatchetRun     run = f.run();
  run.run_cycle();
  const double          ky = yield_acceleration(f.geometry, f.materials);
  const seismic::Record a  = sinusoid_record(2. * ky, 1.3, 2., 0.005);
  EpisodeControls       ec;
  const double          d0 = run.displacement();
  const EpisodeRecord   e  = run.run_episode(a, ec);
  // Measured: 0.65 m (the rigid block alone on the same motion: 0.37 m;
  // DDA's block rocks, 4.7e-3 rad, as Block 1 alone does at Mw >= 7,
  // doc/theory/earthquakes.md); the ledger lost 8.3e4 of 2.3e6 J/m; the
  // crack opened by 0.61 m, the infill dropped 4.6 m.
  EXPECT_GT(e.dynamic_slip, 1e-3);
  EXPECT_GT(e.slip, 1e-3);
  EXPECT_NEAR(run.displacement() - d0, e.slip, 1e-12);
  EXPECT_LE(e.energy_gain, 1e-6 * e.energy_scale)
    << e.energy_gain << " of " << e.energy_scale;
  EXPECT_GT(e.dynamic_steps, 0u);
  // The crack opens by about the slip's horizontal part at the top.
  const double opening
    = e.slip * std::cos(f.geometry.block.slope_deg * pi / 180.);
  EXPECT_GT(e.aperture, 0.5 * opening) << e.aperture << " vs " << opening;
  EXPECT_GT(e.infill_descent, 0.);
  // The next cycle starts from that state.
  run.run_cycle();
  EXPECT_GT(run.displacement(), d0 + 0.5 * e.slip);
}



TEST(RatchetEarthquakes, BadInputNamesTheKey)
{
  const Fixture        &f   = fixture();
  RatchetRun            run = f.run();
  const seismic::Record a   = sinusoid_record(0.1, 2., 0.1, 0.005);
  {
    EpisodeControls ec;
    ec.time_step = 0.;
    expect_error_naming([&]() { run.run_episode(a, ec); },
                        "Ratchet earthquakes/Time step");
  }
  {
    EpisodeControls ec;
    ec.rest_time = -1.;
    expect_error_naming([&]() { run.run_episode(a, ec); },
                        "Ratchet earthquakes/Rest time");
  }
  {
    EpisodeControls ec;
    ec.contact_damping = -0.05;
    expect_error_naming([&]() { run.run_episode(a, ec); },
                        "Ratchet earthquakes/Contact damping ratio");
  }
  {
    RatchetEarthquakeOptions o;
    o.catalogues    = 1;
    o.gr.recurrence = -1.;
    Block1Geometry b1;
    expect_error_naming(
      [&]() {
        run_ratchet_earthquakes(f.scene,
                                f.temperature,
                                f.forcing,
                                8e-6,
                                f.controls,
                                1,
                                b1,
                                Block1Materials(),
                                o);
      },
      "Ratchet earthquakes/Recurrence interval");
  }
  // The engine's setters.
  dda::DdaSystem d(f.scene.blocks, dda::Controls());
  EXPECT_THROW(d.set_dynamic(1.5), InputError);
  dda::SeismicInput s;
  s.mode   = dda::SeismicInput::Mode::displacement;
  s.record = a;
  EXPECT_THROW(d.set_seismic_input(s, 0.), InputError);
}
