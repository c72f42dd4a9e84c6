/**
 * @file
 * Dieterich-Ruina rate-and-state friction (thesis Sec. 2.1.3, Eqs. 2.1-2.3)
 * and three small dynamical systems built on it, all integrated with CVODE
 * through StiffOdeSolver: an imposed velocity step, a spring-slider, and a
 * rigid block on an inclined plane under a horizontal acceleration record.
 * The equations are derived in doc/theory/rate-and-state.md.
 *
 * References: Dieterich, J.H. (1979) J. Geophys. Res. 84(B5), 2161-2168;
 * Ruina, A. (1983) J. Geophys. Res. 88(B12), 10359-10370; Rice, J.R. and
 * Ben-Zion, Y. (1996) PNAS 93, 3811-3818; Lapusta, N., Rice, J.R., Ben-Zion,
 * Y. and Zheng, G. (2000) J. Geophys. Res. 105(B10), 23765-23789;
 * stick events: Karnopp, D. (1985) J. Dyn. Syst. Meas. Control 107(1),
 * 100-103; Leine, R.I., van Campen, D.H., de Kraker, A. and van den Steen,
 * L. (1998) Nonlinear Dynamics 16, 41-54.
 */
#ifndef ROCKDDA_ANALYTICAL_RATE_STATE_H
#define ROCKDDA_ANALYTICAL_RATE_STATE_H

#include <rockdda/analytical/stiff_ode.h>
#include <rockdda/seismic/record.h>

#include <vector>

namespace rockdda::analytical
{
  /**
   * Parameters of the Dieterich-Ruina law with the aging (Dieterich) state
   * evolution law.
   */
  struct RateStateParameters
  {
    /// Reference friction coefficient mu0 at steady sliding at V0 (-).
    double mu0 = 0.6;
    /// Direct-effect parameter A (-), > 0.
    double a = 0.010;
    /// Evolution-effect parameter B (-), >= 0.
    double b = 0.015;
    /// Reference slip rate V0 (m/s), > 0.
    double v0 = 1e-6;
    /// Characteristic slip distance Dc (m), > 0.
    double dc = 1e-5;

    /// Throw InputError naming the key and its valid range if a parameter is
    /// out of range or not finite.
    void
    validate() const;
  };

  /**
   * Friction coefficient, thesis Eq. 2.1:
   * mu = mu0 + A ln(V/V0) + B ln(theta V0/Dc), for slip rate @p v > 0 (m/s)
   * and state @p theta > 0 (s). Throws std::domain_error otherwise.
   */
  double
  friction_coefficient(const RateStateParameters &p,
                       const double               v,
                       const double               theta);

  /**
   * Steady-state friction coefficient, thesis Eq. 2.3:
   * mu_ss = mu0 + (A - B) ln(V/V0), for @p v > 0 (m/s).
   */
  double
  steady_state_friction(const RateStateParameters &p, const double v);

  /// Steady-state value of the state variable, theta_ss = Dc/V (s), v > 0.
  double
  steady_state_theta(const RateStateParameters &p, const double v);

  /**
   * Aging law, thesis Eq. 2.2: d theta/dt = 1 - |V| theta / Dc (s/s, i.e.
   * dimensionless); the slip rate enters as a magnitude so that reversals heal
   * too.
   */
  double
  aging_law_rate(const RateStateParameters &p,
                 const double               v,
                 const double               theta);

  /**
   * Regularised friction coefficient (Rice and Ben-Zion 1996; Lapusta et al.
   * 2000), defined for all slip rates including V = 0 and V < 0:
   * mu = A asinh( V/(2 V0) exp(Psi/A) ),  Psi = mu0 + B ln(theta V0/Dc).
   * It is odd in V (friction opposes slip) and equals Eq. 2.1 to within
   * A/(4 x^2), x = |V|/(2V0) exp(Psi/A), when x >> 1. Evaluated without
   * overflow for any Psi/A.
   */
  double
  regularized_friction_coefficient(const RateStateParameters &p,
                                   const double               v,
                                   const double               theta);

  /**
   * Partial derivatives of the regularised friction coefficient:
   * d mu / d V (s/m) and d mu / d ln(theta) (-). Used for analytical
   * Jacobians. At V = 0, d mu/dV = A/(2 V0) exp(Psi/A), capped at 1e300.
   */
  void
  regularized_friction_derivatives(const RateStateParameters &p,
                                   const double               v,
                                   const double               theta,
                                   double                    &dmu_dv,
                                   double                    &dmu_dln_theta);

  /**
   * Critical stiffness per unit normal stress of a quasi-static
   * spring-slider, k_c = (B - A)/Dc (1/m) (Ruina 1983; Rice and Ruina 1983):
   * steady sliding is linearly stable for k > k_c and unstable for k < k_c.
   * Non-positive for velocity-strengthening friction (always stable).
   */
  double
  critical_stiffness(const RateStateParameters &p);

  /**
   * Time histories produced by the rate-and-state models. All vectors have
   * the same length; entry i is at time[i].
   */
  struct RateStateHistory
  {
    /// Time (s).
    std::vector<double> time;
    /// Slip (m); downslope positive for the sliding block.
    std::vector<double> displacement;
    /// Slip rate (m/s).
    std::vector<double> velocity;
    /// State variable theta (s).
    std::vector<double> theta;
    /// Friction coefficient (-). In a stick phase of the sliding block: the
    /// mobilised friction, driving over normal force (|mu| <= the capacity
    /// mu_reg(V_min, theta)).
    std::vector<double> mu;
    /// Largest |slip rate| (m/s) over every internal step of the integrator
    /// and every sample: independent of the output interval.
    double max_abs_velocity = 0.;
    /// Sliding block: number of stick phases entered (a slip-rate reversal
    /// through V = 0 without a hold is not counted); 0 for the other models.
    unsigned int n_stick_events = 0;
    /// Sliding block: number of times the block started sliding from a
    /// stick phase; 0 for the other models.
    unsigned int n_slip_events = 0;
  };

  /**
   * Velocity-step experiment with imposed slip rate: steady sliding at
   * @p v1 (m/s) for t < 0 (theta = Dc/v1), slip rate @p v2 (m/s) from t = 0.
   * Integrates the aging law (Eq. 2.2) for theta with CVODE on
   * [0, @p duration] (s) and returns n_outputs + 1 equally spaced samples
   * including t = 0 (mu at t = 0 is the value just after the step,
   * mu_ss(v1) + A ln(v2/v1)). The tolerances of @p settings apply to theta
   * (s). Throws InputError for v1, v2, duration <= 0 or n_outputs = 0.
   */
  RateStateHistory
  velocity_step(const RateStateParameters &p,
                const double               v1,
                const double               v2,
                const double               duration,
                const unsigned int         n_outputs,
                const StiffOdeSettings    &settings = StiffOdeSettings());

  /**
   * A single-degree-of-freedom spring-slider: a block on a rate-and-state
   * interface pulled through a spring by a load point at constant velocity.
   * Stresses are divided by the (constant) normal stress sigma.
   *
   * Quasi-static (mass = 0), with radiation damping eta:
   *   mu(V, theta) + eta V = tau0 + k (V_lp t - delta),
   * differentiated in time and solved for d ln V/dt:
   *   d ln V/dt = [k (V_lp - V) - B d ln theta/dt] / (A + eta V),
   *   d ln theta/dt = 1/theta - V/Dc,  d delta/dt = V,
   * unknowns (delta, ln V, ln theta), mu from Eq. 2.1.
   *
   * With inertia (mass > 0):
   *   m dV/dt = tau0 + k (V_lp t - delta) - mu_reg(V, theta) - eta V,
   * unknowns (delta, V, ln theta), mu regularised (slip may reverse).
   * In both cases tau0 is chosen so that the system starts in force balance.
   */
  struct SpringSliderParameters
  {
    /// Interface friction.
    RateStateParameters friction;
    /// Load-point velocity V_lp (m/s), > 0.
    double load_point_velocity = 1e-6;
    /// Spring stiffness per unit normal stress, k = K/(sigma S) (1/m), > 0.
    double stiffness = 100.;
    /// Radiation damping per unit normal stress, eta = G/(2 c_s sigma)
    /// (s/m), >= 0 (Rice 1993); 0 = none.
    double radiation_damping = 0.;
    /// Mass per unit normal force, m = M/(sigma S) (s^2/m), >= 0;
    /// 0 = quasi-static.
    double mass = 0.;
    /// Initial slip rate (m/s); <= 0 means the load-point velocity.
    double initial_velocity = 0.;
    /// Initial state (s); <= 0 means steady state at the load-point velocity,
    /// Dc/V_lp.
    double initial_theta = 0.;

    /// Throw InputError naming the key and valid range for bad values.
    void
    validate() const;
  };

  /**
   * Integrate the spring-slider with CVODE on [0, @p duration] (s) and
   * return n_outputs + 1 equally spaced samples. @p settings apply to the
   * unknowns listed above (per-component tolerances in that order); by
   * default rtol = 1e-8 and atol = 1e-12 for all of them.
   */
  RateStateHistory
  spring_slider(const SpringSliderParameters &p,
                const double                  duration,
                const unsigned int            n_outputs,
                const StiffOdeSettings       &settings = StiffOdeSettings());

  /**
   * A rigid block on a plane of dip alpha with a rate-and-state interface,
   * under gravity and a horizontal inertial acceleration k(t) g (k in g,
   * positive downslope). Per unit mass, with V the downslope slip rate:
   *   dV/dt = g [ (sin a + k cos a) - mu_reg(V, theta) (cos a - k sin a) ],
   *   d ln theta/dt = 1/theta - |V|/Dc,  d delta/dt = V,
   * The regularised law is used because Eq. 2.1 diverges at V = 0; the
   * block may slide upslope (mu_reg is odd in V). The unknowns are
   * (delta, w, ln theta) with V = V_s sinh(w): w behaves like V near 0 and
   * like ln V for |V| >> V_s, so the error control is relative in V over the
   * tens of decades between creep and slip, and mu_reg is nearly linear in
   * w (easy Newton iterations).
   *
   * Stick is a state of the integrator, not a stiff limit of the ODE: the
   * event-driven treatment of Coulomb stick in rigid-block models (Newmark
   * 1965; the switch model of Karnopp 1985 and Leine et al. 1998): while
   * sliding, a CVODE root function stops the integration where |V| falls to
   * the floor V_min (stick_velocity). If the driving force is then within
   * the capacity, |sin a + k cos a| <= mu_reg(V_min, theta) (cos a - k sin a),
   * the block sticks: V = 0, delta constant, theta grows by the aging law
   * with V = 0 (theta = theta_stick + t - t_stick, exact). The release is
   * located on the record's sample grid and by bisection where the driving
   * force first exceeds the capacity in either direction; sliding resumes
   * from V = +-V_min with the current theta (CVodeReInit). A block that
   * reaches V_min while the driving force exceeds the capacity the other
   * way reverses at once (from -+V_min). Creep below V_min is neglected
   * (slip < V_min x hold time). Any A > 0 works, including A -> 0 (the
   * Coulomb limit).
   */
  struct SlidingBlockParameters
  {
    /// Interface friction.
    RateStateParameters friction;
    /// Dip of the plane (degrees), in [0, 90).
    double dip_deg = 30.;
    /// Gravitational acceleration (m/s^2), > 0.
    double gravity = 9.80665;
    /// Initial downslope slip rate (m/s). 0 (released at rest) is replaced
    /// by min(V_balance, 1e-6 V0), V_balance being the slip rate at which
    /// mu_reg balances the driving force: the transient from exactly 0 to
    /// balance lasts ~V*/g, far below any resolvable time step.
    double initial_velocity = 0.;
    /// Initial state (s); <= 0 means Dc/V0 (mu = mu0 at V = V0).
    double initial_theta = 0.;
    /// Velocity scale V_s of the unknown w = asinh(V/V_s) (m/s), >= 0;
    /// 0 = automatic: V* = 2 V0 exp(-Psi/A) at the initial state (clamped to
    /// [1e-280, V0]), for which w = mu_reg/A at fixed theta.
    double velocity_scale = 0.;
    /// Stick floor V_min (m/s), in [0, V0); 0 = automatic:
    /// max(1e-3 V0, 1e3 g eps T), eps the machine epsilon and T the duration
    /// (>= 1 s). The block sticks when |V| falls to V_min and can be held,
    /// and slides again from +-V_min (see above). V_min must be resolvable:
    /// a stop at deceleration a is located to ~V_min/a (s), which must be
    /// far above the round-off of the time (a eps T), and the force balance
    /// is divided by V in the equations, so values below ~1e3 g eps T make
    /// CVODE fail at stops as the unregularised stick did. Creep below V_min
    /// is neglected (slip < V_min x hold time).
    double stick_velocity = 0.;

    /// Throw InputError naming the key and valid range for bad values.
    void
    validate() const;
  };

  /**
   * Integrate the sliding block with CVODE on [0, @p duration] (s), sampling
   * every @p output_interval (s) (the last sample is at @p duration).
   * @p record is the horizontal acceleration k(t) (g, + downslope); an empty
   * record means gravity only. If settings.max_step is 0 it is set to the
   * record's dt so that no input sample is stepped over. Tolerances apply to
   * (delta (m), w (-), ln theta (-)); an atol of 1e-8 on w and ln theta and
   * rtol = 1e-8 are typical. In stick phases the samples have V = 0, the
   * slip of the last stop and the mobilised friction; the numbers of stick
   * and slip events are counted in the history. Throws std::domain_error if
   * the normal force vanishes (cos a - k sin a <= 0: the block lifts off),
   * OdeError if CVODE fails.
   */
  RateStateHistory
  sliding_block(const SlidingBlockParameters &p,
                const seismic::Record        &record,
                const double                  duration,
                const double                  output_interval,
                const StiffOdeSettings       &settings = StiffOdeSettings());
} // namespace rockdda::analytical

#endif
