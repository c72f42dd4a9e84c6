/**
 * @file
 * Contact-free time stepping of 3D DDA blocks.
 */
#include <rockdda/dda3d/block_terms.h>
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
    const double      h  = ctrl.dt;
    const Point       ag = ctrl.ground_acceleration
                             ? ctrl.ground_acceleration(t + 0.5 * h)
                             : Point::Zero();
    const std::size_t n  = system.blocks.size();
    // The engine's block terms (no strain damping, anchors at rest).
    const BlockTerms terms = block_terms(
      system, h, ctrl.dynamic, 1., ag, Point::Zero(), ctrl.fixed_penalty);
    const std::vector<Matrix12> &K = terms.K;
    const std::vector<Vector12> &F = terms.F;
    for (std::size_t b = 0; b < n; ++b)
      {
        const Eigen::LDLT<Matrix12> ldlt(K[b]);
        increments[b] = ldlt.solve(F[b]);
        if (!increments[b].allFinite())
          throw InputError("block " + std::to_string(system.blocks[b].id)
                           + ": the step's solution is not finite");
      }
    for (std::size_t b = 0; b < n; ++b)
      {
        dda3d::apply_increment(system,
                               b,
                               terms.moments[b].centroid,
                               increments[b]);
        Block &block = system.blocks[b];
        block.velocity
          = (2. / h) * increments[b] - ctrl.dynamic * block.velocity;
      }
    t += h;
  }



  void
  FreeBlocks::apply_increment(const std::size_t b, const Vector12 &d)
  {
    dda3d::apply_increment(system,
                           b,
                           system.blocks[b].polyhedron.moments().centroid,
                           d);
    increments[b] = d;
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
