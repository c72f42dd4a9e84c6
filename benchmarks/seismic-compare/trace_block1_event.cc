/**
 * @file
 * benchmarks/seismic-compare: one event of a ratchet-earthquakes catalogue
 * on Block 1 alone (the scene and controls of run_block1_dda() as
 * run_ratchet_earthquakes() uses them), step by step, to trace what DDA does
 * at a given episode time step.
 *   trace_block1_event SEED YEAR DT [PENALTY [TRACE.csv [RECURRENCE]]]
 * SEED: catalogue seed; YEAR: the event of the catalogue in [YEAR, YEAR+1),
 * or -1 for every event whose PGA reaches the yield acceleration
 * (window 200 yr, recurrence 20 yr, b = 1, Mw 6-7.5 at 1 km, Masada site:
 * parameter-files/masada/ratchet-earthquakes-block1.prm); DT (s), PENALTY
 * (N/m, default 1e11). Prints one line: the slip, the rigid block's, the
 * largest rotation, steps (those without a closed contact: the block in
 * the air), cuts, the energy balance change over the
 * dynamic steps and the energy in play; with TRACE.csv, one row per
 * accepted step (time, dt, slip, rotation, the block's velocity, contact
 * states, the normal forces of the two base vertices, the energy terms).
 */
#include <rockdda/coupling/block1_seismic.h>
#include <rockdda/coupling/compare.h>
#include <rockdda/coupling/earthquakes.h>
#include <rockdda/seismic/stochastic.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <string>

using namespace rockdda;

namespace
{
  /// Run @p record on Block 1 at step @p dt and penalty @p penalty; print
  /// the summary line, and one row per step into @p trace_file if given.
  void
  run_event(const seismic::Record           &record,
            const coupling::Block1Geometry  &geometry,
            const coupling::Block1Materials &materials,
            const double                     dt,
            const double                     penalty,
            const std::string               &trace_file)
  {
    const double duration = record.duration();

    // As run_block1_dda() with the controls of run_ratchet_earthquakes().
    coupling::Block1Scene scene
      = coupling::make_block1_seismic_scene(geometry, materials, "Ratchet");
    scene.blocks.seismic.mode   = dda::SeismicInput::Mode::inertial;
    scene.blocks.seismic.record = record;
    {
      const std::size_t n = static_cast<std::size_t>(std::ceil(
                              (duration + 2. * dt) / record.dt - 1e-9))
                            + 1;
      if (scene.blocks.seismic.record.acceleration.size() > n)
        scene.blocks.seismic.record.acceleration.resize(n);
    }
    dda::Controls c;
    c.time_step          = dt;
    c.dynamic            = 1.;
    c.law.normal_penalty = penalty;
    c.solver.threads     = 1;
    c.max_steps = static_cast<unsigned long>(20. * duration / dt) + 1000;
    dda::DdaSystem d(scene.blocks, c);
    d.settle(50);
    const double balance0 = d.energy().balance();

    std::FILE *trace
      = trace_file.empty() ? nullptr : std::fopen(trace_file.c_str(), "w");
    if (trace)
      std::fprintf(trace,
                   "time,dt,iterations,cuts,slip,rotation,vx,vy,omega,"
                   "ground_acc,n_open,n_sliding,n_locked,normal_toe,"
                   "normal_heel,normal_total,shear_total,kinetic,contact,"
                   "potential,strain,friction,load_work,balance\n");
    double        max_rotation = 0.;
    unsigned long airborne     = 0;
    // Vertices of the block: 0 heel, 1 toe (analytical::Block1Section).
    while (d.time() < duration - 1e-3 * dt)
      {
        const dda::StepReport r   = d.step();
        const auto           &blk = d.system().blocks[scene.block];
        max_rotation = std::max(max_rotation, std::abs(blk.rotation));
        // No closed contact: the block is in the air (a bounce).
        airborne += r.n_sliding + r.n_locked == 0 ? 1 : 0;
        if (trace)
          {
            double n_toe = 0., n_heel = 0., n_sum = 0., s_sum = 0.;
            for (const auto &k : d.contacts())
              if (k.state != dda::ContactState::open)
                {
                  n_sum += k.normal_force;
                  s_sum += k.shear_force;
                  if (k.geometry.block_i == scene.block
                      && k.geometry.vertex == 1)
                    n_toe += k.normal_force;
                  if (k.geometry.block_i == scene.block
                      && k.geometry.vertex == 0)
                    n_heel += k.normal_force;
                }
            const auto e = d.energy();
            std::fprintf(
              trace,
              "%.6f,%.4e,%u,%u,%.6e,%.4e,%.4e,%.4e,%.4e,%.4e,%u,%u,%u,"
              "%.5e,%.5e,%.5e,%.5e,%.5e,%.5e,%.5e,%.5e,%.5e,%.5e,"
              "%.5e\n",
              r.time,
              r.dt,
              r.iterations,
              r.cuts,
              coupling::block1_slip(d, scene),
              blk.rotation,
              blk.velocity[0],
              blk.velocity[1],
              blk.velocity[2],
              d.ground_acceleration(r.time)[0],
              r.n_open,
              r.n_sliding,
              r.n_locked,
              n_toe,
              n_heel,
              n_sum,
              s_sum,
              e.kinetic,
              e.contact,
              e.potential,
              e.strain,
              e.friction,
              e.load_work,
              e.balance());
          }
      }
    if (trace)
      std::fclose(trace);
    const auto   e    = d.energy();
    const double slip = coupling::block1_slip(d, scene);
    const double rigid
      = coupling::block1_analytical_slip(geometry, materials, record, duration);
    std::printf("dt %.4e s, penalty %.3e N/m: slip %.2f mm (rigid %.2f mm), "
                "max rotation %.3e rad, %lu steps (%lu airborne), %lu cuts, "
                "balance change "
                "%.3e J/m of %.3e in play\n",
                dt,
                penalty,
                1e3 * slip,
                1e3 * rigid,
                max_rotation,
                d.n_steps,
                airborne,
                d.n_cuts,
                e.balance() - balance0,
                e.scale());
  }
} // namespace

int
main(int argc, char **argv)
{
  if (argc < 4)
    {
      std::fprintf(stderr,
                   "usage: %s SEED YEAR DT [PENALTY [TRACE.csv "
                   "[RECURRENCE]]]\n",
                   argv[0]);
      return 2;
    }
  const auto        seed    = static_cast<std::uint64_t>(std::atoll(argv[1]));
  const double      year    = std::atof(argv[2]);
  const double      dt      = std::atof(argv[3]);
  const double      penalty = argc > 4 ? std::atof(argv[4]) : 1e11;
  const std::string trace_file = argc > 5 ? argv[5] : "";

  coupling::GutenbergRichter gr;
  gr.recurrence = argc > 6 ? std::atof(argv[6]) : 20.;
  seismic::StochasticParameters motion
    = coupling::EarthquakeOptions::default_motion();
  motion.distance = 1000.;
  const coupling::Block1Geometry  geometry;
  const coupling::Block1Materials materials;
  const double ky    = coupling::block1_yield_acceleration(geometry, materials);
  bool         found = false;
  for (const auto &e : coupling::gutenberg_richter_catalogue(gr, 200., seed))
    {
      if (year >= 0. && !(e.time >= year && e.time < year + 1.))
        continue;
      motion.magnitude = e.magnitude;
      const seismic::Record record
        = seismic::simulate(motion, e.motion_seed, true);
      if (year < 0. && record.peak() < ky)
        continue;
      std::printf("event: t = %.3f yr, Mw %.3f, motion seed %llu, PGA "
                  "%.3f g, %.1f s\n",
                  e.time,
                  e.magnitude,
                  static_cast<unsigned long long>(e.motion_seed),
                  record.peak(),
                  record.duration());
      found = true;
      run_event(record, geometry, materials, dt, penalty, trace_file);
    }
  if (!found)
    {
      std::fprintf(stderr,
                   "no event in year %g of catalogue %llu\n",
                   year,
                   static_cast<unsigned long long>(seed));
      return 2;
    }
  return 0;
}
