/**
 * @file
 * Earthquakes inside the coupled thermo-mechanical ratchet (issue 15, item
 * 3): seeded Gutenberg-Richter catalogues whose events hit the same
 * evolving DDA state as the seasonal cycles (RatchetRun::run_episode()),
 * against the same cycles without earthquakes and the earthquakes without
 * cycles, on the ratchet scene and on Block 1 alone (the 'compare'
 * analysis' seismic part). doc/theory/compare.md, "The combined history in
 * DDA", describes the method.
 */
#ifndef ROCKDDA_COUPLING_RATCHET_EARTHQUAKES_H
#define ROCKDDA_COUPLING_RATCHET_EARTHQUAKES_H

#include <rockdda/coupling/block1_seismic.h>
#include <rockdda/coupling/compare.h>
#include <rockdda/coupling/ratchet.h>

#include <cstdint>
#include <string>
#include <vector>

namespace rockdda::coupling
{
  /// The catalogues and how their events run (SI).
  struct RatchetEarthquakeOptions
  {
    /// Magnitude distribution and mean interval between events (yr; one
    /// ratchet cycle is one year). A recurrence shorter than the region's
    /// is an acceleration of the catalogue: more events per cycle.
    GutenbergRichter gr;
    /// Catalogues; catalogue i (0-based) uses seed first_seed + i.
    unsigned int  catalogues = 0;
    std::uint64_t first_seed = 1;
    /// Joyner-Boore distance of every event (m) and whether the motions
    /// carry the Masada site amplification.
    double distance    = 1e3;
    bool   masada_site = true;
    /// Events whose site-amplified PGA is below this (g) do not run (0:
    /// every event runs).
    double minimum_pga = 0.;
    /// The dynamic steps of an episode.
    EpisodeControls episode;
    /// Run the events of each catalogue on a fresh ratchet scene without
    /// thermal cycles too (the seismic part on the same scene).
    bool quakes_on_scene = true;
    /// Block 1 alone (the 'compare' analysis' seismic runs: no cliff, no
    /// infill, this penalty in N/m, the episode's time step), for the
    /// events whose PGA reaches its yield acceleration.
    double block1_penalty = 1e11;
    /// Runs at once (0: one per core); each DDA solver uses one thread.
    unsigned int threads = 0;
  };

  /// One event of one catalogue.
  struct RatchetQuake
  {
    unsigned int   catalogue = 0;
    CatalogueEvent event;
    /// PGA (g) and length (s) of its site-amplified motion.
    double pga = 0., duration = 0.;
    /// Whether it ran (PGA >= RatchetEarthquakeOptions::minimum_pga).
    bool runs = false;
    /// The episode in the coupled run and on the scene without cycles.
    EpisodeRecord coupled, alone;
    /// Slip of Block 1 alone (m): DDA and the rigid block; 0 for an event
    /// whose PGA is below Block 1's yield acceleration (not run: the rigid
    /// block cannot slide).
    double block1 = 0., block1_analytical = 0.;
  };

  /// One catalogue's histories (m, along the bedding plane, + downslope).
  struct RatchetHistory
  {
    unsigned int catalogue = 0;
    /// Events of the catalogue and those that ran.
    unsigned int events = 0, episodes = 0;
    /// Displacement after the last cycle: the coupled run (cycles and
    /// earthquakes), the sum of its episodes' slips, the earthquakes alone
    /// on the scene and on Block 1 alone.
    double coupled = 0., coupled_episodes = 0.;
    double quakes_scene = 0., quakes_block1 = 0.;
    /// Coupled displacement at the end of each year (after its events).
    std::vector<double> yearly;
    /// Wall time of the coupled run (s).
    double wall_time = 0.;
    /// Empty if every run of the catalogue finished, else why not.
    std::string failure;
  };

  /// What run_ratchet_earthquakes() gives.
  struct RatchetEarthquakeResult
  {
    std::vector<RatchetQuake>   quakes;
    std::vector<RatchetHistory> histories;
    /// Threads used; seconds of the motions and of the DDA runs.
    unsigned int threads        = 1;
    double       motion_seconds = 0., dda_seconds = 0.;
  };

  /**
   * For each catalogue over @p cycles years (gutenberg_richter_catalogue(),
   * the motions simulated serially: FFTW planning is not thread-safe), run
   * the coupled history: cycle y + 1 of a RatchetRun, then the events of
   * year [y, y + 1) as RatchetRun::run_episode(), for y = 0 ... cycles - 1;
   * and, if asked, the same events on a fresh RatchetRun without cycles
   * and on Block 1 alone (@p block1, @p block1_materials). The runs go
   * concurrently (run_concurrently(), solvers on one thread each; results
   * independent of the number of threads). A run that fails is recorded
   * (RatchetHistory::failure), not thrown; after SIGINT or SIGTERM the runs
   * not started are recorded as "not run (interrupted)". Throws InputError
   * naming the key ('Ratchet earthquakes/...') for bad options.
   */
  RatchetEarthquakeResult
  run_ratchet_earthquakes(const RatchetScene             &scene,
                          const PeriodicBlockTemperature &temperature,
                          const SeasonalForcing          &forcing,
                          const double                    alpha,
                          const RatchetControls          &controls,
                          const unsigned int              cycles,
                          const Block1Geometry           &block1,
                          const Block1Materials          &block1_materials,
                          const RatchetEarthquakeOptions &options);
} // namespace rockdda::coupling

#endif
