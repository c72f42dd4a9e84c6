#include <rockdda/analytical/rate_state.h>
#include <rockdda/io/error.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <memory>
#include <sstream>
#include <stdexcept>

namespace rockdda::analytical
{
  namespace
  {
    /// Equally spaced output times 0, T/n, ..., T.
    std::vector<double>
    output_times(const double duration, const unsigned int n_outputs)
    {
      std::vector<double> times(n_outputs + 1);
      for (unsigned int i = 0; i <= n_outputs; ++i)
        times[i] = duration * i / n_outputs;
      times.back() = duration;
      return times;
    }

    /// Psi = mu0 + B ln(theta V0/Dc), the state part of Eq. 2.1.
    double
    state_term(const RateStateParameters &p, const double theta)
    {
      return p.mu0 + p.b * std::log(theta * p.v0 / p.dc);
    }

    /// ln x with x = |V|/(2 V0) exp(Psi/A), the asinh argument; V != 0.
    double
    log_asinh_argument(const RateStateParameters &p,
                       const double               v,
                       const double               theta)
    {
      return std::log(std::abs(v) / (2. * p.v0)) + state_term(p, theta) / p.a;
    }

  } // namespace



  void
  RateStateParameters::validate() const
  {
    require_in_range(std::isfinite(mu0),
                     "rate_state.mu0",
                     mu0,
                     "a finite number");
    require_in_range(a > 0., "rate_state.a", a, "a > 0");
    require_in_range(b >= 0., "rate_state.b", b, "b >= 0");
    require_in_range(v0 > 0., "rate_state.v0", v0, "v0 > 0 (m/s)");
    require_in_range(dc > 0., "rate_state.dc", dc, "dc > 0 (m)");
  }



  double
  friction_coefficient(const RateStateParameters &p,
                       const double               v,
                       const double               theta)
  {
    if (!(v > 0.) || !(theta > 0.))
      throw std::domain_error(
        "friction_coefficient: Eq. 2.1 needs slip rate V > 0 and state "
        "theta > 0; use regularized_friction_coefficient at V <= 0");
    return p.mu0 + p.a * std::log(v / p.v0)
           + p.b * std::log(theta * p.v0 / p.dc);
  }



  double
  steady_state_friction(const RateStateParameters &p, const double v)
  {
    if (!(v > 0.))
      throw std::domain_error("steady_state_friction: needs V > 0");
    return p.mu0 + (p.a - p.b) * std::log(v / p.v0);
  }



  double
  steady_state_theta(const RateStateParameters &p, const double v)
  {
    if (!(v > 0.))
      throw std::domain_error("steady_state_theta: needs V > 0");
    return p.dc / v;
  }



  double
  aging_law_rate(const RateStateParameters &p,
                 const double               v,
                 const double               theta)
  {
    return 1. - std::abs(v) * theta / p.dc;
  }



  double
  regularized_friction_coefficient(const RateStateParameters &p,
                                   const double               v,
                                   const double               theta)
  {
    if (v == 0.)
      return 0.;
    const double log_x = log_asinh_argument(p, v, theta);
    // asinh(x) = ln(2x) + 1/(4x^2) + O(x^-4): for ln x > 20 the correction is
    // below 1e-18 and exp(log_x) might overflow, so use the logarithm.
    const double magnitude = (log_x > 20.) ? p.a * (log_x + std::log(2.))
                                           : p.a * std::asinh(std::exp(log_x));
    return v > 0. ? magnitude : -magnitude;
  }



  void
  regularized_friction_derivatives(const RateStateParameters &p,
                                   const double               v,
                                   const double               theta,
                                   double                    &dmu_dv,
                                   double                    &dmu_dln_theta)
  {
    if (v == 0.)
      {
        // d/dV A asinh(V/(2V0) e^{Psi/A}) at 0 = A/(2V0) e^{Psi/A}.
        const double log_value
          = std::log(p.a / (2. * p.v0)) + state_term(p, theta) / p.a;
        dmu_dv        = std::exp(std::min(log_value, 690.));
        dmu_dln_theta = 0.;
        return;
      }
    // With x = |V|/(2V0) e^{Psi/A} and r = x/sqrt(1+x^2):
    // dmu/dV = A r/|V|, dmu/dPsi = sign(V) r, dPsi/dln(theta) = B.
    const double log_x = log_asinh_argument(p, v, theta);
    const double sign  = v > 0. ? 1. : -1.;
    if (log_x >= 0.)
      {
        const double inv_x = std::exp(-log_x); // <= 1
        const double r     = 1. / std::sqrt(1. + inv_x * inv_x);
        dmu_dv             = p.a * r / std::abs(v);
        dmu_dln_theta      = sign * p.b * r;
      }
    else
      {
        // x < 1: dmu/dV = A/(2V0) e^{Psi/A} / sqrt(1+x^2), computed in
        // logarithms so that a tiny |V| cannot overflow A/|V|.
        const double x = std::exp(log_x);
        const double s = std::sqrt(1. + x * x);
        const double log_value
          = std::log(p.a / (2. * p.v0)) + state_term(p, theta) / p.a;
        dmu_dv        = std::exp(std::min(log_value, 690.)) / s;
        dmu_dln_theta = sign * p.b * x / s;
      }
  }



  double
  critical_stiffness(const RateStateParameters &p)
  {
    return (p.b - p.a) / p.dc;
  }



  RateStateHistory
  velocity_step(const RateStateParameters &p,
                const double               v1,
                const double               v2,
                const double               duration,
                const unsigned int         n_outputs,
                const StiffOdeSettings    &settings)
  {
    p.validate();
    require_in_range(v1 > 0., "velocity_step.v1", v1, "v1 > 0 (m/s)");
    require_in_range(v2 > 0., "velocity_step.v2", v2, "v2 > 0 (m/s)");
    require_in_range(duration > 0.,
                     "velocity_step.duration",
                     duration,
                     "> 0 (s)");
    require_in_range(n_outputs > 0,
                     "velocity_step.n_outputs",
                     n_outputs,
                     "at least 1");

    // Unknown: theta (s). d theta/dt = 1 - V2 theta/Dc (Eq. 2.2), which is
    // linear with Jacobian -V2/Dc.
    StiffOdeSolver solver(
      [&p, v2](const double,
               const std::vector<double> &y,
               std::vector<double>       &ydot) {
        ydot[0] = aging_law_rate(p, v2, y[0]);
      },
      {steady_state_theta(p, v1)},
      0.,
      settings,
      [&p, v2](const double,
               const std::vector<double> &,
               std::vector<double> &j) { j[0] = -v2 / p.dc; });

    RateStateHistory history;
    history.max_abs_velocity = v2;
    for (const double t : output_times(duration, n_outputs))
      {
        const double theta = solver.advance(t)[0];
        history.time.push_back(t);
        history.displacement.push_back(v2 * t);
        history.velocity.push_back(v2);
        history.theta.push_back(theta);
        history.mu.push_back(friction_coefficient(p, v2, theta));
      }
    return history;
  }



  void
  SpringSliderParameters::validate() const
  {
    friction.validate();
    require_in_range(load_point_velocity > 0.,
                     "spring_slider.load_point_velocity",
                     load_point_velocity,
                     "> 0 (m/s)");
    require_in_range(stiffness > 0.,
                     "spring_slider.stiffness",
                     stiffness,
                     "> 0 (1/m)");
    require_in_range(radiation_damping >= 0.,
                     "spring_slider.radiation_damping",
                     radiation_damping,
                     ">= 0 (s/m)");
    require_in_range(mass >= 0., "spring_slider.mass", mass, ">= 0 (s^2/m)");
    require_in_range(
      std::isfinite(initial_velocity),
      "spring_slider.initial_velocity",
      initial_velocity,
      "a finite number (m/s; <= 0 means the load-point velocity)");
    require_in_range(std::isfinite(initial_theta),
                     "spring_slider.initial_theta",
                     initial_theta,
                     "a finite number (s; <= 0 means steady state)");
  }



  RateStateHistory
  spring_slider(const SpringSliderParameters &p,
                const double                  duration,
                const unsigned int            n_outputs,
                const StiffOdeSettings       &settings)
  {
    p.validate();
    require_in_range(duration > 0.,
                     "spring_slider.duration",
                     duration,
                     "> 0 (s)");
    require_in_range(n_outputs > 0,
                     "spring_slider.n_outputs",
                     n_outputs,
                     "at least 1");
    const RateStateParameters &f   = p.friction;
    const double               vlp = p.load_point_velocity;
    const double               k   = p.stiffness;
    const double               eta = p.radiation_damping;
    const double v_init = p.initial_velocity > 0. ? p.initial_velocity : vlp;
    const double theta_init
      = p.initial_theta > 0. ? p.initial_theta : steady_state_theta(f, vlp);

    RateStateHistory history;
    if (p.mass == 0.)
      {
        // Quasi-static; unknowns y = (delta, ln V, ln theta).
        StiffOdeSolver solver(
          [&f, vlp, k, eta](const double,
                            const std::vector<double> &y,
                            std::vector<double>       &ydot) {
            const double v         = std::exp(y[1]);
            const double dln_theta = std::exp(-y[2]) - v / f.dc;
            ydot[0]                = v;
            ydot[1] = (k * (vlp - v) - f.b * dln_theta) / (f.a + eta * v);
            ydot[2] = dln_theta;
          },
          {0., std::log(v_init), std::log(theta_init)},
          0.,
          settings);
        history.max_abs_velocity = v_init;
        solver.set_step_observer(
          [&history](const double, const std::vector<double> &y) {
            history.max_abs_velocity
              = std::max(history.max_abs_velocity, std::exp(y[1]));
          });
        for (const double t : output_times(duration, n_outputs))
          {
            const std::vector<double> &y     = solver.advance(t);
            const double               v     = std::exp(y[1]);
            const double               theta = std::exp(y[2]);
            history.time.push_back(t);
            history.displacement.push_back(y[0]);
            history.velocity.push_back(v);
            history.theta.push_back(theta);
            history.mu.push_back(friction_coefficient(f, v, theta));
          }
      }
    else
      {
        // With inertia; unknowns y = (delta, V, ln theta); tau0 balances the
        // initial friction and damping.
        const double m = p.mass;
        const double tau0
          = regularized_friction_coefficient(f, v_init, theta_init)
            + eta * v_init;
        StiffOdeSolver solver(
          [&f, vlp, k, eta, m, tau0](const double               t,
                                     const std::vector<double> &y,
                                     std::vector<double>       &ydot) {
            const double theta = std::exp(y[2]);
            const double mu = regularized_friction_coefficient(f, y[1], theta);
            ydot[0]         = y[1];
            ydot[1] = (tau0 + k * (vlp * t - y[0]) - mu - eta * y[1]) / m;
            ydot[2] = std::exp(-y[2]) - std::abs(y[1]) / f.dc;
          },
          {0., v_init, std::log(theta_init)},
          0.,
          settings,
          [&f, k, eta, m](const double,
                          const std::vector<double> &y,
                          std::vector<double>       &j) {
            double dmu_dv = 0., dmu_dln_theta = 0.;
            regularized_friction_derivatives(
              f, y[1], std::exp(y[2]), dmu_dv, dmu_dln_theta);
            j[0 * 3 + 1] = 1.;
            j[1 * 3 + 0] = -k / m;
            j[1 * 3 + 1] = -(dmu_dv + eta) / m;
            j[1 * 3 + 2] = -dmu_dln_theta / m;
            j[2 * 3 + 1] = -(y[1] > 0. ? 1. : (y[1] < 0. ? -1. : 0.)) / f.dc;
            j[2 * 3 + 2] = -std::exp(-y[2]);
          });
        history.max_abs_velocity = std::abs(v_init);
        solver.set_step_observer(
          [&history](const double, const std::vector<double> &y) {
            history.max_abs_velocity
              = std::max(history.max_abs_velocity, std::abs(y[1]));
          });
        for (const double t : output_times(duration, n_outputs))
          {
            const std::vector<double> &y     = solver.advance(t);
            const double               theta = std::exp(y[2]);
            history.time.push_back(t);
            history.displacement.push_back(y[0]);
            history.velocity.push_back(y[1]);
            history.theta.push_back(theta);
            history.mu.push_back(
              regularized_friction_coefficient(f, y[1], theta));
          }
      }
    return history;
  }



  void
  SlidingBlockParameters::validate() const
  {
    friction.validate();
    require_in_range(dip_deg >= 0. && dip_deg < 90.,
                     "sliding_block.dip",
                     dip_deg,
                     "0 <= dip < 90 (degrees)");
    require_in_range(gravity > 0.,
                     "sliding_block.gravity",
                     gravity,
                     "> 0 (m/s^2)");
    require_in_range(std::isfinite(initial_velocity),
                     "sliding_block.initial_velocity",
                     initial_velocity,
                     "a finite number (m/s)");
    require_in_range(velocity_scale >= 0.,
                     "sliding_block.velocity_scale",
                     velocity_scale,
                     ">= 0 (m/s; 0 = automatic)");
    require_in_range(std::isfinite(initial_theta),
                     "sliding_block.initial_theta",
                     initial_theta,
                     "a finite number (s; <= 0 means Dc/V0)");
    require_in_range(stick_velocity >= 0. && stick_velocity < friction.v0,
                     "sliding_block.stick_velocity",
                     stick_velocity,
                     "0 <= stick_velocity < v0 (m/s; 0 = automatic, "
                     "1e-12 v0)");
  }



  RateStateHistory
  sliding_block(const SlidingBlockParameters &p,
                const seismic::Record        &record,
                const double                  duration,
                const double                  output_interval,
                const StiffOdeSettings       &settings)
  {
    p.validate();
    require_in_range(duration > 0.,
                     "sliding_block.duration",
                     duration,
                     "> 0 (s)");
    require_in_range(output_interval > 0.,
                     "sliding_block.output_interval",
                     output_interval,
                     "> 0 (s)");
    if (!record.acceleration.empty())
      require_in_range(record.dt > 0., "record.dt", record.dt, "> 0 (s)");

    const RateStateParameters &f     = p.friction;
    const double               alpha = p.dip_deg * M_PI / 180.;
    const double               sin_a = std::sin(alpha);
    const double               cos_a = std::cos(alpha);
    const double               g     = p.gravity;
    const double               theta_init
      = p.initial_theta > 0. ? p.initial_theta : f.dc / f.v0;

    // Normal force per unit mass over g, cos a - k sin a; must stay > 0.
    const auto normal = [&record, sin_a, cos_a](const double t) {
      const double n = cos_a - record.at(t) * sin_a;
      if (!(n > 0.))
        {
          std::ostringstream message;
          message << "sliding_block: the normal force vanishes at t = " << t
                  << " s (k = " << record.at(t)
                  << " g): the block lifts off the plane";
          throw std::domain_error(message.str());
        }
      return n;
    };

    StiffOdeSettings ode_settings = settings;
    if (ode_settings.max_step == 0. && !record.acceleration.empty())
      ode_settings.max_step = record.dt;

    // Unknowns y = (delta, w, ln theta) with V = V_s sinh(w): w is linear in
    // V for |V| << V_s and ~ ln(2V/V_s) for |V| >> V_s, so that the error
    // control is relative in V over the tens of decades V spans (creep,
    // stick, slip) and mu_reg is nearly linear in w for the Newton
    // iterations.
    // V_s = V* = 2 V0 exp(-Psi/A) at the initial state unless given: then
    // w = mu/A exactly while theta keeps its initial value.
    const double vs
      = p.velocity_scale > 0.
          ? p.velocity_scale
          : std::clamp(2. * f.v0 * std::exp(-state_term(f, theta_init) / f.a),
                       1e-280,
                       f.v0);
    // asinh(V/V_s) for V > 0, in logarithms (V/V_s may overflow).
    const auto w_of = [vs](const double v) {
      const double l = std::log(v) - std::log(vs);
      return l > 30. ? l + std::log(2.) : std::asinh(std::exp(l));
    };

    // Stick floor and the stick/slip criterion. S = sin a + k cos a is the
    // driving force and N = cos a - k sin a the normal force per unit
    // weight; the capacity at the floor is c(theta) = mu_reg(V_min, theta).
    // excess(t, theta) = |S| - c N > 0: the block cannot be held.
    // The automatic floor is 1e-3 V0, but at least the slip rate that an
    // acceleration of g changes in 1000 round-off units of the time: a stop
    // (V -> 0 at a finite deceleration) must be resolvable in double
    // precision, and round-off in the force balance, divided by V in
    // dw/dt, must stay far below the tolerances.
    const double v_min
      = p.stick_velocity > 0.
          ? p.stick_velocity
          : std::max(1e-3 * f.v0,
                     1e3 * g * std::numeric_limits<double>::epsilon()
                       * std::max(duration, 1.));
    const double w_min   = w_of(v_min);
    const auto   driving = [&record, sin_a, cos_a](const double t) {
      return sin_a + record.at(t) * cos_a;
    };
    const auto excess = [&](const double t, const double theta) {
      return std::abs(driving(t))
             - regularized_friction_coefficient(f, v_min, theta) * normal(t);
    };

    // Initial w. A block released at V = 0 reaches force balance within
    // ~V*/g (< 1e-30 s for usual parameters), far below any resolvable time
    // step; so V = 0 is replaced by min(V_balance, 1e-6 V0), V_balance being
    // the slip rate at which mu_reg equals the driving ratio, or, if
    // V_balance <= V_min, the block starts in a stick phase. Computed in
    // logarithms. So does a start below the floor, 0 < |V| < V_min.
    bool   start_stuck = false;
    double initial_w
      = p.initial_velocity > 0.
          ? w_of(p.initial_velocity)
          : (p.initial_velocity < 0. ? -w_of(-p.initial_velocity) : 0.);
    if (std::abs(p.initial_velocity) < v_min)
      {
        const double mu_balance = driving(0.) / normal(0.);
        const double y          = std::abs(mu_balance) / f.a;
        if (excess(0., theta_init) <= 0.)
          start_stuck = true;
        else
          {
            // ln(V_balance/V_s) = ln sinh(y) + ln(V*) - ln(V_s)
            const double ln_ratio
              = y - std::log(2.) + std::log(-std::expm1(-2. * y))
                + std::log(2. * f.v0) - state_term(f, theta_init) / f.a
                - std::log(vs);
            const double ln_ratio_cap = std::log(1e-6 * f.v0 / vs);
            const double l = std::max(std::min(ln_ratio, ln_ratio_cap),
                                      std::log(v_min) - std::log(vs));
            const double w
              = l > 30. ? l + std::log(2.) : std::asinh(std::exp(l));
            initial_w = mu_balance < 0. ? -w : w;
          }
      }

    const auto rhs =
      [&f, &record, &normal, g, sin_a, cos_a, vs](const double               t,
                                                  const std::vector<double> &y,
                                                  std::vector<double> &ydot) {
        const double v     = vs * std::sinh(y[1]);
        const double theta = std::exp(y[2]);
        const double mu    = regularized_friction_coefficient(f, v, theta);
        ydot[0]            = v;
        ydot[1] = g * ((sin_a + record.at(t) * cos_a) - mu * normal(t))
                  / (vs * std::cosh(y[1]));
        ydot[2] = std::exp(-y[2]) - std::abs(v) / f.dc;
      };
    const auto jacobian =
      [&f, &record, &normal, g, sin_a, cos_a, vs](const double               t,
                                                  const std::vector<double> &y,
                                                  std::vector<double> &j) {
        const double v      = vs * std::sinh(y[1]);
        const double s      = vs * std::cosh(y[1]); // dV/dw
        const double theta  = std::exp(y[2]);
        const double n      = normal(t);
        const double mu     = regularized_friction_coefficient(f, v, theta);
        const double force  = g * ((sin_a + record.at(t) * cos_a) - mu * n);
        double       dmu_dv = 0., dmu_dln_theta = 0.;
        regularized_friction_derivatives(f, v, theta, dmu_dv, dmu_dln_theta);
        const double sgn = v > 0. ? 1. : (v < 0. ? -1. : 0.);
        j[0 * 3 + 1]     = s;
        j[1 * 3 + 1]     = -g * n * dmu_dv - force * v / (s * s);
        j[1 * 3 + 2]     = -g * n * dmu_dln_theta / s;
        j[2 * 3 + 1]     = -sgn * s / f.dc;
        j[2 * 3 + 2]     = -std::exp(-y[2]);
      };

    RateStateHistory history;

    // The sliding phases: CVODE on (delta, w, ln theta), stopped by the
    // event |w| = w_min, |V| decreasing. Created at the first slide.
    std::unique_ptr<StiffOdeSolver> solver;
    const auto                      start_sliding
      = [&](const double t, const std::vector<double> &y) {
          if (!solver)
            {
              solver = std::make_unique<StiffOdeSolver>(
                rhs, y, t, ode_settings, jacobian);
              solver->set_step_observer(
                [&history, vs](const double, const std::vector<double> &z) {
                  history.max_abs_velocity
                    = std::max(history.max_abs_velocity,
                               std::abs(vs * std::sinh(z[1])));
                });
            }
          else
            solver->reinit(t, y);
          // Set after every (re)initialisation: CVODE then ignores an event
          // function that is exactly zero at the start (|w| = w_min on
          // release).
          solver->set_root_functions(1,
                                     [w_min](const double,
                                             const std::vector<double> &z,
                                             std::vector<double>       &e) {
                                       e[0] = std::abs(z[1]) - w_min;
                                     },
                                     {-1});
          history.max_abs_velocity = std::max(history.max_abs_velocity,
                                              std::abs(vs * std::sinh(y[1])));
        };

    // The stick phase: since t_stick, at slip delta_stick, theta grows by
    // the aging law with V = 0 from theta_stick.
    bool       stuck       = false;
    double     t_stick     = 0.;
    double     theta_stick = theta_init;
    double     delta_stick = 0.;
    const auto theta_at
      = [&](const double t) { return theta_stick + (t - t_stick); };
    // Release from stick at t (the excess is > 0 there) or sliding
    // resumed: from +-V_min in the direction of the driving force.
    const auto release
      = [&](const double t, const double delta, const double theta) {
          const double direction = driving(t) >= 0. ? 1. : -1.;
          stuck                  = false;
          start_sliding(t, {delta, direction * w_min, std::log(theta)});
        };
    // The block reached V_min at t: stick, or reverse at once.
    const auto stop
      = [&](const double t, const double delta, const double theta) {
          if (excess(t, theta) > 0.)
            {
              release(t, delta, theta);
              return;
            }
          stuck       = true;
          t_stick     = t;
          theta_stick = theta;
          delta_stick = delta;
          ++history.n_stick_events;
        };
    // The first time in (t_begin, t_end] at which the block cannot be held,
    // or t_end if none (the return value is then false). The driving and
    // normal forces are linear in t between record samples and the capacity
    // grows by B ln(1 + dt/theta) over one, so the sign of the excess is
    // checked at the samples and the change of sign located by bisection to
    // round-off (the release is at the first time where the excess is > 0).
    const auto find_release
      = [&](const double t_begin, const double t_end, double &t_release) {
          const bool   has_record = !record.acceleration.empty();
          const double t_record_end
            = has_record ? (record.acceleration.size() - 1) * record.dt : 0.;
          double t_lo = t_begin;
          while (t_lo < t_end)
            {
              double t_hi = t_end;
              if (has_record && t_lo < t_record_end)
                {
                  const double next
                    = (std::floor(t_lo / record.dt + 1e-9) + 1.) * record.dt;
                  t_hi = std::min(std::max(next, t_lo), t_end);
                  if (t_hi <= t_lo)
                    t_hi = std::min(t_lo + record.dt, t_end);
                }
              if (excess(t_hi, theta_at(t_hi)) > 0.)
                {
                  for (int it = 0;
                       it < 200 && t_hi - t_lo > 4e-16 * std::abs(t_hi);
                       ++it)
                    {
                      const double t_mid = 0.5 * (t_lo + t_hi);
                      if (t_mid <= t_lo || t_mid >= t_hi)
                        break;
                      if (excess(t_mid, theta_at(t_mid)) > 0.)
                        t_hi = t_mid;
                      else
                        t_lo = t_mid;
                    }
                  t_release = t_hi;
                  return true;
                }
              t_lo = t_hi;
            }
          t_release = t_end;
          return false;
        };

    if (start_stuck)
      {
        stuck       = true;
        t_stick     = 0.;
        theta_stick = theta_init;
        delta_stick = 0.;
        ++history.n_stick_events;
      }
    else
      start_sliding(0., {0., initial_w, std::log(theta_init)});

    const auto n_intervals = static_cast<unsigned long>(
      std::ceil(duration / output_interval - 1e-9));
    double       t                   = 0.;
    unsigned int instantaneous_stops = 0;
    for (unsigned long i = 0; i <= n_intervals; ++i)
      {
        const double t_out = std::min(i * output_interval, duration);
        while (t < t_out)
          {
            if (stuck)
              {
                double t_release = t_out;
                if (find_release(t, t_out, t_release))
                  {
                    release(t_release, delta_stick, theta_at(t_release));
                    ++history.n_slip_events;
                  }
                t = t_release;
              }
            else
              {
                const bool   at_floor = solver->advance_to_root(t_out);
                const double t_new    = solver->time();
                if (at_floor)
                  {
                    const std::vector<double> y = solver->state();
                    // A stop right after a reversal at the same instant
                    // would loop: the event functions exclude it unless the
                    // force balance is degenerate.
                    instantaneous_stops
                      = t_new > t ? 0 : instantaneous_stops + 1;
                    if (instantaneous_stops > 10)
                      throw OdeError(
                        "sliding_block: the block keeps stopping and "
                        "reversing at t = "
                        + std::to_string(t_new) + " s");
                    stop(t_new, y[0], std::exp(y[2]));
                  }
                t = t_new;
              }
          }

        history.time.push_back(t_out);
        if (stuck)
          {
            history.displacement.push_back(delta_stick);
            history.velocity.push_back(0.);
            history.theta.push_back(theta_at(t_out));
            history.mu.push_back(driving(t_out) / normal(t_out));
          }
        else
          {
            const std::vector<double> &y     = solver->state();
            const double               v     = vs * std::sinh(y[1]);
            const double               theta = std::exp(y[2]);
            history.displacement.push_back(y[0]);
            history.velocity.push_back(v);
            history.theta.push_back(theta);
            history.mu.push_back(regularized_friction_coefficient(f, v, theta));
          }
      }
    return history;
  }
} // namespace rockdda::analytical
