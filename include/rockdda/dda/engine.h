/**
 * @file
 * DdaSystem: runs 2D DDA time steps (contact detection, open-close
 * iteration, adaptive time step, update) on a BlockSystem and exposes the
 * state.
 */
#ifndef ROCKDDA_DDA_ENGINE_H
#define ROCKDDA_DDA_ENGINE_H

#include <rockdda/dda/assembler.h>
#include <rockdda/dda/block_system.h>
#include <rockdda/dda/contact_law.h>
#include <rockdda/dda/contact_set.h>
#include <rockdda/dda/energy_ledger.h>
#include <rockdda/dda/failure.h>
#include <rockdda/dda/linear_solver.h>
#include <rockdda/dda/plausibility.h>
#include <rockdda/dda/state_check.h>
#include <rockdda/dda/time_step_control.h>

#include <algorithm>
#include <cmath>
#include <functional>
#include <limits>
#include <stdexcept>
#include <string>
#include <vector>

namespace rockdda::dda
{
  /// Numerical controls of a DDA run.
  struct Controls
  {
    /// Maximum (and initial) time step (s), > 0.
    double time_step = 1e-3;
    /// Smallest time step before the run stops (s); 0 = 1e-6 * time_step.
    double min_time_step = 0.;
    /// Dynamic control parameter in [0, 1] (0 static, 1 fully dynamic).
    double dynamic = 1.;
    /// Kelvin-Voigt viscous time of the blocks' strain (s, >= 0;
    /// StrainDamping); 0: none.
    double strain_damping = 0.;
    /// Dashpots of the closed contacts (ContactDamping): ratio of critical
    /// zeta (-, >= 0) of each spring with the lighter free block's mass,
    /// and the numerical step damping beta (-, >= 0); 0: none. Only in
    /// dynamic steps; their work is booked as EnergyLedger::damping.
    double contact_damping = 0., contact_step_damping = 0.;
    /// Open-close iterations that change contact states before the step
    /// is cut; iterations that only update friction forces may add as many
    /// again (the states and the friction forces must both converge).
    unsigned int max_iterations = 12;
    /// Largest vertex displacement per step, as a fraction of the domain
    /// size (the larger side of the bounding box of all blocks).
    double max_displacement_ratio = 0.01;
    /// The allowed vertex displacement per step of a block is also at most
    /// this fraction of the block's own size (keeps contact search and
    /// rotation per step local to the block, whatever the domain size).
    double max_displacement_block_ratio = 0.05;
    /// Contact search distance = search_factor * the allowed vertex
    /// displacement per step.
    double search_factor = 2.5;
    /// Globalise the open-close iteration with an exact line search on the
    /// convex energy of the step (engine_line_search.cc).
    bool line_search = true;
    /// Cut an attempt as soon as the open-close iteration returns bit for
    /// bit to an earlier iterate (it would cycle until the cycle limit or
    /// the iteration limit cuts it anyway): saves the solves of the
    /// attempt and changes no accepted step (doc/theory/dda.md, "Exact
    /// cycles"). Off only to test that.
    bool cut_exact_cycles = true;
    /// A contact that has changed state this many times in one attempt
    /// cycles and is held: an open one stays open, a locked one locked,
    /// while the force it would take to change (compression, tension, or
    /// shear beyond the strength) is at most p_s x hold_fraction x the
    /// smaller block's size (N/m), i.e. a penetration or elastic slip of
    /// at most hold_fraction x that size, and at most 100 force tolerances
    /// (1 % of the lighter block's weight); an open one stays open up to a
    /// penetration of hold_fraction x that size, and at most the lighter
    /// block's weight in force (it carries no force, so it hangs no
    /// block). In static steps (dynamic 0) a
    /// held contact stays held in the next step (Contact::held). Holding
    /// cannot create energy.
    unsigned int hold_after    = 4;
    double       hold_fraction = 1e-7;
    /// A contact that has changed state this many times although held: the
    /// iteration cycles, and the step is cut.
    unsigned int cycle_limit = 12;
    /// CG tolerance while the contact states settle = inexact_factor x the
    /// solver tolerance; the settled states are confirmed by one solve to
    /// the solver tolerance (<= 1: every solve to the solver tolerance).
    double inexact_factor = 1.;
    /// Contact springs.
    ContactLaw law;
    /// Fixed-point spring stiffness (N/m); 0 = 10 * the normal penalty.
    double fixed_penalty = 0.;
    /// Linear solver.
    SolverOptions solver;
    /// Factor by which the time step grows back after a step that
    /// converged without a cut in at most max(2, max_iterations / 2)
    /// iterations (>= 1).
    double growth = 1.3;
    /// Factor by which a step is cut (> 1).
    double cut_factor = 3.;
    /// Physical sanity checks of every step (dda::implausible_state()).
    /// If cutting does not help, the run stops with a diagnosis.
    PlausibilityLimits plausibility;
    /// Stop (DdaFailure) after this many steps in one run_until() call;
    /// 0 = 100 * (duration / time_step) + 1000.
    unsigned long max_steps = 0;
  };

  /// What one accepted step did.
  struct StepReport
  {
    /// Time at the end of the step (s) and its length (s).
    double time = 0., dt = 0.;
    /// Open-close iterations of the accepted attempt, and cuts before it.
    unsigned int iterations = 0, cuts = 0;
    /// Contacts per state at the end of the step.
    unsigned int n_open = 0, n_sliding = 0, n_locked = 0;
    /// Largest vertex displacement in the step (m).
    double max_displacement = 0.;
    /// Linear solver iterations (CG) summed over the step.
    unsigned long solver_iterations = 0;
    /// Strength audit of the accepted state (doc/theory/dda.md): the
    /// largest excess of a contact's force over its strength, relative to
    /// the tolerance the open-close iteration allowed that contact (0: every
    /// contact within its strength; a step above 1 is cut, not accepted).
    double strength_ratio = 0.;
  };

  /**
   * The 2D DDA engine. Owns the scene (validated on construction) and the
   * persistent contact states, and advances them step by step.
   */
  class DdaSystem
  {
  public:
    /// Validate @p scene (throws InputError naming the block) and set up.
    DdaSystem(BlockSystem scene, const Controls &controls);

    /**
     * Advance one accepted step. Cuts the step when the open-close
     * iteration does not converge, a vertex moves too far, the solver fails
     * or the result is not finite; throws DdaFailure with a diagnosis when
     * the step would fall below the minimum time step.
     */
    StepReport
    step();

    /**
     * Settle the scene under gravity before t = 0: @p steps static steps
     * (dynamic control 0, no seismic input, time not advanced), then zero
     * the velocities and take the settled state as the reference for
     * displacements. A scene that starts with uncompressed contact springs
     * otherwise drops onto them at t = 0 and, for small time steps (little
     * numerical damping of the contact vibration), keeps bouncing.
     * @p after_step (if given) is called after each static step with the
     * number of steps done; returning false ends the settling there (an
     * interrupted run).
     */
    void
    settle(const unsigned int                             steps,
           const std::function<bool(const unsigned int)> &after_step = {});

    /**
     * Set the eigenstrain of every block (in the order of the scene's
     * blocks; Block::eigenstrain), e.g. thermal strains from the coupling.
     * The next step loads each block by the change since the last step.
     * Throws InputError if the size differs or a value is not finite.
     */
    void
    set_eigenstrains(const std::vector<Eigen::Vector3d> &eigenstrains);

    /**
     * Add a block between steps (a rock fragment that falls into a crack):
     * @p block in the scene's input coordinates, at rest and stress-free
     * at its Block::eigenstrain (e.g. the thermal strain of the moment it
     * is placed); its displacement and potential energy are measured from
     * where it is placed. Checked as the scene's
     * blocks are at construction, and for overlap with the blocks as they
     * are now (InputError naming it). Contacts it forms are not bonded.
     * Returns its index (the last). A checkpoint() of a run with added
     * blocks restores into an engine of the same scene to which the same
     * blocks were added in the same order.
     */
    int
    add_block(Block block);

    /**
     * Move each block b rigidly by @p shift[b] (m) between two steps: the
     * extrapolation of a cycle jump (coupling::RatchetRun::jump()), not a
     * step of the equations of motion. Stresses, strains, velocities and
     * contact states and forces are kept; the shear reference of every
     * contact moves along its edge with the relative shift of the vertex's
     * block and the edge's, so that a pair moved together keeps its
     * springs exactly and a locked contact stays as stretched as it was.
     * Load and measurement points move with their blocks; a block with a
     * fixed point cannot move (InputError). The energy ledger restarts.
     */
    void
    translate_blocks(const std::vector<geometry::Point> &shift);

    /**
     * The smallest signed distance (m, negative = inside) of a vertex of
     * block @p block from another block's boundary or of another block's
     * vertex from its boundary, with each block b moved by @p shift[b]
     * (empty: as they are), over the blocks whose boxes come within
     * @p distance of its box; +infinity if it is more than @p distance. A
     * probe for translate_blocks(): the depth of a vertex whatever the
     * contact detection would make of it.
     */
    double
    min_gap(const int                           block,
            const std::vector<geometry::Point> &shift,
            const double                        distance) const;

    /// Advance until @p end_time (s); the last step is shortened to end
    /// there. Returns the report of the last step.
    StepReport
    run_until(const double end_time);

    const BlockSystem &
    system() const
    {
      return scene;
    }
    const std::vector<Contact> &
    contacts() const
    {
      return current_contacts;
    }
    /// The block increments D of the last accepted step (6 per block, about
    /// the centroids at the start of that step; empty before the first).
    const Eigen::VectorXd &
    last_increments() const
    {
      return last_solution;
    }
    double
    time() const
    {
      return t;
    }
    double
    time_step() const
    {
      return step_control.current();
    }
    double
    domain_size() const
    {
      return domain;
    }
    /// Allowed vertex displacement per step of block @p b (m): the smaller
    /// of max_displacement_ratio x the domain size and
    /// max_displacement_block_ratio x the block's size.
    double
    allowed_displacement(const int b) const
    {
      return allowed_step[b];
    }
    const std::vector<std::string> &
    warnings() const
    {
      return warning_list;
    }
    /// Solver used in the last step.
    SolverType
    solver_type() const
    {
      return solver.type();
    }
    /// The linear solver (type, threads and ordering of the last step).
    const LinearSolver &
    linear_solver() const
    {
      return solver;
    }
    const Controls &
    controls() const
    {
      return ctrl;
    }

    /**
     * Change the requested time step (s, > 0) from the next step on; the
     * current step is capped by it and grows back by Controls::growth per
     * step after a reduction; the minimum time step keeps its ratio to it.
     * For quasi-static drivers that regularise a stalled equilibrium
     * iteration with a smaller pseudo time step (a larger inertia term).
     */
    void
    set_time_step(const double time_step);

    /**
     * Switch the steps between static (0) and dynamic (1) from the next
     * step on (Controls::dynamic; InputError outside [0, 1]), e.g. a
     * seismic episode within a quasi-static run. Going from static to
     * dynamic starts every block at rest: the velocities of static steps
     * are increments over the pseudo time step, not motion.
     */
    void
    set_dynamic(const double dynamic);

    /**
     * Change the contact dashpots from the next step on
     * (Controls::contact_damping, Controls::contact_step_damping): the
     * ratio of critical @p ratio and the step damping @p step_ratio (both
     * >= 0, InputError otherwise), e.g. a joint's damping during a seismic
     * episode. They act only in dynamic steps.
     */
    void
    set_contact_damping(const double ratio, const double step_ratio = 0.);

    /**
     * Replace the seismic input from the next step on; its records start
     * at the engine time @p start (s) (GroundMotionIntegral), the ground at
     * rest before. Only SeismicInput::Mode::none and inertial: a
     * displacement-mode record would move the fixed points from their
     * anchors at t = 0 (InputError). The directions are normalised as at
     * construction (InputError for a zero one or a vertical record with
     * dt <= 0); the speed bound of the sanity checks grows by the records'
     * peak ground velocities. The energy ledger goes on (the inertial
     * load's work enters load_work).
     */
    void
    set_seismic_input(SeismicInput input, const double start);

    /// Kinetic energy sum 1/2 v^T M v (J/m).
    double
    kinetic_energy() const;
    /// Elastic strain energy of the blocks (J/m).
    double
    strain_energy() const;
    /// Energy stored in closed contact springs (J/m).
    double
    contact_energy() const;
    /// Gravitational potential energy relative to t = 0 (J/m).
    double
    potential_energy() const;

    /// All terms of the energy balance (see EnergyLedger).
    EnergyLedger
    energy() const;

    /// Ground displacement (m) at time @p t in displacement mode: the
    /// horizontal and the vertical record's double integrals along their
    /// directions (zero in the other modes).
    geometry::Point
    ground_displacement(const double t) const;

    /// Ground acceleration (m/s^2) at time @p t of either mode (zero
    /// without seismic input).
    geometry::Point
    ground_acceleration(const double t) const;

    /// Displacement (m) of a block's centroid since t = 0.
    geometry::Point
    centroid_displacement(const int block) const;

    /// Number of steps and cuts so far.
    unsigned long n_steps = 0, n_cuts = 0;
    /// Open-close iterations of the accepted steps, linear solves of all
    /// attempts (cut ones included) and their CG iterations, so far.
    unsigned long n_iterations = 0, n_solves = 0, n_solver_iterations = 0;
    /// Largest StepReport::strength_ratio of the accepted steps so far
    /// (settling steps included; part of the checkpoint): <= 1, since a
    /// step beyond its contacts' strengths and tolerances is cut.
    double worst_strength_ratio = 0.;

    /**
     * Kinematics of each of contacts() as the last accepted step used them
     * (contact length, springs, force tolerance; Assembler::kinematics())
     * and its face group (-1: alone on its face; Assembler::groups()).
     * Empty before the first step of this object (also after restore()).
     */
    const std::vector<ContactKinematics> &
    contact_kinematics() const
    {
      return assembler.kinematics();
    }
    const std::vector<int> &
    face_groups() const
    {
      return assembler.groups();
    }

    /**
     * The state needed to continue the run bit for bit (block geometry,
     * velocities, stresses and strains, moving points, contacts with their
     * states, time, step length, counters and the solver's warm start), as
     * the bytes of a checkpoint file.
     */
    std::string
    checkpoint() const;

    /**
     * Continue from the checkpoint() @p bytes of a run of the same scene
     * (same blocks, vertices and points); throws InputError naming
     * @p source if they do not belong to it or are damaged.
     */
    void
    restore(const std::string &bytes, const std::string &source);

  private:
    /// The largest tolerance of a contact's state check, in weight
    /// tolerances: chatter factors stop at it, holds are capped at it, and
    /// the strength audit never grants more. 1 % of the lighter block's
    /// weight (100 at the default Contact force tolerance of 1e-4), and no
    /// escalation when the tolerance itself is 1 % or more.
    double
    max_tolerance_factor() const
    {
      return max_chatter_factor(ctrl.law.force_tolerance);
    }

    /**
     * Check and normalise @p input's directions and record time steps
     * (InputError naming what is wrong), make it the scene's seismic input
     * and integrate its records from the engine time @p start (s): the
     * constructor's and set_seismic_input()'s common part.
     */
    void
    install_seismic_input(SeismicInput input, const double start);

    StepReport
    advance(const double max_length);
    bool
    try_step(const double                step,
             const std::vector<Contact> &start,
             StepReport                 &report,
             std::string                &why);
    void
    update(const Eigen::VectorXd &d, const double step);
    /// Allowed vertex displacement per step of a block of size @p size (m):
    /// the smaller of the two Controls ratios' bounds.
    double
    allowed_displacement_for(const double size) const;
    /// Runs work in chunks on the linear solver's threads (built per use,
    /// so that it always refers to this object).
    ChunkRunner
    chunks();
    /// Step length alpha in (0, 1] along x_hat - x_k that minimises the
    /// convex energy of the step for the current contact states and
    /// strengths, with the state check's force tolerances times
    /// @p tolerance_factor (engine_line_search.cc).
    double
    line_search(const std::vector<Contact> &contacts,
                const Eigen::VectorXd      &x_k,
                const Eigen::VectorXd      &x_hat,
                const std::vector<double>  &tolerance_factor,
                const std::vector<double>  &hold_tolerance);
    /// Warnings about parameters outside the plausible range for rock
    /// (engine_sanity.cc): E, density, the record's PGA, a penalty too low
    /// for the weight of the blocks.
    void
    add_plausibility_warnings();
    /**
     * The physical sanity checks of an attempted step (Controls): returns
     * an empty string if the state after update() is plausible, else the
     * diagnosis (block, contact, quantity, likely cause). Sets @p balance
     * to the energy balance of the state (when it is computed).
     */
    std::string
    implausible_state(const double energy_before, double &balance) const;
    /**
     * Strength audit of a converged attempt with increments @p x, run once
     * before it is accepted (doc/theory/dda.md, "Strength audit"): every
     * closed contact's tension within its tensile strength, every locked
     * contact's shear within its Mohr-Coulomb strength (members of a face
     * group that the group rule locks: their resultant within the sum of
     * strengths), every sliding contact's friction the strength at its
     * normal force and against its slip, every open contact without
     * compression, each beyond the strength by at most the tolerance the
     * iteration used for it: the force tolerance x @p factor or the
     * @p hold (N/m); a sliding contact's friction within the iteration's
     * friction tolerance of the one assembled from @p assembled_normal
     * (N/m; @p mean_normal the mean normal force of that iteration). Sets
     * @p ratio to the largest excess over tolerance (>= 0); returns the
     * diagnosis naming the blocks if it is above 1, else an empty string.
     */
    std::string
    strength_audit(const std::vector<Contact> &contacts,
                   const Eigen::VectorXd      &x,
                   const std::vector<double>  &factor,
                   const std::vector<double>  &hold,
                   const std::vector<double>  &assembled_normal,
                   const double                mean_normal,
                   double                     &ratio) const;
    /// Shear forces of the locked members of one face group along a
    /// common tangent (N/m): their resultant, the sum of their strengths
    /// and of their tolerances max(force tolerance, hold), and whether the
    /// face is stretched: its members pulled in opposite senses beyond
    /// that tolerance while a block of the face carries an imposed strain
    /// (eigenstrain, e.g. thermal). A stretched face is not locked as a
    /// group: each member slips on its own.
    struct GroupShear
    {
      double resultant = 0., strength = 0., tolerance = 0.;
      bool   stretched = false;
    };
    /// GroupShear of @p members (indices into @p contacts) for the
    /// increments @p x, with the normal force of contact c
    /// @p normal_force(c) (N/m); @p sense gets each member's sign along the
    /// common tangent.
    GroupShear
    group_shear(const std::vector<Contact>       &contacts,
                const Eigen::VectorXd            &x,
                const std::vector<int>           &members,
                const std::function<double(int)> &normal_force,
                const std::vector<double>        &hold,
                std::vector<double>              &sense) const;
    /// Mohr-Coulomb on the resultant of each face group (Assembler::groups):
    /// its locked members slide together or not at all (a held member adds
    /// its hold tolerance, N/m, to the group's).
    void
    check_face_groups(const std::vector<Contact> &contacts,
                      const Eigen::VectorXd      &x,
                      const std::vector<double>  &hold,
                      std::vector<StateCheck>    &checks) const;

    BlockSystem              scene;
    Controls                 ctrl;
    ContactSet               contact_set;
    std::vector<Contact>     current_contacts;
    Assembler                assembler;
    BlockSparseMatrix        matrix;
    LinearSolver             solver;
    GroundMotionIntegral     ground;
    Eigen::VectorXd          last_solution;
    std::vector<std::string> warning_list;
    double                   t = 0., domain = 0.;
    /// The adaptive time step (current, nominal and minimum step).
    TimeStepControl step_control;
    /// Allowed vertex displacement per step of each block (m), and its
    /// size (larger side of its bounding box at t = 0, m).
    std::vector<double> allowed_step, block_size;
    /// Blocks clamped by their fixed points (they move only with the
    /// ground, so their contact search reaches no further than that).
    std::vector<char> clamped_block;
    /// Energy flows since t = 0 (J/m): dissipated by friction, work of
    /// the loads.
    double friction_work = 0., load_work = 0.;
    /// Energy dissipated by the strain damping and the contact dashpots
    /// (J/m).
    double damping_work = 0.;
    /// Fastest motion the scene can produce apart from gravity (m/s): the
    /// initial block speeds and the largest ground velocity of the record.
    double speed_bound = 0.;
    /// Largest motion the last eigenstrain change can produce (m): the
    /// change times the domain size; and the length of the step being
    /// attempted (s). Together they bound the speed of the thermal motion.
    double eigenstrain_motion = 0., attempt_length = 0.;
    /// Energy balance after the last accepted step (NaN: to be computed),
    /// and the state a rejected step restores (kept buffers).
    double      accepted_balance = std::numeric_limits<double>::quiet_NaN();
    BlockSystem backup;
    /// Contacts found by the first detection are intact joints (cohesion
    /// and tensile strength); contacts that form later are not bonded.
    bool first_detection = true;
    /// Why the latest attempt was cut (for the diagnoses).
    std::string last_cut;
    /// Blocks of the scene at construction; those after them were added
    /// by add_block() (their definitions go into checkpoints).
    std::size_t n_scene_blocks = 0;
    /// Options of the contact detection, kept between steps (their
    /// per-block arrays are refilled, not reallocated).
    DetectionOptions detection_options;
    /// The vertical record's integral (empty: no vertical motion).
    GroundMotionIntegral ground_vertical;
  };
} // namespace rockdda::dda

#endif
