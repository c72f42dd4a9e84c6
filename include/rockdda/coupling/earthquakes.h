/**
 * @file
 * Masada Block 1 without infill under earthquakes (thesis 5.5.3, Fig. 5-18,
 * 5.6.2): seeded synthetic motions (Boore 2003, with the Masada site
 * amplification) of each magnitude at one distance, applied to Block 1 in
 * DDA and to the analytical rigid block; the distance up to which each
 * magnitude still triggers sliding; and the mean displacement rate from
 * recurrence intervals. doc/theory/earthquakes.md describes the method.
 */
#ifndef ROCKDDA_COUPLING_EARTHQUAKES_H
#define ROCKDDA_COUPLING_EARTHQUAKES_H

#include <rockdda/coupling/block1_seismic.h>
#include <rockdda/seismic/stochastic.h>

#include <cstdint>
#include <string>
#include <vector>

namespace rockdda::coupling
{
  /// What is simulated for every magnitude, and how DDA runs.
  struct EarthquakeOptions
  {
    /// Moment magnitudes (-), strictly increasing.
    std::vector<double> magnitudes{6., 6.5, 7., 7.5};
    /// Joyner-Boore distance of every event (m), >= 0.
    double distance = 1e3;
    /// Realisations per magnitude (-), >= 1; realisation i (0-based) uses
    /// seed first_seed + i (the same seeds for every magnitude).
    unsigned int  realisations = 12;
    std::uint64_t first_seed   = 1;
    /// The stochastic model; its magnitude and distance are overwritten per
    /// event. The site amplification is the Masada one by default.
    seismic::StochasticParameters motion = default_motion();
    /// DDA control: normal penalty (N/m), time step (s), input mode, static
    /// settling steps (the calibrated pair of the 'calibrate' analysis).
    double                  penalty      = 1e11;
    double                  dt           = 0.005;
    dda::SeismicInput::Mode mode         = dda::SeismicInput::Mode::inertial;
    unsigned int            settle_steps = 50;
    /// Integration step of the analytical sliding block (s), > 0.
    double analytical_dt = 1e-4;
    /// Runs at once (0: one per core); each DDA solver uses one thread.
    unsigned int threads = 0;

    /// SMSIM defaults with SiteAmplification::masada().
    static seismic::StochasticParameters
    default_motion();
  };

  /// One event: one magnitude, one seed.
  struct EarthquakeEvent
  {
    double        magnitude = 0.;
    std::uint64_t seed      = 0;
    /// PGA of the site-amplified motion (g) and its length (s).
    double pga = 0., duration = 0.;
    /// Final slip along the bedding plane (m), + downslope: DDA and the
    /// analytical rigid block on the same motion.
    double dda = 0., analytical = 0.;
    /// Largest |rotation| of the block in DDA (rad), wall time of the DDA
    /// run (s), accepted steps and step cuts.
    double        max_rotation = 0., wall_time = 0.;
    unsigned long steps = 0, cuts = 0;
    /// Empty if DDA finished, else why it stopped.
    std::string failure;
  };

  /**
   * Simulate options.realisations site-amplified motions per magnitude at
   * options.distance (serially: FFTW planning is not thread-safe) and run
   * each in DDA and analytically; the runs go concurrently
   * (run_concurrently(): the results do not depend on the number of
   * threads). Events are ordered by magnitude, then seed. A DDA run that
   * fails is recorded (failure, dda = NaN), not thrown; after SIGINT or
   * SIGTERM the runs not yet done are recorded as "not run (interrupted)"
   * (dda = analytical = NaN). @p threads_used (optional) receives the
   * number of threads.
   */
  std::vector<EarthquakeEvent>
  run_earthquakes(const Block1Geometry    &geometry,
                  const Block1Materials   &materials,
                  const EarthquakeOptions &options,
                  unsigned int            *threads_used = nullptr);

  /// The 16th, 50th and 84th percentiles of a sample.
  struct Spread
  {
    double p16 = 0., median = 0., p84 = 0.;
  };

  /// Percentiles of @p values (linear interpolation between order
  /// statistics, NaNs skipped; all NaN for an empty sample).
  Spread
  spread(std::vector<double> values);

  /// Median over seeds first_seed ... first_seed + realisations - 1 of the
  /// PGA (g) of the motion @p motion (with its site amplification) of
  /// magnitude @p magnitude at Joyner-Boore distance @p distance (m).
  double
  median_pga(seismic::StochasticParameters motion,
             const double                  magnitude,
             const double                  distance,
             const unsigned int            realisations,
             const std::uint64_t           first_seed);

  /**
   * The largest Joyner-Boore distance (m) at which the median PGA of
   * median_pga() still reaches @p yield_acceleration (g), by bisection on
   * [0, @p max_distance] to @p tolerance (m). Returns 0 if the median at 0
   * m is below it and @p max_distance if the median there still reaches it.
   */
  double
  trigger_distance(const seismic::StochasticParameters &motion,
                   const double                         magnitude,
                   const double                         yield_acceleration,
                   const unsigned int                   realisations,
                   const std::uint64_t                  first_seed,
                   const double                         max_distance = 3e5,
                   const double                         tolerance    = 10.);

  /// One magnitude bin of the displacement rate.
  struct RateBin
  {
    /// Lower magnitude of the bin (-) and recurrence interval of events of
    /// at least this magnitude (yr).
    double magnitude = 0., recurrence = 0.;
    /// Events per year in [magnitude, next magnitude) (1/yr).
    double annual_rate = 0.;
    /// Displacement per event of the bin (m): the one at its lower
    /// magnitude.
    double displacement = 0.;
    /// annual_rate x displacement (mm/yr).
    double rate = 0.;
    /// The thesis' reading: displacement / recurrence (mm/yr).
    double rate_single = 0.;
  };

  /**
   * The mean displacement rate of a block from recurrence intervals:
   * @p recurrence[i] (yr) is the mean interval between events of magnitude
   * >= @p magnitudes[i] (increasing); bin i holds the events in
   * [M_i, M_{i+1}) (the last one: M >= M_last), 1/T_i - 1/T_{i+1} per year,
   * each displacing the block by @p displacement[i] (m), its value at the
   * bin's lower magnitude (a lower bound within the bin). Only the first
   * recurrence.size() magnitudes enter. Throws InputError naming @p key for
   * a recurrence interval <= 0, intervals not increasing, or more
   * intervals than magnitudes.
   */
  std::vector<RateBin>
  displacement_rate(const std::vector<double> &magnitudes,
                    const std::vector<double> &displacement,
                    const std::vector<double> &recurrence,
                    const std::string         &key
                    = "Earthquakes/Recurrence intervals");
} // namespace rockdda::coupling

#endif
