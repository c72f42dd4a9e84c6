/**
 * @file
 * The contact dashpots of the 2D engine (dda::ContactDamping, keys
 * `Contact damping ratio` and `Contact step damping` of the `DDA`
 * section): a block ringing on its contact springs decays as
 * exp(-zeta omega t) whatever the step once zeta >> omega dt / 4 (Shi's own
 * numerical damping), a dropped block rebounds with the restitution of a
 * damped spring, the ledger books the dashpots' work, and static steps are
 * untouched.
 */
#include <rockdda/dda/contact_damping.h>
#include <rockdda/io/error.h>

#include <gtest/gtest.h>

#include "dda_test_scenes.h"
#include <cmath>
#include <cstdio>
#include <limits>
#include <string>
#include <tuple>
#include <vector>

using namespace rockdda;
using namespace rockdda::dda;
using test_scenes::g_earth;

namespace
{
  const double pi = std::acos(-1.);

  /// Block of the ring-down: w x h (m), density (kg/m^3), on a clamped
  /// base; contact penalty p (N/m; one spring per corner).
  constexpr double width = 1., height = 1., rho = 2700., penalty = 1e7;

  /// The mass of the block (kg/m) and the frequency (rad/s) of its
  /// vertical mode on its two corner springs (the block itself 1e4 times
  /// stiffer: E = 1e11 Pa).
  const double mass  = rho * width * height;
  const double omega = std::sqrt(2. * penalty / mass);

  /// What a ring-down measured.
  struct RingDown
  {
    /// Decay rate of the oscillation (1/s), from its extremes.
    double rate = 0.;
    /// Largest energy balance above the start (J/m) and the dashpots' work
    /// booked (J/m).
    double gain = 0., booked = 0.;
    /// Steps without a closed contact.
    unsigned long airborne = 0;
  };

  /**
   * Run @p s with @p c for @p periods periods of a mode of angular
   * frequency @p w and measure the decay rate of block @p b's centroid
   * coordinate @p axis (0: x, 1: y): u(t) = u_eq + A exp(-r t) cos(omega_d
   * t). The rate r from the differences of successive extremes of u (each
   * difference is the sum of two adjacent half-cycle amplitudes, so their
   * ratio is exp(-r T_d / 2) exactly for a linear oscillator, without
   * knowing u_eq); the ledger's largest gain over the start relative to
   * @p energy (J/m).
   */
  RingDown
  measure_ring_down(const BlockSystem &s,
                    const Controls    &c,
                    const int          b,
                    const int          axis,
                    const double       w,
                    const double       periods,
                    const double       energy)
  {
    const double        dt = c.time_step;
    DdaSystem           dda(s, c);
    const double        balance0 = dda.energy().balance();
    RingDown            r;
    std::vector<double> extreme_u, extreme_t;
    double              u_prev2 = 0., u_prev = 0.;
    const double        end = periods * 2. * pi / w;
    for (int k = 0; dda.time() < end - 1e-3 * dt; ++k)
      {
        const StepReport step = dda.step();
        r.airborne += step.n_sliding + step.n_locked == 0 ? 1 : 0;
        r.gain         = std::max(r.gain, dda.energy().balance() - balance0);
        const double u = dda.centroid_displacement(b)[axis];
        if (k >= 2 && (u - u_prev) * (u_prev - u_prev2) < 0.)
          {
            // The extreme of the parabola through the last three points.
            const double d2 = u - 2. * u_prev + u_prev2;
            const double x  = 0.5 * (u_prev2 - u) / d2;
            extreme_u.push_back(u_prev - 0.25 * (u - u_prev2) * x);
            extreme_t.push_back(dda.time() - dt + x * dt);
          }
        u_prev2 = u_prev;
        u_prev  = u;
      }
    r.gain /= energy;
    r.booked            = dda.energy().damping;
    const std::size_t n = extreme_u.size();
    EXPECT_GE(n, 6u) << "zeta " << c.contact_damping << ", omega dt " << w * dt;
    if (n >= 3)
      r.rate = -std::log(std::abs(extreme_u[n - 1] - extreme_u[n - 2])
                         / std::abs(extreme_u[1] - extreme_u[0]))
               / (0.5 * (extreme_t[n - 1] + extreme_t[n - 2])
                  - 0.5 * (extreme_t[1] + extreme_t[0]));
    return r;
  }

  /**
   * The normal ring-down: the 1 m block placed on its uncompressed corner
   * springs (p = 1e7 N/m) under gravity drops onto them and oscillates
   * vertically about the static sink m g / 2 p with the amplitude m g / 2 p,
   * at omega = sqrt(2 p / m) = 86 rad/s; with the contact ratio @p zeta and
   * the step omega dt = @p omega_dt, for @p periods periods.
   */
  RingDown
  ring_down(const double zeta, const double omega_dt, const double periods)
  {
    BlockSystem s = test_scenes::one_material_scene(rho, 1e11, 0.25, 60.);
    s.gravity     = geometry::Point(0., -g_earth);
    test_scenes::fix_block(
      s, test_scenes::add_block(s, test_scenes::rectangle(-2., -1., 4., 1.)));
    const int b = test_scenes::add_block(
      s, test_scenes::rectangle(-0.5 * width, 0., width, height));
    Controls c        = test_scenes::controls(omega_dt / omega, 1., penalty);
    c.contact_damping = zeta;
    c.solver.threads  = 1;
    return measure_ring_down(
      s, c, b, 1, omega, periods, mass * g_earth * height);
  }

  /**
   * The shear ring-down: a 2 x 0.5 m block (E = 1e11 Pa) on a joint of
   * shear stiffness k_j = 1e7 Pa/m (friction 80 deg: it never slides) over
   * its 2 m base, i.e. two corner contacts of k_s = k_j x 1 m in series with
   * the shear penalty 4e9 N/m (9.975e6 N/m each), starts at 0.01 m/s along
   * the joint: its centroid oscillates along x on the joint's shear springs
   * at omega_s = sqrt(2 k_s / m) = 86 rad/s (the normal springs of 1e10 N/m
   * and the rocking, 2.7e3 and 4.6e3 rad/s, are far above it).
   */
  RingDown
  shear_ring_down(const double zeta,
                  const double omega_dt,
                  const double periods,
                  double      &omega_s)
  {
    BlockSystem s = test_scenes::one_material_scene(rho, 1e11, 0.25, 80.);
    s.joints[0].shear_stiffness = 1e7;
    s.gravity                   = geometry::Point(0., -g_earth);
    test_scenes::fix_block(
      s, test_scenes::add_block(s, test_scenes::rectangle(-2., -1., 4., 1.)));
    const int b
      = test_scenes::add_block(s, test_scenes::rectangle(-1., 0., 2., 0.5));
    s.blocks[b].velocity[0] = 0.01;
    const double p          = 1e10;
    const double k_s        = 1. / (1. / (0.4 * p) + 1. / 1e7);
    const double m          = rho * 2. * 0.5;
    omega_s                 = std::sqrt(2. * k_s / m);
    Controls c              = test_scenes::controls(omega_dt / omega_s, 1., p);
    c.contact_damping       = zeta;
    c.solver.threads        = 1;
    return measure_ring_down(s, c, b, 0, omega_s, periods, m * g_earth * 0.5);
  }

  /// Result of one drop (DroppedBlockReboundsWithTheRestitutionOf...).
  struct Drop
  {
    /// Upward velocity after the rebound over the downward one before (-).
    double restitution = 0.;
    /// Kinetic energy before, lost, and booked by the dashpots (J/m).
    double kinetic = 0., lost = 0., booked = 0.;
    /// Largest energy balance over the run (J/m).
    double max_balance = -1e300;
    /// Contacts closed at the end.
    unsigned int closed = 0;
  };

  /**
   * A block 0.2 x 0.1 m (2700 kg/m^3, E 10 GPa) 1 mm above a clamped base,
   * without gravity, moving down at v0 = 0.1 m/s; its bottom face lands on
   * its 2 corners (springs p = 1e6 N/m each, 1e-4 of the block's own
   * stiffness E w / h: a rigid bounce) with the dashpot ratio @p zeta, and
   * leaves. The step resolves the bounce: omega dt = @p omega_dt.
   */
  Drop
  drop(const double zeta, const double omega_dt)
  {
    const double v0 = 0.1, p = 1e6, m = 2700. * 0.2 * 0.1;
    const double w = std::sqrt(2. * p / m);
    BlockSystem  s = test_scenes::one_material_scene(2700., 1e10, 0.25, 60.);
    s.gravity      = geometry::Point::Zero();
    test_scenes::fix_block(
      s, test_scenes::add_block(s, test_scenes::rectangle(-1., -1., 2., 1.)));
    const int b
      = test_scenes::add_block(s, test_scenes::rectangle(-0.1, 1e-3, 0.2, 0.1));
    s.blocks[b].velocity[1] = -v0;
    Controls c              = test_scenes::controls(omega_dt / w, 1., p);
    c.contact_damping       = zeta;
    c.solver.threads        = 1;
    DdaSystem dda(s, c);
    Drop      r;
    r.kinetic = dda.energy().kinetic;
    // Until 1 ms after the bounce's damped half period (plus the
    // approach).
    const double zb  = std::sqrt(2.) * zeta;
    const double end = 1e-3 / v0 + pi / (w * std::sqrt(1. - zb * zb)) + 1e-3;
    while (dda.time() < end - 1e-12)
      {
        dda.run_until(std::min(end, dda.time() + c.time_step));
        r.max_balance = std::max(r.max_balance, dda.energy().balance());
      }
    r.restitution = dda.system().blocks[b].velocity[1] / v0;
    r.lost        = r.kinetic - dda.energy().kinetic;
    r.booked      = dda.energy().damping;
    for (const auto &ct : dda.contacts())
      r.closed += ct.state == ContactState::open ? 0 : 1;
    return r;
  }
} // namespace



TEST(DdaContactDamping, RingDownDecaysAtTheDashpotRatioAtEveryStep)
{
  // Two modes of a block on two corner contacts: normal (the 1 m block
  // bouncing on its springs p = 1e7 N/m) and shear (the 2 x 0.5 m block on
  // a 1e7 Pa/m joint, the locked contacts' shear springs; the joint mode of
  // benchmarks/seismic-compare/README.md). The two dashpots c = 2 zeta
  // sqrt(k m) act in parallel on the mode (spring 2 k): its ratio of
  // critical is zeta_m = 2 c / (2 sqrt(2 k m)) = sqrt(2) zeta. Shi's step
  // (Newmark beta = 1/2, gamma = 1) with the dashpot has the amplification
  // determinant 2 / (2 + Omega^2 + 4 zeta_m Omega), Omega = omega dt
  // (doc/theory/dda3d.md, "Contact damping"): the discrete decay rate is
  // r_h = ln(1 + Omega^2 / 2 + 2 zeta_m Omega) / (2 dt) = omega (zeta_m +
  // Omega / 4) to first order. Checks:
  // - the measured rate is r_h within 1 % (a linear oscillator: the
  //   block is 1e4 times stiffer than the springs, shifting omega by
  //   5e-5; the other modes are 30-50 times faster; the extremes are
  //   interpolated to O(Omega^2));
  // - physics: r / omega is zeta_m within the scheme's Omega / 4 (and 1 %):
  //   at Omega = 0.02 and 0.01 the ring-down is the dashpot's, the
  //   numerical part 0.005 and 0.0025 against zeta_m = 0.071 and 0.141;
  // - so the two steps agree within Omega_1 / 4 + 1 %: step-independent;
  // - without dashpots the decay is the scheme's alone, Omega / 4, and
  //   vanishes with the step (halves with it, within 5 %);
  // - the block never leaves its springs, and the ledger creates no
  //   energy (balance <= 1e-9 of m g h above its start) with the dashpots'
  //   work booked (> 0 with dashpots, 0 without).
  for (const bool shear : {false, true})
    for (const double zeta : {0., 0.05, 0.1})
      {
        std::vector<double> ratio;
        for (const double omega_dt : {0.02, 0.01})
          {
            double         w = omega;
            const RingDown r = shear ? shear_ring_down(zeta, omega_dt, 6., w)
                                     : ring_down(zeta, omega_dt, 6.);
            const double   zeta_m = std::sqrt(2.) * zeta;
            const double   dt     = omega_dt / w;
            const double   r_h
              = std::log1p(0.5 * omega_dt * omega_dt + 2. * zeta_m * omega_dt)
                / (2. * dt);
            const double measured = r.rate / w;
            std::printf("%s, zeta %.2f (mode %.4f), omega dt %.3f: decay "
                        "rate / omega %.5f, scheme's exact %.5f (%.2e "
                        "relative), mode + omega dt / 4 %.5f; booked %.3e "
                        "J/m, gain %.2e of m g h, %lu steps in the air\n",
                        shear ? "shear" : "normal",
                        zeta,
                        zeta_m,
                        omega_dt,
                        measured,
                        r_h / w,
                        r.rate / r_h - 1.,
                        zeta_m + 0.25 * omega_dt,
                        r.booked,
                        r.gain,
                        r.airborne);
            EXPECT_NEAR(r.rate, r_h, 1e-2 * r_h);
            EXPECT_NEAR(measured, zeta_m, 0.25 * omega_dt + 1e-2 * r_h / w);
            EXPECT_EQ(r.airborne, 0u);
            EXPECT_LE(r.gain, 1e-9);
            if (zeta > 0.)
              {
                EXPECT_GT(r.booked, 0.);
              }
            else
              {
                EXPECT_EQ(r.booked, 0.);
              }
            ratio.push_back(measured);
          }
        EXPECT_NEAR(ratio[0], ratio[1], 0.25 * 0.02 + 1e-2 * ratio[0]);
        if (zeta == 0.)
          {
            // The scheme's damping halves with the step.
            EXPECT_NEAR(ratio[0] / ratio[1], 2., 0.1);
          }
      }
}



TEST(DdaContactDamping, DroppedBlockReboundsWithTheRestitutionOfADampedSpring)
{
  // The 2 corner springs p and dashpots c = 2 zeta sqrt(p m) in parallel:
  // the bounce is a spring 2 p with a dashpot 2 c, ratio of critical
  // zeta_b = sqrt(2) zeta. A contact opens when its spring force turns
  // tensile, at the end of the half period of the damped oscillation:
  // restitution e = exp(-zeta_b pi / sqrt(1 - zeta_b^2)); the kinetic
  // energy lost, 1 - e^2 of it, is what the dashpots book. Shi's scheme
  // adds its own damping (ratio omega dt / 4), and the contact closes and
  // opens at the end of a step, up to v0 dt inside the spring: an error of
  // order omega dt in e (relative): bound 3 omega dt, the undamped check
  // included. The energy lost beyond the booked part is the scheme's (>= 0,
  // about 2 pi omega dt / 4 of the kinetic energy: bound 2 omega dt).
  const double omega_dt = 3e-3;
  for (const double zeta : {0., 0.05, 0.1, 0.25})
    {
      const Drop   r      = drop(zeta, omega_dt);
      const double zb     = std::sqrt(2.) * zeta;
      const double exact  = std::exp(-zb * pi / std::sqrt(1. - zb * zb));
      const double scheme = r.lost - r.booked;
      std::printf("zeta %.2f (bounce %.3f): restitution %.5f, exact %.5f "
                  "(%.2e relative); kinetic energy lost %.4e J/m, booked "
                  "%.4e J/m, the scheme's %.2e of it; max balance %.3e "
                  "J/m\n",
                  zeta,
                  zb,
                  r.restitution,
                  exact,
                  r.restitution / exact - 1.,
                  r.lost,
                  r.booked,
                  scheme / r.kinetic,
                  r.max_balance);
      EXPECT_EQ(r.closed, 0u) << "the block must have left the base";
      EXPECT_NEAR(r.restitution, exact, 3. * omega_dt * exact);
      EXPECT_NEAR(r.booked,
                  r.kinetic * (1. - exact * exact),
                  2. * 3. * omega_dt * r.kinetic);
      EXPECT_GE(scheme, -1e-9 * r.kinetic);
      EXPECT_LE(scheme, 2. * omega_dt * r.kinetic);
      // No energy created: the ledger starts at the kinetic energy.
      EXPECT_LE(r.max_balance, r.kinetic * (1. + 1e-9));
      if (zeta == 0.)
        {
          EXPECT_EQ(r.booked, 0.);
        }
    }
}



TEST(DdaContactDamping, StaticStepsAreUntouchedByTheDashpots)
{
  // The dashpots act in dynamic steps only (ContactDamping): static steps
  // (dynamic control 0) of a brick wall settling under gravity, with
  // zeta = 0.3 and beta = 1, are those without dashpots bit for bit, and
  // book no damping; the same wall in dynamic steps is changed by them.
  for (const double dynamic : {0., 1.})
    {
      std::vector<BlockSystem> ends;
      std::vector<double>      booked;
      for (const double zeta : {0., 0.3})
        {
          BlockSystem s          = test_scenes::running_bond_wall(3, 3);
          s.gravity              = geometry::Point(0., -g_earth);
          Controls c             = test_scenes::controls(1e-3, dynamic, 1e11);
          c.contact_damping      = zeta;
          c.contact_step_damping = zeta > 0. ? 1. : 0.;
          c.solver.threads       = 1;
          DdaSystem dda(s, c);
          for (int k = 0; k < 20; ++k)
            dda.step();
          ends.push_back(dda.system());
          booked.push_back(dda.energy().damping);
        }
      const double diff = test_scenes::max_vertex_difference(ends[0], ends[1]);
      std::printf("dynamic %.0f: largest vertex difference with dashpots "
                  "%.3e m, booked %.3e J/m\n",
                  dynamic,
                  diff,
                  booked[1]);
      if (dynamic == 0.)
        {
          EXPECT_EQ(diff, 0.);
          EXPECT_EQ(booked[1], 0.);
        }
      else
        {
          EXPECT_GT(diff, 0.);
          EXPECT_GT(booked[1], 0.);
        }
    }
}



TEST(DdaContactDamping, NoRatioDashpotBetweenTwoClampedBlocks)
{
  // A contact between two clamped blocks (a foundation touching a clamped
  // cliff) moves no free block: the lighter free block's mass is infinite
  // and the ratio's dashpot 2 zeta sqrt(k m) would be too (it made the
  // ratchet scene's first dynamic step's load not finite). It is 0; the
  // step damping's beta k h / 2 stays. A free block keeps its own.
  const double         inf = std::numeric_limits<double>::infinity();
  const ContactDamping d(0.05, 0., 1e-3, 1.);
  EXPECT_EQ(d.dashpot(1e10, inf, inf), 0.);
  EXPECT_DOUBLE_EQ(d.dashpot(1e10, inf, 4.), 2. * 0.05 * std::sqrt(4e10));
  const ContactDamping beta(0.05, 1., 1e-3, 1.);
  EXPECT_DOUBLE_EQ(beta.dashpot(1e10, inf, inf), 0.5 * 1e10 * 1e-3);
}



TEST(DdaContactDamping, NegativeRatioIsAnErrorNamingIt)
{
  BlockSystem s = test_scenes::incline_scene(0., 30.);
  for (const auto &[zeta, beta, key] :
       {std::tuple<double, double, const char *>{-0.1,
                                                 0.,
                                                 "contact damping ratio"},
        {0., -1., "contact step damping"},
        {std::nan(""), 0., "contact damping ratio"}})
    {
      Controls c             = test_scenes::controls(1e-3, 1., 1e10);
      c.contact_damping      = zeta;
      c.contact_step_damping = beta;
      try
        {
          DdaSystem dda(s, c);
          ADD_FAILURE() << "no error for " << key;
        }
      catch (const InputError &e)
        {
          EXPECT_NE(std::string(e.what()).find(key), std::string::npos)
            << e.what();
        }
    }
}
