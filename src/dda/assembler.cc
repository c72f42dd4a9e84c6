/**
 * @file
 * Assembly of the 2D DDA equations (Shi 1988, ch. 2-4; Shi 1993).
 */
#include <rockdda/dda/assembler.h>
#include <rockdda/dda/block_step_terms.h>
#include <rockdda/dda/strain_damping.h>

#include <Eigen/Cholesky>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>

namespace rockdda::dda
{
  ContactKinematics
  Assembler::contact_kinematics_of(const BlockSystem      &system,
                                   const ContactCandidate &c,
                                   const double            xi_ref) const
  {
    const auto            &vi = system.blocks[c.block_i].polygon.vertices;
    const auto            &vj = system.blocks[c.block_j].polygon.vertices;
    const int              nj = static_cast<int>(vj.size());
    const geometry::Point &P  = vi[c.vertex];
    const geometry::Point &Q0 = vj[c.edge];
    const geometry::Point &Q1 = vj[(c.edge + 1) % nj];
    const geometry::Point  E  = Q1 - Q0;
    const double           l  = E.norm();
    ContactKinematics      k;
    k.tangent                  = E / l;
    k.edge_length              = l;
    const geometry::Point Pref = Q0 + xi_ref * E;
    // Both springs join the vertex to the material point of block j that
    // coincides with it: the pair of forces acts at one point, so contacts
    // exert no net moment and a rigid rotation of the two blocks together
    // does not stretch them. (Block j's point taken at the projection P0
    // and the shear reference Pref, a gap g away along the normal, made the
    // shear pair a couple g F_s: a free triangulated beam turned as a rigid
    // body by 8e-8 rad per static step.) The gap and the shear offset s0
    // are still measured from the projection and Pref.
    const auto Ti = displacement_matrix(block_moments_[c.block_i].centroid, P);
    const auto Tj = displacement_matrix(block_moments_[c.block_j].centroid, P);
    k.g0          = c.gap;
    k.en          = Ti.transpose() * c.normal;
    k.hn          = -(Tj.transpose() * c.normal);
    k.s0          = k.tangent.dot(P - Pref);
    k.es          = Ti.transpose() * k.tangent;
    k.hs          = -(Tj.transpose() * k.tangent);
    // Round-off of this contact: relative to the smaller block, plus the
    // representation error of the coordinates in the local frame.
    k.tolerance = round_off_tolerance(
      std::min(block_size[c.block_i], block_size[c.block_j]), P, Q0);
    // The springs of a rigid joint (the penalty); set_springs() puts the
    // joint's stiffness in series once the contact length is known.
    k.normal_stiffness = params.law.normal_penalty;
    k.shear_stiffness  = params.law.shear_penalty();
    k.force_tolerance  = force_tolerance_of(k, c.block_i, c.block_j);
    k.weight_tolerance = weight_tolerance_of(c.block_i, c.block_j);
    return k;
  }



  double
  Assembler::weight_tolerance_of(const int block_i, const int block_j) const
  {
    // Force scale: 1e-4 of the weight of the lighter block.
    return contact_weight_tolerance(std::min(mass[block_i](0, 0),
                                             mass[block_j](0, 0)),
                                    params.body_acceleration.norm(),
                                    params.law.force_tolerance);
  }



  double
  Assembler::force_tolerance_of(const ContactKinematics &k,
                                const int                block_i,
                                const int                block_j) const
  {
    return contact_force_tolerance(weight_tolerance_of(block_i, block_j),
                                   k.normal_stiffness,
                                   k.tolerance);
  }



  void
  Assembler::set_springs(const int c, const Contact &contact)
  {
    ContactKinematics   &k = contact_kinematics[c];
    const ContactSprings springs
      = contact_springs(params.law, joints[contact.joint], k.length);
    if (springs.normal == k.normal_stiffness
        && springs.shear == k.shear_stiffness)
      return;
    k.normal_stiffness = springs.normal;
    k.shear_stiffness  = springs.shear;
    k.force_tolerance  = force_tolerance_of(k,
                                           contact.geometry.block_i,
                                           contact.geometry.block_j);
  }



  void
  Assembler::set_dashpots(const BlockSystem &system, const int c)
  {
    ContactKinematics   &k = contact_kinematics[c];
    const ContactDamping dashpots(params.contact_damping,
                                  params.contact_step_damping,
                                  params.dt,
                                  params.dynamic);
    const auto [i, j] = contact_blocks[c];
    // The lighter free block's mass (a clamped block's is infinite).
    const double inf = std::numeric_limits<double>::infinity();
    const double mi  = clamped[i] ? inf : mass[i](0, 0),
                 mj  = clamped[j] ? inf : mass[j](0, 0);
    k.normal_dashpot = dashpots.dashpot(k.normal_stiffness, mi, mj);
    k.shear_dashpot  = dashpots.dashpot(k.shear_stiffness, mi, mj);
    // The relative rates at the start of the step (the carried-over
    // velocity, times the dynamic control, as the inertia term's).
    const Vector6 vi = params.dynamic * system.blocks[i].velocity;
    const Vector6 vj = params.dynamic * system.blocks[j].velocity;
    k.normal_rate    = k.en.dot(vi) + k.hn.dot(vj);
    k.shear_rate     = k.es.dot(vi) + k.hs.dot(vj);
  }



  double
  Assembler::gap(const int c, const Eigen::VectorXd &x) const
  {
    const auto &k = contact_kinematics[c];
    return k.g0 + k.en.dot(x.segment<6>(6 * contact_blocks[c].first))
           + k.hn.dot(x.segment<6>(6 * contact_blocks[c].second));
  }



  double
  Assembler::shear_displacement(const int c, const Eigen::VectorXd &x) const
  {
    const auto &k = contact_kinematics[c];
    return k.s0 + k.es.dot(x.segment<6>(6 * contact_blocks[c].first))
           + k.hs.dot(x.segment<6>(6 * contact_blocks[c].second));
  }



  namespace
  {
    /**
     * The length over which a vertex contact's face overlaps the edge it
     * touches (m), and the key of that pair of faces: the vertex's adjacent
     * edge most nearly parallel to the touched edge, if within ~6 degrees;
     * otherwise a corner touches a face and the length is 0.
     */
    std::pair<double, std::uint64_t>
    face_overlap(const BlockSystem &system, const ContactCandidate &c)
    {
      const auto  &vi       = system.blocks[c.block_i].polygon.vertices;
      const auto  &vj       = system.blocks[c.block_j].polygon.vertices;
      const int    ni       = static_cast<int>(vi.size());
      const int    nj       = static_cast<int>(vj.size());
      const auto  &Q0       = vj[c.edge];
      const auto   E        = vj[(c.edge + 1) % nj] - Q0;
      const double l        = E.norm();
      const auto   t        = E / l;
      double       best_sin = 1.;
      int          face     = -1;
      for (const int f : {(c.vertex + ni - 1) % ni, c.vertex})
        {
          const auto   F = vi[(f + 1) % ni] - vi[f];
          const double s = std::abs(t.x() * F.y() - t.y() * F.x()) / F.norm();
          if (s < best_sin)
            {
              best_sin = s;
              face     = f;
            }
        }
      if (best_sin > 0.1)
        return {0., 0};
      const double u1      = t.dot(vi[face] - Q0);
      const double u2      = t.dot(vi[(face + 1) % ni] - Q0);
      const double overlap = std::max(0.,
                                      std::min(std::max(u1, u2), l)
                                        - std::max(std::min(u1, u2), 0.));
      // Key of the pair of faces (lower block first): 22 bits per block,
      // 10 per face.
      auto part = [](const int block, const int f) {
        return (static_cast<std::uint64_t>(block) << 10)
               | static_cast<std::uint64_t>(f & 0x3ff);
      };
      const std::uint64_t a = part(c.block_i, face);
      const std::uint64_t b = part(c.block_j, c.edge);
      return {overlap, c.block_i < c.block_j ? (a << 32) | b : (b << 32) | a};
    }
  } // namespace



  void
  Assembler::prepare_step(const BlockSystem          &system,
                          const std::vector<Contact> &contacts,
                          const StepParameters       &parameters,
                          BlockSparseMatrix          &matrix)
  {
    params          = parameters;
    joints          = system.joints;
    const int    n  = static_cast<int>(system.blocks.size());
    const double dt = params.dt;
    block_moments_.resize(n);
    block_size.resize(n);
    mass.resize(n);
    base_matrix.resize(n);
    base_rhs.resize(n);
    const StrainDamping damping(params.strain_damping, dt, params.dynamic);
    for (int b = 0; b < n; ++b)
      {
        const Block         &block = system.blocks[b];
        const BlockMaterial &mat   = system.materials[block.material];
        const BlockMoments   m     = block_moments(block.polygon);
        block_moments_[b]          = m;
        block_size[b]              = dda::block_size(block.polygon);
        mass[b]                    = mass_matrix(m, mat.density);
        Matrix6 &K                 = base_matrix[b];
        Vector6 &F                 = base_rhs[b];
        // (dda/block_step_terms.h, shared with 3D.)
        block_step_terms<6, 3, 2>(mass[b],
                                  elasticity_matrix(mat),
                                  m.area,
                                  mat.density,
                                  block.stress,
                                  block.velocity,
                                  params.dynamic,
                                  dt,
                                  1. + damping.factor(),
                                  params.body_acceleration,
                                  K,
                                  F);
        if (block.eigenstrain != block.applied_eigenstrain)
          F.segment<3>(3)
            += m.area * elasticity_matrix(mat) * eigenstrain_step(block);
      }
    for (const auto &l : system.load_points)
      base_rhs[l.block]
        += displacement_matrix(block_moments_[l.block].centroid, l.point)
             .transpose()
           * l.force;
    // Fixed points. A block held by three or more points that are not
    // collinear is clamped: its displacement is prescribed (the least-
    // squares fit of its points' targets, exact for the rigid motions they
    // follow) and eliminated, so it does not ring on penalty springs.
    // Blocks held by one or two points are pinned by penalty springs.
    std::vector<Matrix6> fit(n, Matrix6::Zero());
    std::vector<Vector6> fit_rhs(n, Vector6::Zero());
    for (std::size_t f = 0; f < system.fixed_points.size(); ++f)
      {
        const auto &fp = system.fixed_points[f];
        const auto  T
          = displacement_matrix(block_moments_[fp.block].centroid, fp.point);
        fit[fp.block] += T.transpose() * T;
        fit_rhs[fp.block]
          += T.transpose() * (params.fixed_targets[f] - fp.point);
      }
    clamped.assign(n, 0);
    prescribed.assign(n, Vector6::Zero());
    for (int b = 0; b < n; ++b)
      {
        // (fit(0, 0) is the number of the block's fixed points.)
        if (fit[b](0, 0) == 0.)
          continue;
        if (params.clamped != nullptr && (*params.clamped)[b] != 0)
          {
            clamped[b]    = 1;
            prescribed[b] = fit[b].ldlt().solve(fit_rhs[b]);
          }
        else
          {
            base_matrix[b] += params.fixed_penalty * fit[b];
            base_rhs[b] += params.fixed_penalty * fit_rhs[b];
          }
      }

    // Contacts: kinematics, contact lengths and the block pattern.
    contact_kinematics.resize(contacts.size());
    contact_pair.resize(contacts.size());
    contact_blocks.resize(contacts.size());
    std::vector<std::pair<int, int>> pairs;
    pairs.reserve(contacts.size());
    std::vector<std::pair<std::uint64_t, int>> faces;
    std::vector<double>                        overlap(contacts.size());
    // Kinematics and face overlaps per contact (independent: in chunks).
    std::vector<std::uint64_t> face_key(contacts.size());
    for_each_chunk(params.run_chunks,
                   contacts.size(),
                   contact_grain,
                   [&](const std::size_t lo, const std::size_t hi) {
                     for (std::size_t c = lo; c < hi; ++c)
                       {
                         const auto &g     = contacts[c].geometry;
                         contact_blocks[c] = {g.block_i, g.block_j};
                         contact_kinematics[c]
                           = contact_kinematics_of(system,
                                                   g,
                                                   contacts[c].xi_ref);
                         const auto [o, key] = face_overlap(system, g);
                         overlap[c]          = o;
                         face_key[c]         = key;
                       }
                   });
    for (std::size_t c = 0; c < contacts.size(); ++c)
      {
        const auto &g = contacts[c].geometry;
        pairs.emplace_back(std::min(g.block_i, g.block_j),
                           std::max(g.block_i, g.block_j));
        if (overlap[c] > 0.)
          faces.emplace_back(face_key[c], static_cast<int>(c));
      }
    // The vertex contacts of one pair of faces share its overlap. Detection
    // emits the contacts of a block pair together and the pairs in order,
    // so the keys are sorted but within each block's few contacts:
    // insertion sort is then linear; otherwise a full sort.
    bool by_pair = true;
    for (std::size_t c = 1; c < pairs.size() && by_pair; ++c)
      by_pair = !(pairs[c] < pairs[c - 1]);
    if (by_pair)
      for (std::size_t a = 1; a < faces.size(); ++a)
        for (std::size_t b = a; b > 0 && faces[b] < faces[b - 1]; --b)
          std::swap(faces[b], faces[b - 1]);
    else
      std::sort(faces.begin(), faces.end());
    contact_group.assign(contacts.size(), -1);
    group_start_.assign(1, 0);
    group_members_.clear();
    int n_groups = 0;
    for (std::size_t a = 0; a < faces.size();)
      {
        std::size_t b = a;
        while (b < faces.size() && faces[b].first == faces[a].first)
          ++b;
        for (std::size_t k = a; k < b; ++k)
          {
            contact_kinematics[faces[k].second].length
              = overlap[faces[k].second] / static_cast<double>(b - a);
            if (b - a > 1)
              {
                contact_group[faces[k].second] = n_groups;
                group_members_.push_back(faces[k].second);
              }
          }
        if (b - a > 1)
          group_start_.push_back(static_cast<int>(group_members_.size()));
        n_groups += b - a > 1 ? 1 : 0;
        a = b;
      }
    // The joints' stiffness over the contact lengths, in series with the
    // penalty.
    if (any_joint_stiffness(joints))
      for (std::size_t c = 0; c < contacts.size(); ++c)
        set_springs(static_cast<int>(c), contacts[c]);
    // Their dashpots (the springs' final values) and rates.
    if (damped())
      for (std::size_t c = 0; c < contacts.size(); ++c)
        set_dashpots(system, static_cast<int>(c));
    std::vector<std::pair<int, int>> unique_pairs = pairs;
    std::sort(unique_pairs.begin(), unique_pairs.end());
    unique_pairs.erase(std::unique(unique_pairs.begin(), unique_pairs.end()),
                       unique_pairs.end());
    for (std::size_t c = 0; c < contacts.size(); ++c)
      contact_pair[c] = static_cast<int>(
        std::lower_bound(unique_pairs.begin(), unique_pairs.end(), pairs[c])
        - unique_pairs.begin());
    matrix.reinit(n, unique_pairs);
    assembled_matrix = nullptr;
    // The contacts of each block and of each pair, in contact order, for
    // assemble()'s chunks; the pairs whose coupling a clamp eliminates.
    contacts_of_block
      = items_of_rows(n, contacts.size(), [&](const std::size_t c) {
          return contact_blocks[c];
        });
    contacts_of_pair
      = items_of_rows(static_cast<int>(unique_pairs.size()),
                      contacts.size(),
                      [&](const std::size_t c) {
                        return std::make_pair(contact_pair[c], -1);
                      });
    clamped_pairs.clear();
    for (std::size_t p = 0; p < unique_pairs.size(); ++p)
      if (clamped[unique_pairs[p].first] || clamped[unique_pairs[p].second])
        clamped_pairs.push_back(static_cast<int>(p));
  }



  void
  Assembler::set_shear_reference(const BlockSystem &system,
                                 const int          index,
                                 const Contact     &contact)
  {
    // Only the shear reference changes: the length, the springs and the
    // force tolerance stay.
    const ContactKinematics old = contact_kinematics[index];
    ContactKinematics      &k   = contact_kinematics[index];
    k        = contact_kinematics_of(system, contact.geometry, contact.xi_ref);
    k.length = old.length;
    k.normal_stiffness = old.normal_stiffness;
    k.shear_stiffness  = old.shear_stiffness;
    k.force_tolerance  = old.force_tolerance;
    k.weight_tolerance = old.weight_tolerance;
    if (damped())
      set_dashpots(system, index);
    if (static_cast<std::size_t>(index) < springs_changed.size())
      springs_changed[index] = 1;
  }



  std::vector<double>
  Assembler::contact_lengths(const BlockSystem          &system,
                             const std::vector<Contact> &contacts)
  {
    // The rule of prepare_step(): each pair of faces' overlap shared
    // equally by its vertex contacts.
    std::vector<double>                        length(contacts.size(), 0.);
    std::vector<double>                        overlap(contacts.size(), 0.);
    std::vector<std::pair<std::uint64_t, int>> faces;
    for (std::size_t c = 0; c < contacts.size(); ++c)
      {
        const auto [o, key] = face_overlap(system, contacts[c].geometry);
        overlap[c]          = o;
        if (o > 0.)
          faces.emplace_back(key, static_cast<int>(c));
      }
    std::sort(faces.begin(), faces.end());
    for (std::size_t a = 0; a < faces.size();)
      {
        std::size_t b = a;
        while (b < faces.size() && faces[b].first == faces[a].first)
          ++b;
        for (std::size_t k = a; k < b; ++k)
          length[faces[k].second]
            = overlap[faces[k].second] / static_cast<double>(b - a);
        a = b;
      }
    return length;
  }



  void
  Assembler::add_to_block(const Contact           &ct,
                          const ContactKinematics &kin,
                          const bool               vertex_side,
                          Matrix6                 &Kb) const
  {
    if (ct.state == ContactState::open)
      return;
    const Vector6 &en = vertex_side ? kin.en : kin.hn;
    // The dashpots (ContactDamping): the force -c v' with the end-of-step
    // rate v' = 2 d / h - v adds 2 c / h to the spring (add_to_load: c v to
    // the load).
    const bool damped_step = damped();
    Kb.noalias() += (kin.normal_stiffness
                     + (damped_step ? 2. * kin.normal_dashpot / params.dt : 0.))
                    * en * en.transpose();
    if (ct.state == ContactState::locked)
      {
        const Vector6 &es = vertex_side ? kin.es : kin.hs;
        Kb.noalias()
          += (kin.shear_stiffness
              + (damped_step ? 2. * kin.shear_dashpot / params.dt : 0.))
             * es * es.transpose();
      }
  }



  void
  Assembler::add_to_load(const Contact           &ct,
                         const ContactKinematics &kin,
                         const bool               vertex_side,
                         Eigen::Ref<Vector6>      Fb) const
  {
    if (ct.state == ContactState::open)
      return;
    const Vector6 &en          = vertex_side ? kin.en : kin.hn;
    const Vector6 &es          = vertex_side ? kin.es : kin.hs;
    const bool     damped_step = damped();
    Fb -= (kin.normal_stiffness * kin.g0) * en;
    if (damped_step)
      Fb += (kin.normal_dashpot * kin.normal_rate) * en;
    if (ct.state == ContactState::locked)
      {
        Fb -= (kin.shear_stiffness * kin.s0) * es;
        if (damped_step)
          Fb += (kin.shear_dashpot * kin.shear_rate) * es;
      }
    else
      // Sliding: the friction force opposes the sliding direction.
      Fb
        -= (ct.slide_direction
            * shear_strength(ct, ct.normal_force, kin.length, joints[ct.joint]))
           * es;
  }



  void
  Assembler::add_to_pair(const Contact           &ct,
                         const ContactKinematics &kin,
                         Matrix6                 &Kp) const
  {
    if (ct.state == ContactState::open)
      return;
    // K_ij with i < j: block i's vectors on the left.
    const bool     upper       = ct.geometry.block_i < ct.geometry.block_j;
    const Vector6 &un          = upper ? kin.en : kin.hn;
    const Vector6 &vn          = upper ? kin.hn : kin.en;
    const bool     damped_step = damped();
    Kp.noalias() += (kin.normal_stiffness
                     + (damped_step ? 2. * kin.normal_dashpot / params.dt : 0.))
                    * un * vn.transpose();
    if (ct.state == ContactState::locked)
      {
        const Vector6 &us = upper ? kin.es : kin.hs;
        const Vector6 &vs = upper ? kin.hs : kin.es;
        Kp.noalias()
          += (kin.shear_stiffness
              + (damped_step ? 2. * kin.shear_dashpot / params.dt : 0.))
             * us * vs.transpose();
      }
  }



  int
  Assembler::assemble(const std::vector<Contact> &contacts,
                      BlockSparseMatrix          &K,
                      Eigen::VectorXd            &F)
  {
    const int         n  = static_cast<int>(base_matrix.size());
    const std::size_t nc = contacts.size();
    F.resize(6 * n);
    // Which rows of K change: all at the step's first assembly, then those
    // with a contact whose springs changed (and the clamped pairs, whose
    // coupling is eliminated into F below).
    const bool whole = assembled_matrix != &K || assembled_state.size() != nc;
    dirty_block.assign(n, whole);
    dirty_pair.assign(K.off.size(), whole);
    if (!whole)
      {
        for (std::size_t c = 0; c < nc; ++c)
          if (contacts[c].state != assembled_state[c] || springs_changed[c])
            {
              dirty_block[contact_blocks[c].first]  = 1;
              dirty_block[contact_blocks[c].second] = 1;
              dirty_pair[contact_pair[c]]           = 1;
            }
        for (const int k : clamped_pairs)
          dirty_pair[k] = 1;
      }
    assembled_matrix = &K;
    assembled_state.resize(nc);
    for (std::size_t c = 0; c < nc; ++c)
      assembled_state[c] = contacts[c].state;
    springs_changed.assign(nc, 0);
    const int n_assembled = static_cast<int>(
      std::count(dirty_block.begin(), dirty_block.end(), char(1)));
    // Each block row and each pair adds its contacts in contact order. On
    // threads, each row is written by one chunk; on one (or a scene too
    // small for the 8 chunks from which the runner uses threads) a whole
    // assembly is a single pass over the contacts, which adds them in the
    // same order per row, reading each contact once: the same bits either
    // way.
    const bool threaded
      = params.threads >= 2 && static_cast<std::size_t>(n) >= 8 * block_grain;
    if (whole && !threaded)
      {
        for (int b = 0; b < n; ++b)
          {
            K.diag[b]           = base_matrix[b];
            F.segment<6>(6 * b) = base_rhs[b];
          }
        for (auto &m : K.off)
          m.setZero();
        for (std::size_t c = 0; c < nc; ++c)
          {
            const auto [i, j] = contact_blocks[c];
            const auto &kin   = contact_kinematics[c];
            add_to_block(contacts[c], kin, true, K.diag[i]);
            add_to_load(contacts[c], kin, true, F.segment<6>(6 * i));
            add_to_block(contacts[c], kin, false, K.diag[j]);
            add_to_load(contacts[c], kin, false, F.segment<6>(6 * j));
            add_to_pair(contacts[c], kin, K.off[contact_pair[c]]);
          }
      }
    else
      {
        const auto block_rows = [&](const std::size_t lo,
                                    const std::size_t hi) {
          for (std::size_t b = lo; b < hi; ++b)
            {
              const bool dirty    = dirty_block[b] != 0;
              F.segment<6>(6 * b) = base_rhs[b];
              if (dirty)
                K.diag[b] = base_matrix[b];
              for (int e = contacts_of_block.start[b];
                   e < contacts_of_block.start[b + 1];
                   ++e)
                {
                  const int   c      = contacts_of_block.entry[e] / 2;
                  const bool  vertex = contacts_of_block.entry[e] % 2 == 0;
                  const auto &kin    = contact_kinematics[c];
                  add_to_load(contacts[c], kin, vertex, F.segment<6>(6 * b));
                  if (dirty)
                    add_to_block(contacts[c], kin, vertex, K.diag[b]);
                }
            }
        };
        const auto pair_rows = [&](const std::size_t lo, const std::size_t hi) {
          for (std::size_t p = lo; p < hi; ++p)
            if (dirty_pair[p])
              {
                K.off[p].setZero();
                for (int e = contacts_of_pair.start[p];
                     e < contacts_of_pair.start[p + 1];
                     ++e)
                  {
                    const int c = contacts_of_pair.entry[e] / 2;
                    add_to_pair(contacts[c], contact_kinematics[c], K.off[p]);
                  }
              }
        };
        if (threaded)
          {
            for_each_chunk(params.run_chunks, n, block_grain, block_rows);
            for_each_chunk(params.run_chunks,
                           K.off.size(),
                           pair_grain,
                           pair_rows);
          }
        else
          {
            block_rows(0, n);
            pair_rows(0, K.off.size());
          }
      }
    // Clamped blocks: eliminate their prescribed displacements.
    for (const int k : clamped_pairs)
      {
        const auto [i, j] = K.pairs[k];
        if (clamped[i] && !clamped[j])
          F.segment<6>(6 * j) -= K.off[k].transpose() * prescribed[i];
        else if (clamped[j] && !clamped[i])
          F.segment<6>(6 * i) -= K.off[k] * prescribed[j];
        K.off[k].setZero();
      }
    for (int b = 0; b < n; ++b)
      if (clamped[b])
        F.segment<6>(6 * b) = K.diag[b] * prescribed[b];
    return n_assembled;
  }
} // namespace rockdda::dda
