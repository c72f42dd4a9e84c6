/**
 * @file
 * Scene checks of 3D DDA.
 */
#include <rockdda/dda3d/block_system.h>
#include <rockdda/io/error.h>

#include <cmath>

namespace rockdda::dda3d
{
  void
  validate_and_prepare(BlockSystem &system)
  {
    for (std::size_t m = 0; m < system.materials.size(); ++m)
      {
        const Material   &mat = system.materials[m];
        const std::string name
          = "material " + std::to_string(mat.id >= 0 ? mat.id : int(m));
        if (!(mat.density > 0.) || !std::isfinite(mat.density))
          throw InputError(name + ": density " + std::to_string(mat.density)
                           + " kg/m^3; valid: > 0");
        if (!(mat.young > 0.) || !std::isfinite(mat.young))
          throw InputError(name + ": Young's modulus "
                           + std::to_string(mat.young) + " Pa; valid: > 0");
        if (!(mat.poisson >= 0. && mat.poisson < 0.5))
          throw InputError(name + ": Poisson's ratio "
                           + std::to_string(mat.poisson)
                           + "; valid: 0 <= nu < 0.5");
      }
    for (std::size_t k = 0; k < system.joints.size(); ++k)
      {
        const auto       &j    = system.joints[k];
        const std::string name = "joint material " + std::to_string(k);
        if (!(j.friction_deg >= 0. && j.friction_deg < 90.))
          throw InputError(name + ": friction angle "
                           + std::to_string(j.friction_deg)
                           + " deg; valid: 0 <= phi < 90");
        if (!(j.cohesion >= 0.) || !(j.tensile >= 0.)
            || !(j.normal_stiffness >= 0.) || !(j.shear_stiffness >= 0.))
          throw InputError(name
                           + ": cohesion, tensile strength and "
                             "stiffnesses must be >= 0");
      }
    for (auto &b : system.blocks)
      {
        const std::string name = "block " + std::to_string(b.id);
        if (b.material < 0 || b.material >= int(system.materials.size()))
          throw InputError(name + ": has no material");
        if (!system.joints.empty()
            && (b.joint < 0 || b.joint >= int(system.joints.size())))
          throw InputError(name + ": joint material index "
                           + std::to_string(b.joint) + " does not exist");
        const auto defect = polyhedron_defect(b.polyhedron);
        if (defect)
          throw InputError(name + (defect.face >= 0 ? ", " : ": ")
                           + defect.describe());
        b.initial_centroid = b.polyhedron.moments().centroid;
      }
    auto check_point = [&](const int block, const Point &p, const char *what) {
      if (block < 0 || block >= int(system.blocks.size()))
        throw InputError(std::string(what) + " point on block index "
                         + std::to_string(block) + ", which does not exist");
      if (!system.blocks[block].polyhedron.contains(p))
        throw InputError("block " + std::to_string(system.blocks[block].id)
                         + ": " + what + " point (" + std::to_string(p.x())
                         + ", " + std::to_string(p.y()) + ", "
                         + std::to_string(p.z()) + ") is outside the block");
    };
    for (auto &f : system.fixed_points)
      {
        check_point(f.block, f.point, "fixed");
        f.anchor = f.point;
      }
    for (const auto &l : system.load_points)
      check_point(l.block, l.point, "load");
    for (auto &m : system.measurement_points)
      {
        check_point(m.block, m.point, "measurement");
        m.initial = m.point;
      }
  }
} // namespace rockdda::dda3d
