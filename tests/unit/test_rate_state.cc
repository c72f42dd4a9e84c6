/**
 * @file
 * Unit tests of the rate-and-state friction models (rate_state.h), the CVODE
 * wrapper (stiff_ode.h) and the friction back-analysis (back_analysis.h).
 *
 * Tolerances: the ODE tests run CVODE with rtol = 1e-10 to 1e-11 and
 * absolute tolerances several decades below the size of each unknown. The
 * global error of a BDF integration is typically 1-100 times the local
 * tolerance, so 1e-6 relative leaves at least two decades of margin while
 * still being far below any physically meaningful difference (the friction
 * jump A ln(V2/V1) is ~2e-2). Closed-form algebra (the friction jump, the
 * least-squares fit of exact data) is exact up to round-off and is tested at
 * 1e-12. The back-analysis bisects to 1e-9 degrees, so 1e-6 degrees leaves
 * three decades for the propagation of that error through later segments.
 */
#include <rockdda/analytical/back_analysis.h>
#include <rockdda/analytical/newmark.h>
#include <rockdda/analytical/rate_state.h>
#include <rockdda/analytical/stiff_ode.h>
#include <rockdda/io/error.h>

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <iostream>
#include <string>

using namespace rockdda;
using namespace rockdda::analytical;

namespace
{
  double
  relative_error(const double value, const double reference)
  {
    return std::abs(value - reference) / std::abs(reference);
  }

  /// A sinusoidal horizontal record, amplitude (g), frequency (Hz).
  seismic::Record
  sinusoid(const double amplitude,
           const double frequency,
           const double duration,
           const double dt)
  {
    seismic::Record record;
    record.name  = "sinusoid";
    record.dt    = dt;
    const auto n = static_cast<std::size_t>(std::llround(duration / dt)) + 1;
    for (std::size_t i = 0; i < n; ++i)
      record.acceleration.push_back(amplitude
                                    * std::sin(2. * M_PI * frequency * i * dt));
    return record;
  }
} // namespace



// ---------------------------------------------------------------- CVODE

TEST(StiffOde, StiffLinearSystemMatchesExactSolution)
{
  // y0' = -1e6 (y0 - cos t), y1' = -y1: a stiff and a non-stiff mode. The
  // exact y1 = e^{-t}; y0 tracks cos t up to O(1e-6).
  StiffOdeSettings settings;
  settings.relative_tolerance = 1e-10;
  settings.absolute_tolerance = 1e-14;
  StiffOdeSolver solver(
    [](const double t, const std::vector<double> &y, std::vector<double> &f) {
      f[0] = -1e6 * (y[0] - std::cos(t));
      f[1] = -y[1];
    },
    {1., 1.},
    0.,
    settings);
  const std::vector<double> &y = solver.advance(2.);
  EXPECT_LT(relative_error(y[1], std::exp(-2.)), 1e-8);
  EXPECT_NEAR(y[0], std::cos(2.) + 1e-6 * std::sin(2.), 1e-9);
  // Stiffness handled: an explicit method would need ~1e6 steps.
  EXPECT_LT(solver.n_steps(), 5000);
  EXPECT_EQ(solver.time(), 2.);
}

TEST(StiffOde, FailuresBecomeExceptions)
{
  // y' = y^2, y(0) = 1 blows up at t = 1: must throw, never return inf/NaN.
  StiffOdeSolver blow_up([](const double,
                            const std::vector<double> &y,
                            std::vector<double> &f) { f[0] = y[0] * y[0]; },
                         {1.},
                         0.);
  try
    {
      blow_up.advance(2.);
      FAIL() << "no exception";
    }
  catch (const OdeError &e)
    {
      std::cout << "  [blow-up message] " << e.what() << std::endl;
      EXPECT_NE(std::string(e.what()).find("CV"), std::string::npos);
    }

  // An exception in the right-hand side crosses the C library intact.
  StiffOdeSolver throwing(
    [](const double t, const std::vector<double> &, std::vector<double> &f) {
      if (t > 0.5)
        throw std::domain_error("rhs refused");
      f[0] = 1.;
    },
    {0.},
    0.);
  EXPECT_THROW(throwing.advance(1.), std::domain_error);

  EXPECT_THROW(StiffOdeSolver([](const double,
                                 const std::vector<double> &,
                                 std::vector<double> &) {},
                              {},
                              0.),
               std::invalid_argument);
}



TEST(StiffOde, EventFunctionsStopAtTheirRoots)
{
  // y0' = y1, y1' = -y0 (y0 = cos t): the event g = y0 has roots at
  // pi/2 (decreasing) and 3 pi/2 (increasing). Only increasing zeros are
  // requested, so the first reported root is 3 pi/2; advance_to_root never
  // steps past the output time.
  StiffOdeSettings settings;
  settings.relative_tolerance = 1e-10;
  settings.absolute_tolerance = 1e-12;
  StiffOdeSolver solver(
    [](const double, const std::vector<double> &y, std::vector<double> &f) {
      f[0] = y[1];
      f[1] = -y[0];
    },
    {1., 0.},
    0.,
    settings);
  solver.set_root_functions(1,
                            [](const double,
                               const std::vector<double> &y,
                               std::vector<double>       &g) { g[0] = y[0]; },
                            {+1});
  EXPECT_FALSE(solver.advance_to_root(3.));
  EXPECT_EQ(solver.time(), 3.);
  EXPECT_NEAR(solver.state()[0], std::cos(3.), 1e-8);
  ASSERT_TRUE(solver.advance_to_root(10.));
  EXPECT_NEAR(solver.time(), 1.5 * M_PI, 1e-8);
  EXPECT_EQ(solver.roots_found(), std::vector<int>{1});
  // Restart at the root (g = 0 there is ignored) and find the next one.
  const std::vector<double> y = solver.state();
  solver.reinit(solver.time(), y);
  ASSERT_TRUE(solver.advance_to_root(20.));
  EXPECT_NEAR(solver.time(), 3.5 * M_PI, 1e-7);
}



// ------------------------------------------------------- velocity step

TEST(RateState, VelocityStepJumpDecayAndSteadyState)
{
  RateStateParameters p; // mu0 0.6, A 0.010, B 0.015, V0 1e-6, Dc 1e-5
  StiffOdeSettings    settings;
  settings.relative_tolerance = 1e-11;
  settings.absolute_tolerance = 1e-15; // theta is 0.1 .. 100 s here

  for (const auto &[v1, v2] :
       std::vector<std::pair<double, double>>{{1e-6, 1e-5}, {1e-5, 1e-7}})
    {
      const double     decay = p.dc / v2; // s
      RateStateHistory h = velocity_step(p, v1, v2, 40. * decay, 800, settings);

      // Instantaneous jump A ln(V2/V1).
      const double jump     = h.mu.front() - steady_state_friction(p, v1);
      const double err_jump = relative_error(jump, p.a * std::log(v2 / v1));
      EXPECT_LT(err_jump, 1e-12);

      // New steady state mu0 + (A - B) ln(V2/V0), e^{-40} later.
      const double err_ss
        = relative_error(h.mu.back(),
                         p.mu0 + (p.a - p.b) * std::log(v2 / p.v0));
      EXPECT_LT(err_ss, 1e-6);

      // State decay over Dc/V2.
      double err_theta = 0.;
      for (std::size_t i = 0; i < h.time.size(); ++i)
        {
          const double exact
            = p.dc / v2
              + (p.dc / v1 - p.dc / v2) * std::exp(-h.time[i] / decay);
          err_theta = std::max(err_theta, relative_error(h.theta[i], exact));
        }
      EXPECT_LT(err_theta, 1e-6);
      std::cout << "  [velocity step " << v1 << " -> " << v2
                << "] rel. error: jump " << err_jump << ", steady state "
                << err_ss << ", max theta " << err_theta << std::endl;
    }
}



// ------------------------------------------------------- spring-slider

namespace
{
  StiffOdeSettings
  spring_slider_settings()
  {
    StiffOdeSettings s;
    s.relative_tolerance  = 1e-10;
    s.absolute_tolerances = {1e-16, 1e-12, 1e-12}; // m, ln V, ln theta
    return s;
  }
} // namespace

TEST(RateState, SpringSliderVelocityStrengtheningReachesSteadySliding)
{
  SpringSliderParameters p;
  p.friction.a          = 0.015;
  p.friction.b          = 0.010; // A > B: k_c < 0, always stable
  p.stiffness           = 1000.;
  p.load_point_velocity = 1e-6;
  p.initial_velocity    = 1e-7; // start far from steady state
  const RateStateHistory h
    = spring_slider(p, 3000., 3000, spring_slider_settings());
  const double err_v = relative_error(h.velocity.back(), 1e-6);
  const double err_mu
    = relative_error(h.mu.back(), steady_state_friction(p.friction, 1e-6));
  EXPECT_LT(err_v, 1e-6);
  EXPECT_LT(err_mu, 1e-6);
  std::cout << "  [spring-slider A > B] rel. error: V " << err_v << ", mu "
            << err_mu << std::endl;
}

TEST(RateState, SpringSliderStabilityChangesAtCriticalStiffness)
{
  // Ruina (1983): steady sliding is unstable for k < k_c = (B - A)/Dc.
  SpringSliderParameters p; // B > A
  const double           kc = critical_stiffness(p.friction);
  ASSERT_NEAR(kc, 500., 1e-9);
  p.load_point_velocity = 1e-6;
  p.initial_velocity    = 1.01e-6; // 1 % perturbation
  p.radiation_damping   = 0.5;     // G/(2 c_s sigma), bounds the slip rate

  const double duration = 3000.; // ~300 Dc/V_lp
  // Amplitude of ln(V/V_lp) over the last third of the run.
  const auto late_amplitude = [&](const RateStateHistory &h) {
    double amplitude = 0.;
    for (std::size_t i = 2 * h.time.size() / 3; i < h.time.size(); ++i)
      amplitude = std::max(amplitude, std::abs(std::log(h.velocity[i] / 1e-6)));
    return amplitude;
  };

  p.stiffness                     = 0.8 * kc;
  const RateStateHistory soft     = spring_slider(p, duration, 6000);
  const double           amp_soft = late_amplitude(soft);
  const double           v_max
    = *std::max_element(soft.velocity.begin(), soft.velocity.end());
  const double v_min
    = *std::min_element(soft.velocity.begin(), soft.velocity.end());
  // Stick-slip: the slip rate swings by orders of magnitude around V_lp.
  EXPECT_GT(v_max, 10. * 1e-6);
  EXPECT_LT(v_min, 0.1 * 1e-6);
  EXPECT_GT(amp_soft, std::log(1.01) * 10.);

  p.stiffness                      = 1.2 * kc;
  const RateStateHistory stiff     = spring_slider(p, duration, 6000);
  const double           amp_stiff = late_amplitude(stiff);
  // Decaying oscillation: much smaller than the 1 % initial perturbation.
  EXPECT_LT(amp_stiff, 0.1 * std::log(1.01));
  std::cout << "  [spring-slider] late |ln(V/Vlp)|: k = 0.8 kc " << amp_soft
            << " (V in [" << v_min << ", " << v_max << "] m/s), k = 1.2 kc "
            << amp_stiff << std::endl;
}



TEST(RateState, MaxSlipRateDoesNotDependOnTheOutputInterval)
{
  // Issue 11: max_slip_rate was the largest sampled slip rate, so it
  // depended on the output interval. It is now taken over every integrator
  // step. Stick-slip of a soft spring-slider (k = 0.8 kc): the peaks last a
  // tiny fraction of the period, and 30 samples miss them.
  SpringSliderParameters p;
  p.load_point_velocity         = 1e-6;
  p.initial_velocity            = 1.01e-6;
  p.radiation_damping           = 0.5;
  p.stiffness                   = 0.8 * critical_stiffness(p.friction);
  const RateStateHistory fine   = spring_slider(p, 3000., 6000);
  const RateStateHistory coarse = spring_slider(p, 3000., 30);
  const double           sampled_max_coarse
    = *std::max_element(coarse.velocity.begin(), coarse.velocity.end());
  for (const double v : fine.velocity)
    EXPECT_LE(v, fine.max_abs_velocity * (1. + 1e-12));
  EXPECT_LT(sampled_max_coarse, 0.5 * coarse.max_abs_velocity);
  EXPECT_LT(relative_error(coarse.max_abs_velocity, fine.max_abs_velocity),
            1e-3);
  std::cout << "  [max slip rate] every step: " << fine.max_abs_velocity
            << " / " << coarse.max_abs_velocity
            << " m/s (6000 / 30 outputs); sampled every 100 s: "
            << sampled_max_coarse << " m/s" << std::endl;
}



// ------------------------------------------------------- sliding block

TEST(RateState, SlidingBlockConstantFrictionLimit)
{
  // A -> 0, B = 0: mu = mu0 + A ln(V/V0) -> mu0 (A = 1e-12 changes mu by
  // ~1e-11, i.e. the displacement by ~1e-10 relative).
  SlidingBlockParameters p;
  p.friction.a       = 1e-12;
  p.friction.b       = 0.;
  p.friction.mu0     = 0.6;
  p.dip_deg          = 40.;
  p.initial_velocity = 1e-9; // m/s; see the closed form below
  StiffOdeSettings settings;
  settings.relative_tolerance  = 1e-11;
  settings.absolute_tolerances = {1e-14, 1e-12, 1e-10}; // m, w, ln theta
  const RateStateHistory h
    = sliding_block(p, seismic::Record(), 2., 0.01, settings);
  const double alpha = p.dip_deg * M_PI / 180.;
  const double a
    = p.gravity * (std::sin(alpha) - p.friction.mu0 * std::cos(alpha));
  double err = 0.;
  for (std::size_t i = 10; i < h.time.size(); ++i)
    {
      const double t     = h.time[i];
      const double exact = p.initial_velocity * t + 0.5 * a * t * t;
      err = std::max(err, relative_error(h.displacement[i], exact));
    }
  EXPECT_LT(err, 1e-6);
  std::cout << "  [sliding block, constant-friction limit] max rel. error "
            << err << std::endl;
}

TEST(RateState, SlidingBlockSteepSlopeAccelerates)
{
  SlidingBlockParameters p;                 // A 0.010 < B 0.015
  p.dip_deg = std::atan(0.7) * 180. / M_PI; // tan = 0.7 > mu0 = 0.6
  StiffOdeSettings settings;
  settings.relative_tolerance  = 1e-9;
  settings.absolute_tolerances = {1e-14, 1e-9, 1e-9};
  const RateStateHistory h
    = sliding_block(p, seismic::Record(), 2., 0.01, settings);
  for (std::size_t i = 1; i < h.time.size(); ++i)
    EXPECT_GT(h.velocity[i], h.velocity[i - 1]);
  // Velocity weakening: mu < mu0 once sliding fast, so the block gains speed
  // at least as fast as with Coulomb friction mu0 over the second second.
  const double alpha = p.dip_deg * M_PI / 180.;
  const double a_coulomb
    = p.gravity * (std::sin(alpha) - p.friction.mu0 * std::cos(alpha));
  const std::size_t half = h.time.size() / 2;
  EXPECT_GT((h.velocity.back() - h.velocity[half])
              / (h.time.back() - h.time[half]),
            a_coulomb);
  EXPECT_LT(h.mu.back(), p.friction.mu0);
}

TEST(RateState, SlidingBlockShallowSlopeCreepsAndHeals)
{
  SlidingBlockParameters p;
  p.dip_deg = std::atan(0.5) * 180. / M_PI; // tan = 0.5 < mu0 = 0.6
  // Creep at 1e-14 .. 1e-10 m/s is resolved only above the stick floor
  // (automatic: 1e-3 V0 = 1e-9 m/s); with gravity only the deceleration is
  // tiny, so a floor far below is resolvable.
  p.stick_velocity = 1e-20;
  StiffOdeSettings settings;
  settings.relative_tolerance  = 1e-8;
  settings.absolute_tolerances = {1e-20, 1e-8, 1e-8};
  const RateStateHistory h
    = sliding_block(p, seismic::Record(), 1000., 1., settings);
  // Creep: V decays (theta grows, aging), the slip stays microscopic.
  EXPECT_GT(h.velocity[1], 0.);
  EXPECT_LT(h.velocity[1], 1e-9);
  for (const std::size_t i :
       {std::size_t(1), std::size_t(10), std::size_t(100)})
    EXPECT_LT(h.velocity[10 * i], h.velocity[i]);
  EXPECT_LT(h.displacement.back(), 1e-6);
  EXPECT_GT(h.theta.back(), h.theta.front());
  std::cout << "  [sliding block, creep] V(1 s) " << h.velocity[1]
            << " m/s, V(1000 s) " << h.velocity.back() << " m/s, slip "
            << h.displacement.back() << " m" << std::endl;
}



TEST(RateState, SlidingBlockUnderSinusoidalRecord)
{
  // A record (2 Hz, 0.3 g, dip 20 deg, mu0 = tan 30 deg): stick-slip
  // cycles; the block never moves upslope (k_min = -0.3 g is far from
  // -tan(phi + alpha)), so the slip is non-decreasing, and the block slides
  // only while k exceeds roughly the yield value tan(phi - alpha). Stick is
  // an event of the integrator (issue 17): the block stops once per cycle of
  // the record.
  const seismic::Record  record = sinusoid(0.3, 2., 12., 0.005);
  SlidingBlockParameters p; // A 0.010, B 0.015
  p.friction.mu0 = std::tan(30. * M_PI / 180.);
  p.dip_deg      = 20.;
  StiffOdeSettings settings;
  settings.relative_tolerance  = 1e-6;
  settings.absolute_tolerances = {1e-10, 1e-8, 1e-8};
  const RateStateHistory h     = sliding_block(p, record, 12., 0.01, settings);
  for (std::size_t i = 1; i < h.time.size(); ++i)
    {
      EXPECT_GE(h.displacement[i], h.displacement[i - 1]);
      EXPECT_TRUE(std::isfinite(h.mu[i]));
    }
  EXPECT_GT(h.displacement.back(), 0.1);
  // At rest during the first 0.04 s (k < 0.15 g < yield ~ 0.176 g).
  EXPECT_LT(h.displacement[4], 1e-9);
  // 24 cycles of the record: the block starts at rest (its creep rate,
  // ~1e-16 m/s, is below the floor), then slips and stops once per cycle.
  EXPECT_EQ(h.velocity[0], 0.);
  EXPECT_EQ(h.n_stick_events, 25u);
  EXPECT_EQ(h.n_slip_events, 24u);
  std::cout << "  [sliding block, sinusoid] slip after 12 s "
            << h.displacement.back() << " m, " << h.n_stick_events
            << " stick / " << h.n_slip_events << " slip events, max slip rate "
            << h.max_abs_velocity << " m/s" << std::endl;
}

TEST(RateState, SlidingBlockCoulombLimitMatchesExactNewmark)
{
  // A -> 0, B = 0: the rate-and-state block tends to the rigid-plastic
  // Newmark block with mu0. While sliding at V_min <= V <= V_max,
  // mu_reg = mu0 + A ln(V/V0) (+ A/(4x^2), x ~ e^{mu0/A}: nil), and the
  // stick capacity is mu_reg(V_min) = mu_lo; so the friction always lies in
  // [mu_lo, mu_hi] = mu0 + A [ln(V_min/V0), ln(V_max/V0)], and by
  // comparison of the relative velocities the slip lies between the Newmark
  // slips with mu_hi and mu_lo. The relative acceleration
  // g [(sin a + k cos a) - mu (cos a - k sin a)] is
  // g (cos a + mu sin a)(k - ky(mu)), ky = tan(phi - a), so the exact
  // harmonic solution applies (Newmark 1965), with ky shifted by the error
  // eps = amplitude (omega dt)^2/8 of the linearly interpolated record.
  const double           amplitude = 0.3, frequency = 2., dt = 0.001;
  const double           omega  = 2. * M_PI * frequency;
  const seismic::Record  record = sinusoid(amplitude, frequency, 12., dt);
  SlidingBlockParameters p;
  p.friction.mu0 = std::tan(30. * M_PI / 180.);
  p.friction.a   = 1e-6;
  p.friction.b   = 0.;
  p.dip_deg      = 20.;
  StiffOdeSettings settings;
  settings.relative_tolerance  = 1e-9;
  settings.absolute_tolerances = {1e-12, 1e-9, 1e-9};
  const RateStateHistory h     = sliding_block(p, record, 12., 0.01, settings);

  const double alpha = p.dip_deg * M_PI / 180.;
  const double g     = p.gravity;
  const double v_min = 1e-3 * p.friction.v0; // the automatic stick floor
  const double mu_lo
    = p.friction.mu0 + p.friction.a * std::log(v_min / p.friction.v0);
  const double mu_hi
    = p.friction.mu0
      + p.friction.a * std::log(h.max_abs_velocity / p.friction.v0) + 1e-15;
  const double eps    = amplitude * std::pow(omega * dt, 2) / 8.;
  const auto   factor = [&](const double mu) {
    return g * (std::cos(alpha) + mu * std::sin(alpha));
  };
  const auto ky = [&](const double mu) {
    return (mu * std::cos(alpha) - std::sin(alpha))
           / (std::cos(alpha) + mu * std::sin(alpha));
  };
  const auto newmark = [&](const double mu,
                           const double shift,
                           const double t) {
    return factor(mu)
           * harmonic_sliding_displacement(amplitude, omega, ky(mu) + shift, t);
  };
  const HarmonicSliding cycle
    = harmonic_sliding_cycle(amplitude, omega, ky(p.friction.mu0));
  const double period = 1. / frequency;

  // Integration error: rtol = 1e-9 leaves the slip within ~1e-7 relative of
  // the exact solution of the ODE (test file header); 1e-6 is the slack.
  double       max_err = 0., max_bracket = 0.;
  unsigned int phase_mismatches = 0;
  for (std::size_t i = 1; i < h.time.size(); ++i)
    {
      const double t     = h.time[i];
      const double lower = newmark(mu_hi, eps, t);
      const double upper = newmark(mu_lo, -eps, t);
      const double exact = newmark(p.friction.mu0, 0., t);
      EXPECT_GE(h.displacement[i], lower * (1. - 1e-6) - 1e-12) << t;
      EXPECT_LE(h.displacement[i], upper * (1. + 1e-6) + 1e-12) << t;
      if (exact > 1e-3)
        {
          max_err = std::max(max_err, relative_error(h.displacement[i], exact));
          max_bracket = std::max(max_bracket, (upper - lower) / exact);
        }
      // Stick phases of Newmark: outside [t_start, t_stop] + n T. Compare
      // away from the switches (the bracket moves them by < 1e-3 s).
      const double tau     = std::fmod(t, period);
      const double d_start = std::abs(tau - cycle.t_start);
      const double d_stop  = std::abs(tau - cycle.t_stop);
      if (std::min(d_start, d_stop) > 2e-3)
        {
          const bool newmark_stuck = tau < cycle.t_start || tau > cycle.t_stop;
          if (newmark_stuck != (h.velocity[i] == 0.))
            ++phase_mismatches;
        }
    }
  EXPECT_EQ(phase_mismatches, 0u);
  // The bracket is tight: ~60 A + 2 eps in ky over (amplitude - ky).
  EXPECT_LT(max_bracket, 5e-3);
  // 24 cycles: the block starts at rest (tan 20 deg < mu_lo), slips and
  // stops once per cycle, as the Newmark block.
  EXPECT_EQ(h.n_slip_events, 24u);
  EXPECT_EQ(h.n_stick_events, 25u);
  std::cout << "  [sliding block, Coulomb limit A = 1e-6] slip after 12 s "
            << h.displacement.back() << " m, exact Newmark "
            << newmark(p.friction.mu0, 0., 12.) << " m, max rel. error "
            << max_err << " (bracket width " << max_bracket << "), "
            << h.n_stick_events << " stick / " << h.n_slip_events
            << " slip events" << std::endl;
}

TEST(RateState, SlidingBlockDeepStickThenPulses)
{
  // Held for 1e4 s (theta grows by aging to ~1e4 s: deep stick), then a
  // downslope pulse, a hold, and an upslope pulse strong enough to exceed
  // tan(phi + alpha). Before issue 17 such swings out of deep stick made
  // CVODE fail. Now loose and tight tolerances both pass, agree, and show
  // the physics: no slip during the hold, theta = theta0 + t (aging at
  // V = 0), downslope then upslope slip, and healing (the longer the hold,
  // the stronger the interface and the less the slip).
  const double dt = 0.02, hold = 1e4;
  const auto   make_record = [dt](const double hold_time) {
    seismic::Record r;
    r.name            = "hold and pulses";
    r.dt              = dt;
    const auto n_hold = static_cast<std::size_t>(std::llround(hold_time / dt));
    r.acceleration.assign(n_hold, 0.);
    for (int i = 0; i <= 25; ++i) // +0.6 g half-sine, 0.5 s
      r.acceleration.push_back(0.6 * std::sin(M_PI * i / 25.));
    for (int i = 0; i < 50; ++i) // 1 s at rest
      r.acceleration.push_back(0.);
    for (int i = 0; i <= 25; ++i) // -1.8 g half-sine, 0.5 s
      r.acceleration.push_back(-1.8 * std::sin(M_PI * i / 25.));
    for (int i = 0; i < 50; ++i)
      r.acceleration.push_back(0.);
    return r;
  };
  SlidingBlockParameters p; // A 0.010, B 0.015, theta0 = Dc/V0 = 10 s
  p.friction.mu0 = std::tan(30. * M_PI / 180.);
  p.dip_deg      = 20.;

  // Loose: rtol 1e-6. (At rtol 1e-5 it still runs, but the nucleation of
  // slip after the deep hold, where the friction drops by
  // B ln(theta/theta_ss) ~ 0.3 within a few Dc, is then resolved to ~10 %
  // only.)
  StiffOdeSettings loose;
  loose.relative_tolerance  = 1e-6;
  loose.absolute_tolerances = {1e-8, 1e-6, 1e-6};
  StiffOdeSettings tight;
  tight.relative_tolerance  = 1e-10;
  tight.absolute_tolerances = {1e-14, 1e-10, 1e-10};

  const seismic::Record record   = make_record(hold);
  const double          duration = hold + 3.;
  const std::size_t     i_hold   = static_cast<std::size_t>(hold / 0.5);
  std::vector<double>   slip_down, slip_final;
  for (const StiffOdeSettings &settings : {loose, tight})
    {
      RateStateHistory h;
      ASSERT_NO_THROW(h = sliding_block(p, record, duration, 0.5, settings));
      // The hold: the block creeps at V_balance ~ 1e-16 m/s, then sticks.
      EXPECT_LT(h.displacement[i_hold], 1e-9);
      EXPECT_EQ(h.velocity[i_hold], 0.);
      EXPECT_NEAR(h.theta[i_hold], 10. + hold, 1e-3 * hold);
      for (std::size_t i = 0; i < h.time.size(); ++i)
        EXPECT_TRUE(std::isfinite(h.mu[i]) && std::isfinite(h.theta[i]));
      // After the downslope pulse (t = hold + 1.5 s) and after the upslope
      // one (end).
      const double d_down = h.displacement[i_hold + 3];
      EXPECT_GT(d_down, 1e-3);
      EXPECT_LT(h.displacement.back(), d_down - 1e-3); // moved upslope
      EXPECT_EQ(h.velocity.back(), 0.);                // stuck again
      EXPECT_GE(h.n_slip_events, 2u);
      slip_down.push_back(d_down);
      slip_final.push_back(h.displacement.back());
      std::cout << "  [deep stick, rtol " << settings.relative_tolerance
                << "] theta after the hold " << h.theta[i_hold]
                << " s, slip after the downslope pulse " << d_down
                << " m, final " << h.displacement.back() << " m; "
                << h.n_stick_events << " stick / " << h.n_slip_events
                << " slip events" << std::endl;
    }
  // Loose and tight agree to 1e-3 (global error ~ 100 x rtol 1e-6, test
  // file header, plus the nucleation's sensitivity).
  EXPECT_LT(relative_error(slip_down[0], slip_down[1]), 1e-3);
  EXPECT_LT(std::abs(slip_final[0] - slip_final[1]),
            1e-3 * std::abs(slip_down[1]));

  // Healing: after a 10 s hold the same pulse slides the block further.
  const RateStateHistory short_hold
    = sliding_block(p, make_record(10.), 13., 0.5, tight);
  EXPECT_GT(short_hold.displacement[23], slip_down[1]);
  std::cout << "  [deep stick] slip after the downslope pulse: hold 10 s "
            << short_hold.displacement[23] << " m, hold 1e4 s " << slip_down[1]
            << " m" << std::endl;
}



// ------------------------------------------------------- back-analysis

TEST(BackAnalysis, RecoversPiecewiseFrictionAngles)
{
  const seismic::Record record = sinusoid(0.3, 2., 12., 0.005);
  const double          dip    = 20.;
  const ForwardModel forward = plane_sliding_forward_model(record, dip, 0.002);
  const std::vector<double> boundaries = {0., 4., 8., 12.};
  const std::vector<double> phi_true   = {30., 28., 26.};

  // Synthetic measurement: boundary values from segment-wise runs, plus
  // intermediate samples (run from the segment start) for realism.
  DisplacementHistory measured;
  SlidingState        state;
  measured.time.push_back(0.);
  measured.displacement.push_back(0.);
  for (std::size_t k = 0; k < phi_true.size(); ++k)
    {
      for (double t = boundaries[k] + 0.25; t < boundaries[k + 1] - 1e-9;
           t += 0.25)
        {
          measured.time.push_back(t);
          measured.displacement.push_back(
            forward(phi_true[k], state, boundaries[k], t).displacement);
        }
      state = forward(phi_true[k], state, boundaries[k], boundaries[k + 1]);
      measured.time.push_back(boundaries[k + 1]);
      measured.displacement.push_back(state.displacement);
    }
  ASSERT_GT(state.displacement, 0.01); // the block did slide

  const std::vector<SegmentFit> fits
    = back_analyse_friction_angles(measured, boundaries, forward);
  ASSERT_EQ(fits.size(), 3u);
  double err = 0.;
  for (std::size_t k = 0; k < fits.size(); ++k)
    {
      EXPECT_TRUE(fits[k].moved);
      EXPECT_TRUE(fits[k].bracketed);
      err = std::max(err, std::abs(fits[k].phi_deg - phi_true[k]));
      EXPECT_NEAR(fits[k].computed_displacement,
                  fits[k].measured_displacement,
                  1e-9);
    }
  EXPECT_LT(err, 1e-6);
  // Friction degradation -> faster sliding in later segments.
  EXPECT_GT(fits[2].average_velocity, fits[0].average_velocity);
  std::cout << "  [back-analysis] max |phi - phi_true| = " << err << " deg"
            << std::endl;
}

TEST(BackAnalysis, SteadyStateFitRecoversAMinusB)
{
  const double        mu0 = 0.62, amb = -0.008, v0 = 1e-6;
  std::vector<double> v = {2e-6, 2e-5, 1e-4, 1e-3, 3e-2};
  std::vector<double> mu;
  for (const double vi : v)
    mu.push_back(mu0 + amb * std::log(vi / v0));
  const SteadyStateFrictionFit fit = fit_steady_state_friction(v, mu, v0);
  EXPECT_NEAR(fit.a_minus_b, amb, 1e-12);
  EXPECT_NEAR(fit.mu0, mu0, 1e-12);
  EXPECT_NEAR(fit.r_squared, 1., 1e-12);
  EXPECT_LT(fit.a_minus_b_standard_error, 1e-12);
  EXPECT_EQ(fit.n_points, 5u);
  std::cout << "  [steady-state fit] |error| A-B "
            << std::abs(fit.a_minus_b - amb) << ", mu0 "
            << std::abs(fit.mu0 - mu0) << std::endl;

  // With scatter: positive standard errors, R^2 < 1, estimate still close.
  const std::vector<double> noise = {1e-3, -2e-3, 1.5e-3, -0.5e-3, 0.};
  for (std::size_t i = 0; i < mu.size(); ++i)
    mu[i] += noise[i];
  const SteadyStateFrictionFit noisy = fit_steady_state_friction(v, mu, v0);
  EXPECT_GT(noisy.a_minus_b_standard_error, 0.);
  EXPECT_GT(noisy.mu0_standard_error, 0.);
  EXPECT_LT(noisy.r_squared, 1.);
  EXPECT_NEAR(noisy.a_minus_b, amb, 3. * noisy.a_minus_b_standard_error);
}



// ------------------------------------------------------- bad input

namespace
{
  /// Expect InputError whose message contains @p key.
  template <typename F>
  void
  expect_input_error(F &&f, const std::string &key)
  {
    try
      {
        f();
        ADD_FAILURE() << "no InputError for " << key;
      }
    catch (const InputError &e)
      {
        EXPECT_NE(std::string(e.what()).find(key), std::string::npos)
          << e.what();
      }
  }
} // namespace

TEST(RateState, BadParametersThrowInputError)
{
  for (const double a : {0., -0.01})
    {
      RateStateParameters p;
      p.a = a;
      expect_input_error([&] { p.validate(); }, "rate_state.a");
      expect_input_error([&] { velocity_step(p, 1e-6, 1e-5, 1., 10); },
                         "rate_state.a");
    }
  for (const double dc : {0., -1e-5})
    {
      RateStateParameters p;
      p.dc = dc;
      expect_input_error([&] { p.validate(); }, "rate_state.dc");
    }
  RateStateParameters p;
  p.b = -0.1;
  expect_input_error([&] { p.validate(); }, "rate_state.b");
  p    = RateStateParameters();
  p.v0 = 0.;
  expect_input_error([&] { p.validate(); }, "rate_state.v0");
  p     = RateStateParameters();
  p.mu0 = std::nan("");
  expect_input_error([&] { p.validate(); }, "rate_state.mu0");
  expect_input_error(
    [&] { velocity_step(RateStateParameters(), -1e-6, 1e-5, 1., 10); },
    "velocity_step.v1");

  SlidingBlockParameters block;
  block.dip_deg = 90.;
  expect_input_error([&] { block.validate(); }, "sliding_block.dip");
  block = SlidingBlockParameters();
  for (const double v : {-1e-18, 1e-6, std::nan("")})
    {
      block.stick_velocity = v; // must be in [0, V0 = 1e-6)
      expect_input_error([&] { block.validate(); },
                         "sliding_block.stick_velocity");
    }
  SpringSliderParameters slider;
  slider.stiffness = 0.;
  expect_input_error([&] { slider.validate(); }, "spring_slider.stiffness");
}

TEST(BackAnalysis, BadInputThrowsInputError)
{
  const seismic::Record record = sinusoid(0.3, 2., 4., 0.01);
  const ForwardModel  forward  = plane_sliding_forward_model(record, 20., 0.01);
  DisplacementHistory measured;
  measured.time         = {0., 1., 2., 3., 4.};
  measured.displacement = {0., 0., 0.1, 0.2, 0.3};

  expect_input_error(
    [&] {
      back_analyse_friction_angles(measured, {0., 2., 2., 4.}, forward);
    },
    "back_analysis.segments[2]");
  expect_input_error(
    [&] {
      back_analyse_friction_angles(measured, {0., 3., 1.}, forward);
    },
    "back_analysis.segments[2]");
  expect_input_error(
    [&] { back_analyse_friction_angles(measured, {0.}, forward); },
    "back_analysis.segments");
  expect_input_error(
    [&] {
      back_analyse_friction_angles(measured, {0., 2., 5.}, forward);
    },
    "shorter than the segments");
  DisplacementHistory bad = measured;
  bad.displacement.pop_back();
  expect_input_error(
    [&] {
      back_analyse_friction_angles(bad, {0., 2.}, forward);
    },
    "measured history");

  expect_input_error(
    [] {
      fit_steady_state_friction({1e-6, 0., 1e-4}, {0.6, 0.6, 0.6});
    },
    "friction_fit.velocity[1]");
  expect_input_error(
    [] {
      fit_steady_state_friction({1e-6, -1e-5, 1e-4}, {0.6, 0.6, 0.6});
    },
    "friction_fit.velocity[1]");
  expect_input_error(
    [] {
      fit_steady_state_friction({1e-6, 1e-6, 1e-6}, {0.6, 0.6, 0.7});
    },
    "all velocities are equal");
  expect_input_error([] { plane_sliding_forward_model({}, 95., 0.01); },
                     "back_analysis.dip");
}
