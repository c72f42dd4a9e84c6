/**
 * @file
 * One-dimensional rigid-block sliding (Newmark 1965) under an acceleration
 * record, and the closed-form solution for harmonic input.
 *
 * See doc/theory/newmark-harmonic.md for the equations, the sign
 * conventions and what is detected within a time step.
 */
#ifndef ROCKDDA_ANALYTICAL_NEWMARK_H
#define ROCKDDA_ANALYTICAL_NEWMARK_H

#include <rockdda/analytical/friction.h>
#include <rockdda/seismic/record.h>

#include <vector>

namespace rockdda::analytical
{
  /**
   * Options of a 1D rigid-block (Newmark 1965) sliding analysis.
   *
   * Sign convention (as in SLAMMER, Jibson et al. 2013): a positive input
   * acceleration is the block's downslope-driving (inertial) acceleration;
   * the block slides downslope when the input exceeds the yield acceleration.
   * Displacements are relative to the ground, positive downslope.
   */
  struct NewmarkOptions
  {
    /// Which sliding directions are allowed.
    enum class Direction
    {
      /// Downslope only (the classical Newmark/SLAMMER analysis).
      downslope,
      /// Downslope and upslope. The constant and table models use a
      /// symmetric yield acceleration (upslope sliding when a < -ky); the
      /// plane model takes the upslope resistance from the geometry.
      two_way
    };
    /// How the yield (critical) acceleration is defined.
    enum class YieldModel
    {
      /// ky constant.
      constant,
      /// ky piecewise linear in the cumulative sliding distance.
      table,
      /// Block on a plane of dip alpha with a friction law (Kamai & Hatzor
      /// 2008); the input is the horizontal acceleration.
      plane
    };
    /// Where the start and the end of sliding are placed.
    enum class EventLocation
    {
      /// Within the step (default): sliding starts where the linearly
      /// interpolated input crosses the yield acceleration, and stops where
      /// the relative velocity (quadratic in time for a relative
      /// acceleration linear across the step) returns to zero. Second-order
      /// accurate (doc/theory/newmark-harmonic.md).
      within_step,
      /// At the samples, as SLAMMER's rigorous rigid-block analysis (Jibson
      /// et al. 2013): sliding starts at the beginning of the step whose
      /// end sample exceeds the yield acceleration, with zero relative
      /// acceleration there, and stops at the end of the step in which the
      /// velocity changes sign. First-order accurate; use it to reproduce
      /// SLAMMER results.
      at_samples
    };

    Direction  direction   = Direction::downslope;
    YieldModel yield_model = YieldModel::constant;
    /// Yield acceleration (g), constant model, >= 0.
    double ky = 0.1;
    /// Table model: cumulative sliding distance (m), strictly increasing.
    /// ky is piecewise linear in the distance and held constant beyond the
    /// ends of the table.
    std::vector<double> table_displacement;
    /// Table model: yield acceleration (g) at each table_displacement, >= 0.
    std::vector<double> table_ky;
    /// Plane model: dip of the sliding plane (deg), in [0, 90).
    double dip_deg = 0.;
    /// Plane model: friction coefficient law of the sliding plane (may depend
    /// on the slip rate; the static value is the law at rest).
    FrictionLaw friction;
    /// Integration step (s), >= 0; 0 = the record's dt. Smaller values
    /// sub-step with linear interpolation of the record.
    double time_step = 0.;
    /// Spacing of the stored history samples (s), >= 0; 0 = every step.
    double output_interval = 0.;
    /// Gravitational acceleration (m/s^2), > 0.
    double g = 9.80665;
    /// Location of the start and stop of sliding.
    EventLocation event_location = EventLocation::within_step;
  };

  /// Time history and summary of a Newmark analysis.
  struct NewmarkResult
  {
    /// Times of the stored samples (s).
    std::vector<double> time;
    /// Input acceleration at the stored times (g).
    std::vector<double> acceleration;
    /// Relative velocity of the block (m/s), + downslope.
    std::vector<double> velocity;
    /// Relative displacement of the block (m), + downslope.
    std::vector<double> displacement;
    /// 0 stuck, +1 sliding downslope, -1 sliding upslope.
    std::vector<int> state;
    /// Relative displacement at the end of the record (m).
    double final_displacement = 0.;
    /// Largest |relative velocity| at the step ends (m/s).
    double max_velocity = 0.;
    /// Number of times the block started sliding.
    unsigned int n_slip_events = 0;
    /// Total time spent sliding (s).
    double sliding_duration = 0.;
    /// Number of integration steps.
    unsigned long n_steps = 0;
  };

  /**
   * Integrate the sliding of a rigid block under the acceleration record
   * @p input (g) from rest at t = 0 to the end of the record.
   *
   * The relative velocity is integrated with the average-acceleration
   * (trapezoidal) rule, the displacement likewise. By default the instant
   * the relative velocity returns to zero is located within the step
   * (relative acceleration linear across the step) and the start of sliding
   * by linear interpolation of the input (see NewmarkOptions::EventLocation).
   * A velocity-dependent friction law makes the update implicit; it is solved
   * by safeguarded Newton iterations.
   *
   * Throws InputError for invalid options or record, and std::runtime_error
   * if the block lifts off the plane (normal force <= 0) or the solution
   * becomes non-finite.
   */
  NewmarkResult
  newmark_sliding(const seismic::Record &input, const NewmarkOptions &options);

  /**
   * Check @p options; throws InputError naming the quantity and its valid
   * range (negative time step or output interval, g <= 0, negative or
   * non-finite ky, inconsistent table, dip outside [0, 90) deg, friction
   * angle >= 90 deg, invalid rate-dependence parameters).
   */
  void
  validate(const NewmarkOptions &options);

  /// Exact sliding cycle under a(t) = A sin(omega t) from rest at t = 0.
  struct HarmonicSliding
  {
    /// Start of sliding in the first cycle (s); +inf if ky >= A.
    double t_start;
    /// End of sliding in the first cycle (s); +inf if ky >= A.
    double t_stop;
    /// Displacement per cycle, in units of amplitude * s^2 (multiply by g
    /// for metres when the amplitude is in g).
    double displacement_per_cycle;
  };

  /**
   * Exact (closed-form) downslope sliding for a(t) = A sin(omega t) with
   * constant yield acceleration @p ky (same units as @p amplitude), starting
   * at rest at t = 0 (Newmark 1965). @p omega in rad/s. Each cycle repeats
   * identically. Throws InputError unless A > 0, omega > 0, ky >= 0.
   */
  HarmonicSliding
  harmonic_sliding_cycle(const double amplitude,
                         const double omega,
                         const double ky);

  /**
   * Exact downslope displacement at time @p t (s) for the input of
   * harmonic_sliding_cycle(), partial cycles included, in units of
   * amplitude * s^2.
   */
  double
  harmonic_sliding_displacement(const double amplitude,
                                const double omega,
                                const double ky,
                                const double t);
} // namespace rockdda::analytical

#endif
