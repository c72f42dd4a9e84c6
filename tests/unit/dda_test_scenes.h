/**
 * @file
 * Small scene-building helpers shared by the DDA verification tests
 * (test_dda.cc, test_dda_contacts.cc): rectangles, rotation, a one-material
 * scene, blocks, fixed blocks, controls, the block-on-incline scene and
 * the check that no contact is beyond its strength.
 */
#ifndef ROCKDDA_TESTS_UNIT_DDA_TEST_SCENES_H
#define ROCKDDA_TESTS_UNIT_DDA_TEST_SCENES_H

#include <rockdda/dda/block_system.h>
#include <rockdda/dda/engine.h>

#include <Eigen/Core>

#include <algorithm>
#include <cmath>
#include <initializer_list>
#include <map>
#include <string>
#include <vector>

namespace rockdda::dda::test_scenes
{
  using geometry::Point;
  using geometry::Polygon;

  constexpr double g_earth = 9.80665;

  /// The axis-parallel rectangle [x0, x0 + w] x [y0, y0 + h],
  /// counter-clockwise.
  inline Polygon
  rectangle(const double x0, const double y0, const double w, const double h)
  {
    Polygon p;
    p.vertices = {Point(x0, y0),
                  Point(x0 + w, y0),
                  Point(x0 + w, y0 + h),
                  Point(x0, y0 + h)};
    return p;
  }

  /// A polygon from its vertices (give them counter-clockwise).
  inline Polygon
  polygon(std::initializer_list<Point> vertices)
  {
    Polygon p;
    p.vertices = vertices;
    return p;
  }

  /// @p p rotated by @p angle (rad, counter-clockwise) about @p about.
  inline Polygon
  rotated(const Polygon &p,
          const double   angle,
          const Point    about = Point::Zero())
  {
    Polygon         r = p;
    Eigen::Matrix2d R;
    R << std::cos(angle), -std::sin(angle), std::sin(angle), std::cos(angle);
    for (auto &v : r.vertices)
      v = about + R * (v - about);
    return r;
  }

  /// @p p moved by @p shift.
  inline Polygon
  translated(const Polygon &p, const Point &shift)
  {
    Polygon r = p;
    for (auto &v : r.vertices)
      v += shift;
    return r;
  }

  /// A scene with one block material and one joint material.
  inline BlockSystem
  one_material_scene(const double density = 2700.,
                     const double young   = 1e10,
                     const double nu      = 0.25,
                     const double phi     = 30.)
  {
    BlockSystem s;
    s.materials.push_back({density, young, nu, false});
    JointMaterial j;
    j.friction_deg = phi;
    s.joints.push_back(j);
    return s;
  }

  /// Append a block (id = index) and return its index.
  inline int
  add_block(BlockSystem &s, const Polygon &p, const int material = 0)
  {
    Block b;
    b.id       = static_cast<int>(s.blocks.size());
    b.polygon  = p;
    b.material = material;
    s.blocks.push_back(b);
    return b.id;
  }

  /// Fix a block by its vertices.
  inline void
  fix_block(BlockSystem &s, const int b)
  {
    for (const auto &v : s.blocks[b].polygon.vertices)
      {
        FixedPoint f;
        f.block = b;
        f.point = v;
        s.fixed_points.push_back(f);
      }
  }

  /// Running-bond brick wall of @p rows x @p columns bricks of 2 m x 1 m
  /// (odd rows start and end with a half brick, so the ends are straight)
  /// on a fixed base (block 0); rho 2700 kg/m^3, E 10 GPa, nu 0.25,
  /// friction @p phi (deg), no cohesion; everything moved by @p shift (m).
  inline BlockSystem
  running_bond_wall(const int    rows,
                    const int    columns,
                    const double phi   = 35.,
                    const Point &shift = Point::Zero())
  {
    BlockSystem s     = one_material_scene(2700., 1e10, 0.25, phi);
    const auto  brick = [&](double x, double y, double w) {
      return add_block(s, translated(rectangle(x, y, w, 1.), shift));
    };
    fix_block(s, brick(-2., -1., 2. * columns + 5.));
    for (int r = 0; r < rows; ++r)
      if (r % 2 == 0)
        for (int c = 0; c < columns; ++c)
          brick(2. * c, r * 1., 2.);
      else
        {
          brick(0., r * 1., 1.);
          for (int c = 0; c < columns - 1; ++c)
            brick(2. * c + 1., r * 1., 2.);
          brick(2. * columns - 1., r * 1., 1.);
        }
    return s;
  }

  /// Largest distance (m) between corresponding vertices of two states of
  /// the same scene.
  inline double
  max_vertex_difference(const BlockSystem &a, const BlockSystem &b)
  {
    double diff = 0.;
    for (std::size_t k = 0; k < a.blocks.size(); ++k)
      for (std::size_t v = 0; v < a.blocks[k].polygon.vertices.size(); ++v)
        diff = std::max(diff,
                        (a.blocks[k].polygon.vertices[v]
                         - b.blocks[k].polygon.vertices[v])
                          .norm());
    return diff;
  }

  inline Controls
  controls(const double dt, const double dynamic, const double penalty)
  {
    Controls c;
    c.time_step              = dt;
    c.dynamic                = dynamic;
    c.law.normal_penalty     = penalty;
    c.max_displacement_ratio = 0.01;
    return c;
  }

  /// A block of size w x h resting on a fixed base (block 0), both rotated
  /// by alpha (rad) so that the contact plane dips towards
  /// +x' = (cos a, -sin a). The block (block 1) is centred on the base.
  inline BlockSystem
  incline_scene(const double alpha,
                const double phi_deg,
                const double w           = 1.,
                const double h           = 1.,
                const double base_length = 10.)
  {
    BlockSystem s    = one_material_scene(2700., 1e10, 0.25, phi_deg);
    const int   base = add_block(
      s, rotated(rectangle(-0.5 * base_length, -1., base_length, 1.), -alpha));
    add_block(s, rotated(rectangle(-0.5 * w, 0., w, h), -alpha));
    fix_block(s, base);
    return s;
  }

  /// Displacement of a block's centroid along the slope of incline_scene().
  inline double
  along_slope(const DdaSystem &dda, const int block, const double alpha)
  {
    return dda.centroid_displacement(block).dot(
      Point(std::cos(alpha), -std::sin(alpha)));
  }
  /// Largest excess of a contact force over its strength + 100 f (N/m,
  /// <= 0 when every contact is within), with what it was.
  struct StrengthExcess
  {
    double      value = -1e300;
    std::string what;
  };

  /// Mohr-Coulomb strength (N/m) of a locked contact with normal force
  /// @p n on @p joint over the length @p l: an intact joint N tan(phi) + c l
  /// (tension lowers it, floored at 0), a broken one max(N, 0) tan(phi).
  inline double
  contact_strength(const Contact       &c,
                   const double         n,
                   const double         l,
                   const JointMaterial &joint)
  {
    const double mu = std::tan(joint.friction_deg * M_PI / 180.);
    return c.broken ? std::max(n, 0.) * mu
                    : std::max(0., n * mu + joint.cohesion * l);
  }

  /**
   * Contacts within their strength, checked from outside the engine on
   * the state after the last step (contacts(): normal_force, shear_force;
   * contact_kinematics(): length, force tolerance f): a closed contact's
   * tension at most its tensile strength (intact and locked only), a
   * locked contact alone on its face at most its Mohr-Coulomb strength,
   * the resultant shear of the locked contacts of a face at most the sum of
   * their strengths (the face-group rule), each plus 100 f, the largest
   * tolerance the open-close iteration grants a contact.
   */
  inline StrengthExcess
  strength_excess(const DdaSystem &dda)
  {
    const auto    &contacts = dda.contacts();
    const auto    &kin      = dda.contact_kinematics();
    const auto    &group    = dda.face_groups();
    const auto    &joints   = dda.system().joints;
    StrengthExcess worst;
    const auto     note = [&](const double value, const std::string &what) {
      if (value > worst.value)
        worst = {value, what};
    };
    // Face groups: the vector sum of the members' shear forces on the
    // lower-numbered block (independent of the engine's sign convention).
    struct Face
    {
      Eigen::Vector2d force = Eigen::Vector2d::Zero();
      double          limit = 0.;
    };
    std::map<int, Face> faces;
    for (std::size_t k = 0; k < contacts.size(); ++k)
      {
        const Contact       &c = contacts[k];
        const JointMaterial &j = joints[c.joint];
        // The largest tolerance the iteration grants a contact: 100 x
        // 1e-4 of the lighter block's weight, or its round-off force.
        const double f = escalated_tolerance(kin[k], 100.);
        if (c.state == ContactState::open)
          continue;
        const bool   locked = c.state == ContactState::locked;
        const double T = locked && !c.broken ? j.tensile * kin[k].length : 0.;
        note(-c.normal_force - T - f, "tension");
        if (!locked)
          continue;
        const double S = contact_strength(c, c.normal_force, kin[k].length, j);
        if (group[k] < 0)
          note(std::abs(c.shear_force) - S - f,
               "shear of a locked contact alone on its face");
        else
          {
            Face &face = faces[group[k]];
            face.force += (c.geometry.block_i < c.geometry.block_j ? 1. : -1.)
                          * c.shear_force * kin[k].tangent;
            face.limit += S + f;
          }
      }
    for (const auto &[g, face] : faces)
      note(face.force.norm() - face.limit,
           "resultant shear of a face's locked contacts");
    return worst;
  }

  /// Successive peak tilts of a freely rocking block (free_rocking()).
  struct FreeRocking
  {
    /// Largest |tilt| (rad) between two sign changes of the tilt, the
    /// first the release tilt: one per impact.
    std::vector<double> peaks;
    /// Accepted steps without a closed contact (the block in the air).
    unsigned long airborne = 0;
  };

  /**
   * A w x h block of density @p rho (E 40 GPa, nu 0.2, plane strain,
   * friction 41 deg: it cannot slide) standing on a fixed base under
   * gravity, released at rest tilted by @p tilt (rad) about its left
   * corner, rocks for @p duration (s) of dynamic steps @p dt at the normal
   * penalty @p penalty. Housner (1963) gives the rigid block on a rigid
   * base: every impact keeps 1 - 3/2 sin^2 alpha of the angular velocity
   * (tan alpha = w / h) and the block never leaves the base, so small peak
   * tilts fall by (1 - 3/2 sin^2 alpha)^2 from one impact to the next.
   */
  inline FreeRocking
  free_rocking(const double w,
               const double h,
               const double rho,
               const double tilt,
               const double penalty,
               const double dt,
               const double duration)
  {
    BlockSystem s               = one_material_scene(rho, 4e10, 0.2, 41.);
    s.materials[0].plane_strain = true;
    s.gravity                   = Point(0., -g_earth);
    fix_block(s, add_block(s, rectangle(-0.5 * w, -0.5 * h, 2. * w, 0.5 * h)));
    const int b      = add_block(s, rotated(rectangle(0., 0., w, h), tilt));
    Controls  c      = controls(dt, 1., penalty);
    c.solver.threads = 1;
    DdaSystem   dda(s, c);
    FreeRocking r;
    double      peak = tilt, last = tilt;
    while (dda.time() < duration - 1e-3 * dt)
      {
        const StepReport step = dda.step();
        r.airborne += step.n_sliding + step.n_locked == 0 ? 1 : 0;
        const double th = tilt + dda.system().blocks[b].rotation;
        if (th * last < 0.)
          {
            r.peaks.push_back(peak);
            peak = 0.;
          }
        peak = std::max(peak, std::abs(th));
        last = th;
      }
    return r;
  }

} // namespace rockdda::dda::test_scenes

#endif
