/**
 * @file
 * 3D DDA with contacts (issue 17): blocks coupled by vertex-face and
 * edge-edge contacts with normal and shear penalty springs, Mohr-Coulomb
 * friction, cohesion and tension per joint material, open / sliding /
 * locked states that persist across steps, the open-close iteration with a
 * step cut when it does not converge, and an energy ledger
 * (doc/theory/dda3d.md, "Contacts" and "Open-close iteration").
 */
#ifndef ROCKDDA_DDA3D_ENGINE_H
#define ROCKDDA_DDA3D_ENGINE_H

#include <rockdda/dda/contact_mechanics.h>
#include <rockdda/dda/energy_ledger.h>
#include <rockdda/dda/failure.h>
#include <rockdda/dda/linear_solver.h>
#include <rockdda/dda/plausibility.h>
#include <rockdda/dda/state_check.h>
#include <rockdda/dda/time_step_control.h>
#include <rockdda/dda3d/block_matrices.h>
#include <rockdda/dda3d/contact_detection.h>
#include <rockdda/dda3d/local_scene.h>

#include <Eigen/Core>

#include <cmath>
#include <functional>
#include <string>
#include <vector>

namespace rockdda::dda3d
{
  using dda::ContactLaw;
  using dda::ContactState;
  using dda::JointMaterial;

  /// A 12x2 matrix: the shear displacement's dependence on a block's
  /// unknowns (two tangent directions).
  using Matrix12x2 = Eigen::Matrix<double, 12, 2>;

  /**
   * One contact with its state. The shear reference is a material point of
   * block j (moved with j) that a locked contact's
   * shear spring is measured from; slide_direction is the sliding direction of
   * i relative to j (unit, global) of a sliding contact.
   */
  struct Contact
  {
    ContactCandidate geometry;
    ContactState     state          = ContactState::open;
    ContactState     state_at_start = ContactState::open;
    /// Shear reference on block j (m, the engine's local coordinates); valid if
    /// has_reference.
    Point reference     = Point::Zero();
    bool  has_reference = false;
    /// Sliding direction (unit) of a sliding contact.
    Point slide_direction = Point::Zero();
    /// Normal force (N, compression positive) and shear force on block i
    /// (N, a vector in the contact plane) of the latest solve.
    double normal_force = 0.;
    Point  shear_force  = Point::Zero();
    /// Cohesion and tensile strength are lost once an accepted step ends
    /// with the contact sliding or opened.
    bool broken = false;
    /// Joint material (index into BlockSystem::joints).
    int joint = 0;
    /// Area (m^2) over which cohesion, tensile strength and the joint's
    /// stiffness act: the overlap of the two touching faces shared among
    /// the contacts between them; 0 for a corner or edge on a face.
    double area = 0.;
    /// Slip rate (m/s) whose friction coefficient the step uses
    /// (dda::friction_coefficient()): the magnitude of the shear
    /// displacement increment of the previous accepted step over its
    /// length, 0 for a new contact (the floor V_min), dda::no_slip_rate in
    /// a static step (dynamic control 0: constant friction).
    double slip_rate = 0.;
    /// Held across static steps (dynamic control 0), as in 2D
    /// (dda::Contact::held): the contact cycled in the open-close iteration
    /// of an accepted static step and was held there; it keeps the hold in
    /// the following static steps until a force beyond the hold tolerance
    /// changes its state.
    bool held = false;
  };

  /**
   * Linearised kinematics of one contact over a step (normal n fixed,
   * first-order displacement field, thesis Eq. 2.5): gap
   * g = g0 + e_n . D_i + h_n . D_j, e_n = T_i(p)^T n, h_n = -T_j(q)^T n;
   * shear displacement (two components in the tangent basis t1, t2)
   * s = s0 + E_s^T D_i + H_s^T D_j, E_s = T_i(p)^T [t1 t2],
   * H_s = -T_j(r)^T [t1 t2], r the shear reference, s0 = [t1 t2]^T (p - r).
   */
  struct ContactKinematics
  {
    double          g0 = 0.;
    Vector12        en, hn;
    Matrix12x2      Es, Hs;
    Eigen::Vector2d s0 = Eigen::Vector2d::Zero();
    Point           t1, t2;
    /// Normal and shear spring (N/m): the penalty, in series with the
    /// joint's stiffness over the contact area (dda::contact_springs()).
    double normal_stiffness = 0., shear_stiffness = 0.;
    /// Normal and shear dashpot (N s/m; dda::ContactDamping), 0 without
    /// contact damping.
    double normal_dashpot = 0., shear_dashpot = 0.;
    /// Round-off of the gap and shear displacement (m): the representation
    /// error of the local coordinates of the contact points
    /// (dda::gap_round_off()).
    double tolerance = 0.;
    /// Force below which a state change is noise (N;
    /// dda::contact_force_tolerance()): weight_tolerance, at least the
    /// normal spring times tolerance (independent of the penalty
    /// otherwise).
    double force_tolerance = 0.;
    /// 1e-4 of the weight of the lighter block (N;
    /// dda::contact_weight_tolerance()): the part of force_tolerance that
    /// grows for a chattering contact (dda::escalated_tolerance()).
    double weight_tolerance = 0.;
  };

  /// Result of the Mohr-Coulomb check of one contact after a solve
  /// (dda::check_contact_state()): forces in N, the shear force and the
  /// sliding direction in the tangent basis.
  using StateCheck = dda::StateCheckOf<Eigen::Vector2d>;

  /**
   * The state check of the open-close iteration (dda::check_contact_state(),
   * the one implementation of both engines) of a contact with shear
   * displacement @p s in the contact plane, sliding along the unit vector
   * @p direction (not changed here: the engine sets it from the resultant
   * of the contact's face group, doc/theory/dda3d.md), with the force
   * tolerance @p force_tolerance (N) and the hold tolerance @p hold_tolerance
   * (N; 0: not held).
   */
  StateCheck
  check_state(const Contact           &contact,
              const ContactKinematics &kinematics,
              const Eigen::Vector2d   &direction,
              const double             g,
              const Eigen::Vector2d   &s,
              const double             force_tolerance,
              const JointMaterial     &joint,
              double                   hold_tolerance = 0.);

  /// Controls of the 3D engine.
  struct EngineControls
  {
    /// Time step (s), > 0; cut by 3 when a step fails and grown back by 1.3
    /// after good steps.
    double dt = 1e-3;
    /// Dynamic control parameter (-): 1 dynamic, 0 static.
    double dynamic = 1.;
    /// Kelvin-Voigt viscous time of the blocks' strain (s, >= 0;
    /// dda::StrainDamping): a strain mode of angular frequency omega gets
    /// the damping ratio eta omega / 2; rigid motions are not damped. 0: none.
    double strain_damping = 0.;
    /// Dashpots of the closed contacts as a ratio of critical of each
    /// spring with the lighter free block's mass (-, >= 0;
    /// dda::ContactDamping). 0: none.
    double contact_damping = 0.;
    /// The contacts' numerical dashpot beta k dt / 2 (-, >= 0;
    /// dda::ContactDamping): velocity amplification -1 / (1 + beta) of the
    /// stiff contact modes instead of -1. 0: none.
    double contact_step_damping = 0.;
    /**
     * The end-of-step velocity of the stiff modes (doc/theory/dda3d.md,
     * "Velocity of the stiff modes"): false, Shi's v' = 2 D / dt - v for
     * every block; true, v' is then corrected by the velocity solve
     * (2 M / dt^2 + K) v'' = (2 M / dt^2) v' + K D / dt, K the step's
     * stiffness (closed contacts' springs, fixed points, the blocks'
     * elasticity): a mode stiff for the step (omega dt >> 1) gets the
     * step's mean rate (its velocity amplification ~sqrt(2) / (omega dt)
     * instead of Shi's -1), a resolved one (omega dt << 1) keeps Shi's
     * velocity to O((omega dt)^2); clamped blocks get the exact ground
     * velocity. The kinetic energy it removes is booked as damping.
     */
    bool stiff_velocity = false;
    /**
     * Strength shared within a face group (the closed contacts between two
     * faces that face each other: 3-6 corner and edge springs of one
     * statically indeterminate interface, doc/theory/dda3d.md "Face groups:
     * shared strength"): true, a group's members that are not sliding
     * start to slide only when the sum of their shear spring forces exceeds
     * the sum of their strengths (a member beyond its own strength stays
     * locked while the others have the reserve), otherwise each member's
     * own check; opening and relocking are each member's own. false
     * (default): every contact against its own strength alone (the 2D
     * engine's rule).
     */
    bool face_group_friction = false;
    /// Normal penalty and shear ratio (dda::ContactLaw).
    ContactLaw law;
    /// Penalty of fixed points (N/m); 0: 10 x the normal penalty. Blocks
    /// with 3 or more non-collinear fixed points (and no prescribed motion)
    /// are clamped exactly instead.
    double fixed_penalty = 0.;
    /// Largest vertex displacement per step as a fraction of the block's
    /// size (-): a step that moves a vertex further is cut. The contact
    /// distance is 2.5 x this (DetectionTolerances::distance_factor).
    double max_displacement_ratio = 0.01;
    /// The sanity check of every step (dda::implausible_state(), the 2D
    /// engine's limits).
    dda::PlausibilityLimits plausibility;
    /// Open-close iterations that change a state before the step is cut;
    /// iterations that only update friction may add as many again.
    int max_open_close = 12;
    /// A contact that changes state this many times within one attempt
    /// cycles: the step is cut (dda::OpenCloseLimits, as in 2D).
    unsigned cycle_limit = 12;
    /// A contact that has changed state this many times in one attempt is
    /// held with dda::hold_tolerance() (an elastic slip or penetration of
    /// hold_fraction x the smaller block's size, at most 1 % of the lighter
    /// block's weight; an open one up to its weight), as in 2D.
    unsigned hold_after    = 4;
    double   hold_fraction = 1e-7;
    /// Exact line search along the Newton direction of the open-close
    /// iteration (dda/line_search.h, the 2D engine's). Off by default: the
    /// 3D scenes converge without it, and with it the velocity-weakening
    /// run-out of the shaking-table wedge moves from 1.5 % to 3.4 % of
    /// sliding3d and the 1:1000 column of Dda3dStability takes 17 s
    /// instead of 2 s (doc/theory/dda3d.md).
    bool line_search = false;
    /// The relaxed friction iteration (dda::FrictionRelaxation, the 2D
    /// engine's Aitken relaxation of unconverged sliding contacts). Off by
    /// default in 3D, by measurement: with it the box sliding through the
    /// concave valley of Dda3dConcave takes 131 step cuts instead of 56
    /// (the relaxed normal forces push contacts across their state
    /// thresholds and the iteration returns to earlier iterates), and the
    /// Hoek-Bray bisection of Dda3dContacts 3.4 x the time.
    bool friction_relaxation = false;
    /// CG tolerance while the contact states settle = inexact_factor x the
    /// solver tolerance (inexact Newton, as in 2D); the settled states are
    /// confirmed by one solve to the solver tolerance (<= 1: every solve to
    /// the solver tolerance; ignored by the direct solver).
    double inexact_factor = 1.;
    /// Smallest time step (fraction of dt) before the run stops.
    double min_dt_ratio = 1e-6;
    /// Stop (dda::DdaFailure) after this many steps in one advance_to()
    /// call (-); 0 = 100 x (duration / dt) + 1000, as the 2D engine: a run
    /// whose step stays cut far below dt ends with a diagnosis, not a hang.
    unsigned long max_steps = 0;
    /// Ground acceleration (m/s^2) in the seismic loading mode, at the
    /// middle of each step; empty: none.
    std::function<Point(double)> ground_acceleration;
    /**
     * Ground displacement u_g(t) (m, u_g(0) = 0) in the seismic
     * displacement mode: every clamped block (the foundation) is moved so
     * that its centroid is displaced by u_g at the end of each step (a
     * prescribed translation), and the anchors of the other fixed points
     * follow u_g. Empty: none.
     */
    std::function<Point(double)> ground_displacement;
    /// The linear solver (the 2D engine's, on 12x12 blocks; the
    /// distributed type is not available in 3D).
    dda::SolverOptions solver;
  };

  /// Energies of the ledger (J; dda::EnergyLedger, shared with 2D).
  using Energy = dda::EnergyLedger;

  /// Statistics of the last accepted step.
  struct StepStatistics
  {
    /// Open-close iterations, cuts and CG iterations (summed over the
    /// iterations; 0 with the direct solver).
    int    iterations = 0, cuts = 0, solver_iterations = 0;
    double dt   = 0.;
    int    open = 0, sliding = 0, locked = 0;
    /// The strength audit's worst excess over a contact's strength in
    /// units of its tolerance (dda::StrengthAudit; <= 1, or the step is
    /// cut).
    double strength_ratio = 0.;
  };

  /**
   * 3D DDA with contacts. Each step: detect contacts on the geometry at the
   * start of the step (broad and narrow phase), transfer the states of
   * the previous step, then the open-close iteration: assemble the block
   * terms (as FreeBlocks) and the contact springs into a block-sparse
   * matrix of 12x12 blocks (pattern: the contact pairs of the step), solve
   * (dda::LinearSolverOf<12>: block sparse Cholesky or D-ILU preconditioned CG
   * warm-started from the previous step), check every contact, until no state
   * changes and the friction of sliding contacts has converged. A step that
   * does not converge, or moves a vertex further than the allowed displacement,
   * is redone with dt / 3. The scene is moved to a local origin on
   * construction.
   */
  class Engine : public LocalScene
  {
  public:
    /// Validate @p system and keep it; throws InputError.
    Engine(BlockSystem system, const EngineControls &controls);

    /// One accepted step (cut as often as needed); throws dda::DdaFailure
    /// when the step would fall below EngineControls::min_dt_ratio x dt.
    void
    step();

    /// Step until time @p t_end (the last step shortened to end there);
    /// throws dda::DdaFailure after EngineControls::max_steps steps.
    void
    advance_to(const double t_end);

    /**
     * @p n static steps (dynamic control 0) under gravity and the constant
     * loads, without seismic input, before t = 0: the contacts take up the
     * weight without the undamped bounce of a dynamic start (blocks given
     * touching, with zero penetration, oscillate about the penetrated
     * equilibrium with an amplitude of W / k_n, and the friction with
     * them). Afterwards the time is unchanged, the velocities are zero and
     * the settled state is the reference of displacements (centroids and
     * measurement points at t = 0) and of the energy ledger's potential,
     * friction and load work.
     */
    void
    settle(const unsigned int                             n,
           const std::function<bool(const unsigned int)> &after_step = {});

    /**
     * The state a run continues from, as raw bytes (the 2D engine's
     * binary format, dda::DdaSystem::checkpoint()): block geometry,
     * velocities, stresses and strains, fixed, load and measurement points,
     * the contacts with their states, shear references and forces, the
     * time, the current step length, the counters and the energy ledger.
     * restore() on an engine built from the same scene and controls
     * continues bit for bit.
     */
    std::string
    checkpoint() const;

    /**
     * Continue from checkpoint() bytes @p bytes; throws InputError naming
     * @p source (the file) for a truncated, damaged or foreign checkpoint
     * (another format or scene), leaving the engine unchanged.
     */
    void
    restore(const std::string &bytes, const std::string &source);

    /// Accepted steps, time-step cuts and open-close iterations of the
    /// accepted steps so far (settling steps excluded, their cuts
    /// included, as in 2D).
    unsigned long n_steps = 0, n_cuts = 0, n_iterations = 0;
    /// Largest StepStatistics::strength_ratio of the accepted steps so far
    /// (kept in checkpoints; <= 1).
    double worst_strength_ratio = 0.;


    /// The contacts at the end of the last accepted step.
    const std::vector<Contact> &
    contacts() const
    {
      return stored;
    }

    /// The energy ledger at the end of the last accepted step.
    Energy
    energy() const;

    /// Length of the next step (s): the time step, or less after a cut
    /// until it has grown back.
    double
    time_step() const
    {
      return steps_.current();
    }

    /// Statistics of the last accepted step.
    const StepStatistics &
    statistics() const
    {
      return stats;
    }

    /// The linear solver (its type for the current pattern, threads).
    const dda::LinearSolverOf<12> &
    linear_solver() const
    {
      return solver;
    }

    /// Whether block @p b is clamped by its fixed points.
    bool
    clamped(const std::size_t b) const
    {
      return clamped_[b];
    }

  private:
    /// One attempt of a step of length @p h; false if it must be cut, with
    /// the reason in why_.
    bool
    try_step(const double h);

    /// One step of at most @p max_length (s), cut until it converges.
    void
    advance(double max_length);

    EngineControls ctrl;
    /// The adaptive time step (dda::TimeStepControl, shared with 2D).
    dda::TimeStepControl steps_;
    std::vector<char>    clamped_;
    std::vector<Contact> stored;
    bool                 first_detection = true;
    double friction_work = 0., load_work = 0., contact_energy = 0.;
    /// Energy dissipated by the strain damping (J).
    double                       damping_work = 0.;
    StepStatistics               stats;
    dda::BlockSparseMatrixOf<12> matrix;
    dda::LinearSolverOf<12>      solver;
    /// The displacement increments of the last accepted step (12 per
    /// block; empty before the first): the CG's starting guess.
    Eigen::VectorXd last_solution;
    /// Why the last attempt was cut (for the diagnosis of a run whose step
    /// falls below its minimum).
    std::string why_;
    /// The fastest translation at construction (m/s) and a bound on the
    /// ground's speed so far (m/s), for the sanity check's speed bound.
    double initial_speed_ = 0., ground_speed_ = 0.;
  };
} // namespace rockdda::dda3d

#endif
