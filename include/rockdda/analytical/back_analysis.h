/**
 * @file
 * Back-analysis of interface friction from measured sliding (thesis
 * Sec. 4.7.3, Table 4-2 and Fig. 4-10): piecewise-constant friction angles,
 * one per time segment, fitted to a measured displacement history of a block
 * on an inclined plane under a horizontal input record; and a least-squares
 * fit of the steady-state rate dependence mu = mu0 + (A - B) ln(V/V0)
 * (thesis Eq. 2.3) to friction-versus-velocity data.
 */
#ifndef ROCKDDA_ANALYTICAL_BACK_ANALYSIS_H
#define ROCKDDA_ANALYTICAL_BACK_ANALYSIS_H

#include <rockdda/seismic/record.h>

#include <cstddef>
#include <functional>
#include <vector>

namespace rockdda::analytical
{
  /// Kinematic state of a block sliding on a plane, downslope positive.
  struct SlidingState
  {
    /// Displacement along the plane (m).
    double displacement = 0.;
    /// Velocity along the plane (m/s).
    double velocity = 0.;
  };

  /**
   * Forward model used by the back-analysis: integrate the block from state
   * @p start at time @p t_begin (s) to @p t_end (s) with a constant friction
   * angle @p phi_deg (degrees) and return the state at t_end. Any model may
   * be plugged in (e.g. the Newmark rigid-block module or the 3D wedge
   * solution); the back-analysis only requires that the displacement at
   * t_end be a continuous, non-increasing function of phi_deg.
   */
  using ForwardModel = std::function<SlidingState(const double        phi_deg,
                                                  const SlidingState &start,
                                                  const double        t_begin,
                                                  const double        t_end)>;

  /**
   * The default forward model: a rigid block on a plane of dip @p dip_deg
   * (degrees) under the horizontal inertial acceleration k(t) of @p record
   * (g, positive downslope), Coulomb friction mu = tan(phi), downslope
   * sliding only (Newmark 1965 with a dip):
   *   dv/dt = g [(sin a + k cos a) - tan(phi) (cos a - k sin a)]  while v > 0,
   * and the block sticks (v = 0) while that acceleration is <= 0. Integrated
   * with the trapezoidal (average-acceleration) rule with steps of at most
   * @p time_step (s) (each [t_begin, t_end] is split into equal steps); a
   * block that stops within a step stops at the linearly interpolated zero
   * of v. Throws InputError for dip outside [0, 90), time_step <= 0 or
   * gravity <= 0, and std::domain_error if cos a - k sin a <= 0 (lift-off).
   * The record is copied into the returned model.
   */
  ForwardModel
  plane_sliding_forward_model(const seismic::Record &record,
                              const double           dip_deg,
                              const double           time_step,
                              const double           gravity = 9.80665);

  /// A measured displacement history, sampled at strictly increasing times.
  struct DisplacementHistory
  {
    /// Sample times (s), strictly increasing.
    std::vector<double> time;
    /// Downslope displacement (m) at each sample time.
    std::vector<double> displacement;
  };

  /// Settings of the friction-angle back-analysis.
  struct BackAnalysisSettings
  {
    /// Bisection bracket for phi (degrees), 0 <= lower < upper < 90.
    double phi_lower_deg = 0.;
    double phi_upper_deg = 89.;
    /// Bisection stops when the bracket is narrower than this (degrees).
    double tolerance_deg = 1e-9;
    /// Velocity of the block at the first segment boundary (m/s).
    double initial_velocity = 0.;
  };

  /// The fit of one time segment.
  struct SegmentFit
  {
    /// Segment [t_begin, t_end] (s).
    double t_begin = 0.;
    double t_end   = 0.;
    /// Fitted friction angle (degrees).
    double phi_deg = 0.;
    /// Measured displacement at t_end, interpolated linearly (m).
    double measured_displacement = 0.;
    /// Displacement computed with phi_deg at t_end (m).
    double computed_displacement = 0.;
    /// Average sliding velocity over the segment, measured (m/s) (thesis
    /// Fig. 4-10 plots tan(phi) against it).
    double average_velocity = 0.;
    /// False if the measured displacement does not increase over the
    /// segment: phi is then only a lower bound (the smallest angle that
    /// keeps the block at rest), not an identified value.
    bool moved = true;
    /// False if the measured displacement lies outside the range the
    /// forward model reaches with the bracket; phi is then the bracket end.
    bool bracketed = true;
  };

  /**
   * Fit one friction angle per time segment, sequentially (thesis Sec.
   * 4.7.3): segment k spans [boundaries[k], boundaries[k+1]]; starting from
   * the measured displacement at boundaries[0] and
   * settings.initial_velocity, phi_k is found by bisection so that the
   * forward model, run from the state reached at the end of segment k-1,
   * reproduces the measured displacement at boundaries[k+1]. This relies on
   * the displacement being non-increasing in phi. Throws InputError if the
   * boundaries are fewer than 2 or not strictly increasing, if the measured
   * history is malformed (sizes differ, fewer than 2 samples, times not
   * strictly increasing, non-finite values) or does not cover the segments,
   * or if the settings are out of range.
   */
  std::vector<SegmentFit>
  back_analyse_friction_angles(const DisplacementHistory  &measured,
                               const std::vector<double>  &boundaries,
                               const ForwardModel         &forward,
                               const BackAnalysisSettings &settings
                               = BackAnalysisSettings());

  /// Result of fit_steady_state_friction().
  struct SteadyStateFrictionFit
  {
    /// Reference friction mu0 at V0 (-) and its standard error.
    double mu0                = 0.;
    double mu0_standard_error = 0.;
    /// A - B (-) and its standard error.
    double a_minus_b                = 0.;
    double a_minus_b_standard_error = 0.;
    /// Reference velocity used (m/s).
    double v0 = 1e-6;
    /// Coefficient of determination (-); 1 for an exact fit.
    double r_squared = 1.;
    /// Number of data points.
    std::size_t n_points = 0;
  };

  /**
   * Fit mu = mu0 + (A - B) ln(V/V0) (thesis Eq. 2.3) to data (V_i, mu_i) by
   * ordinary linear least squares in x = ln(V/V0). Standard errors are the
   * usual ones, s^2 = SSR/(n-2), se(A-B) = s/sqrt(Sxx),
   * se(mu0) = s sqrt(1/n + xbar^2/Sxx). Throws InputError for sizes that
   * differ, fewer than 3 points, V <= 0, non-finite values, all V equal, or
   * v0 <= 0.
   */
  SteadyStateFrictionFit
  fit_steady_state_friction(const std::vector<double> &velocity,
                            const std::vector<double> &mu,
                            const double               v0 = 1e-6);
} // namespace rockdda::analytical

#endif
