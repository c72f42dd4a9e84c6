/**
 * @file
 * The contact dashpots of the 3D engine (dda::ContactDamping, key
 * `Contact damping ratio`): the restitution of a damped spring and the
 * energy the dashpots book.
 */
#include <rockdda/dda/contact_damping.h>
#include <rockdda/dda3d/engine.h>
#include <rockdda/dda3d/generators.h>

#include <gtest/gtest.h>

#include "dda3d_test_scenes.h"
#include <cmath>
#include <cstdio>
#include <vector>

using namespace rockdda;
using namespace rockdda::dda3d;

namespace
{
  const double pi = std::acos(-1.);

  /// The 1 m cube (E = 1e13 Pa, a rigid block) resting on a clamped 6 x 3 x
  /// 1 m base under gravity: the scene of the stiff-mode tests.
  BlockSystem
  stiff_cube_on_base()
  {
    return test_scenes::incline_scene(0.,
                                      30.,
                                      Point(-3., -1.5, -1.),
                                      Point(3., 1.5, 0.),
                                      Point(-0.5, -0.5, 0.),
                                      Point(0.5, 0.5, 1.),
                                      {2700., 1e13, 0.25, 1})
      .system;
  }

  /// A box 0.2 x 0.2 x 0.1 m 1 mm above a clamped base, without gravity,
  /// moving down at @p v0 (m/s): the scene of the drop tests.
  BlockSystem
  falling_box(const double v0)
  {
    BlockSystem s = test_scenes::incline_scene(0.,
                                               30.,
                                               Point(-0.5, -0.5, -0.5),
                                               Point(0.5, 0.5, 0.),
                                               Point(-0.1, -0.1, 1e-3),
                                               Point(0.1, 0.1, 0.101),
                                               {2700., 1e10, 0.25, 1})
                      .system;
    s.gravity               = Point::Zero();
    s.blocks[1].velocity(2) = -v0;
    return s;
  }

  /// What 200 steps of a block resting on its contact springs show.
  struct Resting
  {
    /// Largest |total normal force / weight - 1| of a step after the
    /// first 20 (-), largest energy balance (J), largest speed of block 1
    /// after the first 20 steps (m/s).
    double worst = 0., balance = -1e300, speed = 0.;
  };

  /// Advance @p engine by 200 steps of @p dt with a block of weight
  /// @p weight (N) resting on the contacts.
  Resting
  rest_on_springs(Engine &engine, const double dt, const double weight)
  {
    Resting r;
    for (int k = 1; k <= 200; ++k)
      {
        engine.advance_to(k * dt);
        r.balance     = std::max(r.balance, engine.energy().balance());
        double normal = 0.;
        for (const auto &ct : engine.contacts())
          normal += ct.state == ContactState::open ? 0. : ct.normal_force;
        if (k > 20)
          {
            r.worst = std::max(r.worst, std::abs(normal / weight - 1.));
            r.speed
              = std::max(r.speed, engine.scene().blocks[1].velocity.norm());
          }
      }
    return r;
  }

  /// Result of one drop.
  struct Drop
  {
    /// Upward velocity after the rebound over the downward one before (-).
    double restitution = 0.;
    /// Kinetic energy before, lost, and booked by the dashpots (J).
    double kinetic = 0., lost = 0., booked = 0.;
    /// Largest energy balance over the run (J).
    double max_balance = -1e300;
    /// omega dt of the bounce (-).
    double omega_dt = 0.;
  };

  /**
   * A box 0.2 x 0.2 x 0.1 m (2700 kg/m^3, E 10 GPa) 1 mm above a clamped
   * base, without gravity, moving down at v0 = 0.1 m/s; its bottom face
   * lands on its 4 corners (springs p = 1e6 N/m each, 1e-3 of the box's own
   * stiffness E A / h: a rigid bounce) with the dashpot ratio @p zeta, and
   * leaves. The step resolves the bounce: omega dt = @p omega_dt.
   */
  Drop
  drop(const double zeta, const double omega_dt)
  {
    const double   v0    = 0.1;
    BlockSystem    s     = falling_box(v0);
    const double   m     = 2700. * 0.2 * 0.2 * 0.1;
    const double   p     = 1e6;
    const double   omega = std::sqrt(4. * p / m);
    EngineControls c;
    c.law.normal_penalty = p;
    c.contact_damping    = zeta;
    c.dt                 = omega_dt / omega;
    Engine engine(s, c);
    Drop   r;
    r.omega_dt = omega_dt;
    r.kinetic  = engine.energy().kinetic;
    // Until 1 ms after the bounce's half period (plus the approach).
    const double end = 1e-3 / v0 + pi / omega + 1e-3;
    while (engine.time() < end - 1e-12)
      {
        engine.advance_to(std::min(end, engine.time() + c.dt));
        r.max_balance = std::max(r.max_balance, engine.energy().balance());
      }
    const auto &b = engine.scene().blocks[1];
    r.restitution = b.velocity(2) / v0;
    r.lost        = r.kinetic - engine.energy().kinetic;
    r.booked      = engine.energy().damping;
    EXPECT_EQ(engine.statistics().open,
              engine.statistics().open + engine.statistics().locked
                + engine.statistics().sliding)
      << "the box must have left the base";
    return r;
  }
} // namespace



TEST(Dda3dContactDamping, DroppedBoxReboundsWithTheRestitutionOfADampedSpring)
{
  // The 4 corner springs k and dashpots c = 2 zeta sqrt(k m) act in
  // parallel: the bounce is a spring 4 k with a dashpot 4 c, ratio of
  // critical zeta_b = 4 c / (2 sqrt(4 k m)) = 2 zeta. A contact opens when
  // its spring force turns tensile, i.e. at the end of the half period of
  // the damped oscillation: restitution e = exp(-zeta_b pi / sqrt(1 -
  // zeta_b^2)); the kinetic energy lost, 1 - e^2 of it, is what the
  // dashpots book. Shi's scheme adds its own damping, ratio omega dt / 4
  // (doc/theory/dda3d.md), and the contact closes and opens at the end of
  // a step, up to v0 dt inside the spring: an error of order omega dt in e
  // (relative): bound 3 omega dt, the 0.3 % undamped check included. The
  // energy lost beyond the booked part is the scheme's (>= 0, <= 2 pi
  // omega dt / 4 of the kinetic energy, bound 2 omega dt).
  for (const double zeta : {0., 0.05, 0.1, 0.25})
    {
      const Drop   r      = drop(zeta, 1e-3 * 3.);
      const double zb     = 2. * zeta;
      const double exact  = std::exp(-zb * pi / std::sqrt(1. - zb * zb));
      const double scheme = r.lost - r.booked;
      std::printf("zeta %.2f (bounce %.2f): restitution %.5f, exact %.5f "
                  "(%.2e relative); kinetic energy lost %.4e J, booked %.4e "
                  "J, the scheme's %.2e of it; max balance %.3e J\n",
                  zeta,
                  zb,
                  r.restitution,
                  exact,
                  r.restitution / exact - 1.,
                  r.lost,
                  r.booked,
                  scheme / r.kinetic,
                  r.max_balance);
      EXPECT_NEAR(r.restitution, exact, 3. * r.omega_dt * exact);
      EXPECT_NEAR(r.booked,
                  r.kinetic * (1. - exact * exact),
                  2. * 3. * r.omega_dt * r.kinetic);
      EXPECT_GE(scheme, -1e-9 * r.kinetic);
      EXPECT_LE(scheme, 2. * r.omega_dt * r.kinetic);
      // No energy created: the ledger starts at the kinetic energy.
      EXPECT_LE(r.max_balance, r.kinetic * (1. + 1e-9));
      if (zeta == 0.)
        {
          EXPECT_EQ(r.booked, 0.);
        }
    }
}



TEST(Dda3dContactDamping, DashpotIsTwiceZetaSqrtKmOfTheLighterBlock)
{
  // c = 2 zeta sqrt(k m); 2 c / h its stiffness in Shi's step; none in a
  // static step.
  const dda::ContactDamping d(0.3, 0., 1e-3, 1.);
  EXPECT_DOUBLE_EQ(d.dashpot(4e6, 2., 9.), 2. * 0.3 * std::sqrt(4e6 * 2.));
  EXPECT_DOUBLE_EQ(d.stiffness(5.), 1e4);
  const dda::ContactDamping none(0.3, 1., 1e-3, 0.);
  EXPECT_FALSE(none.active());
  EXPECT_EQ(none.dashpot(4e6, 2., 9.), 0.);
}



TEST(Dda3dContactDamping, StepDampingRemovesTheAlternatingVelocityOfAStiffMode)
{
  // A 1 m cube (2700 kg/m^3) resting on a clamped base on its 4 corner
  // springs p = 1e11 N/m: its bounce has omega dt = sqrt(4 p / m) dt = 61
  // at dt = 5 ms. It starts on uncompressed springs and sinks by W / 4 p.
  // Undamped, Shi's update keeps a velocity that changes sign every step
  // (amplification -(Omega^2 - 4) / (Omega^2 + 2) = -0.998): the normal
  // force alternates about the weight by 2 m v / dt, 1e-3 W measured, for
  // the whole run. With the step damping beta = 1 both eigenvalues of the
  // mode are ~1 / Omega (doc/theory/dda3d.md): after 20 steps nothing is
  // left of it (Omega^-20), and every step's normal force equals the
  // weight but for the block's own strain mode, which the contact dashpots
  // do not touch (its corners do not move: 6e-9 W measured with E = 1e13
  // Pa, p / (E L) = 1e-2; with E = 1e10 Pa it is 5e-5 W). Bound 1e-6 W;
  // undamped the bound must fail (the check that the test can). The
  // ledger books the dashpots' work and creates no energy (balance <=
  // 1e-9 m g L above its start, 0).
  for (const double beta : {0., 1.})
    {
      const BlockSystem s = stiff_cube_on_base();
      EngineControls    c;
      c.dt                   = 0.005;
      c.law.normal_penalty   = 1e11;
      c.contact_step_damping = beta;
      Engine        engine(s, c);
      const double  weight = 2700. * 9.80665;
      const Resting r      = rest_on_springs(engine, c.dt, weight);
      const double  worst = r.worst, balance = r.balance;
      std::printf("beta %.0f: largest |normal force / weight - 1| of a step "
                  "after the first 20: %.3e; damping booked %.3e J, max "
                  "balance %.2e J\n",
                  beta,
                  worst,
                  engine.energy().damping,
                  balance);
      if (beta > 0.)
        {
          EXPECT_LT(worst, 1e-6);
        }
      else
        {
          EXPECT_GT(worst, 1e-6);
        }
      EXPECT_LT(balance, 1e-9 * weight * 1.);
    }
}



TEST(Dda3dContactDamping, StiffModeVelocityRestsABlockOnStiffSpringsAtOnce)
{
  // The scene of StepDampingRemovesTheAlternatingVelocityOfAStiffMode (1 m
  // cube on 4 corner springs p = 1e11 N/m, omega dt = 61), with the
  // stiff-mode velocity solve (EngineControls::stiff_velocity) instead of
  // dashpots. For one spring-mass mode of Omega = omega dt the velocity
  // solve's amplification matrix has both eigenvalues ~sqrt(2) / Omega
  // (doc/theory/dda3d.md, "Velocity of the stiff modes"): the mode is
  // gone after a few steps and every step's normal force equals the
  // weight, the exact static answer, but for round-off of the
  // 1e11 N/m springs (the block's own strain mode is in the solve too).
  // Bound 1e-6 W, which Shi's velocity fails (1e-3 W). The kinetic
  // energy it removes is booked as damping, >= 0, and the ledger creates
  // none.
  for (const bool stiff : {false, true})
    {
      const BlockSystem s = stiff_cube_on_base();
      EngineControls    c;
      c.dt                 = 0.005;
      c.law.normal_penalty = 1e11;
      c.stiff_velocity     = stiff;
      Engine        engine(s, c);
      const double  weight = 2700. * 9.80665;
      const Resting r      = rest_on_springs(engine, c.dt, weight);
      const double  worst = r.worst, balance = r.balance, speed = r.speed;
      std::printf("stiff-mode velocity %d: largest |normal force / weight - "
                  "1| of a step after the first 20: %.3e, largest |v| "
                  "%.3e; damping booked %.3e J, max balance %.2e J\n",
                  int(stiff),
                  worst,
                  speed,
                  engine.energy().damping,
                  balance);
      if (stiff)
        {
          EXPECT_LT(worst, 1e-6);
          EXPECT_GE(engine.energy().damping, 0.);
        }
      else
        {
          EXPECT_GT(worst, 1e-6);
          EXPECT_EQ(engine.energy().damping, 0.);
        }
      EXPECT_LT(balance, 1e-9 * weight * 1.);
    }
}



TEST(Dda3dContactDamping, StiffModeVelocityMakesAStiffImpactInelastic)
{
  // The dropped box of DroppedBoxReboundsWithTheRestitutionOfADampedSpring
  // (0.2 x 0.2 x 0.1 m, no gravity, v0 = 0.1 m/s onto 4 corner springs
  // p), two steps:
  // - stiff, p = 1e11 N/m, dt = 1 ms (omega dt = 190): Shi's velocity
  //   flips sign every step in the contact mode (amplification -1 +
  //   6 / Omega^2) and the box leaves with nearly v0 (restitution ~1); with
  //   the stiff-mode velocity the impact is that of a rigid, inelastic
  //   contact (Moreau): restitution 0 but for what the velocity solve
  //   leaves of a stiff mode, amplification sqrt(2) / Omega (bound
  //   2 / Omega = 1e-2 on |v| / v0), and the kinetic energy 1/2 m v0^2 is
  //   lost, booked as damping but for Shi's own loss k d^2 / 2 in the
  //   springs of the closing step (bound 1 % of it; >= 0);
  // - resolved, p = 1e6 N/m, omega dt = 3e-3: the velocity solve changes
  //   Shi's by O(Omega^2) (doc/theory/dda3d.md): the elastic bounce keeps
  //   restitution 1 within 3 Omega, as without it.
  const double v0 = 0.1, m = 2700. * 0.2 * 0.2 * 0.1;
  for (const double p : {1e11, 1e6})
    for (const bool stiff : {false, true})
      {
        BlockSystem    s     = falling_box(v0);
        const double   omega = std::sqrt(4. * p / m);
        EngineControls c;
        c.law.normal_penalty = p;
        c.stiff_velocity     = stiff;
        c.dt                 = p > 1e9 ? 1e-3 : 3e-3 / omega;
        Engine       engine(s, c);
        const double kinetic = engine.energy().kinetic;
        const double end     = 1e-3 / v0 + pi / omega + 20. * c.dt;
        double       balance = -1e300;
        while (engine.time() < end - 1e-12)
          {
            engine.advance_to(std::min(end, engine.time() + c.dt));
            balance = std::max(balance, engine.energy().balance());
          }
        const double e  = engine.scene().blocks[1].velocity(2) / v0;
        const auto  &st = engine.statistics();
        std::printf("p %.0e N/m (omega dt %.1e), stiff-mode velocity %d: "
                    "restitution %.5f, |v| / v0 %.2e, contacts open %d of "
                    "%d, damping booked %.6e of the kinetic energy, max "
                    "balance %.2e J\n",
                    p,
                    omega * c.dt,
                    int(stiff),
                    e,
                    engine.scene().blocks[1].velocity.norm() / v0,
                    st.open,
                    st.open + st.locked + st.sliding,
                    engine.energy().damping / kinetic,
                    balance);
        if (p > 1e9 && stiff)
          {
            EXPECT_LT(engine.scene().blocks[1].velocity.norm(),
                      2. / (omega * c.dt) * v0);
            EXPECT_NEAR(engine.energy().damping, kinetic, 1e-2 * kinetic);
            EXPECT_LE(engine.energy().damping, kinetic);
          }
        else if (p > 1e9)
          {
            EXPECT_GT(e, 0.9);
          }
        else
          {
            EXPECT_NEAR(e, 1., 3. * omega * c.dt);
          }
        EXPECT_LE(balance, kinetic * (1. + 1e-9));
      }
}



TEST(Dda3dContactDamping, StiffModeVelocityCarriesABlockStuckToAMovingBase)
{
  // Displacement mode: the clamped base of StiffModeVelocityRestsABlock...
  // follows u_g(t) = U (1 - cos w t) along x (U = 1 cm, 2 Hz: peak
  // acceleration U w^2 = 0.16 g, below tan 30 deg = 0.58 g: the cube
  // sticks). Exact: the cube moves with the ground, v = U w sin w t. The
  // contact modes are stiff (p = 1e11 N/m, omega dt = 61 normal, 39 in
  // shear): Shi's velocity keeps an alternating residual in them that the
  // start (the ground acceleration jumps to U w^2 at t = 0) excites and
  // nothing damps (measured 5.4e-5 m/s = 4e-4 U w). The velocity solve
  // leaves of it the factor 2 / (2 + Omega^2) per step (1.3e-3 in shear,
  // doc/theory/dda3d.md) and gives the base the exact ground velocity, so
  // the cube's velocity is the ground's but for the springs' elastic rate
  // (m U w^3 / 4 k_s = 3.3e-7 m/s): bound 1e-5 U w = 1.3e-6 m/s after the
  // first 20 steps, which Shi's fails; the base itself within 1e-6 U w
  // (the central difference of u_g). The cube's displacement relative to
  // the base is the shear springs' (m a / (4 k_s) ~ 3e-8 m) either way:
  // bound 1e-6 m.
  const double U = 0.01, w = 4. * pi;
  for (const bool stiff : {false, true})
    {
      const BlockSystem s = stiff_cube_on_base();
      EngineControls    c;
      c.dt                  = 0.005;
      c.law.normal_penalty  = 1e11;
      c.stiff_velocity      = stiff;
      c.ground_displacement = [&](const double t) {
        return Point(U * (1. - std::cos(w * t)), 0., 0.);
      };
      Engine engine(s, c);
      engine.settle(20);
      double worst = 0., base = 0., relative = 0.;
      for (int k = 1; k <= 200; ++k)
        {
          engine.advance_to(k * c.dt);
          const double t  = engine.time();
          const double vg = U * w * std::sin(w * t);
          const auto  &b  = engine.scene().blocks;
          if (k > 20)
            worst = std::max(worst, std::abs(b[1].velocity(0) - vg));
          if (stiff)
            base = std::max(base, std::abs(b[0].velocity(0) - vg));
          relative = std::max(
            relative, (engine.displacement(1) - engine.displacement(0)).norm());
        }
      std::printf("stiff-mode velocity %d: largest |v - v_g| of the cube "
                  "after 20 steps %.3e m/s (U w = %.3e), of the base %.3e "
                  "m/s; cube - base %.3e m\n",
                  int(stiff),
                  worst,
                  U * w,
                  base,
                  relative);
      if (stiff)
        {
          EXPECT_LT(worst, 1e-5 * U * w);
          EXPECT_LT(base, 1e-6 * U * w);
        }
      else
        {
          EXPECT_GT(worst, 1e-5 * U * w);
        }
      EXPECT_LT(relative, 1e-6);
    }
}
