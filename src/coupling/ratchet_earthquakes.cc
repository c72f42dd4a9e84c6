#include <rockdda/analytical/yield.h>
#include <rockdda/coupling/concurrent_runs.h>
#include <rockdda/coupling/earthquakes.h>
#include <rockdda/coupling/ratchet_earthquakes.h>
#include <rockdda/io/error.h>
#include <rockdda/io/output.h>

#include <chrono>
#include <cmath>
#include <limits>

namespace rockdda::coupling
{
  namespace
  {
    constexpr double nan = std::numeric_limits<double>::quiet_NaN();

    double
    seconds_since(const std::chrono::steady_clock::time_point start)
    {
      return std::chrono::duration<double>(std::chrono::steady_clock::now()
                                           - start)
        .count();
    }
  } // namespace



  RatchetEarthquakeResult
  run_ratchet_earthquakes(const RatchetScene             &scene,
                          const PeriodicBlockTemperature &temperature,
                          const SeasonalForcing          &forcing,
                          const double                    alpha,
                          const RatchetControls          &controls,
                          const unsigned int              cycles,
                          const Block1Geometry           &block1,
                          const Block1Materials          &block1_materials,
                          const RatchetEarthquakeOptions &o)
  {
    require_in_range(o.gr.b_value > 0. && std::isfinite(o.gr.b_value),
                     "Ratchet earthquakes/b-value",
                     o.gr.b_value,
                     "> 0");
    require_in_range(o.gr.max_magnitude > o.gr.min_magnitude,
                     "Ratchet earthquakes/Maximum magnitude",
                     o.gr.max_magnitude,
                     "> 'Minimum magnitude'");
    require_in_range(o.gr.recurrence > 0. && std::isfinite(o.gr.recurrence),
                     "Ratchet earthquakes/Recurrence interval",
                     o.gr.recurrence,
                     "> 0 yr");
    require_in_range(o.distance >= 0. && std::isfinite(o.distance),
                     "Ratchet earthquakes/Distance",
                     o.distance,
                     ">= 0 m");
    require_in_range(o.minimum_pga >= 0. && std::isfinite(o.minimum_pga),
                     "Ratchet earthquakes/Minimum PGA",
                     o.minimum_pga,
                     ">= 0 g");
    require_in_range(o.episode.time_step > 0.,
                     o.episode.time_step_key,
                     o.episode.time_step,
                     "> 0 s");
    require_in_range(o.episode.rest_time >= 0.,
                     o.episode.rest_time_key,
                     o.episode.rest_time,
                     ">= 0 s");
    require_in_range(o.episode.contact_damping >= 0.
                       && std::isfinite(o.episode.contact_damping),
                     o.episode.contact_damping_key,
                     o.episode.contact_damping,
                     ">= 0");
    require_in_range(o.block1_penalty > 0.,
                     "Ratchet earthquakes/Block 1 penalty",
                     o.block1_penalty,
                     "> 0 N/m");
    const auto start = std::chrono::steady_clock::now();

    // The catalogues and their motions (serially: FFTW planning).
    seismic::StochasticParameters motion = EarthquakeOptions::default_motion();
    if (!o.masada_site)
      motion.site = seismic::SiteAmplification();
    motion.distance = o.distance;
    const double ky
      = analytical::plane_yield_acceleration(block1.slope_deg,
                                             block1_materials.friction_deg);
    RatchetEarthquakeResult      result;
    std::vector<seismic::Record> records;
    result.histories.resize(o.catalogues);
    for (unsigned int c = 0; c < o.catalogues; ++c)
      {
        result.histories[c].catalogue = c;
        for (const auto &e : gutenberg_richter_catalogue(
               o.gr, static_cast<double>(cycles), o.first_seed + c))
          {
            motion.magnitude = e.magnitude;
            RatchetQuake q;
            q.catalogue = c;
            q.event     = e;
            records.push_back(seismic::simulate(motion, e.motion_seed, true));
            q.pga      = records.back().peak();
            q.duration = records.back().duration();
            q.runs     = q.pga >= o.minimum_pga;
            result.quakes.push_back(q);
            ++result.histories[c].events;
            result.histories[c].episodes += q.runs ? 1 : 0;
          }
      }
    result.motion_seconds = seconds_since(start);

    // Jobs: the coupled run of each catalogue, then (if asked) its events
    // alone on the scene and on Block 1.
    RatchetControls rc = controls;
    rc.threads         = 1;
    Block1RunControls b1;
    b1.mode             = dda::SeismicInput::Mode::inertial;
    b1.penalty          = o.block1_penalty;
    b1.dt               = o.episode.time_step;
    b1.max_steps_per_dt = 20.;
    b1.wall_time_limit  = 120.;
    b1.penalty_key      = "Ratchet earthquakes/Block 1 penalty";
    b1.time_step_key    = o.episode.time_step_key;
    b1.section          = "Ratchet";
    std::vector<std::string> alone_failure(o.catalogues);
    const std::size_t n_jobs = o.catalogues * (o.quakes_on_scene ? 2u : 1u);
    const auto        done
      = run_concurrently(n_jobs, o.threads, [&](const std::size_t job) {
          const unsigned int c = static_cast<unsigned int>(job % o.catalogues);
          RatchetHistory    &h = result.histories[c];
          if (job < o.catalogues)
            {
              // The coupled history.
              const auto t0 = std::chrono::steady_clock::now();
              try
                {
                  RatchetRun  run(scene, temperature, forcing, alpha, rc);
                  std::size_t k = 0;
                  while (k < result.quakes.size()
                         && result.quakes[k].catalogue != c)
                    ++k;
                  for (unsigned int y = 0; y < cycles; ++y)
                    {
                      try
                        {
                          run.run_cycle();
                        }
                      catch (const dda::DdaFailure &x)
                        {
                          throw dda::DdaFailure("thermal cycle "
                                                + std::to_string(y + 1) + ": "
                                                + x.what());
                        }
                      for (; k < result.quakes.size()
                             && result.quakes[k].catalogue == c
                             && result.quakes[k].event.time < y + 1.;
                           ++k)
                        if (result.quakes[k].runs)
                          {
                            try
                              {
                                result.quakes[k].coupled
                                  = run.run_episode(records[k], o.episode);
                              }
                            catch (const dda::DdaFailure &x)
                              {
                                throw dda::DdaFailure(
                                  "earthquake after cycle "
                                  + std::to_string(y + 1) + " (Mw "
                                  + io::format_number(
                                    result.quakes[k].event.magnitude, 3)
                                  + "): " + x.what());
                              }
                            h.coupled_episodes += result.quakes[k].coupled.slip;
                          }
                      h.yearly.push_back(run.displacement());
                    }
                  h.coupled = run.displacement();
                }
              catch (const std::exception &x)
                {
                  h.failure = std::string("coupled run: ") + x.what();
                  h.coupled = nan;
                }
              h.wall_time = seconds_since(t0);
              return;
            }
          // The events alone: on the scene without cycles, on Block 1.
          try
            {
              RatchetRun run(scene, temperature, forcing, alpha, rc);
              for (std::size_t k = 0; k < result.quakes.size(); ++k)
                {
                  RatchetQuake &q = result.quakes[k];
                  if (q.catalogue != c || !q.runs)
                    continue;
                  q.alone = run.run_episode(records[k], o.episode);
                  if (q.pga >= ky)
                    {
                      q.block1 = run_block1_dda(block1,
                                                block1_materials,
                                                records[k],
                                                b1,
                                                q.duration)
                                   .slip;
                      q.block1_analytical = block1_analytical_slip(
                        block1, block1_materials, records[k], q.duration);
                    }
                  h.quakes_block1 += q.block1;
                }
              h.quakes_scene = run.displacement();
            }
          catch (const std::exception &x)
            {
              alone_failure[c] = std::string("earthquakes alone: ") + x.what();
              h.quakes_scene = h.quakes_block1 = nan;
            }
        });
    for (std::size_t job = 0; job < n_jobs; ++job)
      if (!done.done[job])
        {
          RatchetHistory &h = result.histories[job % o.catalogues];
          if (job < o.catalogues)
            h.coupled = nan;
          else
            h.quakes_scene = h.quakes_block1 = nan;
          h.failure = "not run (interrupted)";
        }
    if (!o.quakes_on_scene)
      for (auto &h : result.histories)
        h.quakes_scene = h.quakes_block1 = nan;
    for (unsigned int c = 0; c < o.catalogues; ++c)
      if (!alone_failure[c].empty())
        result.histories[c].failure
          += (result.histories[c].failure.empty() ? "" : "; ")
             + alone_failure[c];
    result.threads     = done.threads;
    result.dda_seconds = seconds_since(start) - result.motion_seconds;
    return result;
  }
} // namespace rockdda::coupling
