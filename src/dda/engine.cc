/**
 * @file
 * The 2D DDA time step: contact detection, open-close iteration with
 * adaptive time step, and the update with Shi's constant-acceleration
 * scheme (Shi 1988; Doolin & Sitar 2004).
 */
#include <rockdda/dda/block_matrices.h>
#include <rockdda/dda/contact_law.h>
#include <rockdda/dda/engine.h>
#include <rockdda/io/error.h>
#include <rockdda/io/output.h>

#include <Eigen/Cholesky>

#include <algorithm>
#include <cmath>
#include <limits>

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
    // Domain size from the raw coordinates (finite ones), for tolerances.
    Eigen::Vector4d box(1e300, 1e300, -1e300, -1e300);
    double          max_coordinate = 0.;
    for (const auto &b : scene.blocks)
      for (const auto &p : b.polygon.vertices)
        if (p.allFinite())
          {
            box[0]         = std::min(box[0], p.x());
            box[1]         = std::min(box[1], p.y());
            box[2]         = std::max(box[2], p.x());
            box[3]         = std::max(box[3], p.y());
            max_coordinate = std::max(max_coordinate, p.cwiseAbs().maxCoeff());
          }
    domain = std::max(box[2] - box[0], box[3] - box[1]);
    if (!(domain > 0.) || !std::isfinite(domain))
      throw InputError("the scene's blocks have no extent");
    validate_and_prepare(scene, warning_list, 1e-6 * domain);
    if (!(ctrl.time_step > 0.) || !std::isfinite(ctrl.time_step))
      throw InputError("time step " + num(ctrl.time_step)
                       + " s; valid: dt > 0");
    if (!(ctrl.dynamic >= 0. && ctrl.dynamic <= 1.))
      throw InputError("dynamic control " + num(ctrl.dynamic)
                       + "; valid: 0 <= k <= 1");
    if (!(ctrl.law.normal_penalty > 0.)
        || !std::isfinite(ctrl.law.normal_penalty))
      throw InputError("contact penalty " + num(ctrl.law.normal_penalty)
                       + " N/m; valid: p > 0");
    if (!(ctrl.law.shear_ratio > 0.))
      throw InputError("shear penalty ratio " + num(ctrl.law.shear_ratio)
                       + "; valid: > 0");
    if (!(ctrl.max_displacement_ratio > 0.))
      throw InputError("maximum displacement ratio "
                       + num(ctrl.max_displacement_ratio) + "; valid: > 0");
    if (ctrl.max_iterations < 1)
      ctrl.max_iterations = 1;
    if (ctrl.fixed_penalty <= 0.)
      ctrl.fixed_penalty = 10. * ctrl.law.normal_penalty;
    dt_min
      = ctrl.min_time_step > 0. ? ctrl.min_time_step : 1e-6 * ctrl.time_step;
    dt            = ctrl.time_step;
    gap_tolerance = 1e-12 * (domain + max_coordinate);
    std::vector<double> sizes;
    for (const auto &b : scene.blocks)
      {
        const Eigen::Vector4d bb = b.polygon.bounding_box();
        sizes.push_back(std::max(bb[2] - bb[0], bb[3] - bb[1]));
      }
    std::nth_element(sizes.begin(),
                     sizes.begin() + sizes.size() / 2,
                     sizes.end());
    allowed_step
      = std::min(ctrl.max_displacement_ratio * domain,
                 ctrl.max_displacement_block_ratio * sizes[sizes.size() / 2]);
    if (scene.seismic.mode != SeismicInput::Mode::none)
      ground = GroundMotionIntegral(scene.seismic.record, scene.seismic.g);
  }



  void
  DdaSystem::settle(const unsigned int steps)
  {
    const double dynamic = ctrl.dynamic;
    const auto   mode    = scene.seismic.mode;
    ctrl.dynamic         = 0.;
    scene.seismic.mode   = SeismicInput::Mode::none;
    try
      {
        for (unsigned int k = 0; k < steps; ++k)
          {
            advance(std::numeric_limits<double>::infinity());
            t = 0.;
          }
      }
    catch (...)
      {
        ctrl.dynamic       = dynamic;
        scene.seismic.mode = mode;
        throw;
      }
    ctrl.dynamic       = dynamic;
    scene.seismic.mode = mode;
    t                  = 0.;
    n_steps            = 0;
    dt                 = ctrl.time_step;
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



  StepReport
  DdaSystem::run_until(const double end_time)
  {
    StepReport report;
    report.time             = t;
    const double        eps = 1e-9 * ctrl.time_step;
    const unsigned long limit
      = ctrl.max_steps > 0
          ? ctrl.max_steps
          : static_cast<unsigned long>(100. * std::max(0., end_time - t)
                                       / ctrl.time_step)
              + 1000;
    unsigned long steps = 0;
    while (t < end_time - eps)
      {
        if (++steps > limit)
          throw DdaFailure(
            "stopped at t = " + num(t) + " s after " + std::to_string(limit)
            + " steps (step limit): the time step stayed at " + num(dt)
            + " s, far below the requested " + num(ctrl.time_step) + " s");
        report = advance(end_time - t);
      }
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
    DetectionOptions detection;
    detection.search_distance       = ctrl.search_factor * allowed_step;
    detection.penetration_limit     = allowed_step;
    detection.coincidence_tolerance = 0.2 * detection.search_distance;
    std::vector<Contact> start
      = contact_set.transfer(detect_contacts(polys, detection), gap_tolerance);
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
      }

    StepReport  report;
    std::string why;
    unsigned    cuts = 0;
    for (;;)
      {
        const double h = std::min(dt, max_length);
        if (try_step(h, start, report, why))
          break;
        ++cuts;
        ++n_cuts;
        dt = h / ctrl.cut_factor;
        if (dt < dt_min)
          throw DdaFailure("step " + std::to_string(n_steps + 1)
                           + " at t = " + num(t) + " s: " + why
                           + "; cutting the time step further would go below "
                             "the minimum "
                           + num(dt_min)
                           + " s. Check the penalty, the time "
                             "step and the geometry.");
      }
    report.cuts = cuts;
    if (cuts == 0 && report.iterations <= std::max(2u, ctrl.max_iterations / 2))
      dt = std::min(ctrl.time_step, dt * ctrl.growth);
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
    par.dt                 = h;
    par.dynamic            = ctrl.dynamic;
    par.law                = ctrl.law;
    par.fixed_penalty      = ctrl.fixed_penalty;
    par.gap_tolerance      = gap_tolerance;
    par.reversal_tolerance = 1e-6 * allowed_step;
    par.body_acceleration  = scene.gravity;
    const auto mode        = scene.seismic.mode;
    if (mode == SeismicInput::Mode::inertial)
      par.body_acceleration.x() -= ground.acceleration(t + 0.5 * h);
    const double ug = mode == SeismicInput::Mode::displacement
                        ? ground.displacement(t + h)
                        : 0.;
    par.fixed_targets.resize(scene.fixed_points.size());
    for (std::size_t f = 0; f < scene.fixed_points.size(); ++f)
      {
        const auto &fp = scene.fixed_points[f];
        par.fixed_targets[f]
          = fp.anchor + geometry::Point(fp.moves_with_ground ? ug : 0., 0.);
      }
    assembler.prepare_step(scene, contacts, par, matrix);
    solver.new_pattern(matrix);

    Eigen::VectorXd x = last_solution;
    if (x.size() != static_cast<long>(6 * scene.blocks.size()))
      x = Eigen::VectorXd::Zero(6 * scene.blocks.size());
    Eigen::VectorXd F;
    report.solver_iterations = 0;
    bool     converged       = false;
    unsigned changes         = 0;
    unsigned it              = 0;
    while (it < ctrl.max_iterations)
      {
        ++it;
        assembler.assemble(contacts, matrix, F);
        if (!F.allFinite())
          {
            why = "the load vector is not finite";
            return false;
          }
        // After an iteration without state changes (only the friction
        // forces were updated) the matrix is unchanged: reuse its
        // factorisation.
        if (!solver.solve(matrix, F, x, it > 1 && changes == 0))
          {
            why = "the linear solver failed ("
                  + std::string(solver.type() == SolverType::direct
                                  ? "matrix not positive definite"
                                  : "CG did not converge")
                  + ")";
            return false;
          }
        report.solver_iterations += solver.last_iterations();
        if (!x.allFinite())
          {
            why = "the displacement increment is not finite";
            return false;
          }
        changes                   = 0;
        unsigned friction_changes = 0;
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
        const double friction_tolerance
          = 1e-3 * (n_closed > 0 ? force_sum / n_closed : 0.)
            + gap_tolerance * ctrl.law.normal_penalty;
        for (std::size_t c = 0; c < contacts.size(); ++c)
          {
            Contact                 &ct  = contacts[c];
            const ContactKinematics &kin = assembler.kinematics()[c];
            const auto               Di = x.segment<6>(6 * ct.geometry.block_i);
            const auto               Dj = x.segment<6>(6 * ct.geometry.block_j);
            const double     g = kin.g0 + kin.en.dot(Di) + kin.hn.dot(Dj);
            const double     s = kin.s0 + kin.es.dot(Di) + kin.hs.dot(Dj);
            const StateCheck r
              = check_state(ct, kin, g, s, ctrl.law, scene.joints[ct.joint]);
            // The friction of a sliding contact used the normal force of
            // the previous iteration; iterate until it agrees (implicit
            // friction), which suppresses a rocking instability when the
            // time step resolves the contact vibration.
            if (ct.state == ContactState::sliding
                && r.state == ContactState::sliding
                && std::abs(r.normal_force - ct.normal_force)
                     > 1e-3 * std::abs(r.normal_force) + friction_tolerance)
              ++friction_changes;
            ct.normal_force = r.normal_force;
            ct.shear_force  = r.shear_force;
            if (r.changed)
              {
                ++changes;
                const ContactState old = ct.state;
                ct.state               = r.state;
                if (r.state == ContactState::locked
                    || (r.state == ContactState::sliding
                        && old == ContactState::open))
                  {
                    ct.xi_ref = ct.geometry.xi;
                    if (r.state == ContactState::locked
                        && old == ContactState::sliding)
                      {
                        // Force continuity: the shear spring starts from
                        // the friction force the contact carried, i.e.
                        // at displacement dir * strength / p_s from its
                        // reference, instead of dropping to zero.
                        ct.xi_ref
                          += r.shear_force
                             / (ctrl.law.shear_penalty() * kin.edge_length);
                      }
                    assembler.set_shear_reference(scene, c, ct);
                  }
                else if (r.state == ContactState::open
                         && old != ContactState::open)
                  ct.broken = true;
                if (r.state == ContactState::sliding)
                  ct.broken = true;
              }
            if (r.state == ContactState::sliding)
              ct.slide_direction = r.slide_direction;
          }
        // States settled; the friction force is iterated further while
        // the budget lasts (never a reason to cut the step).
        if (changes == 0
            && (friction_changes == 0 || it + 1 >= ctrl.max_iterations))
          {
            converged = true;
            break;
          }
      }
    if (!converged)
      {
        why = "the open-close iteration did not converge in "
              + std::to_string(ctrl.max_iterations) + " iterations ("
              + std::to_string(changes) + " contacts still changing state)";
        return false;
      }

    // Largest vertex displacement.
    double max_d = 0.;
    int    worst = 0;
    for (std::size_t b = 0; b < scene.blocks.size(); ++b)
      {
        const Vector6 D = x.segment<6>(6 * b);
        const auto   &c = assembler.moments()[b].centroid;
        for (const auto &p : scene.blocks[b].polygon.vertices)
          {
            const double d = (displacement_matrix(c, p) * D).norm();
            if (d > max_d)
              {
                max_d = d;
                worst = static_cast<int>(b);
              }
          }
      }
    if (max_d > allowed_step)
      {
        why = "block " + std::to_string(scene.blocks[worst].id) + " moved "
              + num(max_d) + " m in one step, more than the allowed "
              + num(allowed_step) + " m (min of "
              + num(ctrl.max_displacement_ratio) + " x domain size "
              + num(domain) + " m and " + num(ctrl.max_displacement_block_ratio)
              + " x median block size)";
        return false;
      }

    update(x, h);
    current_contacts = std::move(contacts);
    contact_set.store(current_contacts);
    last_solution = x;
    t += h;
    ++n_steps;
    report.time             = t;
    report.dt               = h;
    report.iterations       = it;
    report.max_displacement = max_d;
    report.n_open = report.n_sliding = report.n_locked = 0;
    for (const auto &c : current_contacts)
      (c.state == ContactState::open      ? report.n_open
       : c.state == ContactState::sliding ? report.n_sliding
                                          : report.n_locked)++;
    return true;
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
        block.velocity = (2. / h) * D - ctrl.dynamic * block.velocity;
        const Eigen::Matrix3d C
          = elasticity_matrix(scene.materials[block.material]);
        Eigen::Vector3d sigma = block.stress + C * D.segment<3>(3);
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
        block.strain = rotate(block.strain + D.segment<3>(3), 0.5);
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



  double
  DdaSystem::kinetic_energy() const
  {
    double e = 0.;
    for (const auto &b : scene.blocks)
      {
        const Matrix6 M = mass_matrix(block_moments(b.polygon),
                                      scene.materials[b.material].density);
        e += 0.5 * b.velocity.dot(M * b.velocity);
      }
    return e;
  }



  double
  DdaSystem::strain_energy() const
  {
    double e = 0.;
    for (const auto &b : scene.blocks)
      {
        const Eigen::Matrix3d C
          = elasticity_matrix(scene.materials[b.material]);
        e += 0.5 * b.polygon.area() * b.stress.dot(C.ldlt().solve(b.stress));
      }
    return e;
  }



  double
  DdaSystem::contact_energy() const
  {
    double       e  = 0.;
    const double p  = ctrl.law.normal_penalty;
    const double ps = ctrl.law.shear_penalty();
    for (const auto &c : current_contacts)
      {
        if (c.state == ContactState::open)
          continue;
        e += 0.5 * c.normal_force * c.normal_force / p;
        if (c.state == ContactState::locked)
          e += 0.5 * c.shear_force * c.shear_force / ps;
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
        e -= scene.materials[b.material].density * m.area
             * scene.gravity.dot(m.centroid - b.initial_centroid);
      }
    return e;
  }



  geometry::Point
  DdaSystem::centroid_displacement(const int block) const
  {
    const Block &b = scene.blocks[block];
    return block_moments(b.polygon).centroid - b.initial_centroid;
  }
} // namespace rockdda::dda
