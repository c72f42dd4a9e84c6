/**
 * @file
 * Assembly of the 2D DDA equations (Shi 1988, ch. 2-4; Shi 1993).
 */
#include <rockdda/dda/assembler.h>

#include <algorithm>
#include <cmath>

namespace rockdda::dda
{
  ContactKinematics
  Assembler::contact_kinematics_of(const BlockSystem               &system,
                                   const std::vector<BlockMoments> &moments,
                                   const ContactCandidate          &c,
                                   const double                     xi_ref,
                                   const double                     tolerance)
  {
    const auto            &vi = system.blocks[c.block_i].polygon.vertices;
    const auto            &vj = system.blocks[c.block_j].polygon.vertices;
    const int              ni = static_cast<int>(vi.size());
    const int              nj = static_cast<int>(vj.size());
    const geometry::Point &P  = vi[c.vertex];
    const geometry::Point &Q0 = vj[c.edge];
    const geometry::Point &Q1 = vj[(c.edge + 1) % nj];
    const geometry::Point  E  = Q1 - Q0;
    const double           l  = E.norm();
    ContactKinematics      k;
    k.tangent                  = E / l;
    k.edge_length              = l;
    k.tolerance                = tolerance;
    const geometry::Point P0   = Q0 + c.xi * E;
    const geometry::Point Pref = Q0 + xi_ref * E;
    const auto Ti  = displacement_matrix(moments[c.block_i].centroid, P);
    const auto Tj0 = displacement_matrix(moments[c.block_j].centroid, P0);
    const auto Tjr = displacement_matrix(moments[c.block_j].centroid, Pref);
    k.g0           = c.gap;
    k.en           = Ti.transpose() * c.normal;
    k.hn           = -(Tj0.transpose() * c.normal);
    k.s0           = k.tangent.dot(P - Pref);
    k.es           = Ti.transpose() * k.tangent;
    k.hs           = -(Tjr.transpose() * k.tangent);
    // Contact length: half of the shorter of the edge and the vertex's
    // adjacent edge that is most nearly parallel to it.
    const geometry::Point a1 = vi[(c.vertex + ni - 1) % ni] - P;
    const geometry::Point a2 = vi[(c.vertex + 1) % ni] - P;
    const double          p1 = std::abs(c.normal.dot(a1)) / a1.norm();
    const double          p2 = std::abs(c.normal.dot(a2)) / a2.norm();
    const double          la = p1 < p2 ? a1.norm() : a2.norm();
    k.length                 = 0.5 * std::min(l, la);
    return k;
  }



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
    mass.resize(n);
    base_matrix.resize(n);
    base_rhs.resize(n);
    for (int b = 0; b < n; ++b)
      {
        const Block         &block = system.blocks[b];
        const BlockMaterial &mat   = system.materials[block.material];
        const BlockMoments   m     = block_moments(block.polygon);
        block_moments_[b]          = m;
        mass[b]                    = mass_matrix(m, mat.density);
        Matrix6 &K                 = base_matrix[b];
        Vector6 &F                 = base_rhs[b];
        K                          = (2. / (dt * dt)) * mass[b];
        K.block<3, 3>(3, 3) += m.area * elasticity_matrix(mat);
        F = (2. / dt) * (mass[b] * (params.dynamic * block.velocity));
        F.segment<3>(3) -= m.area * block.stress;
        F.segment<2>(0) += mat.density * m.area * params.body_acceleration;
      }
    for (const auto &l : system.load_points)
      base_rhs[l.block]
        += displacement_matrix(block_moments_[l.block].centroid, l.point)
             .transpose()
           * l.force;
    for (std::size_t f = 0; f < system.fixed_points.size(); ++f)
      {
        const auto &fp = system.fixed_points[f];
        const auto  T
          = displacement_matrix(block_moments_[fp.block].centroid, fp.point);
        base_matrix[fp.block] += params.fixed_penalty * T.transpose() * T;
        base_rhs[fp.block] += params.fixed_penalty * T.transpose()
                              * (params.fixed_targets[f] - fp.point);
      }

    // Contacts: kinematics and the block pattern.
    contact_kinematics.resize(contacts.size());
    contact_pair.resize(contacts.size());
    std::vector<std::pair<int, int>> pairs;
    pairs.reserve(contacts.size());
    for (std::size_t c = 0; c < contacts.size(); ++c)
      {
        const auto &g         = contacts[c].geometry;
        contact_kinematics[c] = contact_kinematics_of(
          system, block_moments_, g, contacts[c].xi_ref, params.gap_tolerance);
        contact_kinematics[c].reversal_tolerance = params.reversal_tolerance;
        pairs.emplace_back(std::min(g.block_i, g.block_j),
                           std::max(g.block_i, g.block_j));
      }
    std::vector<std::pair<int, int>> unique_pairs = pairs;
    std::sort(unique_pairs.begin(), unique_pairs.end());
    unique_pairs.erase(std::unique(unique_pairs.begin(), unique_pairs.end()),
                       unique_pairs.end());
    for (std::size_t c = 0; c < contacts.size(); ++c)
      contact_pair[c] = static_cast<int>(
        std::lower_bound(unique_pairs.begin(), unique_pairs.end(), pairs[c])
        - unique_pairs.begin());
    matrix.reinit(n, unique_pairs);
  }



  void
  Assembler::set_shear_reference(const BlockSystem &system,
                                 const int          index,
                                 const Contact     &contact)
  {
    contact_kinematics[index]                    = contact_kinematics_of(system,
                                                      block_moments_,
                                                      contact.geometry,
                                                      contact.xi_ref,
                                                      params.gap_tolerance);
    contact_kinematics[index].reversal_tolerance = params.reversal_tolerance;
  }



  void
  Assembler::assemble(const std::vector<Contact> &contacts,
                      BlockSparseMatrix          &K,
                      Eigen::VectorXd            &F) const
  {
    const int n = static_cast<int>(base_matrix.size());
    F.resize(6 * n);
    for (int b = 0; b < n; ++b)
      {
        K.diag[b]           = base_matrix[b];
        F.segment<6>(6 * b) = base_rhs[b];
      }
    for (auto &m : K.off)
      m.setZero();
    const double p          = params.law.normal_penalty;
    const double ps         = params.law.shear_penalty();
    auto         add_spring = [&](const int      c,
                          const double   k,
                          const Vector6 &e,
                          const Vector6 &h,
                          const double   g0) {
      const auto &g = contacts[c].geometry;
      const int   i = g.block_i, j = g.block_j;
      K.diag[i].noalias() += k * e * e.transpose();
      K.diag[j].noalias() += k * h * h.transpose();
      if (i < j)
        K.off[contact_pair[c]].noalias() += k * e * h.transpose();
      else
        K.off[contact_pair[c]].noalias() += k * h * e.transpose();
      F.segment<6>(6 * i) -= (k * g0) * e;
      F.segment<6>(6 * j) -= (k * g0) * h;
    };
    for (int c = 0; c < static_cast<int>(contacts.size()); ++c)
      {
        const Contact           &ct  = contacts[c];
        const ContactKinematics &kin = contact_kinematics[c];
        if (ct.state == ContactState::open)
          continue;
        add_spring(c, p, kin.en, kin.hn, kin.g0);
        if (ct.state == ContactState::locked)
          add_spring(c, ps, kin.es, kin.hs, kin.s0);
        else
          {
            // Sliding: the friction force opposes the sliding direction.
            const double f = ct.slide_direction
                             * shear_strength(ct,
                                              ct.normal_force,
                                              kin.length,
                                              joints[ct.joint]);
            F.segment<6>(6 * ct.geometry.block_i) -= f * kin.es;
            F.segment<6>(6 * ct.geometry.block_j) -= f * kin.hs;
          }
      }
  }
} // namespace rockdda::dda
