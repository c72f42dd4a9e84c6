/**
 * @file
 * The 2D DDA time step: contact detection, open-close iteration with
 * adaptive time step, and the update with Shi's constant-acceleration
 * scheme (Shi 1988; Doolin & Sitar 2004).
 */
#include <rockdda/dda/block_matrices.h>
#include <rockdda/dda/block_step_terms.h>
#include <rockdda/dda/contact_law.h>
#include <rockdda/dda/engine.h>
#include <rockdda/dda/friction_relaxation.h>
#include <rockdda/dda/logarithmic_strain.h>
#include <rockdda/dda/open_close.h>
#include <rockdda/dda/state_check.h>
#include <rockdda/dda/step_driver.h>
#include <rockdda/dda/strain_damping.h>
#include <rockdda/io/error.h>
#include <rockdda/io/output.h>

#include <Eigen/Cholesky>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>
#include <set>

namespace rockdda::dda
{
  namespace
  {
    std::string
    num(const double x, const int digits = 6)
    {
      return io::format_number(x, digits);
    }
  } // namespace



  DdaSystem::DdaSystem(BlockSystem scene_in, const Controls &controls)
      : scene(std::move(scene_in))
      , ctrl(controls)
      , solver(controls.solver)
  {
    if (scene.blocks.empty())
      throw InputError("the scene has no blocks");
    if (scene.joints.empty())
      scene.joints.push_back(JointMaterial());
    // Bounding box of the raw coordinates (finite ones).
    Eigen::Vector4d box(1e300, 1e300, -1e300, -1e300);
    for (const auto &b : scene.blocks)
      for (const auto &p : b.polygon.vertices)
        if (p.allFinite())
          {
            box[0] = std::min(box[0], p.x());
            box[1] = std::min(box[1], p.y());
            box[2] = std::max(box[2], p.x());
            box[3] = std::max(box[3], p.y());
          }
    if (!(box[2] >= box[0])
        || !std::isfinite(box[2] - box[0] + box[3] - box[1]))
      throw InputError("the scene's blocks have no extent");
    // Work in coordinates relative to the lower-left corner of the scene's
    // bounding box, so that the round-off does not depend on where the
    // scene sits: for a translated scene both the vertices and the corner
    // move by the same amount, and their difference is the same number.
    const geometry::Point corner(box[0], box[1]);
    for (auto &b : scene.blocks)
      for (auto &p : b.polygon.vertices)
        p -= corner;
    for (auto &f : scene.fixed_points)
      f.point -= corner;
    for (auto &l : scene.load_points)
      l.point -= corner;
    for (auto &m : scene.measurement_points)
      m.point -= corner;
    scene.origin += corner;
    // Validate (and set the initial centroids and anchors) in the local
    // coordinates.
    validate_and_prepare(scene, warning_list, 1e-6);
    // Domain size: twice the largest distance of a vertex from the mean
    // vertex (invariant under rotation, unlike the box).
    geometry::Point mean  = geometry::Point::Zero();
    std::size_t     count = 0;
    for (const auto &b : scene.blocks)
      for (const auto &p : b.polygon.vertices)
        {
          mean += p;
          ++count;
        }
    mean /= static_cast<double>(count);
    domain = 0.;
    for (const auto &b : scene.blocks)
      for (const auto &p : b.polygon.vertices)
        domain = std::max(domain, 2. * (p - mean).norm());
    if (!(domain > 0.) || !std::isfinite(domain))
      throw InputError("the scene's blocks have no extent");
    install_seismic_input(std::move(scene.seismic), 0.);
    if (!(ctrl.time_step > 0.) || !std::isfinite(ctrl.time_step))
      throw InputError("time step " + num(ctrl.time_step)
                       + " s; valid: dt > 0");
    if (!(ctrl.dynamic >= 0. && ctrl.dynamic <= 1.))
      throw InputError("dynamic control " + num(ctrl.dynamic)
                       + "; valid: 0 <= k <= 1");
    if (!(ctrl.strain_damping >= 0.) || !std::isfinite(ctrl.strain_damping))
      throw InputError("strain damping " + num(ctrl.strain_damping)
                       + " s; valid: >= 0 s");
    set_contact_damping(ctrl.contact_damping, ctrl.contact_step_damping);
    if (!(ctrl.law.normal_penalty > 0.)
        || !std::isfinite(ctrl.law.normal_penalty))
      throw InputError("contact penalty " + num(ctrl.law.normal_penalty)
                       + " N/m; valid: p > 0");
    if (!(ctrl.law.shear_ratio > 0.))
      throw InputError("shear penalty ratio " + num(ctrl.law.shear_ratio)
                       + "; valid: > 0");
    if (const std::string e = shear_penalty_error(ctrl.law); !e.empty())
      throw InputError(e);
    for (std::size_t j = 0; j < scene.joints.size(); ++j)
      for (const auto &[what, k] :
           {std::pair<const char *, double>{"normal",
                                            scene.joints[j].normal_stiffness},
            {"shear", scene.joints[j].shear_stiffness}})
        if (!(k >= 0.) || !std::isfinite(k))
          throw InputError("joint material " + std::to_string(j + 1) + ": "
                           + what + " stiffness " + num(k)
                           + " Pa/m; valid: >= 0 and finite (0: a rigid "
                             "joint, only the contact penalty acts)");
    if (!(ctrl.max_displacement_ratio > 0.))
      throw InputError("maximum displacement ratio "
                       + num(ctrl.max_displacement_ratio) + "; valid: > 0");
    if (ctrl.max_iterations < 1)
      ctrl.max_iterations = 1;
    if (ctrl.fixed_penalty <= 0.)
      ctrl.fixed_penalty = 10. * ctrl.law.normal_penalty;
    step_control
      = TimeStepControl(ctrl.time_step,
                        ctrl.min_time_step > 0. ? ctrl.min_time_step
                                                : 1e-6 * ctrl.time_step,
                        ctrl.cut_factor,
                        ctrl.growth);
    for (const auto &b : scene.blocks)
      {
        block_size.push_back(dda::block_size(b.polygon));
        allowed_step.push_back(allowed_displacement_for(block_size.back()));
      }
    clamped_block  = clamped_blocks(scene);
    n_scene_blocks = scene.blocks.size();
    add_plausibility_warnings();
    // The vertical ground velocity bounds the block speeds too.
    speed_bound += ground_vertical.peak_velocity();
  }



  void
  DdaSystem::settle(const unsigned int                             steps,
                    const std::function<bool(const unsigned int)> &after_step)
  {
    const double dynamic = ctrl.dynamic;
    const auto   mode    = scene.seismic.mode;
    ctrl.dynamic         = 0.;
    scene.seismic.mode   = SeismicInput::Mode::none;
    static_steps(
      steps,
      after_step,
      [&]() {
        advance(std::numeric_limits<double>::infinity());
        t = 0.;
      },
      [&]() {
        ctrl.dynamic       = dynamic;
        scene.seismic.mode = mode;
      });
    t                   = 0.;
    n_steps             = 0;
    n_iterations        = 0;
    n_solves            = 0;
    n_solver_iterations = 0;
    accepted_balance    = std::numeric_limits<double>::quiet_NaN();
    friction_work       = 0.;
    load_work           = 0.;
    damping_work        = 0.;
    step_control.reset();
    last_solution.setZero();
    for (auto &b : scene.blocks)
      {
        b.velocity.setZero();
        b.initial_centroid = block_moments(b.polygon).centroid;
      }
    for (auto &m : scene.measurement_points)
      m.initial = m.point;
  }



  StepReport
  DdaSystem::step()
  {
    return advance(std::numeric_limits<double>::infinity());
  }



  void
  DdaSystem::set_time_step(const double time_step)
  {
    if (!(time_step > 0.) || !std::isfinite(time_step))
      throw InputError("time step " + num(time_step) + " s; valid: dt > 0");
    step_control.set_nominal(time_step);
    ctrl.time_step = time_step;
  }



  StepReport
  DdaSystem::run_until(const double end_time)
  {
    StepReport report;
    report.time = t;
    run_to(
      step_control,
      t,
      end_time,
      ctrl.max_steps,
      ctrl.time_step,
      [&](const double max_length) { report = advance(max_length); },
      "",
      last_cut);
    return report;
  }



  StepReport
  DdaSystem::advance(const double max_length)
  {
    // Contact detection once per step (the geometry does not change when
    // the step is cut).
    std::vector<geometry::Polygon> polys;
    polys.reserve(scene.blocks.size());
    for (const auto &b : scene.blocks)
      polys.push_back(b.polygon);
    DetectionOptions &detection = detection_options;
    detection.run_chunks        = chunks();
    detection.reach.resize(polys.size());
    detection.vertex_reach.resize(polys.size());
    // A clamped block moves only with the ground (displacement mode).
    const bool moving_ground
      = scene.seismic.mode == SeismicInput::Mode::displacement;
    const double ground_step
      = !moving_ground ? 0.
        : scene.seismic.vertical_record.acceleration.empty()
          ? std::abs(ground.displacement(t + step_control.current())
                     - ground.displacement(t))
          : (ground_displacement(t + step_control.current())
             - ground_displacement(t))
              .norm();
    for (std::size_t b = 0; b < polys.size(); ++b)
      {
        detection.vertex_reach[b] = ctrl.search_factor * allowed_step[b];
        detection.reach[b] = clamped_block[b] ? ctrl.search_factor * ground_step
                                              : detection.vertex_reach[b];
      }
    // Shortest-path rule of vertex-vertex contacts: the vertices move on as
    // in the previous step.
    if (last_solution.size() == static_cast<long>(6 * polys.size()))
      {
        detection.predicted.resize(polys.size());
        for (std::size_t b = 0; b < polys.size(); ++b)
          {
            detection.predicted[b].clear();
            const Vector6 D = last_solution.segment<6>(6 * b);
            const auto    c = block_moments(polys[b]).centroid;
            for (const auto &p : polys[b].vertices)
              detection.predicted[b].push_back(displacement_matrix(c, p) * D);
          }
      }
    // A new contact touching within round-off starts closed.
    const auto touching = [&](const ContactCandidate &c) {
      return round_off_tolerance(std::min(block_size[c.block_i],
                                          block_size[c.block_j]),
                                 polys[c.block_i].vertices[c.vertex],
                                 geometry::Point::Zero());
    };
    std::vector<Contact> start
      = contact_set.transfer(detect_contacts(polys, detection),
                             touching,
                             first_detection);
    first_detection = false;
    for (auto &c : start)
      {
        // A tagged edge carries its own joint material; otherwise the weaker
        // of the two blocks' joint materials applies.
        const auto &edges = scene.blocks[c.geometry.block_j].edge_joints;
        const int   a     = scene.blocks[c.geometry.block_i].joint;
        const int   b     = scene.blocks[c.geometry.block_j].joint;
        c.joint           = !edges.empty() ? edges[c.geometry.edge]
                            : scene.joints[a].friction_deg <= scene.joints[b].friction_deg
                              ? a
                              : b;
        // The slip rate of the friction law: the previous step's, none in
        // a static step (constant friction), 0 after static steps.
        c.slip_rate
          = ctrl.dynamic == 0. ? no_slip_rate : std::max(c.slip_rate, 0.);
      }

    StepReport report;
    report.cuts = take_step(
      step_control,
      max_length,
      ctrl.max_iterations,
      [&](const double h, unsigned &iterations) {
        const bool accepted = try_step(h, start, report, last_cut);
        iterations          = report.iterations;
        return accepted;
      },
      [&]() { ++n_cuts; },
      "",
      n_steps + 1,
      t,
      last_cut,
      "");
    return report;
  }



  bool
  DdaSystem::try_step(const double                h,
                      const std::vector<Contact> &start,
                      StepReport                 &report,
                      std::string                &why)
  {
    std::vector<Contact> contacts = start;
    StepParameters       par;
    par.dt                   = h;
    par.dynamic              = ctrl.dynamic;
    par.strain_damping       = ctrl.strain_damping;
    par.contact_damping      = ctrl.contact_damping;
    par.contact_step_damping = ctrl.contact_step_damping;
    par.law                  = ctrl.law;
    par.fixed_penalty        = ctrl.fixed_penalty;
    par.body_acceleration    = scene.gravity;
    const auto   mode        = scene.seismic.mode;
    const double a_ground    = mode == SeismicInput::Mode::inertial
                                 ? ground.acceleration(t + 0.5 * h)
                                 : 0.;
    par.body_acceleration -= a_ground * scene.seismic.direction;
    // Vertical component (0 without a vertical record).
    const double a_vertical = mode == SeismicInput::Mode::inertial
                                ? ground_vertical.acceleration(t + 0.5 * h)
                                : 0.;
    if (a_vertical != 0.)
      par.body_acceleration -= a_vertical * scene.seismic.vertical;
    const double ug = mode == SeismicInput::Mode::displacement
                        ? ground.displacement(t + h)
                        : 0.;
    const double uv = mode == SeismicInput::Mode::displacement
                        ? ground_vertical.displacement(t + h)
                        : 0.;
    par.fixed_targets.resize(scene.fixed_points.size());
    for (std::size_t f = 0; f < scene.fixed_points.size(); ++f)
      {
        const auto &fp = scene.fixed_points[f];
        par.fixed_targets[f]
          = fp.anchor
            + (fp.moves_with_ground ? ug : 0.) * scene.seismic.direction;
        if (fp.moves_with_ground && uv != 0.)
          par.fixed_targets[f] += uv * scene.seismic.vertical;
      }
    par.run_chunks = chunks();
    par.threads    = solver.n_threads();
    par.clamped    = &clamped_block;
    assembler.prepare_step(scene, contacts, par, matrix);
    solver.new_pattern(matrix, &scene.blocks);

    Eigen::VectorXd x = last_solution;
    if (x.size() != static_cast<long>(6 * scene.blocks.size()))
      x = Eigen::VectorXd::Zero(6 * scene.blocks.size());
    Eigen::VectorXd F;
    report.solver_iterations = 0;
    unsigned changes = 0, friction_changes = 0;
    // Open-close iterations of this attempt (run_open_close(): the states
    // settle within max_iterations; iterations that change no state only
    // update the friction forces and reuse the factorisation or
    // preconditioner, for up to max_iterations more).
    unsigned         it = 0;
    std::vector<int> flips(contacts.size(), 0);
    Eigen::VectorXd  x_prev;
    bool             damped_last = false;
    bool             confirming  = false;
    // Tolerances of each contact's state check. A contact near zero force
    // that keeps changing state (chatter): its force tolerance grows 10x
    // per further change, to at most 100x (1 % of the lighter block's
    // weight). A contact that has changed state hold_after times cycles in
    // the open-close iteration: it is held (Controls::hold_fraction).
    std::vector<double> factor(contacts.size(), 1.), hold(contacts.size(), 0.);
    // The normal force each contact's friction was assembled with in the
    // latest iteration, and their mean over the closed contacts (for the
    // strength audit of the converged state).
    std::vector<double> assembled_normal(contacts.size(), 0.);
    double              mean_normal = 0.;
    // Relaxed friction iteration (dda::FrictionRelaxation, both engines'):
    // Aitken's relaxation of the unconverged sliding contacts' friction.
    FrictionRelaxation relaxation(contacts.size());
    const auto         update_factors = [&]() {
      for (std::size_t c = 0; c < contacts.size(); ++c)
        {
          factor[c] = chatter_factor(flips[c], ctrl.law.force_tolerance);
          hold[c]   = 0.;
          if (is_held(flips[c], ctrl.hold_after, contacts[c].held))
            {
              // (dda::hold_tolerance(), the rule of both engines.) At most
              // 1 % of the lighter block's weight: a light block between
              // stiff ones (an infill wedge) is not hung on a held contact,
              // and no held contact exceeds its strength by more. Before
              // the cap a contact that still cycled got the slip bound
              // alone, 1.6e4 N for the ratchet's wedge, 3x its weight:
              // accepted locked contacts then carried shear far beyond
              // Mohr-Coulomb and pushed. (Without the weight bound on open
              // contacts an impact in the valley run-out of
              // Invariance.TranslationScalingRotation was held open up to
              // more than the block's weight, and its run-out spread 0.8 %
              // under 1e-13 perturbations.)
              const auto &g   = contacts[c].geometry;
              const auto &kin = assembler.kinematics()[c];
              hold[c] = hold_tolerance(contacts[c].state == ContactState::open,
                                       kin.normal_stiffness,
                                       kin.shear_stiffness,
                                       ctrl.hold_fraction,
                                       std::min(block_size[g.block_i],
                                                block_size[g.block_j]),
                                       kin.weight_tolerance,
                                       kin.force_tolerance,
                                       ctrl.law.force_tolerance);
            }
        }
    };
    // Checks every contact against the increments x: new states, forces
    // and the counts of state and friction changes.
    const auto update_states = [&](const Eigen::VectorXd &x) {
      changes          = 0;
      friction_changes = 0;

      // Force scale of the friction iteration: the mean normal force of
      // the closed contacts (previous iteration).
      double   force_sum = 0.;
      unsigned n_closed  = 0;
      for (const auto &ct : contacts)
        if (ct.state != ContactState::open)
          {
            force_sum += std::abs(ct.normal_force);
            ++n_closed;
          }
      const double mean_force = n_closed > 0 ? force_sum / n_closed : 0.;
      mean_normal             = mean_force;
      std::vector<StateCheck> checks(contacts.size());
      for_each_chunk(chunks(),
                     contacts.size(),
                     256,
                     [&](const std::size_t lo, const std::size_t hi) {
                       for (std::size_t c = lo; c < hi; ++c)
                         {
                           const int                ci = static_cast<int>(c);
                           ContactKinematics        chatter;
                           const ContactKinematics *k
                             = &assembler.kinematics()[c];
                           if (factor[c] != 1. || hold[c] != 0.)
                             {
                               chatter = *k;
                               chatter.force_tolerance
                                 = escalated_tolerance(*k, factor[c]);
                               chatter.hold_tolerance = hold[c];
                               k                      = &chatter;
                             }
                           checks[c]
                             = check_state(contacts[c],
                                           *k,
                                           assembler.gap(ci, x),
                                           assembler.shear_displacement(ci, x),
                                           scene.joints[contacts[c].joint]);
                         }
                     });
      check_face_groups(contacts, x, hold, checks);
      for (std::size_t c = 0; c < contacts.size(); ++c)
        {
          Contact                 &ct  = contacts[c];
          const ContactKinematics &kin = assembler.kinematics()[c];
          const int                ci  = static_cast<int>(c);
          const StateCheck        &r   = checks[c];
          // The friction of a sliding contact used the normal force of
          // the previous iteration; iterate until it agrees (implicit
          // friction), which suppresses a rocking instability when the
          // time step resolves the contact vibration.
          const bool keeps_sliding = ct.state == ContactState::sliding
                                     && r.state == ContactState::sliding;
          const bool unconverged
            = keeps_sliding
              && std::abs(r.normal_force - ct.normal_force)
                   > friction_tolerance(r.normal_force,
                                        mean_force,
                                        kin.force_tolerance);
          friction_changes += unconverged;
          assembled_normal[c] = ct.normal_force;
          // Only the unconverged contacts are relaxed (and define omega):
          // the others take their new force as it is.
          relaxation.set_residual(c,
                                  unconverged
                                      && !frictionless(ct,
                                                       scene.joints[ct.joint])
                                    ? r.normal_force - ct.normal_force
                                    : 0.);
          ct.normal_force = r.normal_force;
          ct.shear_force  = r.shear_force;
          if (r.changed)
            {
              ++changes;
              ++flips[c];
              const ContactState old = ct.state;
              ct.state               = r.state;
              if (r.state == ContactState::locked
                  || (r.state == ContactState::sliding
                      && old == ContactState::open))
                {
                  // A contact that locks takes the shear spring of the
                  // step's start: the iterations of a step are not time,
                  // so a contact that locked the step and slid only in an
                  // iteration keeps its reference, and one that slid into
                  // the step starts its spring from the friction force it
                  // carried then (force continuity: at displacement
                  // dir * S / k_s from its reference, instead of dropping
                  // to zero). Rebasing on the strength of the current
                  // iteration instead pre-stretched the spring by the
                  // change of the normal force within the step, elastic
                  // energy no work paid for: +864 J/m (4.6 % of the energy
                  // in play) in one step of an earthquake episode of the
                  // ratchet (issue 15).
                  // (lock_anchor(): the rule of both engines.)
                  const Contact   &at_start = start[c];
                  const LockAnchor anchor
                    = r.state == ContactState::locked
                        ? lock_anchor(at_start.state, old, true)
                        : LockAnchor::here;
                  if (anchor == LockAnchor::start_spring)
                    ct.xi_ref = at_start.xi_ref;
                  else
                    {
                      ct.xi_ref = ct.geometry.projection;
                      if (anchor == LockAnchor::start_friction)
                        ct.xi_ref += at_start.shear_force
                                     / (kin.shear_stiffness * kin.edge_length);
                    }
                  assembler.set_shear_reference(scene, ci, ct);
                }
            }
          if (r.state == ContactState::sliding)
            ct.slide_direction = r.slide_direction;
        }
      relaxation.relax(changes > 0 || friction_changes == 0,
                       [&](const std::size_t c, const double d) {
                         contacts[c].normal_force = assembled_normal[c] + d;
                       });
    };
    // The iteration is a deterministic map of its state: the increments,
    // each contact's state, slide direction, shear reference and forces,
    // the chatter and hold tolerances (functions of a contact's changes,
    // constant from flip_cap on) and the friction relaxation. If that state
    // repeats exactly, the iteration cycles for good and the step would be
    // cut at cycle_limit or max_iterations anyway: cut it now. The accepted
    // steps are bit for bit those of running the cycle out.
    const int flip_cap = std::max(static_cast<int>(ctrl.hold_after),
                                  2
                                    + static_cast<int>(std::ceil(std::log10(
                                      std::max(max_tolerance_factor(), 1.)))));
    std::set<std::pair<std::uint64_t, std::uint64_t>> visited;
    const auto                                        fingerprint = [&]() {
      IterateFingerprint f;
      for (Eigen::Index i = 0; i < x.size(); ++i)
        f.add(x[i]);
      for (std::size_t c = 0; c < contacts.size(); ++c)
        {
          const Contact &ct = contacts[c];
          f.add(static_cast<std::uint64_t>(ct.state)
                | static_cast<std::uint64_t>(ct.slide_direction + 1) << 8
                | static_cast<std::uint64_t>(ct.held) << 16
                | static_cast<std::uint64_t>(std::min(flips[c], flip_cap))
                    << 24);
          f.add(ct.xi_ref);
          f.add(ct.normal_force);
          f.add(ct.shear_force);
          f.add(relaxation.previous_residual(c));
        }
      f.add(relaxation.omega());
      f.add(static_cast<std::uint64_t>(relaxation.has_residual())
            | static_cast<std::uint64_t>(damped_last) << 1
            | static_cast<std::uint64_t>(confirming) << 2
            | static_cast<std::uint64_t>(changes == 0) << 3
            | static_cast<std::uint64_t>(friction_changes == 0) << 4);
      return f.value();
    };
    // The contact that changed state most often in this attempt, for the
    // diagnosis of an iteration that cycles.
    const auto most_changed = [&]() {
      const auto  most = std::max_element(flips.begin(), flips.end());
      const auto &g    = contacts[most - flips.begin()].geometry;
      return "the contact of block "
             + std::to_string(scene.blocks[g.block_i].id) + " on block "
             + std::to_string(scene.blocks[g.block_j].id) + " changed state "
             + std::to_string(*most) + " times";
    };
    // The shared driver (dda/open_close.h) with this engine's exact-cycle
    // cut, inexact solves, line search and holds.
    bool       loose        = false;
    const auto may_continue = [&](const unsigned done, std::string &reason) {
      // (From the fourth iteration on: most steps converge before, and a
      // cycle that began earlier repeats an iterate recorded after it.)
      if (ctrl.cut_exact_cycles && done >= 3 && !contacts.empty()
          && !visited.insert(fingerprint()).second)
        {
          reason = "the open-close iteration cycles (iteration "
                   + std::to_string(done) + " returned to an earlier iterate; "
                   + most_changed() + ")";
          return false;
        }
      return true;
    };
    const auto solve = [&](const unsigned iteration, std::string &reason) {
      it = iteration;
      assembler.assemble(contacts, matrix, F);
      if (!F.allFinite())
        {
          reason = "the load vector is not finite";
          return false;
        }
      // After an iteration without state changes (only the friction
      // forces were updated) the matrix is unchanged: reuse its
      // factorisation. While the states settle, CG solves to a looser
      // tolerance (inexact Newton); the settled states are confirmed by a
      // solve to the solver's tolerance.
      x_prev = x;
      // The first solve of a step is exact: on a settled scene it is
      // usually the only one.
      loose = ctrl.inexact_factor > 1. && it > 1 && !confirming
              && solver.type() != SolverType::direct;
      if (!solver.solve(matrix,
                        F,
                        x,
                        it > 1 && changes == 0,
                        loose ? ctrl.inexact_factor * ctrl.solver.tolerance
                              : 0.))
        {
          reason = "the linear solver failed ("
                   + std::string(solver.type() == SolverType::direct
                                   ? "matrix not positive definite"
                                   : "CG did not converge")
                   + ")";
          return false;
        }
      report.solver_iterations += solver.last_iterations();
      ++n_solves;
      n_solver_iterations += solver.last_iterations();
      if (!x.allFinite())
        {
          reason = "the displacement increment is not finite";
          return false;
        }
      return true;
    };
    const auto check = [&](const unsigned) {
      // Line search along the Newton direction (engine_line_search.cc),
      // from the second iteration on (the first starts from the previous
      // step's increments, not from a point of the current states).
      // The state check's tolerances for this iteration (they depend on
      // the state changes so far), used by the search and the check.
      update_factors();
      double alpha = 1.;
      if (ctrl.line_search && it > 1 && !damped_last)
        {
          alpha = line_search(contacts, x_prev, x, factor, hold);
          if (alpha < 1.)
            x = x_prev + alpha * (x - x_prev);
        }
      update_states(x);
      // A damped step after which no state changed: the next step is a
      // full one (the line search stopped at a state's tolerance band).
      damped_last = alpha < 1. && changes == 0;
      if (alpha < 1. && changes == 0)
        friction_changes = std::max(friction_changes, 1u);
      // Settled on inexact solves: confirm with a solve to the solver
      // tolerance.
      confirming = changes == 0 && friction_changes == 0 && loose;
      OpenCloseCheck r;
      r.state_changes    = changes;
      r.friction_changes = friction_changes;
      r.confirm          = confirming;
      r.most_changes     = static_cast<unsigned>(
        flips.empty() ? 0 : *std::max_element(flips.begin(), flips.end()));
      return r;
    };
    OpenCloseLimits limits;
    limits.max_iterations = ctrl.max_iterations;
    limits.cycle_limit    = ctrl.cycle_limit;
    if (!run_open_close(
          limits, may_continue, solve, check, most_changed, it, why))
      return false;

    // No contact beyond its strength by more than its tolerance, whatever
    // path (chatter, hold, face group) accepted it.
    double strength_ratio = 0.;
    {
      const std::string excess = strength_audit(contacts,
                                                x,
                                                factor,
                                                hold,
                                                assembled_normal,
                                                mean_normal,
                                                strength_ratio);
      if (!excess.empty())
        {
          why = excess;
          return false;
        }
    }

    // Largest vertex displacement, relative to each block's allowance.
    double max_d = 0., worst_ratio = 0.;
    int    worst = 0;
    for (std::size_t b = 0; b < scene.blocks.size(); ++b)
      {
        const Vector6 D = x.segment<6>(6 * b);
        const auto   &c = assembler.moments()[b].centroid;
        for (const auto &p : scene.blocks[b].polygon.vertices)
          {
            const double d = (displacement_matrix(c, p) * D).norm();
            max_d          = std::max(max_d, d);
            if (d / allowed_step[b] > worst_ratio)
              {
                worst_ratio = d / allowed_step[b];
                worst       = static_cast<int>(b);
              }
          }
      }
    if (worst_ratio > 1.)
      {
        why = "block " + std::to_string(scene.blocks[worst].id) + " moved "
              + num(worst_ratio * allowed_step[worst])
              + " m in one step, more than its allowed "
              + num(allowed_step[worst]) + " m (min of "
              + num(ctrl.max_displacement_ratio) + " x domain size "
              + num(domain) + " m and " + num(ctrl.max_displacement_block_ratio)
              + " x its size)";
        return false;
      }

    // The energy at the start of the step, and what a rejected state must
    // restore.
    if (!std::isfinite(accepted_balance))
      accepted_balance = energy().balance();
    const double energy_before   = accepted_balance;
    const double friction_before = friction_work, load_before = load_work,
                 damping_before = damping_work;
    // Accepted: energy flows of the step, and joints broken by the
    // accepted states; each contact's slip rate, |s - s0| / h (its shear
    // displacement increment over the step), for the next step's friction
    // (friction_coefficient()).
    std::vector<double> slip_rates(contacts.size());
    for (std::size_t c = 0; c < contacts.size(); ++c)
      {
        Contact &ct = contacts[c];
        slip_rates[c]
          = std::abs(assembler.shear_displacement(static_cast<int>(c), x)
                     - assembler.kinematics()[c].s0)
            / h;
        // Static steps (dynamic control 0) are an iteration towards
        // equilibrium: a contact held in one stays held in the next (its
        // hold ends when it changes state beyond it). Dynamic steps carry
        // their history in the velocities, and no hold.
        ct.held = stays_held(ctrl.dynamic,
                             flips[c],
                             ctrl.hold_after,
                             ct.held,
                             ct.state == ct.state_at_start);
        if (ct.state == ContactState::sliding)
          {
            // The joint is elastic-plastic: a sliding contact's shear spring
            // stays stretched by its friction force S_s, storing
            // S_s^2 / 2 k_s (contact_energy), which a relocking contact
            // keeps (force continuity). The work the blocks did on it this
            // step, -S_s (s - s0) (the step applies the friction force over
            // the whole slip), less the change of that stored energy, is
            // dissipated. (Counting it all as dissipation and none as stored
            // made the ledger jump by S_s^2 / 2 k_s at every relock: one
            // earthquake episode of the ratchet gained 0.25 % of the energy
            // in play so.)
            const auto  &kin = assembler.kinematics()[c];
            const double s
              = assembler.shear_displacement(static_cast<int>(c), x);
            const double k = kin.shear_stiffness;
            const double stored_before
              = start[c].state == ContactState::open
                  ? 0.
                  : 0.5 * start[c].shear_force * start[c].shear_force / k;
            friction_work
              += -ct.shear_force * (s - kin.s0)
                 - (0.5 * ct.shear_force * ct.shear_force / k - stored_before);
            ct.broken = true;
          }
        else if (ct.state == ContactState::open
                 && ct.state_at_start != ContactState::open)
          ct.broken = true;
      }
    for (const auto &l : scene.load_points)
      load_work += l.force.dot(
        displacement_matrix(assembler.moments()[l.block].centroid, l.point)
        * x.segment<6>(6 * l.block));
    // Work of the eigenstrain change on the stress, -A sigma_mid . d eps*
    // (exact: the stress is linear in the step).
    for (std::size_t b = 0; b < scene.blocks.size(); ++b)
      {
        const Block &block = scene.blocks[b];
        if (block.eigenstrain == block.applied_eigenstrain)
          continue;
        const Eigen::Vector3d de = eigenstrain_step(block);
        const Eigen::Matrix3d C
          = elasticity_matrix(scene.materials[block.material]);
        const Eigen::Vector3d sigma_mid
          = block.stress + 0.5 * C * (x.segment<3>(6 * b + 3) - de);
        load_work += -assembler.moments()[b].area * sigma_mid.dot(de);
      }
    const StrainDamping damping(ctrl.strain_damping, h, ctrl.dynamic);
    if (damping.active())
      for (std::size_t b = 0; b < scene.blocks.size(); ++b)
        if (!clamped_block[b])
          damping_work += damping.dissipation(
            assembler.moments()[b].area
              * elasticity_matrix(scene.materials[scene.blocks[b].material]),
            Eigen::Vector3d(x.segment<3>(6 * b + 3)));
    // The contact dashpots' work c v' d over the step (d the gap or shear
    // increment, v' = 2 d / h - v its end-of-step rate): dissipated.
    if (assembler.damped())
      for (std::size_t c = 0; c < contacts.size(); ++c)
        {
          const Contact &ct = contacts[c];
          if (ct.state == ContactState::open)
            continue;
          const auto  &kin = assembler.kinematics()[c];
          const int    ci  = static_cast<int>(c);
          const double dg  = assembler.gap(ci, x) - kin.g0;
          damping_work
            += kin.normal_dashpot * (2. * dg / h - kin.normal_rate) * dg;
          if (ct.state == ContactState::locked)
            {
              const double ds = assembler.shear_displacement(ci, x) - kin.s0;
              damping_work
                += kin.shear_dashpot * (2. * ds / h - kin.shear_rate) * ds;
            }
        }
    if (a_ground != 0.)
      for (std::size_t b = 0; b < scene.blocks.size(); ++b)
        load_work += -a_ground * assembler.masses()[b](0, 0)
                     * scene.seismic.direction.dot(x.segment<2>(6 * b));
    if (a_vertical != 0.)
      for (std::size_t b = 0; b < scene.blocks.size(); ++b)
        load_work += -a_vertical * assembler.masses()[b](0, 0)
                     * scene.seismic.vertical.dot(x.segment<2>(6 * b));

    // (Assignment into the kept buffers reuses their memory.)
    backup.blocks             = scene.blocks;
    backup.fixed_points       = scene.fixed_points;
    backup.load_points        = scene.load_points;
    backup.measurement_points = scene.measurement_points;
    attempt_length            = h;
    update(x, h);
    std::swap(current_contacts, contacts);
    t += h;
    double            balance     = energy_before;
    const std::string implausible = implausible_state(energy_before, balance);
    if (!implausible.empty())
      {
        scene.blocks             = backup.blocks;
        scene.fixed_points       = backup.fixed_points;
        scene.load_points        = backup.load_points;
        scene.measurement_points = backup.measurement_points;
        std::swap(current_contacts, contacts);
        t -= h;
        friction_work = friction_before;
        load_work     = load_before;
        damping_work  = damping_before;
        why           = implausible;
        return false;
      }
    accepted_balance = balance;
    for (std::size_t c = 0; c < current_contacts.size(); ++c)
      current_contacts[c].slip_rate = slip_rates[c];
    contact_set.store(current_contacts);
    last_solution = x;
    ++n_steps;
    report.time       = t;
    report.dt         = h;
    report.iterations = it;
    n_iterations += it;
    report.max_displacement = max_d;
    report.strength_ratio   = strength_ratio;
    worst_strength_ratio    = std::max(worst_strength_ratio, strength_ratio);
    report.n_open = report.n_sliding = report.n_locked = 0;
    for (const auto &c : current_contacts)
      (c.state == ContactState::open      ? report.n_open
       : c.state == ContactState::sliding ? report.n_sliding
                                          : report.n_locked)++;
    return true;
  }



  ChunkRunner
  DdaSystem::chunks()
  {
    return [this](const std::size_t                                    n,
                  const std::size_t                                    grain,
                  const std::function<void(std::size_t, std::size_t)> &f) {
      solver.for_chunks(n, grain, f);
    };
  }



  void
  DdaSystem::check_face_groups(const std::vector<Contact> &contacts,
                               const Eigen::VectorXd      &x,
                               const std::vector<double>  &hold,
                               std::vector<StateCheck>    &checks) const
  {
    const auto         &start  = assembler.group_start();
    const auto         &member = assembler.group_members();
    std::vector<int>    members;
    std::vector<double> sense;
    for (std::size_t g = 0; g + 1 < start.size(); ++g)
      {
        // Members: contacts that are locked, or closing, and stay closed.
        members.clear();
        for (int k = start[g]; k < start[g + 1]; ++k)
          {
            const int      c  = member[k];
            const Contact &ct = contacts[c];
            // A frictionless contact carries no shear at all.
            if (ct.state != ContactState::sliding
                && !frictionless(ct, scene.joints[ct.joint])
                && checks[c].state != ContactState::open)
              members.push_back(c);
          }
        // If every member stays locked on its own, so does the group
        // (|sum F| <= sum |F| <= sum S): nothing to decide.
        bool any_slides = false;
        for (const int c : members)
          any_slides = any_slides || checks[c].state == ContactState::sliding;
        if (members.size() < 2 || !any_slides)
          continue;
        const GroupShear gs = group_shear(
          contacts,
          x,
          members,
          [&](const int c) { return checks[c].normal_force; },
          hold,
          sense);
        // A stretched face (GroupShear): each member slips on its own (the
        // individual checks stand).
        if (gs.stretched)
          continue;
        const bool slides = std::abs(gs.resultant) > gs.strength + gs.tolerance;
        for (std::size_t m = 0; m < members.size(); ++m)
          {
            StateCheck &r = checks[members[m]];
            if (!slides)
              r.state = ContactState::locked;
            else
              {
                r.state           = ContactState::sliding;
                r.slide_direction = sense[m] * gs.resultant > 0. ? 1 : -1;
              }
            r.changed = r.state != contacts[members[m]].state;
          }
      }
  }



  DdaSystem::GroupShear
  DdaSystem::group_shear(const std::vector<Contact>       &contacts,
                         const Eigen::VectorXd            &x,
                         const std::vector<int>           &members,
                         const std::function<double(int)> &normal_force,
                         const std::vector<double>        &hold,
                         std::vector<double>              &sense) const
  {
    GroupShear            gs;
    double                most = 0., least = 0.;
    const geometry::Point u = assembler.kinematics()[members[0]].tangent;
    sense.resize(members.size());
    for (std::size_t m = 0; m < members.size(); ++m)
      {
        const int   c   = members[m];
        const auto &kin = assembler.kinematics()[c];
        const auto &g   = contacts[c].geometry;
        sense[m]        = (g.block_i < g.block_j ? 1. : -1.)
                   * (kin.tangent.dot(u) >= 0. ? 1. : -1.);
        const double f
          = sense[m] * kin.shear_stiffness * assembler.shear_displacement(c, x);
        most  = std::max(most, f);
        least = std::min(least, f);
        gs.resultant += f;
        gs.strength += shear_strength(contacts[c],
                                      normal_force(c),
                                      kin.length,
                                      scene.joints[contacts[c].joint]);
        gs.tolerance
          += std::min(std::max(kin.force_tolerance, hold[c]),
                      escalated_tolerance(kin, max_tolerance_factor()));
      }
    // Members pulled in opposite senses: the face is stretched or
    // shortened, not dragged as a rigid face, if a block of it is strained
    // by an imposed strain (a thermal eigenstrain; the ratchet's thermal
    // creep, RatchetCoupled.CleanCrackCreepsOnlyAboveAJointStiffness).
    // The opposite corner forces of blocks strained only by their contact
    // loads (the Poisson expansion of a loaded brick, ~ +-nu W) are
    // self-equilibrated: the group holds them on its resultant (checked
    // one by one they cost the settling static wall of benchmarks/
    // dda-scaling 0.5 open-close iterations per step, 2.34 against 1.84,
    // for the same settlement, and broke cohesive joints at step 1).
    const auto &g = contacts[members[0]].geometry;
    gs.stretched  = most > gs.tolerance && least < -gs.tolerance
                   && (!scene.blocks[g.block_i].eigenstrain.isZero()
                       || !scene.blocks[g.block_j].eigenstrain.isZero());
    return gs;
  }



  void
  DdaSystem::update(const Eigen::VectorXd &x, const double h)
  {
    const auto &moments = assembler.moments();
    for (std::size_t b = 0; b < scene.blocks.size(); ++b)
      {
        Block        &block = scene.blocks[b];
        const Vector6 D     = x.segment<6>(6 * b);
        const auto   &c     = moments[b].centroid;
        for (auto &p : block.polygon.vertices)
          p = move_point(c, D, p);
        block.velocity
          = end_of_step_velocity(D, block.velocity, h, ctrl.dynamic);
        const Eigen::Matrix3d C
          = elasticity_matrix(scene.materials[block.material]);
        // The stress adds the logarithmic strain of the step's stretch
        // I + E, less that of the eigenstrain's ratio (1 + e) / (1 + a), which
        // is not elastic (doc/theory/dda.md, "Strain update"): the stress is
        // then a function of the block's shape and its eigenstrain, whatever
        // the path.
        Eigen::Matrix2d E;
        E << D[3], 0.5 * D[5], 0.5 * D[5], D[4];
        const Eigen::Matrix2d L = logarithmic_strain_increment<2>(E);
        const Eigen::Vector3d h(L(0, 0), L(1, 1), 2. * L(0, 1));
        const Eigen::Vector3d de = eigenstrain_step(block);
        const Eigen::Vector3d h_star(std::log1p(de[0]),
                                     std::log1p(de[1]),
                                     de[2]);
        Eigen::Vector3d       sigma = block.stress + C * (h - h_star);
        block.applied_eigenstrain   = block.eigenstrain;
        // Rotate the accumulated stress and strain with the block.
        const double    cr = std::cos(D[2]), sr = std::sin(D[2]);
        Eigen::Matrix2d R;
        R << cr, -sr, sr, cr;
        auto rotate = [&](const Eigen::Vector3d &v, const double shear_factor) {
          Eigen::Matrix2d S;
          S << v[0], shear_factor * v[2], shear_factor * v[2], v[1];
          const Eigen::Matrix2d Sr = R * S * R.transpose();
          return Eigen::Vector3d(Sr(0, 0), Sr(1, 1), Sr(0, 1) / shear_factor);
        };
        block.stress = rotate(sigma, 1.);
        block.strain = rotate(block.strain + h, 0.5);
        block.rotation += D[2];
      }
    for (auto &f : scene.fixed_points)
      f.point = move_point(moments[f.block].centroid,
                           x.segment<6>(6 * f.block),
                           f.point);
    for (auto &l : scene.load_points)
      l.point = move_point(moments[l.block].centroid,
                           x.segment<6>(6 * l.block),
                           l.point);
    for (auto &m : scene.measurement_points)
      m.point = move_point(moments[m.block].centroid,
                           x.segment<6>(6 * m.block),
                           m.point);
  }



  void
  DdaSystem::set_eigenstrains(const std::vector<Eigen::Vector3d> &eigenstrains)
  {
    if (eigenstrains.size() != scene.blocks.size())
      throw InputError("set_eigenstrains: "
                       + std::to_string(eigenstrains.size())
                       + " eigenstrains for "
                       + std::to_string(scene.blocks.size()) + " blocks");
    for (std::size_t b = 0; b < eigenstrains.size(); ++b)
      if (!eigenstrains[b].allFinite())
        throw InputError("set_eigenstrains: the eigenstrain of block "
                         + std::to_string(scene.blocks[b].id)
                         + " is not finite");
    eigenstrain_motion = 0.;
    for (std::size_t b = 0; b < eigenstrains.size(); ++b)
      {
        scene.blocks[b].eigenstrain = eigenstrains[b];
        eigenstrain_motion
          = std::max(eigenstrain_motion,
                     eigenstrain_step(scene.blocks[b]).cwiseAbs().maxCoeff()
                       * domain);
      }
  }



  double
  DdaSystem::allowed_displacement_for(const double size) const
  {
    return std::min(ctrl.max_displacement_ratio * domain,
                    ctrl.max_displacement_block_ratio * size);
  }



  int
  DdaSystem::add_block(Block block)
  {
    for (auto &p : block.polygon.vertices)
      p -= scene.origin;
    block.velocity.setZero();
    block.stress.setZero();
    block.strain.setZero();
    block.applied_eigenstrain = block.eigenstrain; // stress-free as placed
    block.rotation            = 0.;
    validate_added_block(scene, block, warning_list, 1e-6);
    scene.blocks.push_back(std::move(block));
    const auto &b = scene.blocks.back();
    block_size.push_back(dda::block_size(b.polygon));
    allowed_step.push_back(allowed_displacement_for(block_size.back()));
    clamped_block.push_back(0);
    if (last_solution.size() > 0)
      last_solution.conservativeResizeLike(
        Eigen::VectorXd::Zero(6 * scene.blocks.size()));
    accepted_balance = std::numeric_limits<double>::quiet_NaN();
    return static_cast<int>(scene.blocks.size()) - 1;
  }



  void
  DdaSystem::translate_blocks(const std::vector<geometry::Point> &shift)
  {
    if (shift.size() != scene.blocks.size())
      throw InputError("translate_blocks: " + std::to_string(shift.size())
                       + " shifts for " + std::to_string(scene.blocks.size())
                       + " blocks");
    for (const auto &f : scene.fixed_points)
      if (shift[f.block].squaredNorm() > 0.)
        throw InputError("translate_blocks: block "
                         + std::to_string(scene.blocks[f.block].id)
                         + " has a fixed point and cannot move");
    // The shear references first, on the edges as they are (a translation
    // does not change an edge's vector).
    for (auto &c : current_contacts)
      {
        const auto           &g = c.geometry;
        const auto           &v = scene.blocks[g.block_j].polygon.vertices;
        const geometry::Point E = v[(g.edge + 1) % v.size()] - v[g.edge];
        const double          dxi
          = (shift[g.block_i] - shift[g.block_j]).dot(E) / E.squaredNorm();
        c.xi_ref += dxi;
        c.geometry.xi = std::clamp(c.geometry.xi + dxi, 0., 1.);
        c.geometry.projection += dxi;
      }
    contact_set.store(current_contacts);
    for (std::size_t b = 0; b < scene.blocks.size(); ++b)
      for (auto &p : scene.blocks[b].polygon.vertices)
        p += shift[b];
    for (auto &p : scene.load_points)
      p.point += shift[p.block];
    for (auto &p : scene.measurement_points)
      p.point += shift[p.block];
    accepted_balance = std::numeric_limits<double>::quiet_NaN();
  }



  double
  DdaSystem::min_gap(const int                           block,
                     const std::vector<geometry::Point> &shift,
                     const double                        distance) const
  {
    const auto moved = [&](const std::size_t b) {
      geometry::Polygon p = scene.blocks[b].polygon;
      if (!shift.empty())
        for (auto &v : p.vertices)
          v += shift[b];
      return p;
    };
    // Signed distance of point x from polygon q's boundary (negative
    // inside): the depth of a vertex, whatever the detection's rules.
    const auto signed_distance = [](const geometry::Point   &x,
                                    const geometry::Polygon &q) {
      double d = std::numeric_limits<double>::infinity();
      for (std::size_t e = 0; e < q.vertices.size(); ++e)
        {
          const geometry::Point &a  = q.vertices[e];
          const geometry::Point &b  = q.vertices[(e + 1) % q.vertices.size()];
          const geometry::Point  ab = b - a;
          const double           t
            = std::clamp((x - a).dot(ab) / ab.squaredNorm(), 0., 1.);
          d = std::min(d, (x - a - t * ab).norm());
        }
      return q.contains(x) ? -d : d;
    };
    const geometry::Polygon self = moved(block);
    const auto              box  = self.bounding_box();
    double                  gap  = std::numeric_limits<double>::infinity();
    for (std::size_t b = 0; b < scene.blocks.size(); ++b)
      {
        if (static_cast<int>(b) == block)
          continue;
        const geometry::Polygon other = moved(b);
        const auto              ob    = other.bounding_box();
        if (ob[0] > box[2] + distance || ob[2] < box[0] - distance
            || ob[1] > box[3] + distance || ob[3] < box[1] - distance)
          continue;
        for (const auto &x : self.vertices)
          gap = std::min(gap, signed_distance(x, other));
        for (const auto &x : other.vertices)
          gap = std::min(gap, signed_distance(x, self));
      }
    return gap <= distance ? gap : std::numeric_limits<double>::infinity();
  }



  double
  DdaSystem::kinetic_energy() const
  {
    double e = 0.;
    for (const auto &b : scene.blocks)
      {
        e += kinetic_energy_of(
          b.velocity,
          mass_matrix(block_moments(b.polygon),
                      scene.materials[b.material].density));
      }
    return e;
  }



  double
  DdaSystem::strain_energy() const
  {
    double e = 0.;
    for (const auto &b : scene.blocks)
      {
        e += strain_energy_of(b.polygon.area(),
                              b.stress,
                              elasticity_matrix(scene.materials[b.material]));
      }
    return e;
  }



  double
  DdaSystem::contact_energy() const
  {
    double       e  = 0.;
    const double p  = ctrl.law.normal_penalty;
    const double ps = ctrl.law.shear_penalty();
    // With joint stiffnesses each contact's springs depend on its length,
    // taken at the current geometry by the rule of the assembly: the
    // penalty and the joint in series store N^2 / 2 (1/p + 1/(k_n l)).
    const bool          compliant = any_joint_stiffness(scene.joints);
    std::vector<double> length;
    if (compliant)
      length = Assembler::contact_lengths(scene, current_contacts);
    for (std::size_t k = 0; k < current_contacts.size(); ++k)
      {
        const Contact &c = current_contacts[k];
        if (c.state == ContactState::open)
          continue;
        const ContactSprings springs
          = compliant
              ? contact_springs(ctrl.law, scene.joints[c.joint], length[k])
              : ContactSprings{p, ps};
        // Locked and sliding (the elastic part of a sliding joint).
        e += 0.5 * c.normal_force * c.normal_force / springs.normal
             + 0.5 * c.shear_force * c.shear_force / springs.shear;
      }
    return e;
  }



  double
  DdaSystem::potential_energy() const
  {
    double e = 0.;
    for (const auto &b : scene.blocks)
      {
        const BlockMoments m = block_moments(b.polygon);
        e += gravity_potential_of(scene.materials[b.material].density,
                                  m.area,
                                  scene.gravity,
                                  geometry::Point(m.centroid
                                                  - b.initial_centroid));
      }
    return e;
  }



  EnergyLedger
  DdaSystem::energy() const
  {
    EnergyLedger e;
    e.kinetic   = kinetic_energy();
    e.strain    = strain_energy();
    e.contact   = contact_energy();
    e.potential = potential_energy();
    e.friction  = friction_work;
    e.damping   = damping_work;
    // Fixed-point springs of the blocks that are not clamped.
    const double ug = scene.seismic.mode == SeismicInput::Mode::displacement
                        ? ground.displacement(t)
                        : 0.;
    const double uv = scene.seismic.mode == SeismicInput::Mode::displacement
                        ? ground_vertical.displacement(t)
                        : 0.;
    for (const auto &f : scene.fixed_points)
      if (!clamped_block[f.block])
        {
          geometry::Point target
            = f.anchor
              + (f.moves_with_ground ? ug : 0.) * scene.seismic.direction;
          if (f.moves_with_ground && uv != 0.)
            target += uv * scene.seismic.vertical;
          e.fixed
            += 0.5 * ctrl.fixed_penalty * (f.point - target).squaredNorm();
        }
    e.load_work = load_work;
    return e;
  }



  geometry::Point
  DdaSystem::ground_displacement(const double time) const
  {
    if (scene.seismic.mode != SeismicInput::Mode::displacement)
      return geometry::Point::Zero();
    return ground.displacement(time) * scene.seismic.direction
           + ground_vertical.displacement(time) * scene.seismic.vertical;
  }



  geometry::Point
  DdaSystem::ground_acceleration(const double time) const
  {
    if (scene.seismic.mode == SeismicInput::Mode::none)
      return geometry::Point::Zero();
    return ground.acceleration(time) * scene.seismic.direction
           + ground_vertical.acceleration(time) * scene.seismic.vertical;
  }



  geometry::Point
  DdaSystem::centroid_displacement(const int block) const
  {
    const Block &b = scene.blocks[block];
    return block_moments(b.polygon).centroid - b.initial_centroid;
  }



  void
  DdaSystem::set_dynamic(const double dynamic)
  {
    if (!(dynamic >= 0. && dynamic <= 1.))
      throw InputError("dynamic control " + num(dynamic)
                       + "; valid: 0 <= k <= 1");
    if (ctrl.dynamic == 0. && dynamic > 0.)
      {
        for (auto &b : scene.blocks)
          b.velocity.setZero();
        // The kinetic energy changed: the sanity check's reference balance
        // is recomputed at the next step.
        accepted_balance = std::numeric_limits<double>::quiet_NaN();
      }
    ctrl.dynamic = dynamic;
  }



  void
  DdaSystem::set_contact_damping(const double ratio, const double step_ratio)
  {
    if (!(ratio >= 0.) || !std::isfinite(ratio))
      throw InputError("contact damping ratio " + num(ratio) + "; valid: >= 0");
    if (!(step_ratio >= 0.) || !std::isfinite(step_ratio))
      throw InputError("contact step damping " + num(step_ratio)
                       + "; valid: >= 0");
    ctrl.contact_damping      = ratio;
    ctrl.contact_step_damping = step_ratio;
  }



  void
  DdaSystem::install_seismic_input(SeismicInput input, const double start)
  {
    const double dn = input.direction.norm();
    if (!(dn > 0.) || !std::isfinite(dn))
      throw InputError("the seismic direction has no length");
    input.direction /= dn;
    if (input.mode != SeismicInput::Mode::none
        && !input.record.acceleration.empty() && !(input.record.dt > 0.))
      throw InputError("seismic record '" + input.record.name + "': time step "
                       + num(input.record.dt) + " s; valid: dt > 0");
    if (!input.vertical_record.acceleration.empty())
      {
        const double vn = input.vertical.norm();
        if (!(vn > 0.) || !std::isfinite(vn))
          throw InputError("the vertical seismic direction has no length");
        input.vertical /= vn;
        if (!(input.vertical_record.dt > 0.))
          throw InputError("vertical seismic record '"
                           + input.vertical_record.name + "': time step "
                           + num(input.vertical_record.dt)
                           + " s; valid: dt > 0");
      }
    scene.seismic   = std::move(input);
    ground          = GroundMotionIntegral();
    ground_vertical = GroundMotionIntegral();
    if (scene.seismic.mode != SeismicInput::Mode::none)
      {
        ground
          = GroundMotionIntegral(scene.seismic.record, scene.seismic.g, start);
        if (!scene.seismic.vertical_record.acceleration.empty())
          ground_vertical = GroundMotionIntegral(scene.seismic.vertical_record,
                                                 scene.seismic.g,
                                                 start);
      }
  }



  void
  DdaSystem::set_seismic_input(SeismicInput input, const double start)
  {
    if (input.mode == SeismicInput::Mode::displacement)
      throw InputError("a seismic input in displacement mode cannot start "
                       "during a run (its fixed points move from their "
                       "anchors at t = 0); use the inertial mode");
    if (!std::isfinite(start))
      throw InputError("seismic input start " + num(start)
                       + " s; valid: finite");
    install_seismic_input(std::move(input), start);
    speed_bound += ground.peak_velocity() + ground_vertical.peak_velocity();
  }
} // namespace rockdda::dda
