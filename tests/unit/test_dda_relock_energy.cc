/**
 * @file
 * The energy ledger of a shaken stack whose contacts stick and slip while
 * their normal forces swing within a step (doc/theory/dda.md, "Force
 * continuity at lock"): a contact that slides into a step and locks in it
 * must not get a shear spring pre-stretched by the change of its normal
 * force within the step, elastic energy that no work paid for.
 */
#include <rockdda/dda/block_system.h>
#include <rockdda/dda/engine.h>

#include <gtest/gtest.h>

#include "dda_test_scenes.h"
#include <cmath>

using namespace rockdda;
using namespace rockdda::dda;
using namespace rockdda::dda::test_scenes;

namespace
{
  /// a sin(2 pi f t + phase) (g) sampled at 1 ms over @p T (s).
  seismic::Record
  sine(const double a, const double f, const double phase, const double T)
  {
    seismic::Record r;
    r.name = "sine";
    r.dt   = 1e-3;
    for (unsigned int k = 0; k * r.dt <= T; ++k)
      r.acceleration.push_back(a * std::sin(2. * M_PI * f * k * r.dt + phase));
    return r;
  }

  /// What a shaken run did: the largest gain of the ledger's balance in one
  /// step relative to the energy in play then, and the contacts that slid
  /// into a step and ended it locked.
  struct LedgerRun
  {
    double       worst_gain = -1e300;
    unsigned int relocks    = 0;
  };

  /// Three 1 m x 0.5 m blocks stacked on a fixed base (each shifted 0.1 m
  /// to the right of the one below), friction 30 deg, joint shear stiffness
  /// @p joint_shear (Pa/m) in series with the penalty @p penalty (N/m),
  /// shaken in loading mode for 1.5 s by 1.5 g at 3 Hz horizontally and
  /// @p vertical (g) at 7 Hz vertically, at the time step @p dt (s).
  LedgerRun
  shaken_stack(const double joint_shear,
               const double penalty,
               const double vertical,
               const double dt)
  {
    BlockSystem s               = one_material_scene(2700., 1e10, 0.25, 30.);
    s.joints[0].shear_stiffness = joint_shear;
    fix_block(s, add_block(s, rectangle(-5., -1., 10., 1.)));
    for (int k = 0; k < 3; ++k)
      add_block(s, rectangle(-0.5 + 0.1 * k, 0.5 * k, 1., 0.5));
    s.seismic.mode            = SeismicInput::Mode::inertial;
    s.seismic.record          = sine(1.5, 3., 0., 2.);
    s.seismic.vertical_record = sine(vertical, 7., 0.3, 2.);
    DdaSystem dda(s, controls(dt, 1., penalty));
    dda.settle(20);
    LedgerRun run;
    while (dda.time() < 1.5)
      {
        const double before = dda.energy().balance();
        dda.step();
        run.worst_gain
          = std::max(run.worst_gain,
                     (dda.energy().balance() - before) / dda.energy().scale());
        for (const Contact &c : dda.contacts())
          run.relocks += c.state_at_start == ContactState::sliding
                         && c.state == ContactState::locked;
      }
    return run;
  }
} // namespace

// The time integration (Newmark beta 1/2, gamma 1) only dissipates, so the
// balance kinetic + strain + contact + potential + friction - load work
// may not rise in a step beyond the ledger's residue across lock/slide
// changes: at most 1.8e-3 of the energy in play over 26 variants of this
// stack (joint shear 1e7-1e8 Pa/m, penalty 1e12-1e13 N/m, 1-5 ms, vertical
// 0.6-0.9 g). The limit is 1 % of the energy in play, as run.sh of
// benchmarks/seismic-compare checks the earthquake episodes. Soft joint
// springs in series with the penalty make a relocking contact's spring
// energy (dN tan(phi))^2 / (2 k_s) large: with the spring rebased on the
// strength of the current iteration (engine.cc before a8a85b1) these two
// stacks gained 5.0e-2 and 4.9e-2 of the energy in play in one step (with
// the step's start spring: 1.2e-3 and 5.4e-4).
TEST(DdaRelockEnergy, ShakenStackNeverGainsEnergy)
{
  for (const auto &[joint_shear, vertical, dt] :
       {std::tuple{1e7, 0.9, 2e-3}, std::tuple{1e8, 0.6, 1e-3}})
    {
      const LedgerRun run = shaken_stack(joint_shear, 1e12, vertical, dt);
      SCOPED_TRACE("joint shear " + std::to_string(joint_shear) + " Pa/m");
      // The scene exercises the rule: contacts slide into steps and lock.
      EXPECT_GT(run.relocks, 10u);
      EXPECT_LE(run.worst_gain, 1e-2);
    }
}
