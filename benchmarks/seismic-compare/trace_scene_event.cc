/**
 * @file
 * benchmarks/seismic-compare: one event of a ratchet-earthquakes catalogue
 * on the ratchet scene without cycles (RatchetRun::run_episode() on a fresh
 * scene, as "earthquakes alone on the scene"), with parts of the scene
 * changed, to find which part needs a short episode time step.
 *   trace_scene_event SEED YEAR DT [KEY=VALUE ...]
 * SEED, YEAR: the event of catalogue SEED in [YEAR, YEAR + 1) (window 200
 * yr, recurrence 20 yr, b = 1, Mw 6-7.5 at 1 km, Masada site); DT: episode
 * time step (s). Changes (defaults: parameter-files/masada/
 * ratchet-earthquakes-block1.prm): penalty=N/m (1e13), infill=0|1 (1),
 * slices=N (4), bedding_shear=Pa/m (1e9), cliff=m (8), crack_top=m (0.2),
 * crack_bottom=m (0.02), damping=- (0: the episode's contact damping ratio,
 * EpisodeControls::contact_damping). The heat solution is a cheap one (degree
 * 1, 24 steps a cycle): only the eigenstrains of the settled scene depend on
 * it. Prints the episode's slip, dynamic slip, largest rotation, steps, cuts
 * and energy balance change.
 */
#include <rockdda/coupling/compare.h>
#include <rockdda/coupling/earthquakes.h>
#include <rockdda/coupling/ratchet.h>
#include <rockdda/coupling/ratchet_scene.h>
#include <rockdda/seismic/stochastic.h>

#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <string>

using namespace rockdda;
using namespace rockdda::coupling;

int
main(int argc, char **argv)
{
  if (argc < 4)
    {
      std::fprintf(stderr, "usage: %s SEED YEAR DT [KEY=VALUE ...]\n", argv[0]);
      return 2;
    }
  const auto   seed = static_cast<std::uint64_t>(std::atoll(argv[1]));
  const double year = std::atof(argv[2]);
  const double dt   = std::atof(argv[3]);

  RatchetGeometry  geometry;
  RatchetMaterials materials;
  RatchetControls  controls;
  EpisodeControls  ec;
  geometry.infill_top_depth         = 6.;
  geometry.infill_height            = 2.;
  geometry.supply_distance          = 2.;
  geometry.slices                   = 4;
  materials.bedding_shear_stiffness = 1e9;
  controls.penalty                  = 1e13;
  controls.threads                  = 1;
  for (int a = 4; a < argc; ++a)
    {
      const std::string arg = argv[a];
      const auto        eq  = arg.find('=');
      const std::string key = arg.substr(0, eq);
      const double      v   = std::atof(arg.substr(eq + 1).c_str());
      if (key == "penalty")
        controls.penalty = v;
      else if (key == "infill")
        geometry.infill = v != 0.;
      else if (key == "slices")
        geometry.slices = static_cast<unsigned int>(v);
      else if (key == "bedding_shear")
        materials.bedding_shear_stiffness = v;
      else if (key == "cliff")
        geometry.cliff_width = v;
      else if (key == "crack_top")
        geometry.crack_top_width = v;
      else if (key == "crack_bottom")
        geometry.crack_bottom_width = v;
      else if (key == "damping")
        ec.contact_damping = v;
      else
        {
          std::fprintf(stderr, "unknown key %s\n", key.c_str());
          return 2;
        }
    }
  if (!geometry.infill)
    geometry.supply_distance = 0.;

  GutenbergRichter gr;
  gr.recurrence                        = 20.;
  seismic::StochasticParameters motion = EarthquakeOptions::default_motion();
  motion.distance                      = 1000.;
  seismic::Record record;
  bool            found = false;
  for (const auto &e : gutenberg_richter_catalogue(gr, 200., seed))
    if (e.time >= year && e.time < year + 1.)
      {
        motion.magnitude = e.magnitude;
        record           = seismic::simulate(motion, e.motion_seed, true);
        found            = true;
        std::printf("event: t = %.3f yr, Mw %.3f, PGA %.3f g, %.1f s\n",
                    e.time,
                    e.magnitude,
                    record.peak(),
                    record.duration());
        break;
      }
  if (!found)
    {
      std::fprintf(stderr, "no event in that year\n");
      return 2;
    }

  const auto         start = std::chrono::steady_clock::now();
  SeasonalForcing    forcing;
  const RatchetScene scene = make_ratchet_scene(geometry, materials);
  HeatControls       heat;
  heat.degree            = 1;
  heat.time_step         = forcing.period / 24.;
  heat.spin_up_cycles    = 3;
  heat.samples_per_cycle = 24;
  const PeriodicBlockTemperature temperature(scene.heat_blocks, forcing, heat);
  RatchetRun run(scene, temperature, forcing, 8e-6, controls);
  ec.time_step          = dt;
  const EpisodeRecord r = run.run_episode(record, ec);
  const double        sec
    = std::chrono::duration<double>(std::chrono::steady_clock::now() - start)
        .count();
  std::printf("dt %.4e s, contact damping %.3f: slip %.3f mm (dynamic %.3f "
              "mm), max rotation %.3e rad, %lu dynamic steps, %lu cuts, "
              "balance change %.3e of %.3e J/m, %.1f s\n",
              dt,
              ec.contact_damping,
              1e3 * r.slip,
              1e3 * r.dynamic_slip,
              r.max_rotation,
              r.dynamic_steps,
              r.dynamic_cuts,
              r.energy_gain,
              r.energy_scale,
              sec);
  return 0;
}
