/**
 * @file
 * Per-block terms of a 3D DDA step and the block update (Shi 2001).
 */
#include <rockdda/dda/block_step_terms.h>
#include <rockdda/dda/logarithmic_strain.h>
#include <rockdda/dda3d/block_terms.h>

namespace rockdda::dda3d
{
  BlockTerms
  block_terms(const BlockSystem &system,
              const double       h,
              const double       dynamic,
              const double       elastic_factor,
              const Point       &a_ground,
              const Point       &u_ground,
              const double       fixed_penalty)
  {
    const std::size_t n = system.blocks.size();
    BlockTerms        r;
    r.moments.resize(n);
    r.K.resize(n);
    r.F.resize(n);
    r.external.assign(n, Vector12::Zero());
    const bool seismic = a_ground.squaredNorm() > 0.;
    for (std::size_t b = 0; b < n; ++b)
      {
        const Block    &block = system.blocks[b];
        const Material &mat   = system.materials[block.material];
        r.moments[b]          = block.polyhedron.moments();
        const auto &m         = r.moments[b];
        // (dda/block_step_terms.h, shared with 2D.) The loading-mode
        // ground acceleration is a body force: its part is also kept as
        // the external load whose work the ledger books.
        dda::block_step_terms<12, 6, 3>(mass_matrix(m, mat.density),
                                        elasticity_matrix(mat),
                                        m.volume,
                                        mat.density,
                                        block.stress,
                                        block.velocity,
                                        dynamic,
                                        h,
                                        elastic_factor,
                                        Point(system.gravity - a_ground),
                                        r.K[b],
                                        r.F[b]);
        if (seismic)
          r.external[b] = body_force(m, mat.density, -a_ground);
      }
    for (const auto &l : system.load_points)
      {
        const Vector12 f
          = point_load(r.moments[l.block].centroid, l.point, l.force);
        r.F[l.block] += f;
        r.external[l.block] += f;
      }
    for (const auto &f : system.fixed_points)
      {
        const Point &c = r.moments[f.block].centroid;
        r.K[f.block] += fixed_point_stiffness(c, f.point, fixed_penalty);
        r.F[f.block] += fixed_penalty
                        * displacement_matrix(c, f.point).transpose()
                        * (f.anchor + u_ground - f.point);
      }
    return r;
  }



  void
  apply_increment(BlockSystem      &system,
                  const std::size_t b,
                  const Point      &c,
                  const Vector12   &d)
  {
    Block &block = system.blocks[b];
    for (auto &v : block.polyhedron.vertices)
      v = move_point(c, d, v);
    for (auto &f : system.fixed_points)
      if (f.block == int(b))
        f.point = move_point(c, d, f.point);
    for (auto &l : system.load_points)
      if (l.block == int(b))
        l.point = move_point(c, d, l.point);
    for (auto &m : system.measurement_points)
      if (m.block == int(b))
        m.point = move_point(c, d, m.point);
    const Matrix6 C = elasticity_matrix(system.materials[block.material]);
    const Eigen::Matrix3d R = rotation_matrix(rotation_vector(d));
    // The logarithmic strain of the step's stretch, as in 2D: the stress
    // is a function of the shape.
    const Vector6   s = d.tail<6>();
    Eigen::Matrix3d E;
    E << s[0], 0.5 * s[3], 0.5 * s[5], 0.5 * s[3], s[1], 0.5 * s[4], 0.5 * s[5],
      0.5 * s[4], s[2];
    const Eigen::Matrix3d L = dda::logarithmic_strain_increment<3>(E);
    Vector6               e;
    e << L(0, 0), L(1, 1), L(2, 2), 2. * L(0, 1), 2. * L(1, 2), 2. * L(0, 2);
    block.stress = rotate_voigt(block.stress + C * e, R, 1.);
    block.strain = rotate_voigt(block.strain + e, R, 0.5);
  }
} // namespace rockdda::dda3d
