/**
 * @file
 * The coupled thermo-mechanical ratchet: annual cycles of quasi-static DDA
 * steps of a RatchetScene loaded by the thermal eigenstrains of the
 * periodic block temperatures (thesis 5.4; the study driver's core).
 */
#ifndef ROCKDDA_COUPLING_RATCHET_H
#define ROCKDDA_COUPLING_RATCHET_H

#include <rockdda/coupling/ratchet_scene.h>
#include <rockdda/coupling/thermal_load.h>
#include <rockdda/dda/engine.h>
#include <rockdda/seismic/record.h>

#include <array>
#include <deque>
#include <limits>
#include <memory>
#include <string>
#include <vector>

namespace rockdda::coupling
{
  /// Numerical controls of the quasi-static DDA of a ratchet run.
  struct RatchetControls
  {
    /// Normal contact penalty (N/m); 0 = automatic (dda::automatic_penalty).
    double penalty = 0.;
    /// Pseudo time step of the static steps (s): only the inertia term
    /// 2 M / dt^2 that regularises them depends on it. 0 = automatic
    /// (RatchetRun::quasi_static_time_step()): the quasi-static limit.
    double pseudo_time_step = 0.;
    /// A sample is in equilibrium when a static step moves no vertex by more
    /// than this fraction of the block height (1e-8: 0.15 um for Block 1,
    /// 1e-3 of the ratchet per cycle; tighter tolerances meet the
    /// micro-chatter of the infill's contacts, ~1e-7 m per step).
    double equilibrium_tolerance = 1e-8;
    /// Static steps allowed per sample before the run stops (DdaFailure).
    unsigned int max_steps_per_sample = 20000;
    /// Static steps that settle the scene under gravity before cycle 1.
    unsigned int settle_steps = 30;
    /// Temperature samples per cycle at which the DDA is brought to
    /// equilibrium (a divisor of the heat table's samples is exact).
    unsigned int steps_per_cycle = 24;
    /// Threads of the DDA's linear solver (dda::SolverOptions::threads;
    /// 0: the default). Concurrent runs use 1.
    int threads = 0;
    /// dda::Controls::cut_exact_cycles (off only to test that it changes no
    /// accepted step).
    bool cut_exact_cycles = true;
    /// Cycle jumps (RatchetRun::jump()): the most cycles one jump skips (0:
    /// none); the simulated cycles whose mean motion it extrapolates (>= 1;
    /// the cycle after a jump is not among them); the relative change of
    /// the slip per cycle between two jumps' windows up to which the next
    /// jump doubles (beyond it, it halves; the first is 2 jump_window).
    unsigned int jump_max       = 0;
    unsigned int jump_window    = 4;
    double       jump_tolerance = 0.1;
  };

  /// How RatchetRun::run_episode() runs an earthquake (SI).
  struct EpisodeControls
  {
    /// Time step of the dynamic steps (s), > 0 (the calibrated 0.005 s of
    /// the 'calibrate' analysis).
    double time_step = 0.005;
    /// Dynamic steps after the end of the record (s), >= 0: the ground at
    /// rest, the block decelerates and stops on its bedding plane before
    /// the run returns to static steps (which drop any motion left).
    double rest_time = 2.;
    /// Gravitational acceleration converting the record's g to m/s^2.
    double g = 9.80665;
    /// Ratio of critical (-, >= 0) of the dashpots in parallel with the
    /// closed contacts' springs in the dynamic steps (dda::ContactDamping;
    /// the bedding joint's physical damping); 0: none.
    double contact_damping = 0.;
    /// Key names in the errors.
    std::string time_step_key = "Ratchet earthquakes/Time step";
    std::string rest_time_key = "Ratchet earthquakes/Rest time";
    std::string contact_damping_key
      = "Ratchet earthquakes/Contact damping ratio";
  };

  /// What one earthquake did to a ratchet run (SI; along the bedding
  /// plane, + downslope).
  struct EpisodeRecord
  {
    /// Change of RatchetRun::displacement() over the dynamic steps, and
    /// over the whole episode (dynamic steps, the return to static steps
    /// and the new equilibrium: the infill dropping into the opening).
    double dynamic_slip = 0., slip = 0.;
    /// Change of the crack aperture at the top over the episode (m).
    double aperture = 0.;
    /// Descent of the newest infill fragment over the episode (m).
    double infill_descent = 0.;
    /// Largest |rotation| of a block slice during the dynamic steps (rad).
    double max_rotation = 0.;
    /// Energy ledger over the dynamic steps (J/m): change of
    /// dda::EnergyLedger::balance() (<= 0 up to round-off: the time
    /// integration only dissipates) and the energy in play at the end.
    double energy_gain = 0., energy_scale = 0.;
    /// Dynamic steps and cuts; static steps and cuts of the return.
    unsigned long dynamic_steps = 0, dynamic_cuts = 0;
    unsigned long static_steps = 0, static_cuts = 0;
    /// Infill fragments in the crack after the episode.
    unsigned int fragments = 0;
  };

  /// What one cycle did (SI; displacement down the bedding plane).
  struct CycleRecord
  {
    unsigned int cycle = 0;
    /// Block displacement since the start and during this cycle (m).
    double displacement = 0., permanent = 0.;
    /// Change of the crack aperture at the top since the start (m).
    double aperture = 0.;
    /// Descent of the infill since the start (m).
    double infill_descent = 0.;
    /// Contacts per state at the end of the cycle.
    unsigned int n_open = 0, n_sliding = 0, n_locked = 0;
    /// Static DDA steps and step cuts of the cycle.
    unsigned long steps = 0, cuts = 0;
    /// Samples accepted as stationary although a contact kept switching
    /// between states (see RatchetRun::equilibrate), and the largest vertex
    /// motion per step or limit-cycle amplitude of the slip or aperture in
    /// such a sample (m).
    unsigned int stationary_samples = 0;
    double       chatter            = 0.;
    /// Infill fragments in the crack at the end of the cycle (the first
    /// and those supplied; RatchetGeometry::supply_distance).
    unsigned int fragments = 0;
    /// Elastic energy stored at the end of the cycle (the same phase every
    /// cycle), J per metre of out-of-plane thickness: the blocks' strain
    /// energy and the contact and fixed-point springs'. A cycle that only
    /// repeats itself stores the same energy.
    double stored_energy = 0.;
  };

  /**
   * What RatchetRun::jump() did: the cycles it skipped and the state before
   * and after them (SI; displacement down the bedding plane, changes since
   * the start as in CycleRecord).
   */
  struct JumpRecord
  {
    /// Cycles extrapolated (0: no jump was possible).
    unsigned int cycles = 0;
    /// Block displacement, crack aperture and infill descent before and
    /// after the jump (m).
    double displacement_before = 0., displacement_after = 0.;
    double aperture_before = 0., aperture_after = 0.;
    double descent_before = 0., descent_after = 0.;
    /// Smallest fraction of its extrapolated motion that an infill fragment
    /// was given (1: all; less where the full motion would have pressed it
    /// deeper into a face than it was; it then drops the rest in the next
    /// cycle).
    double infill_fraction = 1.;
    /// Largest sideways offset given to a fragment, as a fraction of its
    /// extrapolated motion (RatchetRun::jump()).
    double infill_offset = 0.;
  };

  /// One temperature sample within a cycle (the loop of thesis Fig. 5-6).
  struct SampleRecord
  {
    double phase        = 0.; ///< fraction of the period
    double air          = 0.; ///< air temperature, deg C
    double block_mean   = 0.; ///< area mean temperature of the block, deg C
    double displacement = 0.; ///< m, since the start
    double aperture     = 0.; ///< m, change since the start
  };

  /**
   * Runs the cycles. The DDA steps are static (dynamic control 0); at each
   * sample the eigenstrains are set and static steps are taken until the
   * motion per step is below the equilibrium tolerance, so the number of
   * steps per season adapts: many while contacts change state, one or two
   * while nothing moves.
   */
  class RatchetRun
  {
  public:
    RatchetRun(const RatchetScene             &scene,
               const PeriodicBlockTemperature &temperature,
               const SeasonalForcing          &forcing,
               const double                    alpha,
               const RatchetControls          &controls);

    /// Run the next cycle; @p samples (optional) receives its samples.
    CycleRecord
    run_cycle(std::vector<SampleRecord> *samples = nullptr);

    /**
     * A cycle jump (cycle-jump extrapolation of a periodic ratchet, as in
     * the fatigue and ratcheting literature: Lemaitre & Chaboche 1990;
     * Cojocaru & Karlsson 2006). Skips m cycles, at most @p cycles, by
     * moving every block by m times its mean motion per cycle over the
     * RatchetControls::jump_window cycles simulated since the last jump
     * (the first cycle after a jump is not among them: it settles what the
     * jump left).
     * - m: RatchetControls::jump_window x 2 at first, then as
     *   review_jump() sets it; at most RatchetControls::jump_max; with a
     *   supply rule, short of the newest fragment's supply; shortened to
     *   the fraction of its drift that an infill fragment can descend
     *   (the wedge reaching the crack's bottom).
     * - The block's slices move together, along the bedding plane; the
     *   cliff stays.
     * - Each infill fragment, oldest first, moves as far along its own
     *   mean motion as it can without pressing into a face deeper than its
     *   deepest contact once the block moved, with a sideways offset that
     *   keeps it between the faces (the rest it drops in the next cycle).
     * - Stresses and contact springs are kept
     *   (dda::DdaSystem::translate_blocks()).
     *
     * Returns cycles = 0 if jumps are off or the window is not full yet.
     */
    JumpRecord
    jump(const unsigned int cycles);
    /**
     * Review the last jump once the window after it is full: its slip per
     * cycle against the window the jump extrapolated. If they differ by at
     * most RatchetControls::jump_tolerance (relative) beyond two standard
     * errors of the difference of the two means (the cycles' scatter: a
     * change the windows cannot resolve is not one), the jump stands and
     * the next one doubles (up to RatchetControls::jump_max). Beyond it a jump
     * of more than one cycle is undone: the run returns to its state
     * before the jump (cycles() says where) and the next jump is half as
     * long, so a change of regime inside a jump (a burst, the wedge
     * reaching the crack's bottom) costs simulated cycles, not accuracy.
     * Returns whether the run was rewound; @p change (optional) receives
     * the relative change.
     */
    bool
    review_jump(double *change = nullptr);
    /// Cycles simulated since the last jump (or the start) that jump() can
    /// extrapolate from: its window is full at RatchetControls::jump_window.
    unsigned int
    cycles_in_window() const
    {
      return history.empty() ? 0
                             : static_cast<unsigned int>(history.size()) - 1;
    }

    /**
     * An earthquake between two cycles (after cycles() of them), on the
     * same DDA state: the engine switches to dynamic steps of
     * EpisodeControls::time_step with @p record (g, positive towards +x,
     * the scene's downslope-horizontal direction) as an inertial load on
     * every block (dda::DdaSystem::set_seismic_input()) until the record's
     * end plus the rest time, the eigenstrains held at those of the end of
     * the last cycle; then it returns to static steps at the pseudo time
     * step (the blocks at rest; the step grows back from the dynamic one by
     * dda::Controls::growth), brings the scene to equilibrium (the infill
     * drops into what the quake opened) and applies the supply rule. The
     * next run_cycle() resumes the thermal cycling from this state. Throws
     * InputError naming the key for a time step <= 0 or a rest time < 0,
     * dda::DdaFailure if DDA cannot continue.
     */
    EpisodeRecord
    run_episode(const seismic::Record &record, const EpisodeControls &controls);

    /// Block displacement down the bedding plane since the start (m): the
    /// mean of its base corners' displacements (the slip).
    double
    displacement() const;
    /// The automatic pseudo time step of @p scene's static steps (s) at the
    /// normal penalty @p penalty (N/m): 2 M / dt^2 = 1e-9 p for the
    /// heaviest block slice, the quasi-static limit.
    static double
    quasi_static_time_step(const RatchetScene &scene, const double penalty);
    /// The pseudo time step of the static steps in use (s).
    double
    time_step() const
    {
      return pseudo_time_step;
    }
    /// Change of the crack aperture at the top since the start (m).
    double
    aperture() const;
    /// Descent of the first infill fragment since the start (m; 0 without
    /// infill).
    double
    infill_descent() const;
    /// Cycles done.
    unsigned int
    cycles() const
    {
      return n_cycles;
    }
    const dda::DdaSystem &
    dda() const
    {
      return *engine;
    }
    /// The state to continue bit for bit (DDA state and cycle count).
    std::string
    checkpoint() const;
    /// Continue from checkpoint() bytes (InputError naming @p source).
    void
    restore(const std::string &bytes, const std::string &source);

  private:
    /**
     * Bring the scene to equilibrium at @p time, adding to the steps, cuts
     * and chatter of @p record. Equilibrium: a step that moves no vertex
     * by more than the tolerance, or (a contact at the friction limit that
     * switches between sliding and locked every few steps, moving one
     * vertex back and forth) 100 steps, cut or not, over which the base
     * slip and the crack aperture stay within the tolerance, or (a light
     * fragment rocking between the crack's faces) a bounded limit cycle:
     * over two successive windows of 200 steps the means of the slip and the
     * aperture agree within the tolerance and their amplitude is at most 10
     * tolerances. The pseudo time step stays that of the run. A sample
     * still not in equilibrium after RatchetControls::max_steps_per_sample
     * steps stops the run with dda::DdaFailure, whose message says whether
     * the slip and the aperture were still drifting (something slides or
     * creeps) or cycling without drift (contact states flipping).
     */
    void
    equilibrate(const double time, CycleRecord &record);
    double
    raw_aperture() const;
    /**
     * The supply rule: if the newest fragment's top has descended by the
     * scene's supply distance, place a new fragment of the infill's height
     * at the infill's initial position, spanning the crack as it is now
     * less a clearance of 1e-3 of its width on each side (it drops and
     * wedges), stress-free at the air temperature of @p time.
     */
    void
    supply(const double time);
    /// x of the straight face through vertices @p a and @p b at height y.
    double
    face_x(const std::pair<int, int> &a,
           const std::pair<int, int> &b,
           const double               y) const;
    /// Current position of vertex (block, index).
    const geometry::Point &
    vertex(const std::pair<int, int> &v) const;

    const RatchetScene             &scene;
    const PeriodicBlockTemperature &temperature;
    SeasonalForcing                 forcing;
    double                          alpha;
    RatchetControls                 ctrl;
    std::unique_ptr<dda::DdaSystem> engine;
    /// The scene's heat map, extended by the supplied fragments (air).
    BlockHeatMap heat_map;
    /// DDA indices of the infill fragments, oldest first, and the height
    /// of each one's top when it was placed (m, engine coordinates; the
    /// first's at t = 0, before settling).
    std::vector<int>    fragments;
    std::vector<double> fragment_tops;
    /// Every block's centroid (engine coordinates) at the end of the
    /// simulated cycles since the last jump, fragment supply or earthquake
    /// (the first is the end of the cycle after it), at most
    /// RatchetControls::jump_window + 1 of them.
    std::deque<std::vector<geometry::Point>> history;
    /// Length of the next jump before its limits (cycles).
    unsigned int next_jump = 1;
    /// The jump under review (review_jump()): the state before it
    /// (checkpoint(), empty: none), its length, its window's slip per
    /// cycle and that mean's standard error (m).
    std::string  pending_state;
    unsigned int pending_cycles = 0;
    double       pending_slip = 0., pending_error = 0.;
    /// The block's mean slip per cycle over the window and its standard
    /// error from the cycles' scatter (m).
    std::array<double, 2>
                 window_slip() const;
    unsigned int n_cycles  = 0;
    double       aperture0 = 0., last_displacement = 0.;
    double       tolerance = 0.;
    /// The pseudo time step in use (s): RatchetControls::pseudo_time_step
    /// or, if that is 0, quasi_static_time_step().
    double pseudo_time_step = 0.;
    double block_area       = 0.;
    /// Sum of the base corners' positions after settling (m).
    geometry::Point base_corners0 = geometry::Point::Zero();
  };
} // namespace rockdda::coupling

#endif
