/**
 * @file
 * Scene-building helper shared by the 3D DDA verification tests
 * (test_dda3d.cc, test_dda3d_stability.cc) and benchmarks/dda3d: the
 * box-on-incline scene and the running-bond brick wall.
 */
#ifndef ROCKDDA_TESTS_UNIT_DDA3D_TEST_SCENES_H
#define ROCKDDA_TESTS_UNIT_DDA3D_TEST_SCENES_H

#include <rockdda/dda/contact_mechanics.h>
#include <rockdda/dda3d/block_system.h>
#include <rockdda/dda3d/generators.h>

#include <Eigen/Geometry>

#include <cmath>

namespace rockdda::dda3d::test_scenes
{
  /// A box-on-incline scene and the frame it was built in.
  struct InclineScene
  {
    BlockSystem system;
    /// Rotation of the scene: its columns are the slope's down-dip
    /// direction, the strike and the slope's upward normal (global).
    Eigen::Matrix3d frame = Eigen::Matrix3d::Identity();
  };

  /**
   * A box slider [@p slider_lo, @p slider_hi] (block id 2) on a base box
   * [@p base_lo, @p base_hi] (block id 1, clamped by 4 non-collinear fixed
   * points inside it), both given with the slope's top in the plane z = 0
   * and then rotated by @p alpha_deg about y (dipping towards +x), then by
   * @p R, then shifted by @p shift; gravity R (0, 0, -9.80665) m/s^2. One
   * block material @p material, one joint of friction @p phi_deg.
   */
  inline InclineScene
  incline_scene(const double           alpha_deg,
                const double           phi_deg,
                const Point           &base_lo,
                const Point           &base_hi,
                const Point           &slider_lo,
                const Point           &slider_hi,
                const Material        &material = {2700., 1e10, 0.25, 1},
                const Eigen::Matrix3d &R        = Eigen::Matrix3d::Identity(),
                const Point           &shift    = Point::Zero())
  {
    const double    alpha = alpha_deg * std::acos(-1.) / 180.;
    Eigen::Matrix3d Ry;
    Ry = Eigen::AngleAxisd(alpha, Point::UnitY());
    InclineScene out;
    out.frame            = R * Ry;
    const auto Q         = out.frame;
    auto       moved_box = [&](const Point &lo, const Point &hi) {
      Polyhedron p = make_box(lo, hi);
      for (auto &v : p.vertices)
        v = Q * v + shift;
      return p;
    };
    BlockSystem &s = out.system;
    s.materials.push_back(material);
    dda::JointMaterial joint;
    joint.friction_deg = phi_deg;
    s.joints.push_back(joint);
    Block base;
    base.id           = 1;
    base.material     = 0;
    base.polyhedron   = moved_box(base_lo, base_hi);
    Block slider      = base;
    slider.id         = 2;
    slider.polyhedron = moved_box(slider_lo, slider_hi);
    s.blocks          = {base, slider};
    const Point c     = 0.5 * (base_lo + base_hi);
    const Point h     = 0.5 * (base_hi - base_lo);
    for (const Point &p :
         {Point(c.x() - 2. / 3. * h.x(), c.y() - 2. / 3. * h.y(), c.z()),
          Point(c.x() + 2. / 3. * h.x(), c.y() - 2. / 3. * h.y(), c.z()),
          Point(c.x(), c.y() + 2. / 3. * h.y(), c.z()),
          Point(c.x(), c.y(), c.z() - 0.6 * h.z())})
      s.fixed_points.push_back({0, Q * p + shift, Point::Zero()});
    s.gravity = R * Point(0., 0., -9.80665);
    return out;
  }


  /// Appends a box block [@p lo, @p hi] of material 0 to @p s, with the
  /// next id (1-based).
  inline void
  add_box_block(BlockSystem &s, const Point &lo, const Point &hi)
  {
    Block b;
    b.id         = int(s.blocks.size()) + 1;
    b.material   = 0;
    b.polyhedron = make_box(lo, hi);
    s.blocks.push_back(b);
  }


  /**
   * A running-bond wall of @p rows x @p columns bricks (2 m long in x, 1 m
   * thick in y, 1 m high in z; odd rows start and end with a half brick)
   * on a clamped base 1 m thick, 2 m wider than the wall on every side;
   * granite-like material (2700 kg/m^3, 10 GPa, 0.25), friction 35 deg.
   */
  inline BlockSystem
  brick_wall(const int rows, const int columns)
  {
    BlockSystem s;
    s.materials.push_back({2700., 1e10, 0.25, 1});
    dda::JointMaterial j;
    j.friction_deg = 35.;
    s.joints.push_back(j);
    auto brick
      = [&](const Point &lo, const Point &hi) { add_box_block(s, lo, hi); };
    brick(Point(-2., -2., -1.), Point(2. * columns + 2., 3., 0.));
    for (const auto &v : s.blocks[0].polyhedron.vertices)
      s.fixed_points.push_back({0, v, Point::Zero()});
    for (int r = 0; r < rows; ++r)
      {
        const double z0 = r, z1 = r + 1.;
        if (r % 2 == 0)
          for (int c = 0; c < columns; ++c)
            brick(Point(2. * c, 0., z0), Point(2. * c + 2., 1., z1));
        else
          {
            brick(Point(0., 0., z0), Point(1., 1., z1));
            for (int c = 0; c < columns - 1; ++c)
              brick(Point(2. * c + 1., 0., z0), Point(2. * c + 3., 1., z1));
            brick(Point(2. * columns - 1., 0., z0),
                  Point(2. * columns, 1., z1));
          }
      }
    return s;
  }
} // namespace rockdda::dda3d::test_scenes

#endif
