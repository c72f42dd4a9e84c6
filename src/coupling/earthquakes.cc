#include <rockdda/coupling/concurrent_runs.h>
#include <rockdda/coupling/earthquakes.h>
#include <rockdda/io/error.h>
#include <rockdda/io/interrupt.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

namespace rockdda::coupling
{
  seismic::StochasticParameters
  EarthquakeOptions::default_motion()
  {
    seismic::StochasticParameters p;
    p.site = seismic::SiteAmplification::masada();
    return p;
  }



  std::vector<EarthquakeEvent>
  run_earthquakes(const Block1Geometry    &geometry,
                  const Block1Materials   &materials,
                  const EarthquakeOptions &o,
                  unsigned int            *threads_used)
  {
    constexpr double nan = std::numeric_limits<double>::quiet_NaN();
    require_in_range(o.realisations >= 1,
                     "Earthquakes/Number of realisations",
                     o.realisations,
                     ">= 1");
    for (std::size_t i = 1; i < o.magnitudes.size(); ++i)
      require_in_range(o.magnitudes[i] > o.magnitudes[i - 1],
                       "Earthquakes/Magnitudes",
                       o.magnitudes[i],
                       "strictly increasing");

    // The motions, serially (FFTW plans are made here); SIGINT / SIGTERM
    // ends the list.
    std::vector<EarthquakeEvent> events;
    std::vector<seismic::Record> records;
    for (const double m : o.magnitudes)
      for (unsigned int i = 0;
           i < o.realisations && io::interrupt_signal() == 0;
           ++i)
        {
          seismic::StochasticParameters p = o.motion;
          p.magnitude                     = m;
          p.distance                      = o.distance;
          EarthquakeEvent e;
          e.magnitude = m;
          e.seed      = o.first_seed + i;
          records.push_back(seismic::simulate(p, e.seed, true));
          e.pga      = records.back().peak();
          e.duration = records.back().duration();
          events.push_back(e);
        }

    // DDA and the analytical block, concurrently. Each run is stopped
    // after 20 steps per dt on average or 60 s of wall time (some stick-slip
    // runs creep with ever smaller steps) and by SIGINT / SIGTERM.
    Block1RunControls c;
    c.mode             = o.mode;
    c.penalty          = o.penalty;
    c.dt               = o.dt;
    c.settle_steps     = o.settle_steps;
    c.max_steps_per_dt = 20.;
    c.wall_time_limit  = 60.;
    c.stop             = []() { return io::interrupt_signal() != 0; };
    c.penalty_key      = "Earthquakes/Penalty";
    c.time_step_key    = "Earthquakes/Time step";
    c.section          = "Earthquakes";
    const auto runs
      = run_concurrently(events.size(), o.threads, [&](const std::size_t j) {
          EarthquakeEvent &e = events[j];
          e.analytical       = block1_analytical_slip(
            geometry, materials, records[j], e.duration, o.analytical_dt);
          try
            {
              const Block1Run r = run_block1_dda(
                geometry, materials, records[j], c, e.duration);
              e.dda          = r.slip;
              e.max_rotation = r.max_rotation;
              e.steps        = r.steps;
              e.cuts         = r.cuts;
              e.wall_time    = r.wall_time;
              if (r.stopped)
                {
                  e.failure = "interrupted";
                  e.dda     = nan;
                }
            }
          catch (const std::exception &x)
            {
              e.failure = x.what();
              e.dda     = nan;
            }
        });
    for (std::size_t j = 0; j < events.size(); ++j)
      if (!runs.done[j])
        {
          events[j].failure    = "not run (interrupted)";
          events[j].dda        = nan;
          events[j].analytical = nan;
        }
    if (threads_used != nullptr)
      *threads_used = runs.threads;
    return events;
  }



  Spread
  spread(std::vector<double> v)
  {
    v.erase(std::remove_if(v.begin(),
                           v.end(),
                           [](const double x) { return !std::isfinite(x); }),
            v.end());
    Spread s;
    if (v.empty())
      {
        s.p16 = s.median = s.p84 = std::numeric_limits<double>::quiet_NaN();
        return s;
      }
    std::sort(v.begin(), v.end());
    const auto q = [&](const double p) {
      const double      x = p * (v.size() - 1);
      const std::size_t k = static_cast<std::size_t>(std::floor(x));
      if (k + 1 >= v.size())
        return v.back();
      return v[k] + (x - k) * (v[k + 1] - v[k]);
    };
    s.p16    = q(0.16);
    s.median = q(0.5);
    s.p84    = q(0.84);
    return s;
  }



  double
  median_pga(seismic::StochasticParameters motion,
             const double                  magnitude,
             const double                  distance,
             const unsigned int            realisations,
             const std::uint64_t           first_seed)
  {
    motion.magnitude = magnitude;
    motion.distance  = distance;
    std::vector<double> pga;
    for (unsigned int i = 0; i < realisations; ++i)
      pga.push_back(seismic::simulate(motion, first_seed + i, true).peak());
    return spread(pga).median;
  }



  double
  trigger_distance(const seismic::StochasticParameters &motion,
                   const double                         magnitude,
                   const double                         ky,
                   const unsigned int                   realisations,
                   const std::uint64_t                  first_seed,
                   const double                         max_distance,
                   const double                         tolerance)
  {
    const auto pga = [&](const double r) {
      return median_pga(motion, magnitude, r, realisations, first_seed);
    };
    if (pga(0.) < ky)
      return 0.;
    if (pga(max_distance) >= ky)
      return max_distance;
    double lo = 0., hi = max_distance;
    while (hi - lo > tolerance)
      {
        const double mid           = 0.5 * (lo + hi);
        (pga(mid) >= ky ? lo : hi) = mid;
      }
    return lo;
  }



  std::vector<RateBin>
  displacement_rate(const std::vector<double> &magnitudes,
                    const std::vector<double> &displacement,
                    const std::vector<double> &recurrence,
                    const std::string         &key)
  {
    if (recurrence.size() > magnitudes.size())
      throw InputError(
        "key '" + key + "' has " + std::to_string(recurrence.size())
        + " recurrence intervals for " + std::to_string(magnitudes.size())
        + " magnitudes; give at most one per magnitude");
    for (std::size_t i = 0; i < recurrence.size(); ++i)
      {
        require_in_range(recurrence[i] > 0. && std::isfinite(recurrence[i]),
                         key,
                         recurrence[i],
                         "> 0 yr");
        if (i > 0)
          require_in_range(recurrence[i] > recurrence[i - 1],
                           key,
                           recurrence[i],
                           "> the interval of the smaller magnitude "
                             + std::to_string(recurrence[i - 1])
                             + " yr (larger events are rarer)");
      }
    std::vector<RateBin> bins;
    for (std::size_t i = 0; i < recurrence.size(); ++i)
      {
        RateBin b;
        b.magnitude  = magnitudes[i];
        b.recurrence = recurrence[i];
        b.annual_rate
          = 1. / recurrence[i]
            - (i + 1 < recurrence.size() ? 1. / recurrence[i + 1] : 0.);
        b.displacement = std::max(0., displacement[i]);
        b.rate         = 1e3 * b.annual_rate * b.displacement;
        b.rate_single  = 1e3 * b.displacement / b.recurrence;
        bins.push_back(b);
      }
    return bins;
  }
} // namespace rockdda::coupling
