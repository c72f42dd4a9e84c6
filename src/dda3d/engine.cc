/**
 * @file
 * 3D DDA with contacts: contact kinematics and springs, Mohr-Coulomb state
 * checks, the open-close iteration with step cutting, and the energy
 * ledger (Shi 1988, 2001; doc/theory/dda3d.md).
 */
#include <rockdda/dda/block_step_terms.h>
#include <rockdda/dda/contact_damping.h>
#include <rockdda/dda/contact_history.h>
#include <rockdda/dda/friction_relaxation.h>
#include <rockdda/dda/line_search.h>
#include <rockdda/dda/open_close.h>
#include <rockdda/dda/state_check.h>
#include <rockdda/dda/step_driver.h>
#include <rockdda/dda/strain_damping.h>
#include <rockdda/dda/strength_audit.h>
#include <rockdda/dda3d/block_terms.h>
#include <rockdda/dda3d/engine.h>
#include <rockdda/io/error.h>
#include <rockdda/io/output.h>

#include <Eigen/Cholesky>
#include <Eigen/Dense>
#include <Eigen/Geometry>

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <map>
#include <set>
#include <tuple>

namespace rockdda::dda3d
{
  StateCheck
  check_state(const Contact           &contact,
              const ContactKinematics &kin,
              const Eigen::Vector2d   &direction,
              const double             g,
              const Eigen::Vector2d   &s,
              const double             f,
              const JointMaterial     &joint,
              const double             hold)
  {
    dda::StateCheckSprings k;
    k.normal_stiffness = kin.normal_stiffness;
    k.shear_stiffness  = kin.shear_stiffness;
    k.force_tolerance  = f;
    k.hold_tolerance   = hold;
    k.extent           = contact.area;
    return dda::check_contact_state(contact, direction, g, s, k, joint);
  }



  namespace
  {
    /// A unit vector perpendicular to @p n.
    Point
    perpendicular(const Point &n)
    {
      const Point a = std::abs(n.x()) < 0.6   ? Point::UnitX()
                      : std::abs(n.y()) < 0.6 ? Point::UnitY()
                                              : Point::UnitZ();
      return (a - a.dot(n) * n).normalized();
    }

    /// Area of the overlap of two convex faces facing each other, in the
    /// plane of @p fb (Sutherland-Hodgman clipping in 2D coordinates).
    double
    face_overlap(const Polyhedron &A,
                 const int         fa,
                 const Polyhedron &B,
                 const int         fb)
    {
      const Point n = B.face_normal(fb);
      const Point u = perpendicular(n);
      const Point v = n.cross(u);
      auto        to
        = [&](const Point &p) { return Eigen::Vector2d(u.dot(p), v.dot(p)); };
      std::vector<Eigen::Vector2d> clip, subject;
      for (const int k : B.faces[fb])
        clip.push_back(to(B.vertices[k]));
      // A's face is counter-clockwise about -n: reverse it.
      for (auto it = A.faces[fa].rbegin(); it != A.faces[fa].rend(); ++it)
        subject.push_back(to(A.vertices[*it]));
      auto cross = [](const Eigen::Vector2d &a, const Eigen::Vector2d &b) {
        return a.x() * b.y() - a.y() * b.x();
      };
      for (std::size_t e = 0; e < clip.size() && !subject.empty(); ++e)
        {
          const Eigen::Vector2d c0 = clip[e], c1 = clip[(e + 1) % clip.size()];
          auto                  side
            = [&](const Eigen::Vector2d &p) { return cross(c1 - c0, p - c0); };
          std::vector<Eigen::Vector2d> out;
          for (std::size_t k = 0; k < subject.size(); ++k)
            {
              const auto &p   = subject[k],
                         &q   = subject[(k + 1) % subject.size()];
              const double sp = side(p), sq = side(q);
              if (sp >= 0.)
                out.push_back(p);
              if ((sp >= 0.) != (sq >= 0.))
                out.push_back(p + (q - p) * (sp / (sp - sq)));
            }
          subject = out;
        }
      double a = 0.;
      for (std::size_t k = 0; k < subject.size(); ++k)
        a += cross(subject[k], subject[(k + 1) % subject.size()]);
      return std::max(0., 0.5 * a);
    }

    /// The faces of block i's feature of candidate @p c (the faces at the
    /// vertex, or the two faces of the edge).
    std::vector<int>
    feature_faces(const Polyhedron      &p,
                  const PolyhedronEdges &edges,
                  const ContactType      type,
                  const int              feature)
    {
      std::vector<int> out;
      if (type == ContactType::vertex_face)
        {
          for (int f = 0; f < int(p.faces.size()); ++f)
            if (std::find(p.faces[f].begin(), p.faces[f].end(), feature)
                != p.faces[f].end())
              out.push_back(f);
        }
      else
        out = {edges.face[feature][0], edges.face[feature][1]};
      return out;
    }
  } // namespace



  Engine::Engine(BlockSystem system_in, const EngineControls &c)
      : LocalScene(std::move(system_in))
      , ctrl(c)
      , solver(c.solver)
  {
    if (ctrl.solver.type == dda::SolverType::distributed)
      throw InputError("3D DDA: the distributed linear solver is 2D only; "
                       "valid: automatic, direct, iterative");
    if (!(ctrl.dt > 0.) || !std::isfinite(ctrl.dt))
      throw InputError("time step " + std::to_string(ctrl.dt)
                       + " s; valid: > 0");
    if (!(ctrl.dynamic >= 0. && ctrl.dynamic <= 1.))
      throw InputError("dynamic control " + std::to_string(ctrl.dynamic)
                       + "; valid: 0-1");
    if (!(ctrl.strain_damping >= 0. && std::isfinite(ctrl.strain_damping)))
      throw InputError("strain damping " + std::to_string(ctrl.strain_damping)
                       + " s; valid: >= 0 s");
    if (!(ctrl.contact_damping >= 0. && std::isfinite(ctrl.contact_damping)))
      throw InputError("contact damping ratio "
                       + std::to_string(ctrl.contact_damping)
                       + "; valid: >= 0");
    if (!(ctrl.contact_step_damping >= 0.
          && std::isfinite(ctrl.contact_step_damping)))
      throw InputError("contact step damping "
                       + std::to_string(ctrl.contact_step_damping)
                       + "; valid: >= 0");
    if (!(ctrl.law.normal_penalty > 0.) || !(ctrl.law.shear_ratio > 0.))
      throw InputError("contact penalty and shear ratio must be > 0");
    if (const std::string e = dda::shear_penalty_error(ctrl.law); !e.empty())
      throw InputError(e);
    if (!(ctrl.max_displacement_ratio > 0.))
      throw InputError("maximum displacement ratio must be > 0");
    if (ctrl.fixed_penalty <= 0.)
      ctrl.fixed_penalty = 10. * ctrl.law.normal_penalty;
    if (system.joints.empty() && system.blocks.size() > 1)
      throw InputError("a scene of several blocks needs a joint material");
    validate_and_prepare(system);
    check_overlaps(system, 1e-6, origin_);
    // Clamped blocks: 3 or more non-collinear fixed points.
    clamped_.assign(system.blocks.size(), 0);
    for (const auto &b : system.blocks)
      initial_speed_ = std::max(initial_speed_, b.velocity.head<3>().norm());
    for (std::size_t b = 0; b < system.blocks.size(); ++b)
      {
        std::vector<Point> pts;
        for (const auto &f : system.fixed_points)
          if (f.block == int(b))
            pts.push_back(f.point);
        const double s = system.blocks[b].polyhedron.size();
        for (std::size_t x = 0; x < pts.size() && !clamped_[b]; ++x)
          for (std::size_t y = x + 1; y < pts.size() && !clamped_[b]; ++y)
            for (std::size_t z = y + 1; z < pts.size() && !clamped_[b]; ++z)
              if ((pts[y] - pts[x]).cross(pts[z] - pts[x]).norm()
                  > 1e-6 * s * s)
                clamped_[b] = 1;
      }
    steps_ = dda::TimeStepControl(ctrl.dt, ctrl.min_dt_ratio * ctrl.dt);
  }



  void
  Engine::step()
  {
    advance(std::numeric_limits<double>::infinity());
  }



  void
  Engine::advance(const double max_length)
  {
    // (dda::take_step(), the loop of both engines.) A failed attempt
    // restores what it changed.
    const BlockSystem          saved_system   = system;
    const std::vector<Contact> saved_contacts = stored;
    const Eigen::VectorXd      saved_solution = last_solution;
    const double saved_friction = friction_work, saved_load = load_work,
                 saved_damping = damping_work, saved_contact = contact_energy;
    double     h_taken = 0.;
    const auto cuts    = dda::take_step(
      steps_,
      max_length,
      static_cast<unsigned>(ctrl.max_open_close),
      [&](const double h, unsigned &iterations) {
        h_taken             = h;
        const bool accepted = try_step(h);
        iterations          = static_cast<unsigned>(stats.iterations);
        return accepted;
      },
      [&]() {
        system         = saved_system;
        stored         = saved_contacts;
        last_solution  = saved_solution;
        friction_work  = saved_friction;
        load_work      = saved_load;
        damping_work   = saved_damping;
        contact_energy = saved_contact;
      },
      "3D DDA: ",
      n_steps + 1,
      t,
      why_,
      " (Minimum time step ratio " + io::format_number(ctrl.min_dt_ratio, 3)
        + " x " + io::format_number(ctrl.dt, 3) + " s)");
    t += h_taken;
    ++n_steps;
    n_cuts += cuts;
    n_iterations += stats.iterations;
    stats.cuts      = static_cast<int>(cuts);
    stats.dt        = h_taken;
    first_detection = false;
  }



  void
  Engine::advance_to(const double t_end)
  {
    dda::run_to(
      steps_,
      t,
      t_end,
      ctrl.max_steps,
      ctrl.dt,
      [&](const double max_length) { advance(max_length); },
      "3D DDA: ",
      why_);
  }



  void
  Engine::settle(const unsigned int                             n,
                 const std::function<bool(const unsigned int)> &after_step)
  {
    const EngineControls saved = ctrl;
    const double         t0    = t;
    ctrl.dynamic               = 0.;
    ctrl.ground_acceleration   = nullptr;
    ctrl.ground_displacement   = nullptr;
    dda::static_steps(
      n, after_step, [&]() { step(); }, [&]() { ctrl = saved; });
    t = t0;
    steps_.reset();
    for (auto &b : system.blocks)
      {
        b.velocity.setZero();
        b.initial_centroid = b.polyhedron.moments().centroid;
      }
    for (auto &m : system.measurement_points)
      m.initial = m.point;
    friction_work = 0.;
    load_work     = 0.;
    damping_work  = 0.;
    n_steps       = 0;
    n_iterations  = 0;
  }



  bool
  Engine::try_step(const double h)
  {
    const std::size_t n = system.blocks.size();
    // The ledger at the start of the step (the sanity check's reference).
    const double balance_before = energy().balance();
    Point        a              = system.gravity;
    Point        ag             = Point::Zero();
    if (ctrl.ground_acceleration)
      {
        ag = ctrl.ground_acceleration(t + 0.5 * h);
        a -= ag;
      }
    const dda::StrainDamping damping(ctrl.strain_damping, h, ctrl.dynamic);
    // The contacts' dashpots (their end-of-step velocity is 2 D / h - v).
    const dda::ContactDamping dashpots(ctrl.contact_damping,
                                       ctrl.contact_step_damping,
                                       h,
                                       ctrl.dynamic);
    // Displacement mode: the ground's displacement at the end of the step;
    // clamped blocks get the translation that puts their centroid there.
    const Point ug = ctrl.ground_displacement ? ctrl.ground_displacement(t + h)
                                              : Point::Zero();
    // The block terms (shared with FreeBlocks), with the strain damping.
    BlockTerms                            terms   = block_terms(system,
                                   h,
                                   ctrl.dynamic,
                                   1. + damping.factor(),
                                   ag,
                                   ug,
                                   ctrl.fixed_penalty);
    const std::vector<PolyhedronMoments> &moments = terms.moments;
    std::vector<Matrix12>                &K0      = terms.K;
    std::vector<Vector12>                &F0      = terms.F;
    const std::vector<Vector12>          &Fext    = terms.external;
    std::vector<double>                   mass(n), size(n);
    for (std::size_t b = 0; b < n; ++b)
      {
        mass[b] = system.materials[system.blocks[b].material].density
                  * moments[b].volume;
        size[b] = system.blocks[b].polyhedron.size();
      }
    std::vector<Vector12> prescribed(n, Vector12::Zero());
    if (ctrl.ground_displacement)
      for (std::size_t b = 0; b < n; ++b)
        if (clamped_[b])
          prescribed[b].head<3>()
            = ug - (moments[b].centroid - system.blocks[b].initial_centroid);

    // Contacts: detection on the geometry at the start of the step.
    DetectionTolerances tol;
    tol.distance_factor = 2.5 * ctrl.max_displacement_ratio;
    std::vector<const Polyhedron *> polys(n);
    for (std::size_t b = 0; b < n; ++b)
      polys[b] = &system.blocks[b].polyhedron;
    // Per-pair and per-contact loops in fixed chunks on the linear
    // solver's threads (as the 2D engine): the same results on any number.
    const dda::ChunkRunner chunks
      = [this](const std::size_t n_items,
               const std::size_t grain,
               const auto       &f) { solver.for_chunks(n_items, grain, f); };
    // The edges of the blocks in a detected pair, reused by the face
    // groups below (the same geometry).
    std::vector<PolyhedronEdges> edges;
    const auto candidates = detect_contacts(polys, tol, chunks, &edges);

    // Transfer of the stored states: by (type, i, a, j, b); a vertex that
    // passed to another face of the same block keeps a closed state: the
    // contact it had is no longer detected (it went round a convex edge of
    // block j). A vertex that still touches its face and approaches
    // another one (a reflex edge of j, the corner of a valley) keeps its
    // contact, and the new face's contact starts from its own gap: handed
    // the first contact's state, force and sliding direction it pulled the
    // vertex onto the floor with the slope's force (a box sliding into a
    // valley stopped there, the step cut below its minimum).
    // (dda::ContactHistory, the 2D engine's rule.)
    using Key       = std::tuple<int, int, int, int, int>;
    using VertexKey = std::tuple<int, int, int>;
    std::vector<Key> detected;
    detected.reserve(candidates.size());
    for (const auto &g : candidates)
      detected.emplace_back(int(g.type), g.i, g.a, g.j, g.b);
    std::sort(detected.begin(), detected.end());
    dda::ContactHistory<Key, VertexKey> history;
    {
      std::vector<Key>                        keys;
      std::vector<std::pair<bool, VertexKey>> vertex_keys;
      for (const auto &c : stored)
        {
          const auto &g = c.geometry;
          keys.emplace_back(int(g.type), g.i, g.a, g.j, g.b);
          vertex_keys.emplace_back(g.type == ContactType::vertex_face
                                     && c.state != ContactState::open,
                                   VertexKey{g.i, g.a, g.j});
        }
      history.store(keys, vertex_keys);
    }
    std::vector<Contact> contacts(candidates.size());
    // The shear force each contact carried at the start of the step (N;
    // zero if new or open), whose spring energy the ledger had stored.
    std::vector<Point> shear_at_start(candidates.size(), Point::Zero());
    for (std::size_t k = 0; k < candidates.size(); ++k)
      {
        const auto &g = candidates[k];
        Contact    &c = contacts[k];
        c.geometry    = g;
        c.joint       = system.blocks[g.j].joint;
        const VertexKey vertex{g.i, g.a, g.j};
        const auto      m
          = history.find(Key{int(g.type), g.i, g.a, g.j, g.b},
                         g.type == ContactType::vertex_face ? &vertex : nullptr,
                         detected);
        const Contact *old          = m.index >= 0 ? &stored[m.index] : nullptr;
        const bool     same_feature = m.same_feature;
        if (old)
          {
            // (dda::continue_contact(): the rule of both engines.)
            dda::continue_contact(c,
                                  *old,
                                  same_feature,
                                  [](Contact &to, const Contact &from) {
                                    to.reference     = from.reference;
                                    to.has_reference = from.has_reference;
                                  });
            if (same_feature && old->state != ContactState::open)
              shear_at_start[k] = old->shear_force;
          }
        else
          {
            // A new contact is closed within the round-off of its gap and
            // of the input coordinates, which were rounded at their global
            // magnitude (the local origin's) before the exact shift.
            const double round_off
              = dda::round_off_tolerance(std::min(size[g.i], size[g.j]),
                                         g.p,
                                         g.q)
                + dda::coordinate_round_off(origin_, origin_);
            c.state
              = g.gap <= round_off ? ContactState::locked : ContactState::open;
            c.broken = !first_detection;
          }
        if (c.state != ContactState::locked)
          c.has_reference = false;
        // The slip rate of the friction law: the previous step's, none in
        // a static step (constant friction), 0 after static steps.
        c.slip_rate
          = ctrl.dynamic == 0. ? dda::no_slip_rate : std::max(c.slip_rate, 0.);
      }
    // Contact areas: the overlap of the two faces facing each other,
    // shared among the contacts between them (a face group).
    std::vector<int> group(contacts.size(), -1);
    int              n_groups = 0;
    // The contacts of each face group, in contact order.
    std::vector<std::vector<std::size_t>> group_members;
    {
      // Every candidate's blocks are in a pair of the broad phase:
      // detection computed their edges.
      auto edges_of
        = [&](const int b) -> const PolyhedronEdges & { return edges[b]; };
      std::map<std::tuple<int, int, int, int>, std::vector<std::size_t>> groups;
      for (std::size_t k = 0; k < contacts.size(); ++k)
        {
          const auto &g = contacts[k].geometry;
          const auto  fi
            = feature_faces(*polys[g.i], edges_of(g.i), g.type, g.a);
          std::vector<int> fj
            = g.type == ContactType::vertex_face
                ? std::vector<int>{g.b}
                : feature_faces(*polys[g.j], edges_of(g.j), g.type, g.b);
          bool found = false;
          for (const int x : fi)
            for (const int y : fj)
              if (!found
                  && polys[g.i]->face_normal(x).dot(polys[g.j]->face_normal(y))
                       < -std::cos(0.1))
                {
                  found          = true;
                  const auto key = g.i < g.j ? std::make_tuple(g.i, x, g.j, y)
                                             : std::make_tuple(g.j, y, g.i, x);
                  groups[key].push_back(k);
                }
        }
      for (const auto &[key, members] : groups)
        {
          const auto [bi, fi, bj, fj] = key;
          const double area = face_overlap(*polys[bi], fi, *polys[bj], fj);
          for (const auto k : members)
            {
              contacts[k].area = area / double(members.size());
              group[k]         = n_groups;
            }
          group_members.push_back(members);
          ++n_groups;
        }
    }

    // Kinematics.
    const double                   body_accel = a.norm();
    std::vector<ContactKinematics> kin(contacts.size());
    auto                           set_shear = [&](const std::size_t k) {
      auto                       &c = contacts[k];
      auto                       &K = kin[k];
      const auto                 &g = c.geometry;
      const Point                 r = c.has_reference ? c.reference : g.q;
      Eigen::Matrix<double, 3, 2> tb;
      tb.col(0) = K.t1;
      tb.col(1) = K.t2;
      K.Es = displacement_matrix(moments[g.i].centroid, g.p).transpose() * tb;
      // Block j's material point at the vertex, as in 2D
      // (dda/assembler.cc): the force pair acts at one point.
      K.Hs = -displacement_matrix(moments[g.j].centroid, g.p).transpose() * tb;
      K.s0 = tb.transpose() * (g.p - r);
    };
    dda::for_each_chunk(
      chunks,
      contacts.size(),
      128,
      [&](const std::size_t lo, const std::size_t hi) {
        for (std::size_t k = lo; k < hi; ++k)
          {
            auto       &c = contacts[k];
            auto       &K = kin[k];
            const auto &g = c.geometry;
            K.g0          = g.gap;
            K.en = displacement_matrix(moments[g.i].centroid, g.p).transpose()
                   * g.normal;
            K.hn = -displacement_matrix(moments[g.j].centroid, g.p).transpose()
                   * g.normal;
            K.t1 = perpendicular(g.normal);
            K.t2 = g.normal.cross(K.t1);
            set_shear(k);
            const auto springs
              = dda::contact_springs(ctrl.law, system.joints[c.joint], c.area);
            K.normal_stiffness = springs.normal;
            K.shear_stiffness  = springs.shear;
            {
              // The lighter free block's mass (a clamped block's is
              // infinite).
              const double inf = std::numeric_limits<double>::infinity();
              const double mi  = clamped_[g.i] ? inf : mass[g.i],
                           mj  = clamped_[g.j] ? inf : mass[g.j];
              K.normal_dashpot = dashpots.dashpot(springs.normal, mi, mj);
              K.shear_dashpot  = dashpots.dashpot(springs.shear, mi, mj);
            }
            // The shared rule of both engines (dda/contact_mechanics.h) with
            // the representation error of the local coordinates the gap and
            // the shear displacement are measured from as the round-off
            // (gap_round_off(), unpadded). No floor relative to the block
            // size: times the spring it would let a locked contact carry k_n
            // 1e-12 L beyond its strength, a force that grows with the
            // penalty (0.2 N, 2.6 % of the shaking-table wedge's weight per
            // contact at 1e12 N/m: the wedge stuck).
            K.tolerance = dda::gap_round_off(g.p, g.q);
            K.weight_tolerance
              = dda::contact_weight_tolerance(std::min(mass[g.i], mass[g.j]),
                                              body_accel,
                                              ctrl.law.force_tolerance);
            K.force_tolerance = dda::contact_force_tolerance(K.weight_tolerance,
                                                             K.normal_stiffness,
                                                             K.tolerance);
            c.state_at_start  = c.state;
          }
      });
    // Sliding directions in each contact's tangent basis.
    std::vector<Eigen::Vector2d> dir(contacts.size(), Eigen::Vector2d::Zero());
    for (std::size_t k = 0; k < contacts.size(); ++k)
      {
        const Eigen::Vector2d d(kin[k].t1.dot(contacts[k].slide_direction),
                                kin[k].t2.dot(contacts[k].slide_direction));
        dir[k] = d.norm() > 1e-12 ? Eigen::Vector2d(d.normalized())
                                  : Eigen::Vector2d::Zero();
      }

    // The matrix pattern: the pairs of blocks in contact (in any state: the
    // states change within the step), clamped blocks decoupled; the slot
    // of each contact's off-diagonal block.
    std::vector<int> slot(contacts.size(), -1);
    {
      std::vector<std::pair<int, int>> pairs;
      pairs.reserve(contacts.size());
      for (const auto &c : contacts)
        {
          const int i = c.geometry.i, j = c.geometry.j;
          if (!clamped_[i] && !clamped_[j] && i != j)
            pairs.emplace_back(std::min(i, j), std::max(i, j));
        }
      std::sort(pairs.begin(), pairs.end());
      pairs.erase(std::unique(pairs.begin(), pairs.end()), pairs.end());
      for (std::size_t k = 0; k < contacts.size(); ++k)
        {
          const int i = contacts[k].geometry.i, j = contacts[k].geometry.j;
          if (!clamped_[i] && !clamped_[j] && i != j)
            slot[k] = static_cast<int>(
              std::lower_bound(pairs.begin(),
                               pairs.end(),
                               std::make_pair(std::min(i, j), std::max(i, j)))
              - pairs.begin());
        }
      matrix.reinit(static_cast<int>(n), pairs);
    }
    solver.new_pattern(matrix);
    // The contacts of each block and of each pair of blocks (the matrix's
    // off-diagonal slots), in contact order, for the assembly's chunks.
    const auto by_block
      = dda::items_of_rows(int(n), contacts.size(), [&](const std::size_t k) {
          return std::make_pair(contacts[k].geometry.i, contacts[k].geometry.j);
        });
    const auto by_slot
      = dda::items_of_rows(int(matrix.off.size()),
                           contacts.size(),
                           [&](const std::size_t k) {
                             return std::make_pair(slot[k], -1);
                           });
    // Contact k's springs between the unknowns of its blocks a and b (0:
    // block i, 1: block j): the 12x12 block (a, b) of k_n g_n g_n^T, plus
    // k_s G_s G_s^T if locked, in the stacked unknowns (D_i, D_j), g_n =
    // [e_n; h_n] and G_s = [E_s; H_s]; each spring with its dashpot's
    // 2 c / h.
    auto springs_of = [&](const std::size_t k,
                          const int         a,
                          const int         b,
                          const bool        with_dashpots) {
      const auto  &K = kin[k];
      const double cn
        = with_dashpots ? dashpots.stiffness(K.normal_dashpot) : 0.,
        cs       = with_dashpots ? dashpots.stiffness(K.shear_dashpot) : 0.;
      Matrix12 m = (K.normal_stiffness + cn) * (a == 0 ? K.en : K.hn)
                   * (b == 0 ? K.en : K.hn).transpose();
      if (contacts[k].state == ContactState::locked)
        m += (K.shear_stiffness + cs) * (a == 0 ? K.Es : K.Hs)
             * (b == 0 ? K.Es : K.Hs).transpose();
      return m;
    };
    auto spring_block = [&](const std::size_t k, const int a, const int b) {
      return springs_of(k, a, b, true);
    };
    // The upper block K_ij (i < j) of each pair of the matrix: the springs
    // of its closed contacts (with their dashpots' 2 c / h if asked).
    auto fill_pairs = [&](const bool with_dashpots) {
      dda::for_each_chunk(chunks,
                          matrix.off.size(),
                          32,
                          [&](const std::size_t lo, const std::size_t hi) {
                            for (std::size_t p = lo; p < hi; ++p)
                              {
                                matrix.off[p].setZero();
                                for (int e = by_slot.start[p];
                                     e < by_slot.start[p + 1];
                                     ++e)
                                  {
                                    const std::size_t k = by_slot.entry[e] / 2;
                                    if (contacts[k].state == ContactState::open)
                                      continue;
                                    const bool upper = contacts[k].geometry.i
                                                       < contacts[k].geometry.j;
                                    matrix.off[p] += springs_of(k,
                                                                upper ? 0 : 1,
                                                                upper ? 1 : 0,
                                                                with_dashpots);
                                  }
                              }
                          });
    };
    // Calls f(k, side) for each closed contact k of block b, in contact
    // order; side 0: b is the contact's block i, 1: its block j.
    auto for_closed_contacts_of = [&](const std::size_t b, const auto &f) {
      for (int e = by_block.start[b]; e < by_block.start[b + 1]; ++e)
        {
          const std::size_t k = by_block.entry[e] / 2;
          if (contacts[k].state != ContactState::open)
            f(k, by_block.entry[e] % 2);
        }
    };
    // The blocks' velocities at the start of the step as Shi's scheme
    // carries them (times the dynamic control), and contact k's normal
    // and shear rates of the stacked vectors (x_i, x_j).
    std::vector<Vector12> v0(n);
    for (std::size_t b = 0; b < n; ++b)
      v0[b] = ctrl.dynamic * system.blocks[b].velocity;
    auto normal_rate
      = [&](const std::size_t k, const std::vector<Vector12> &x) {
          return kin[k].en.dot(x[contacts[k].geometry.i])
                 + kin[k].hn.dot(x[contacts[k].geometry.j]);
        };
    auto shear_rate = [&](const std::size_t k, const std::vector<Vector12> &x) {
      return Eigen::Vector2d(kin[k].Es.transpose() * x[contacts[k].geometry.i]
                             + kin[k].Hs.transpose()
                                 * x[contacts[k].geometry.j]);
    };

    // Open-close iteration.
    const int       N = 12 * int(n);
    Eigen::VectorXd D = last_solution.size() == N
                          ? last_solution
                          : Eigen::VectorXd(Eigen::VectorXd::Zero(N));
    // Whether the contact states (hence the matrix) changed since the
    // last solve: an iteration that only updated friction forces reuses
    // the factorisation or preconditioner.
    bool states_changed = true;
    // Whether the latest iteration was a damped step of the line search
    // after which no state changed (the next one is then a full step).
    bool             damped_last       = false;
    int              solver_iterations = 0;
    std::vector<int> changes(contacts.size(), 0);
    // The friction force of each sliding contact in the last solve (N, on
    // block i, in the tangent basis): the energy ledger books its work.
    std::vector<Eigen::Vector2d> friction_applied(contacts.size(),
                                                  Eigen::Vector2d::Zero());
    // The normal force each sliding contact's friction was assembled with
    // in the latest solve (N), and the mean normal force of the closed
    // contacts then (the friction iteration's force scale, N).
    std::vector<double> assembled_normal(contacts.size(), 0.);
    double              n_mean = 0.;
    // The relaxed friction iteration (dda::FrictionRelaxation, the 2D
    // engine's).
    dda::FrictionRelaxation relaxation(contacts.size());
    // Whether the latest solve was inexact, and whether the states settled
    // on it (a solve to the solver's tolerance confirms them).
    bool                  loose = false, confirming = false;
    std::vector<Vector12> Db(n);
    // Contact k's gap and shear displacement at the end of the step of the
    // last solve.
    auto gap_after
      = [&](const std::size_t k) { return kin[k].g0 + normal_rate(k, Db); };
    auto shear_after = [&](const std::size_t k) {
      return Eigen::Vector2d(kin[k].s0 + shear_rate(k, Db));
    };
    // Face groups: the resultant of the members' shear displacements
    // (oriented as on block i of the group's first member), the
    // direction in which a member that starts to slide slides, so that
    // the self-equilibrated part of the corner springs (Poisson
    // expansion, a small relative rotation) does not turn the friction
    // of a face sliding as a whole.
    // A resultant below 1e-6 of the sum of the members' slips is
    // round-off of a purely self-equilibrated pattern (e.g. the Poisson
    // spreading of a light column's foot: the face is not sliding as a
    // whole); each member then slides along its own slip. (Taking that
    // noise's direction for all pushed a 1 mm x 1 mm x 1 m column standing
    // on a level base sideways with 4 times its friction force, rocked it
    // and the open-close iteration never converged.)
    // The spin of a face group (Goyal, Ruina & Papadopoulos 1991: the
    // friction of a face sliding in its plane opposes the local slip of
    // the faces' relative rigid motion, translation and spin about the
    // normal): each member slides along the resultant plus the spin term
    // members x omega n x (p - c), omega the relative rigid rotation of the
    // group's two blocks about the group's normal in the step (rotation
    // unknowns of D_i - D_j: neither the strains nor the locked springs'
    // stored stretch), c the members' centroid, less the members' mean
    // elastic range S / k_s at the rms radius R (a twist that the shear
    // springs carry below their strength is not a sliding spin: the
    // rocking of a cube on a shaken plane or the torsional vibration of a
    // column's foot). Only in planar contact:
    // when each of the two blocks touches (closed contacts) only through
    // faces parallel to the group's (within the group's 0.1 rad), so that
    // it can spin about that normal; otherwise omega = 0 and the group
    // slides along its resultant as before. (A spin fitted to the
    // members' slips, s0 included, took the torsion of the locked springs
    // of a partly locked group for a spin: 0.24-0.34 of the translation in
    // the shaking-table wedge, whose faces cannot spin; it moved the
    // wedge's onset of sliding by a cycle.)
    std::vector<Point>  resultant(n_groups, Point::Zero());
    std::vector<double> slip_sum(n_groups, 0.), spin(n_groups, 0.),
      radius2(n_groups, 0.), elastic(n_groups, 0.);
    std::vector<int> group_i(n_groups, -1), group_j(n_groups, -1),
      members(n_groups, 0);
    std::vector<Point> centroid(n_groups, Point::Zero()),
      group_normal(n_groups, Point::Zero()), block_normal(n, Point::Zero());
    std::vector<char> planar(n, 1);
    // +1 if contact k's block i is its group's block i, else -1.
    auto orientation = [&](const std::size_t k) {
      return contacts[k].geometry.i == group_i[group[k]] ? 1. : -1.;
    };
    auto slip3 = [&](const std::size_t k) {
      const auto           &K = kin[k];
      const Eigen::Vector2d s = shear_after(k);
      return Point(s.x() * K.t1 + s.y() * K.t2);
    };
    auto group_direction
      = [&](const std::size_t k, const Eigen::Vector2d &fallback) {
          if (group[k] < 0)
            return fallback;
          const int gk = group[k];
          Point     r  = resultant[gk];
          if (spin[gk] != 0.)
            {
              const Point &nrm    = group_normal[gk];
              const Point  offset = contacts[k].geometry.p - centroid[gk];
              r += (members[gk] * spin[gk])
                   * nrm.cross(offset - offset.dot(nrm) * nrm);
            }
          r *= orientation(k);
          if (!(r.norm() > 1e-2 * slip_sum[gk]))
            return fallback;
          const Eigen::Vector2d d(kin[k].t1.dot(r), kin[k].t2.dot(r));
          return d.norm() > 0. ? Eigen::Vector2d(d.normalized()) : fallback;
        };
    // The state check of the latest solve: each contact's own
    // (check_state()), with the force tolerance it used (N).
    std::vector<StateCheck> checks(contacts.size());
    std::vector<double>     check_tolerance(contacts.size(), 0.);
    // Face group gk shares its strength (EngineControls::face_group_friction,
    // doc/theory/dda3d.md "face groups: shared strength"): the corner and
    // edge springs of two faces in contact are one statically indeterminate
    // interface, whose distribution of shear among its members is the
    // penalty's choice, not the physics'. Its members that stay closed and
    // are not sliding (locked, or closing now) share their strength: none
    // of them starts to slide while the sum of their shear spring forces
    // |k_s s| is within the sum of their Mohr-Coulomb strengths (as locked)
    // plus the sum of their tolerances, even if one of them exceeds its
    // own (the members that slide carry exactly their strength and add the
    // same to both sums). Otherwise, and for the members' tension and a
    // sliding member's relock, each member's own check decides. Then the
    // group's resultant satisfies Mohr-Coulomb, |sum F_k| <= sum |F_k| <=
    // sum S_k (+ tolerances), no member carries tension beyond its own
    // tolerance, and the rule only removes slides that the members' own
    // checks would start.
    std::vector<std::size_t> sharing;
    auto                     decide_group = [&](const int gk) {
      sharing.clear();
      double tolerance = 0., demand = 0., strength = 0.;
      bool   any_slides = false;
      for (const std::size_t k : group_members[gk])
        {
          const auto &c = contacts[k];
          if (checks[k].state == ContactState::open
              || c.state == ContactState::sliding)
            continue;
          const auto &joint = system.joints[c.joint];
          if (dda::frictionless(c, joint))
            return;
          Contact locked = c;
          locked.state   = ContactState::locked;
          sharing.push_back(k);
          demand += kin[k].shear_stiffness * shear_after(k).norm();
          strength += dda::shear_strength(locked,
                                          checks[k].normal_force,
                                          locked.area,
                                          joint);
          tolerance += check_tolerance[k];
          any_slides = any_slides || checks[k].state == ContactState::sliding;
        }
      if (sharing.size() < 2 || !any_slides || demand > strength + tolerance)
        return;
      for (const std::size_t k : sharing)
        {
          auto &r = checks[k];
          if (r.state != ContactState::sliding)
            continue;
          r.state     = ContactState::locked;
          r.direction = dir[k];
          r.shear_force = -kin[k].shear_stiffness * shear_after(k);
          r.changed = r.state != contacts[k].state;
        }
    };
    // The contact that changed state most often in this attempt, for the
    // diagnosis of an iteration that cycles.
    const auto most_changed = [&]() {
      const auto  most = std::max_element(changes.begin(), changes.end());
      const auto &g    = contacts[most - changes.begin()].geometry;
      return "the contact of block " + std::to_string(system.blocks[g.i].id)
             + " on block " + std::to_string(system.blocks[g.j].id)
             + " changed state " + std::to_string(*most) + " times";
    };
    // An iteration that returned bit for bit to an earlier iterate cycles
    // for good (dda::IterateFingerprint, as in 2D): cut the attempt now.
    // Each contact's change count enters up to where its chatter
    // tolerance stops growing.
    const int flip_cap
      = std::max(static_cast<int>(ctrl.hold_after),
                 2
                   + static_cast<int>(std::ceil(std::log10(
                     dda::max_chatter_factor(ctrl.law.force_tolerance)))));
    std::set<std::pair<std::uint64_t, std::uint64_t>> visited;
    const auto may_continue = [&](const unsigned done, std::string &reason) {
      if (done < 3 || contacts.empty())
        return true;
      dda::IterateFingerprint f;
      for (Eigen::Index i = 0; i < D.size(); ++i)
        f.add(D[i]);
      for (std::size_t k = 0; k < contacts.size(); ++k)
        {
          const auto &c = contacts[k];
          f.add(static_cast<std::uint64_t>(c.state)
                | static_cast<std::uint64_t>(c.has_reference) << 8
                | static_cast<std::uint64_t>(std::min(changes[k], flip_cap))
                    << 16);
          f.add(dir[k].x());
          f.add(dir[k].y());
          f.add(c.normal_force);
          for (int d = 0; d < 3; ++d)
            {
              f.add(c.reference[d]);
              f.add(c.shear_force[d]);
            }
        }
      for (std::size_t k = 0; k < contacts.size(); ++k)
        f.add(relaxation.previous_residual(k));
      f.add(relaxation.omega());
      f.add(static_cast<std::uint64_t>(damped_last)
            | static_cast<std::uint64_t>(relaxation.has_residual()) << 1
            | static_cast<std::uint64_t>(confirming) << 2);
      if (visited.insert(f.value()).second)
        return true;
      reason = "the open-close iteration cycles (iteration "
               + std::to_string(done) + " returned to an earlier iterate; "
               + most_changed() + ")";
      return false;
    };
    // The shared driver (dda/open_close.h); this engine's iteration is
    // assemble, solve, check.
    // Contact k's force tolerance in this iteration: chatter
    // (dda::chatter_factor(), the 2D rule) gives 10 x and 100 x the weight
    // part after two and three changes, at most 1 % of the weight; the
    // round-off part stays a floor. A contact that cycles is held
    // (dda::hold_tolerance(), the 2D rule).
    auto chatter_tolerance = [&](const std::size_t k) {
      return dda::escalated_tolerance(
        kin[k].weight_tolerance,
        kin[k].force_tolerance,
        dda::chatter_factor(changes[k], ctrl.law.force_tolerance));
    };
    auto held_tolerance = [&](const std::size_t k) {
      const auto &c = contacts[k];
      const auto &K = kin[k];
      return dda::is_held(changes[k], ctrl.hold_after, c.held)
               ? dda::hold_tolerance(c.state == ContactState::open,
                                     K.normal_stiffness,
                                     K.shear_stiffness,
                                     ctrl.hold_fraction,
                                     std::min(size[c.geometry.i],
                                              size[c.geometry.j]),
                                     K.weight_tolerance,
                                     K.force_tolerance,
                                     ctrl.law.force_tolerance)
               : 0.;
    };
    // The increments before the latest solve (the line search's x_k).
    Eigen::VectorXd       D_prev;
    std::vector<Vector12> Db_prev(n);
    // The exact line search of the open-close iteration (dda/line_search.h,
    // the 2D engine's): the step length along D - D_prev.
    auto line_search = [&]() {
      const Eigen::VectorXd d = D - D_prev;
      Eigen::VectorXd       Kd;
      matrix.vmult(d, Kd);
      const double a = d.dot(Kd);
      if (!(a > 0.) || !std::isfinite(a))
        return 1.;
      for (std::size_t b = 0; b < n; ++b)
        Db_prev[b] = D_prev.segment<12>(12 * b);
      std::vector<dda::LineSearchTerm<Eigen::Vector2d>> terms(contacts.size());
      dda::for_each_chunk(
        chunks,
        contacts.size(),
        128,
        [&](const std::size_t lo, const std::size_t hi) {
          for (std::size_t k = lo; k < hi; ++k)
            {
              const auto &c     = contacts[k];
              const auto &K     = kin[k];
              const auto &joint = system.joints[c.joint];
              auto       &t     = terms[k];
              t.g               = K.g0 + normal_rate(k, Db_prev);
              t.dg              = gap_after(k) - t.g;
              t.s             = Eigen::Vector2d(K.s0 + shear_rate(k, Db_prev));
              t.ds            = shear_after(k) - t.s;
              t.p             = K.normal_stiffness;
              t.ps            = K.shear_stiffness;
              t.closed        = c.state != ContactState::open;
              const double f  = chatter_tolerance(k);
              t.f_hold        = std::max(f, held_tolerance(k));
              t.f_open        = c.state == ContactState::locked ? t.f_hold : f;
              t.linear_normal = t.closed && !c.broken
                                && c.state == ContactState::locked
                                && joint.tensile > 0.;
              // The locked members of a face group are left linear, as in
              // 2D.
              t.shear = t.closed && !dda::frictionless(c, joint)
                        && !(c.state == ContactState::locked && group[k] >= 0);
              if (t.shear)
                dda::set_line_search_shear(
                  t,
                  c.state,
                  f,
                  dir[k],
                  dda::shear_strength(c, c.normal_force, c.area, joint));
              t.moves = t.dg != 0. || t.ds.squaredNorm() != 0.;
            }
        });
      return dda::exact_line_search(
        terms, a, [&](const std::size_t k, const double nf) {
          return dda::shear_strength(contacts[k],
                                     nf,
                                     contacts[k].area,
                                     system.joints[contacts[k].joint]);
        });
    };
    const auto solve = [&](const unsigned iteration, std::string &reason) {
      // The contact springs, in chunks of blocks (diagonal blocks and
      // loads) and of pairs (off-diagonal blocks), each adding its
      // contacts in contact order: the serial sums, on any number of
      // threads.
      Eigen::VectorXd F(N);
      dda::for_each_chunk(
        chunks, n, 8, [&](const std::size_t lo, const std::size_t hi) {
          for (std::size_t b = lo; b < hi; ++b)
            {
              auto &Kb = matrix.diag[b];
              auto  Fb = F.segment<12>(12 * b);
              Kb       = K0[b];
              Fb       = F0[b];
              for_closed_contacts_of(
                b, [&](const std::size_t k, const int side) {
                  const auto  &c = contacts[k];
                  const auto  &K = kin[k];
                  const double S
                    = c.state == ContactState::sliding ? dda::shear_strength(
                        c, c.normal_force, c.area, system.joints[c.joint])
                                                       : 0.;
                  if (side == 0 && c.state == ContactState::sliding)
                    friction_applied[k] = -S * dir[k];
                  if (clamped_[b])
                    return;
                  const Vector12   &e_n = side == 0 ? K.en : K.hn;
                  const Matrix12x2 &e_s = side == 0 ? K.Es : K.Hs;
                  Kb += spring_block(k, side, side);
                  // Stacked unknowns (D_i, D_j): gap g = g0 + [en; hn] . x.
                  Vector12 f = -K.normal_stiffness * K.g0 * e_n;
                  if (c.state == ContactState::locked)
                    f -= K.shear_stiffness * e_s * K.s0;
                  else // sliding: friction against the sliding direction
                    f -= S * e_s * dir[k];
                  // The dashpots' c v terms.
                  if (dashpots.active())
                    {
                      f += K.normal_dashpot * normal_rate(k, v0) * e_n;
                      if (c.state == ContactState::locked)
                        f += K.shear_dashpot * e_s * shear_rate(k, v0);
                    }
                  Fb += f;
                  // A clamped partner's prescribed motion moves to the
                  // right side.
                  const int other = side == 0 ? c.geometry.j : c.geometry.i;
                  if (clamped_[other])
                    Fb -= spring_block(k, side, 1 - side) * prescribed[other];
                });
              if (clamped_[b])
                {
                  Kb.setIdentity();
                  Fb = prescribed[b];
                }
            }
        });
      // The upper block K_ij (i < j) of each pair.
      fill_pairs(true);
      D_prev = D;
      // While the states settle, CG solves to a looser tolerance (inexact
      // Newton, as in 2D); the first solve of a step is exact (on a settled
      // scene usually the only one).
      loose = ctrl.inexact_factor > 1. && iteration > 1 && !confirming
              && solver.type() != dda::SolverType::direct;
      if (!solver.solve(matrix,
                        F,
                        D,
                        !states_changed,
                        loose ? ctrl.inexact_factor * ctrl.solver.tolerance
                              : 0.))
        {
          reason = "the linear solver failed";
          return false;
        }
      if (!D.allFinite())
        {
          reason = "the displacement increment is not finite";
          return false;
        }
      solver_iterations += solver.last_iterations();
      for (std::size_t b = 0; b < n; ++b)
        Db[b] = D.segment<12>(12 * b);
      return true;
    };
    const auto check = [&](const unsigned iteration) {
      // Line search along the Newton direction, from the second iteration
      // on (the first starts from the previous step's increments, not
      // from a point of the current states), as in 2D.
      double alpha = 1.;
      if (ctrl.line_search && iteration > 1 && !damped_last)
        {
          alpha = line_search();
          if (alpha < 1.)
            {
              D = D_prev + alpha * (D - D_prev);
              for (std::size_t b = 0; b < n; ++b)
                Db[b] = D.segment<12>(12 * b);
            }
        }
      // State check.
      n_mean       = 0.;
      int n_closed = 0;
      for (const auto &c : contacts)
        if (c.state != ContactState::open)
          {
            n_mean += std::abs(c.normal_force);
            ++n_closed;
          }
      n_mean = n_closed ? n_mean / n_closed : 0.;
      std::fill(resultant.begin(), resultant.end(), Point::Zero());
      std::fill(slip_sum.begin(), slip_sum.end(), 0.);
      std::fill(spin.begin(), spin.end(), 0.);
      std::fill(group_i.begin(), group_i.end(), -1);
      std::fill(members.begin(), members.end(), 0);
      std::fill(centroid.begin(), centroid.end(), Point::Zero());
      std::fill(block_normal.begin(), block_normal.end(), Point::Zero());
      std::fill(planar.begin(), planar.end(), 1);
      for (std::size_t k = 0; k < contacts.size(); ++k)
        if (contacts[k].state != ContactState::open)
          {
            const auto &geo = contacts[k].geometry;
            for (const int b : {geo.i, geo.j})
              if (block_normal[b].squaredNorm() == 0.)
                block_normal[b] = geo.normal;
              else if (std::abs(block_normal[b].dot(geo.normal))
                       < std::cos(0.1))
                planar[b] = 0;
            if (group[k] < 0)
              continue;
            const int gk = group[k];
            if (group_i[gk] < 0)
              {
                group_i[gk]      = geo.i;
                group_j[gk]      = geo.j;
                group_normal[gk] = geo.normal;
              }
            const Point sk = slip3(k);
            resultant[gk] += orientation(k) * sk;
            slip_sum[gk] += sk.norm();
            centroid[gk] += geo.p;
            ++members[gk];
          }
      for (int gk = 0; gk < n_groups; ++gk)
        if (members[gk] > 0)
          centroid[gk] /= members[gk];
      std::fill(radius2.begin(), radius2.end(), 0.);
      std::fill(elastic.begin(), elastic.end(), 0.);
      for (std::size_t k = 0; k < contacts.size(); ++k)
        if (group[k] >= 0 && contacts[k].state != ContactState::open
            && planar[group_i[group[k]]] && planar[group_j[group[k]]])
          {
            const auto  &c   = contacts[k];
            const int    gk  = group[k];
            const Point &nrm = group_normal[gk];
            const Point  r   = c.geometry.p - centroid[gk];
            radius2[gk] += (r - r.dot(nrm) * nrm).squaredNorm();
            elastic[gk] += dda::shear_strength(c,
                                               c.normal_force,
                                               c.area,
                                               system.joints[c.joint])
                           / kin[k].shear_stiffness;
          }
      for (int gk = 0; gk < n_groups; ++gk)
        if (radius2[gk] > 0.)
          {
            const double omega
              = group_normal[gk].dot(rotation_vector(Db[group_i[gk]])
                                     - rotation_vector(Db[group_j[gk]]));
            const double R = std::sqrt(radius2[gk] / members[gk]);
            spin[gk]       = std::copysign(
              std::max(0., std::abs(omega) * R - elastic[gk] / members[gk]) / R,
              omega);
          }
      // Each contact's check writes only its own contact, direction,
      // kinematics and change count; the chunks' flags are joined after.
      // First every contact against its own strength (in chunks), then
      // the face groups' shared strength (serial, in group order), then
      // the new states are applied (in chunks).
      const std::size_t                    grain = 128;
      std::vector<std::array<unsigned, 2>> flags((contacts.size() + grain - 1)
                                                 / grain);
      dda::for_each_chunk(chunks,
                          contacts.size(),
                          grain,
                          [&](const std::size_t lo, const std::size_t hi) {
                            for (std::size_t k = lo; k < hi; ++k)
                              {
                                const auto &c = contacts[k];
                                const auto &K = kin[k];
                                // Chatter (dda::chatter_factor(), the 2D
                                // rule): 10 x and 100 x the weight part
                                // after two and three changes, at most 1 %
                                // of the weight; the round-off part stays a
                                // floor.
                                check_tolerance[k] = chatter_tolerance(k);
                                const double hold  = held_tolerance(k);
                                checks[k]          = check_state(c,
                                                        K,
                                                        dir[k],
                                                        gap_after(k),
                                                        shear_after(k),
                                                        check_tolerance[k],
                                                        system.joints[c.joint],
                                                        hold);
                              }
                          });
      if (ctrl.face_group_friction)
        for (int gk = 0; gk < n_groups; ++gk)
          decide_group(gk);
      dda::for_each_chunk(
        chunks,
        contacts.size(),
        grain,
        [&](const std::size_t lo, const std::size_t hi) {
          const std::size_t c_k = lo / grain;
          for (std::size_t k = lo; k < hi; ++k)
            {
              auto                 &c = contacts[k];
              const auto           &K = kin[k];
              const Eigen::Vector2d s = shear_after(k);
              const double          f = check_tolerance[k];
              auto                  r = checks[k];
              if (r.changed && r.state == ContactState::sliding)
                r.direction = group_direction(k, r.direction);
              bool friction_changed = false;
              if (r.changed)
                {
                  ++flags[c_k][0];
                  ++changes[k];
                  // Force continuity at lock (dda::lock_anchor(), the
                  // rule of both engines, with the 3D variant).
                  if (r.state == ContactState::locked)
                    {
                      // The 3D variant (start_forces false) anchors at the
                      // current iteration's friction force or where the
                      // contact touches; never at the step's start.
                      if (dda::lock_anchor(c.state_at_start, c.state, false)
                          == dda::LockAnchor::current_friction)
                        {
                          const double S = dda::shear_strength(
                            c, c.normal_force, c.area, system.joints[c.joint]);
                          const Point d3
                            = dir[k].x() * K.t1 + dir[k].y() * K.t2;
                          c.reference
                            = c.geometry.q - (S / K.shear_stiffness) * d3;
                          c.has_reference = true;
                        }
                      else // LockAnchor::here
                        c.has_reference = false;
                    }
                  c.state = r.state;
                  set_shear(k);
                }
              double residual = 0.;
              if (!r.changed && c.state == ContactState::sliding)
                {
                  // Only the unconverged contacts are relaxed (and define
                  // omega): the others take their new force as it is.
                  if (std::abs(r.normal_force - c.normal_force)
                      > dda::friction_tolerance(r.normal_force, n_mean, f))
                    {
                      friction_changed = true;
                      if (!dda::frictionless(c, system.joints[c.joint]))
                        residual = r.normal_force - c.normal_force;
                    }
                  // A face group slides along the resultant of its slip in
                  // this step: the direction it started with (the trial
                  // spring forces, which in a wedge include the wedging
                  // across the axis) is corrected within the step.
                  if (group[k] >= 0 && K.shear_stiffness * s.norm() > f)
                    {
                      const Eigen::Vector2d dn = group_direction(k, dir[k]);
                      if ((dn - dir[k]).norm() > 1e-3)
                        {
                          r.direction      = dn;
                          friction_changed = true;
                        }
                    }
                }
              flags[c_k][1] += friction_changed;
              relaxation.set_residual(k, residual);
              assembled_normal[k] = c.normal_force;
              c.normal_force      = r.normal_force;
              dir[k]              = r.direction;
              const Point fs3
                = r.shear_force.x() * K.t1 + r.shear_force.y() * K.t2;
              c.shear_force = fs3;
            }
        });
      dda::OpenCloseCheck r;
      for (const auto &f : flags)
        {
          r.state_changes += f[0];
          r.friction_changes += f[1];
        }
      states_changed = r.state_changes > 0;
      relaxation.relax(!ctrl.friction_relaxation || r.state_changes > 0
                         || r.friction_changes == 0,
                       [&](const std::size_t k, const double d) {
                         contacts[k].normal_force = assembled_normal[k] + d;
                       });
      // A damped step after which no state changed: the next step is a
      // full one (the line search stopped at a state's tolerance band).
      damped_last = alpha < 1. && r.state_changes == 0;
      if (damped_last)
        r.friction_changes = std::max(r.friction_changes, 1u);
      // Settled on an inexact solve: confirm with a solve to the solver
      // tolerance.
      confirming     = r.state_changes == 0 && r.friction_changes == 0 && loose;
      r.confirm      = confirming;
      r.most_changes = static_cast<unsigned>(
        changes.empty() ? 0
                        : *std::max_element(changes.begin(), changes.end()));
      return r;
    };
    dda::OpenCloseLimits limits;
    limits.max_iterations = static_cast<unsigned>(ctrl.max_open_close);
    limits.cycle_limit    = ctrl.cycle_limit;
    unsigned iterations   = 0;
    if (!dda::run_open_close(
          limits, may_continue, solve, check, most_changed, iterations, why_))
      return false;

    // The strength audit (dda::StrengthAudit, the checks of both engines):
    // no contact beyond its strength by more than its tolerance, whatever
    // path (chatter, hold, face group, friction relaxation) accepted it.
    double strength_ratio = 0.;
    {
      dda::StrengthAudit audit;
      std::vector<int>   suspect;
      for (std::size_t k = 0; k < contacts.size(); ++k)
        {
          const auto           &c     = contacts[k];
          const auto           &K     = kin[k];
          const auto           &joint = system.joints[c.joint];
          const Eigen::Vector2d s     = shear_after(k);
          dda::AuditedContact   a;
          a.state          = c.state;
          a.normal_force   = -K.normal_stiffness * gap_after(k);
          a.tolerance      = check_tolerance[k];
          a.hold_tolerance = std::max(a.tolerance, held_tolerance(k));
          a.open_tolerance = a.hold_tolerance;
          if (c.state != ContactState::open)
            {
              const bool locked = c.state == ContactState::locked;
              a.tensile_limit
                = locked && !c.broken ? joint.tensile * c.area : 0.;
              a.strength
                = dda::shear_strength(c, a.normal_force, c.area, joint);
              a.locked_shear = K.shear_stiffness * s.norm();
              a.in_group     = ctrl.face_group_friction && group[k] >= 0;
              a.frictionless = dda::frictionless(c, joint);
              if (!locked && !a.frictionless)
                {
                  a.friction_carried = friction_applied[k].norm();
                  a.friction_tolerance
                    = dda::friction_coefficient(joint, c.slip_rate)
                      * dda::friction_tolerance(a.normal_force,
                                                n_mean,
                                                a.tolerance);
                  a.slip_against = -K.shear_stiffness * s.dot(dir[k]);
                }
            }
          if (!audit.judge_contact(static_cast<int>(k), a))
            suspect.push_back(group[k]);
        }
      std::sort(suspect.begin(), suspect.end());
      suspect.erase(std::unique(suspect.begin(), suspect.end()), suspect.end());
      // A face group that shares its strength (decide_group): the sum of its
      // locked members' shear spring forces against the sum of their
      // strengths and tolerances.
      for (const int gk : suspect)
        {
          double demand = 0., strength = 0., tolerance = 0.;
          int    first = -1;
          for (const std::size_t k : group_members[gk])
            {
              const auto &c = contacts[k];
              if (c.state != ContactState::locked)
                continue;
              first = first < 0 ? static_cast<int>(k) : first;
              demand += kin[k].shear_stiffness * shear_after(k).norm();
              strength
                += dda::shear_strength(c,
                                       -kin[k].normal_stiffness * gap_after(k),
                                       c.area,
                                       system.joints[c.joint]);
              tolerance += std::max(check_tolerance[k], held_tolerance(k));
            }
          audit.judge(first,
                      "shear of its locked face group",
                      demand,
                      strength,
                      tolerance);
        }
      if (audit.ratio() > 1.)
        {
          const auto &g = contacts[audit.worst_contact()].geometry;
          why_          = audit.diagnosis(system.blocks[g.i].id,
                                 system.blocks[g.j].id,
                                 "N");
          return false;
        }
      strength_ratio = audit.ratio();
    }

    // Step size: no vertex moves further than the allowed displacement.
    for (std::size_t b = 0; b < n; ++b)
      {
        if (clamped_[b])
          continue;
        const double limit = ctrl.max_displacement_ratio * size[b];
        for (const auto &v : system.blocks[b].polyhedron.vertices)
          if ((displacement_matrix(moments[b].centroid, v) * Db[b]).norm()
              > limit)
            {
              why_ = "block " + std::to_string(system.blocks[b].id)
                     + " moved more than its allowed "
                     + io::format_number(limit, 3)
                     + " m in one step (Maximum displacement ratio x its "
                       "size)";
              return false;
            }
      }

    // The end-of-step velocities: Shi's v' = 2 D / h - v (a clamped block's:
    // the step's mean), and with the stiff-mode velocity solve
    // (doc/theory/dda3d.md, "Velocity of the stiff modes")
    //   (2 M / h^2 + K) v'' = (2 M / h^2) v' + K D / h,
    // K the step's stiffness without dashpots (elasticity, fixed points,
    // closed contacts' springs): each spring's relative velocity is drawn
    // to its mean rate in the step with the weight k against the inertia
    // 2 M / h^2. Clamped blocks move with the ground: its exact velocity.
    std::vector<Vector12> v_end(n);
    for (std::size_t b = 0; b < n; ++b)
      v_end[b] = clamped_[b]
                   ? Vector12(Db[b] / h)
                   : dda::end_of_step_velocity(Db[b],
                                               system.blocks[b].velocity,
                                               h,
                                               ctrl.dynamic);
    double kinetic_removed = 0.;
    if (ctrl.stiff_velocity && ctrl.dynamic > 0.)
      {
        Point vg = Point::Zero(), dug = Point::Zero();
        if (ctrl.ground_displacement)
          {
            // The ground displacement is C^2 (exact integral of a
            // piecewise linear record, or sampled at dt / 20): its central
            // difference over 2e-3 h is its velocity to round-off.
            const double d = 1e-3 * h;
            vg             = (ctrl.ground_displacement(t + h + d)
                  - ctrl.ground_displacement(t + h - d))
                 / (2. * d);
            dug = ug - ctrl.ground_displacement(t);
          }
        std::vector<Vector12> vc(n, Vector12::Zero());
        std::vector<Matrix12> M(n);
        for (std::size_t b = 0; b < n; ++b)
          {
            M[b] = mass_matrix(
              moments[b], system.materials[system.blocks[b].material].density);
            if (clamped_[b])
              vc[b].head<3>() = vg;
          }
        Eigen::VectorXd F(N), V(N);
        for (std::size_t b = 0; b < n; ++b)
          V.segment<12>(12 * b) = clamped_[b] ? vc[b] : v_end[b];
        dda::for_each_chunk(
          chunks, n, 8, [&](const std::size_t lo, const std::size_t hi) {
            for (std::size_t b = lo; b < hi; ++b)
              {
                auto &Kb = matrix.diag[b];
                auto  Fb = F.segment<12>(12 * b);
                if (clamped_[b])
                  {
                    Kb.setIdentity();
                    Fb = vc[b];
                    continue;
                  }
                const Matrix12 inertia = (2. / (h * h)) * M[b];
                Kb                     = K0[b];
                Fb = inertia * v_end[b] + (K0[b] - inertia) * (Db[b] / h);
                for_closed_contacts_of(
                  b, [&](const std::size_t k, const int side) {
                    const auto &c     = contacts[k];
                    const int   other = side == 0 ? c.geometry.j : c.geometry.i;
                    const Matrix12 own = springs_of(k, side, side, false);
                    Kb += own;
                    Fb += own * (Db[b] / h)
                          + springs_of(k, side, 1 - side, false)
                              * (Db[other] / h - vc[other]);
                  });
              }
          });
        // Fixed points: their anchors move with the ground.
        for (const auto &f : system.fixed_points)
          if (!clamped_[f.block])
            F.segment<12>(12 * f.block)
              += ctrl.fixed_penalty
                 * displacement_matrix(moments[f.block].centroid, f.point)
                     .transpose()
                 * (vg - dug / h);
        fill_pairs(false);
        if (!solver.solve(matrix, F, V, false) || !V.allFinite())
          {
            why_ = "the velocity solve of the stiff modes failed";
            return false;
          }
        solver_iterations += solver.last_iterations();
        for (std::size_t b = 0; b < n; ++b)
          {
            const Vector12 v
              = clamped_[b] ? vc[b] : Vector12(V.segment<12>(12 * b));
            if (!clamped_[b])
              kinetic_removed
                += 0.5 * v_end[b].dot(M[b] * v_end[b]) - 0.5 * v.dot(M[b] * v);
            v_end[b] = v;
          }
      }

    // Accept: energy terms of the step, contact states, geometry.
    // The kinetic energy the stiff-mode velocity solve removed.
    damping_work += kinetic_removed;
    for (std::size_t b = 0; b < n; ++b)
      {
        load_work += Fext[b].dot(Db[b]);
        if (damping.active() && !clamped_[b])
          damping_work += damping.dissipation(
            moments[b].volume
              * elasticity_matrix(system.materials[system.blocks[b].material]),
            Vector6(Db[b].tail<6>()));
      }
    if (dashpots.active())
      {
        // The dashpots' work c v' . d over the step, v' = 2 D / h - v.
        std::vector<Vector12> v1(n);
        for (std::size_t b = 0; b < n; ++b)
          v1[b] = dda::end_of_step_velocity(Db[b],
                                            system.blocks[b].velocity,
                                            h,
                                            ctrl.dynamic);
        for (std::size_t k = 0; k < contacts.size(); ++k)
          if (contacts[k].state != ContactState::open)
            {
              damping_work += kin[k].normal_dashpot * normal_rate(k, v1)
                              * normal_rate(k, Db);
              if (contacts[k].state == ContactState::locked)
                damping_work += kin[k].shear_dashpot
                                * shear_rate(k, v1).dot(shear_rate(k, Db));
            }
      }
    for (std::size_t k = 0; k < contacts.size(); ++k)
      {
        auto       &c = contacts[k];
        const auto &K = kin[k];
        const int   j = c.geometry.j;
        if (c.state == ContactState::sliding)
          {
            const Eigen::Vector2d s = shear_after(k);
            const double          S = dda::shear_strength(c,
                                                 c.normal_force,
                                                 c.area,
                                                 system.joints[c.joint]);
            // The joint is elastic-plastic, as in 2D (dda/engine.cc): a
            // sliding contact's shear spring stays stretched by its
            // friction force S, storing S^2 / 2 k_s (contact_energy), which
            // a relocking contact keeps (force continuity). Dissipated: the
            // work of the friction force over this step's slip (the shear
            // displacement increment, not s0, which holds the spring's
            // stretch of a contact that was locked at the start) less the
            // change of that stored energy; the force is the one the last
            // solve applied. (Counting S . s, with s0, and
            // storing nothing made the ledger gain S^2 / 2 k_s at every
            // lock-to-slide and every relock: 2.4e-4 m g L in 0.2 s of a
            // block on an incline at a penalty of 1e-3 E L.)
            const Eigen::Vector2d slip = shear_rate(k, Db);
            const double          stored_before
              = shear_at_start[k].squaredNorm() / (2. * K.shear_stiffness);
            friction_work
              += -friction_applied[k].dot(slip)
                 - (0.5 * S * S / K.shear_stiffness - stored_before);
            // The next step's sliding direction: this step's slip (of the
            // face group as a whole).
            if (K.shear_stiffness * s.norm() > K.force_tolerance)
              dir[k] = group_direction(k, s.normalized());
          }
        c.slide_direction = dir[k].x() * K.t1 + dir[k].y() * K.t2;
        if (c.state == ContactState::sliding
            || (c.state == ContactState::open
                && c.state_at_start != ContactState::open))
          c.broken = true;
        if (c.state == ContactState::locked)
          {
            // The shear reference is a material point of block j.
            const Point r   = c.has_reference ? c.reference : c.geometry.q;
            c.reference     = move_point(moments[j].centroid, Db[j], r);
            c.has_reference = true;
          }
        else
          c.has_reference = false;
        // The next step's slip rate (dda::friction_coefficient()): the
        // shear displacement increment of this step over its length.
        c.slip_rate = shear_rate(k, Db).norm() / h;
        // Static steps (dynamic control 0) are an iteration towards
        // equilibrium: a contact held in one stays held in the next until it
        // changes state beyond its hold (the 2D rule). Dynamic steps carry
        // their history in the velocities, and no hold.
        c.held = dda::stays_held(ctrl.dynamic,
                                 changes[k],
                                 ctrl.hold_after,
                                 c.held,
                                 c.state == c.state_at_start);
      }
    for (std::size_t b = 0; b < n; ++b)
      {
        apply_increment(system, b, moments[b].centroid, Db[b]);
        system.blocks[b].velocity = v_end[b];
      }
    stored                  = std::move(contacts);
    last_solution           = D;
    stats.iterations        = iterations;
    stats.solver_iterations = solver_iterations;
    stats.strength_ratio    = strength_ratio;
    worst_strength_ratio    = std::max(worst_strength_ratio, strength_ratio);
    stats.open = stats.sliding = stats.locked = 0;
    for (const auto &c : stored)
      (c.state == ContactState::open      ? stats.open
       : c.state == ContactState::sliding ? stats.sliding
                                          : stats.locked)++;
    // The contact springs' energy at the end of the step, from the forces
    // of the last solve.
    contact_energy = 0.;
    for (std::size_t k = 0; k < stored.size(); ++k)
      if (stored[k].state != ContactState::open)
        {
          contact_energy += stored[k].normal_force * stored[k].normal_force
                              / (2. * kin[k].normal_stiffness)
                            + stored[k].shear_force.squaredNorm()
                                / (2. * kin[k].shear_stiffness);
        }

    // No physically impossible state (dda::implausible_state(), the check
    // of both engines): energy created, a contact penetrated deeper than a
    // fraction of its blocks, a block strained beyond small strain or
    // faster than the scene can make it. advance() restores the state and
    // cuts the step.
    {
      // The ground's speed so far: the integral of |a_g| (loading mode),
      // or the fastest step of the prescribed motion (displacement mode).
      const double ground_speed
        = ctrl.ground_displacement
            ? std::max(ground_speed_,
                       (ug - ctrl.ground_displacement(t)).norm() / h)
            : ground_speed_ + ag.norm() * h;
      dda::PlausibilityInput in;
      in.time = t + h;
      if (!ctrl.ground_displacement)
        {
          const Energy e  = energy();
          in.check_energy = true;
          in.energy_gain  = e.balance() - balance_before;
          in.energy_scale = e.scale();
        }
      in.normal_penalty = ctrl.law.normal_penalty;
      in.motion_bound
        = system.gravity.norm() * (t + h) + initial_speed_ + ground_speed;
      double largest = 0.;
      in.blocks.reserve(n);
      for (std::size_t b = 0; b < n; ++b)
        {
          const auto &blk = system.blocks[b];
          largest         = std::max(largest, size[b]);
          in.blocks.push_back(
            {blk.id,
             0.5 * mass[b] * blk.velocity.head<3>().squaredNorm(),
             blk.velocity.head<3>().norm(),
             blk.strain.cwiseAbs().maxCoeff(),
             system.materials[blk.material].young});
        }
      in.speed_floor = 1e-9 * largest / ctrl.dt;
      for (const auto &c : stored)
        if (c.state != ContactState::open)
          in.contacts.push_back(
            {system.blocks[c.geometry.i].id,
             system.blocks[c.geometry.j].id,
             c.normal_force,
             std::min(size[c.geometry.i], size[c.geometry.j])});
      why_ = dda::implausible_state(ctrl.plausibility, in);
      if (!why_.empty())
        return false;
      ground_speed_ = ground_speed;
    }
    return true;
  }



  Energy
  Engine::energy() const
  {
    Energy e;
    for (const auto &b : system.blocks)
      {
        const Material &mat = system.materials[b.material];
        const auto      m   = b.polyhedron.moments();
        e.kinetic
          += dda::kinetic_energy_of(b.velocity, mass_matrix(m, mat.density));
        e.strain
          += dda::strain_energy_of(m.volume, b.stress, elasticity_matrix(mat));
        e.potential
          += dda::gravity_potential_of(mat.density,
                                       m.volume,
                                       system.gravity,
                                       Point(m.centroid - b.initial_centroid));
      }
    // The springs of the fixed points of blocks that are not clamped; the
    // anchors follow the ground.
    const Point ug
      = ctrl.ground_displacement ? ctrl.ground_displacement(t) : Point::Zero();
    for (const auto &f : system.fixed_points)
      if (!clamped_[f.block])
        e.fixed += 0.5 * ctrl.fixed_penalty
                   * (f.point - (f.anchor + ug)).squaredNorm();
    e.contact   = contact_energy;
    e.friction  = friction_work;
    e.damping   = damping_work;
    e.load_work = load_work;
    return e;
  }
} // namespace rockdda::dda3d
