/**
 * @file
 * Contact-free time stepping of 3D DDA blocks.
 */
#include <rockdda/dda3d/free_blocks.h>
#include <rockdda/io/error.h>

#include <Eigen/Cholesky>

#include <algorithm>
#include <cmath>
#include <limits>

namespace rockdda::dda3d
{
  FreeBlocks::FreeBlocks(BlockSystem system_in, const FreeStepControls &c)
      : LocalScene(std::move(system_in))
      , ctrl(c)
  {
    if (!(ctrl.dt > 0.) || !std::isfinite(ctrl.dt))
      throw InputError("time step " + std::to_string(ctrl.dt)
                       + " s; valid: > 0");
    if (!(ctrl.dynamic >= 0. && ctrl.dynamic <= 1.))
      throw InputError("dynamic control " + std::to_string(ctrl.dynamic)
                       + "; valid: 0-1");
    if (!(ctrl.fixed_penalty > 0.) || !std::isfinite(ctrl.fixed_penalty))
      throw InputError("fixed point penalty "
                       + std::to_string(ctrl.fixed_penalty)
                       + " N/m; valid: > 0");
    validate_and_prepare(system);
    increments.assign(system.blocks.size(), Vector12::Zero());
  }



  void
  FreeBlocks::step()
  {
    const double h = ctrl.dt;
    Point        a = system.gravity;
    if (ctrl.ground_acceleration)
      a -= ctrl.ground_acceleration(t + 0.5 * h);
    const std::size_t              n = system.blocks.size();
    std::vector<PolyhedronMoments> moments(n);
    std::vector<Matrix12>          K(n);
    std::vector<Vector12>          F(n);
    for (std::size_t b = 0; b < n; ++b)
      {
        const Block    &block = system.blocks[b];
        const Material &mat   = system.materials[block.material];
        moments[b]            = block.polyhedron.moments();
        const auto    &m      = moments[b];
        const Matrix12 M      = mass_matrix(m, mat.density);
        K[b]                  = (2. / (h * h)) * M;
        K[b].block<6, 6>(6, 6) += m.volume * elasticity_matrix(mat);
        F[b] = (2. / h) * (M * (ctrl.dynamic * block.velocity))
               + body_force(m, mat.density, a)
               + initial_stress_load(m.volume, block.stress);
      }
    for (const auto &l : system.load_points)
      F[l.block] += point_load(moments[l.block].centroid, l.point, l.force);
    for (const auto &f : system.fixed_points)
      {
        const Point &c = moments[f.block].centroid;
        K[f.block] += fixed_point_stiffness(c, f.point, ctrl.fixed_penalty);
        F[f.block] += ctrl.fixed_penalty
                      * displacement_matrix(c, f.point).transpose()
                      * (f.anchor - f.point);
      }
    for (std::size_t b = 0; b < n; ++b)
      {
        const Eigen::LDLT<Matrix12> ldlt(K[b]);
        increments[b] = ldlt.solve(F[b]);
        if (!increments[b].allFinite())
          throw InputError("block " + std::to_string(system.blocks[b].id)
                           + ": the step's solution is not finite");
      }
    // Points first: apply_increment() recomputes the centroid from the
    // geometry it moves.
    for (std::size_t b = 0; b < n; ++b)
      {
        apply_increment(b, increments[b]);
        Block &block = system.blocks[b];
        block.velocity
          = (2. / h) * increments[b] - ctrl.dynamic * block.velocity;
      }
    t += h;
  }



  void
  FreeBlocks::apply_increment(const std::size_t b, const Vector12 &d)
  {
    Block      &block = system.blocks[b];
    const Point c     = block.polyhedron.moments().centroid;
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
    const Vector6         e = d.tail<6>();
    block.stress            = rotate_voigt(block.stress + C * e, R, 1.);
    block.strain            = rotate_voigt(block.strain + e, R, 0.5);
    increments[b]           = d;
  }



  double
  FreeBlocks::kinetic_energy() const
  {
    double e = 0.;
    for (const auto &b : system.blocks)
      {
        const Matrix12 M = mass_matrix(b.polyhedron.moments(),
                                       system.materials[b.material].density);
        e += 0.5 * b.velocity.dot(M * b.velocity);
      }
    return e;
  }
} // namespace rockdda::dda3d
