/**
 * @file
 * The parts of a DDA engine's checkpoint that the 2D and the 3D scene
 * share: the fixed, load and measurement points and the linear solver's
 * warm start (written as raw doubles, counts checked against the scene on
 * reading).
 */
#ifndef ROCKDDA_DDA_SCENE_CHECKPOINT_H
#define ROCKDDA_DDA_SCENE_CHECKPOINT_H

#include <rockdda/io/binary_stream.h>
#include <rockdda/io/error.h>

#include <Eigen/Core>

#include <cstdint>
#include <string>

namespace rockdda::dda
{
  /// Append the current positions of the fixed, load and measurement
  /// points (and the latter's initial ones) of @p scene (a 2D or 3D block
  /// system) to @p w.
  template <typename System>
  void
  put_scene_points(io::BinaryWriter &w, const System &scene)
  {
    w.put<std::uint64_t>(scene.fixed_points.size());
    for (const auto &f : scene.fixed_points)
      w.put_fixed(f.point);
    w.put<std::uint64_t>(scene.load_points.size());
    for (const auto &l : scene.load_points)
      w.put_fixed(l.point);
    w.put<std::uint64_t>(scene.measurement_points.size());
    for (const auto &m : scene.measurement_points)
      {
        w.put_fixed(m.point);
        w.put_fixed(m.initial);
      }
  }

  /// Read what put_scene_points() wrote into @p scene; throws InputError
  /// if a count differs from the scene's (another scene).
  template <typename System>
  void
  get_scene_points(io::BinaryReader &r, System &scene)
  {
    r.expect_count(scene.fixed_points.size(), "fixed points");
    for (auto &f : scene.fixed_points)
      r.get_fixed(f.point);
    r.expect_count(scene.load_points.size(), "load points");
    for (auto &l : scene.load_points)
      r.get_fixed(l.point);
    r.expect_count(scene.measurement_points.size(), "measurement points");
    for (auto &m : scene.measurement_points)
      {
        r.get_fixed(m.point);
        r.get_fixed(m.initial);
      }
  }

  /// Append the linear solver's starting guess @p x (the last accepted
  /// step's increments; empty before the first) to @p w.
  inline void
  put_warm_start(io::BinaryWriter &w, const Eigen::VectorXd &x)
  {
    w.put<std::uint64_t>(x.size());
    for (Eigen::Index i = 0; i < x.size(); ++i)
      w.put(x[i]);
  }

  /// Read what put_warm_start() wrote: empty or @p size values; throws
  /// InputError naming @p source otherwise.
  inline Eigen::VectorXd
  get_warm_start(io::BinaryReader  &r,
                 const std::size_t  size,
                 const std::string &source)
  {
    const auto n = r.get<std::uint64_t>();
    if (n != 0 && n != size)
      throw InputError(source + ": the checkpoint is damaged (warm start of "
                       + std::to_string(n) + " values)");
    Eigen::VectorXd x(static_cast<Eigen::Index>(n));
    for (Eigen::Index i = 0; i < x.size(); ++i)
      x[i] = r.get<double>();
    return x;
  }
} // namespace rockdda::dda

#endif
