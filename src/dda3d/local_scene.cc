/**
 * @file
 * A 3D DDA scene at its local origin.
 */
#include <rockdda/dda3d/local_scene.h>

#include <limits>
#include <utility>

namespace rockdda::dda3d
{
  LocalScene::LocalScene(BlockSystem system_in)
      : system(std::move(system_in))
  {
    Point lo = Point::Constant(std::numeric_limits<double>::infinity());
    for (const auto &b : system.blocks)
      for (const auto &v : b.polyhedron.vertices)
        lo = lo.cwiseMin(v);
    origin_ = lo.allFinite() ? lo : Point::Zero();
    for (auto &b : system.blocks)
      for (auto &v : b.polyhedron.vertices)
        v -= origin_;
    for (auto &f : system.fixed_points)
      f.point -= origin_;
    for (auto &l : system.load_points)
      l.point -= origin_;
    for (auto &m : system.measurement_points)
      m.point -= origin_;
  }



  Point
  LocalScene::centroid(const std::size_t b) const
  {
    return origin_ + system.blocks[b].polyhedron.moments().centroid;
  }



  Point
  LocalScene::displacement(const std::size_t b) const
  {
    return system.blocks[b].polyhedron.moments().centroid
           - system.blocks[b].initial_centroid;
  }



  Point
  LocalScene::measurement_point(const std::size_t m) const
  {
    return origin_ + system.measurement_points[m].point;
  }
} // namespace rockdda::dda3d
