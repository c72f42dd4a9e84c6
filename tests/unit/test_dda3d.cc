/**
 * @file
 * Verification of the first layer of 3D DDA (issue 17): exact polyhedron
 * moments, generators, the 12-DOF block matrices, contact-free time
 * stepping (rigid rotation, free fall, static elastic response) and bad
 * input. Every test prints its measured errors.
 */
#include <rockdda/analytical/sliding3d.h>
#include <rockdda/analytical/yield.h>
#include <rockdda/dda/hdf5_output.h>
#include <rockdda/dda3d/block_file.h>
#include <rockdda/dda3d/block_matrices.h>
#include <rockdda/dda3d/contact_detection.h>
#include <rockdda/dda3d/engine.h>
#include <rockdda/dda3d/free_blocks.h>
#include <rockdda/dda3d/generators.h>
#include <rockdda/dda3d/vtu_output.h>
#include <rockdda/io/error.h>

#include <Eigen/Dense>
#include <gtest/gtest.h>

#include "dda3d_test_scenes.h"
#include "vtu_reader.h"
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <functional>
#include <map>
#include <random>
#include <set>
#include <sstream>
#include <string>
#include <unistd.h>
#include <utility>
#include <vector>

using namespace rockdda;
using namespace rockdda::dda3d;

namespace
{
  const double pi = std::acos(-1.);

  /// Closed-form moments of a set of disjoint axis-aligned boxes (lo, hi):
  /// integral x_i x_j over a box is a product of 1D integrals.
  PolyhedronMoments
  boxes_moments(const std::vector<std::pair<Point, Point>> &boxes)
  {
    double          V = 0.;
    Point           s = Point::Zero();
    Eigen::Matrix3d S = Eigen::Matrix3d::Zero();
    for (const auto &[lo, hi] : boxes)
      {
        Point i0, i1, i2; // integral of 1, x, x^2 along each axis
        for (int k = 0; k < 3; ++k)
          {
            i0[k] = hi[k] - lo[k];
            i1[k] = (hi[k] * hi[k] - lo[k] * lo[k]) / 2.;
            i2[k] = (std::pow(hi[k], 3) - std::pow(lo[k], 3)) / 3.;
          }
        V += i0.prod();
        for (int k = 0; k < 3; ++k)
          {
            s[k] += i1[k] * i0.prod() / i0[k];
            for (int l = 0; l < 3; ++l)
              S(k, l) += k == l ? i2[k] * i0.prod() / i0[k]
                                : i1[k] * i1[l] * i0.prod() / (i0[k] * i0[l]);
          }
      }
    PolyhedronMoments m;
    m.volume   = V;
    m.centroid = s / V;
    m.second   = S - V * m.centroid * m.centroid.transpose();
    return m;
  }

  /// Right tetrahedron (0, a e_x, b e_y, c e_z): Dirichlet's integral
  /// integral x^p y^q z^r = a^(p+1) b^(q+1) c^(r+1) p! q! r! / (p+q+r+3)!.
  PolyhedronMoments
  right_tetrahedron_moments(const double a, const double b, const double c)
  {
    const Point       L(a, b, c);
    PolyhedronMoments m;
    m.volume   = a * b * c / 6.;
    m.centroid = L / 4.;
    for (int k = 0; k < 3; ++k)
      for (int l = 0; l < 3; ++l)
        m.second(k, l) = (k == l ? 2. : 1.) * a * b * c * L[k] * L[l] / 120.
                         - m.volume * m.centroid[k] * m.centroid[l];
    return m;
  }

  /// Largest relative difference of two sets of moments (volume, centroid
  /// relative to @p length, second moments relative to their norm).
  double
  moment_error(const PolyhedronMoments &a,
               const PolyhedronMoments &b,
               const double             length)
  {
    return std::max({std::abs(a.volume - b.volume) / std::abs(b.volume),
                     (a.centroid - b.centroid).norm() / length,
                     (a.second - b.second).norm() / b.second.norm()});
  }

  Polyhedron
  transformed(Polyhedron p, const Eigen::Matrix3d &R, const Point &shift)
  {
    for (auto &v : p.vertices)
      v = R * v + shift;
    return p;
  }

  PolyhedronMoments
  transformed(PolyhedronMoments m, const Eigen::Matrix3d &R, const Point &shift)
  {
    m.centroid = R * m.centroid + shift;
    m.second   = R * m.second * R.transpose();
    return m;
  }

  /// The L-shaped polygon [0, 2] x [0, 1] + [0, 1] x [1, 2] (area 3).
  geometry::Polygon
  l_polygon()
  {
    geometry::Polygon p;
    p.vertices = {{0., 0.}, {2., 0.}, {2., 1.}, {1., 1.}, {1., 2.}, {0., 2.}};
    return p;
  }

  /// A scene of one block of @p poly with material (rho, E, nu), no gravity.
  BlockSystem
  one_block(const Polyhedron &poly,
            const double      rho = 2700.,
            const double      E   = 1e10,
            const double      nu  = 0.25)
  {
    BlockSystem s;
    s.materials.push_back({rho, E, nu, 1});
    Block b;
    b.id         = 1;
    b.polyhedron = poly;
    b.material   = 0;
    s.blocks.push_back(b);
    s.gravity.setZero();
    return s;
  }

  /// The largest volume change (relative) and vertex distance from the
  /// exact rigid rotation (relative to the block size).
  std::pair<double, double>
  rotation_errors(const Polyhedron      &initial,
                  const Polyhedron      &now,
                  const Eigen::Matrix3d &R,
                  const Point           &c0,
                  const Point           &c1)
  {
    double d = 0.;
    for (std::size_t k = 0; k < initial.vertices.size(); ++k)
      d = std::max(
        d, (now.vertices[k] - (c1 + R * (initial.vertices[k] - c0))).norm());
    const double V0 = initial.signed_volume();
    return {std::abs(now.signed_volume() - V0) / V0, d / initial.size()};
  }
} // namespace



// ---------------------------------------------------------------------------
// Exact geometry.

TEST(Dda3dGeometry, MomentsAgainstClosedFormsTranslatedAndRotated)
{
  struct Case
  {
    const char       *name;
    Polyhedron        poly;
    PolyhedronMoments exact;
  };
  const std::vector<Case> cases
    = {{"unit cube",
        make_box(Point(0., 0., 0.), Point(1., 1., 1.)),
        boxes_moments({{Point(0., 0., 0.), Point(1., 1., 1.)}})},
       {"tetrahedron",
        make_tetrahedron(Point(0., 0., 0.),
                         Point(1., 0., 0.),
                         Point(0., 2., 0.),
                         Point(0., 0., 3.)),
        right_tetrahedron_moments(1., 2., 3.)},
       {"L-shaped prism",
        make_prism(l_polygon(), 0., 1.5),
        boxes_moments({{Point(0., 0., 0.), Point(2., 1., 1.5)},
                       {Point(0., 1., 0.), Point(1., 2., 1.5)}})}};
  // 120 deg about (1, 1, 1) / sqrt 3 permutes the axes exactly; use an
  // irrational rotation instead.
  const Eigen::Matrix3d R
    = Eigen::AngleAxisd(0.7, Point(1., -2., 3.).normalized())
        .toRotationMatrix();
  const Point utm(5e5, 4e6, 0.);
  for (const auto &c : cases)
    {
      EXPECT_FALSE(polyhedron_defect(c.poly)) << c.name;
      const double L = c.poly.size();
      // (1) as given, (2) rotated about the origin, (3) shifted to UTM
      // coordinates (an exact shift of these dyadic coordinates): 1e-12.
      const double e1 = moment_error(c.poly.moments(), c.exact, L);
      const double e2
        = moment_error(transformed(c.poly, R, Point::Zero()).moments(),
                       transformed(c.exact, R, Point::Zero()),
                       L);
      const double e3 = moment_error(
        transformed(c.poly, Eigen::Matrix3d::Identity(), utm).moments(),
        transformed(c.exact, Eigen::Matrix3d::Identity(), utm),
        L);
      // (4) rotated, then at UTM: the coordinates themselves are rounded to
      // half an ulp of 4e6 (u = 2.3e-10 m), which moves the volume by up to
      // (surface / volume) u relative; bound 10 x that.
      const double e4   = moment_error(transformed(c.poly, R, utm).moments(),
                                     transformed(c.exact, R, utm),
                                     L);
      double       area = 0.;
      for (std::size_t f = 0; f < c.poly.faces.size(); ++f)
        {
          Point n = Point::Zero();
          for (std::size_t k = 0; k < c.poly.faces[f].size(); ++k)
            n += c.poly.vertices[c.poly.faces[f][k]].cross(
              c.poly
                .vertices[c.poly.faces[f][(k + 1) % c.poly.faces[f].size()]]);
          area += 0.5 * n.norm();
        }
      const double bound4 = 10. * area / c.exact.volume * 0.5
                            * std::ldexp(1., std::ilogb(4e6) - 52) / L;
      std::printf("%-15s relative error: given %.2e, rotated %.2e, at UTM "
                  "%.2e (bound 1e-12); rotated at UTM %.2e (bound %.1e)\n",
                  c.name,
                  e1,
                  e2,
                  e3,
                  e4,
                  bound4);
      EXPECT_LT(e1, 1e-12) << c.name;
      EXPECT_LT(e2, 1e-12) << c.name;
      EXPECT_LT(e3, 1e-12) << c.name;
      EXPECT_LT(e4, bound4) << c.name;
    }
}



TEST(Dda3dGeometry, GeneratorsAndConvexCuts)
{
  // A prism from a clockwise polygon is the same block.
  geometry::Polygon cw = l_polygon();
  std::reverse(cw.vertices.begin(), cw.vertices.end());
  const Polyhedron prism = make_prism(cw, 0., 1.5);
  EXPECT_FALSE(polyhedron_defect(prism));
  EXPECT_NEAR(prism.signed_volume(), 4.5, 1e-13);
  // Vertex order does not matter for a tetrahedron.
  const Polyhedron tet = make_tetrahedron(Point(0., 0., 0.),
                                          Point(0., 2., 0.),
                                          Point(1., 0., 0.),
                                          Point(0., 0., 3.));
  EXPECT_FALSE(polyhedron_defect(tet));
  EXPECT_NEAR(tet.signed_volume(), 1., 1e-14);

  // Unit cube cut by the plane dipping 45 deg to the east through its
  // centre: x + z <= 1 keeps half of it, a triangular prism.
  const Polyhedron cube = make_box(Point::Zero(), Point::Ones());
  const Polyhedron half
    = clip_convex(cube, {half_space_from_dip(45., 90., Point::Constant(0.5))});
  EXPECT_FALSE(polyhedron_defect(half));
  EXPECT_EQ(half.vertices.size(), 6u);
  EXPECT_EQ(half.faces.size(), 5u);
  EXPECT_NEAR(half.signed_volume(), 0.5, 1e-14);
  // The corner x + y + z <= 1.5 of the cube (a hexagonal cap): volume 1/2
  // by symmetry.
  const Polyhedron corner = clip_convex(cube, {{Point(1., 1., 1.), 1.5}});
  EXPECT_FALSE(polyhedron_defect(corner));
  EXPECT_NEAR(corner.signed_volume(), 0.5, 1e-14);
  EXPECT_EQ(corner.faces.size(), 7u);
  // A block cut from a 1 m slab by two vertical joint sets.
  const Polyhedron slab  = make_box(Point(0., 0., 0.), Point(10., 10., 1.));
  const Polyhedron piece = clip_convex(
    slab,
    {half_space_from_dip(90., 90., Point(4., 0., 0.)),         // x <= 4
     half_space_from_dip(90., 0., Point(0., 3., 0.)),          // y <= 3
     half_space_from_dip(60., 90., Point(1., 0., 0.), true)}); // above
  EXPECT_FALSE(polyhedron_defect(piece));
  // The joint dips 60 deg east through (1, 0, 0): x from 1 - z / tan 60
  // to 4, y 0-3, z 0-1.
  EXPECT_NEAR(piece.signed_volume(),
              3. * (3. + 0.5 / std::tan(pi / 3.)),
              1e-12);

  // The shaking-table wedge (thesis 4.6: joints 51.4/065.8 and
  // 51.4/295.2), under a slope face 80/000 with a horizontal top: its
  // volume against the tetrahedron of the four planes' corners, found
  // independently by solving the 3x3 systems of each three planes.
  const double     H = 0.5;
  const Polyhedron wedge
    = make_tetrahedral_wedge({51.4, 65.8, 51.4, 295.2, 80., 0.},
                             H,
                             Point(0., 0., 1.));
  EXPECT_FALSE(polyhedron_defect(wedge));
  ASSERT_EQ(wedge.vertices.size(), 4u);
  std::vector<HalfSpace> planes;
  {
    const double deg = pi / 180.;
    const Point  down(std::cos(80. * deg) * std::sin(0.),
                     std::cos(80. * deg) * std::cos(0.),
                     -std::sin(80. * deg));
    const Point  toe = Point(0., 0., 1.) + H / std::sin(80. * deg) * down;
    planes           = {{Point::UnitZ(), 1.},
                        half_space_from_dip(80., 0., Point(0., 0., 1.)),
                        half_space_from_dip(51.4, 65.8, toe, true),
                        half_space_from_dip(51.4, 295.2, toe, true)};
  }
  std::vector<Point> corners;
  for (int skip = 0; skip < 4; ++skip)
    {
      Eigen::Matrix3d A;
      Point           b;
      int             r = 0;
      for (int k = 0; k < 4; ++k)
        if (k != skip)
          {
            A.row(r) = planes[k].normal.transpose();
            b[r++]   = planes[k].offset;
          }
      corners.push_back(A.partialPivLu().solve(b));
    }
  const double V_exact
    = std::abs((corners[1] - corners[0])
                 .dot((corners[2] - corners[0]).cross(corners[3] - corners[0])))
      / 6.;
  std::printf("shaking-table wedge (H = %.1f m): volume %.6e m^3, against "
              "the corners' tetrahedron %.2e relative\n",
              H,
              wedge.signed_volume(),
              std::abs(wedge.signed_volume() - V_exact) / V_exact);
  EXPECT_NEAR(wedge.signed_volume(), V_exact, 1e-12 * V_exact);
  // Its lowest vertex is the toe, where the joints' line daylights.
  double zmin = 1.;
  for (const auto &v : wedge.vertices)
    zmin = std::min(zmin, v.z());
  EXPECT_NEAR(zmin, 1. - H, 1e-12);
  // Joints that do not daylight: no tetrahedron.
  EXPECT_THROW(make_tetrahedral_wedge({80., 65.8, 80., 295.2, 40., 0.},
                                      H,
                                      Point::Zero()),
               InputError);
}



// ---------------------------------------------------------------------------
// Block matrices.

TEST(Dda3dBlocks, DisplacementMassAndElasticityMatrices)
{
  // T of Eq. 2.5: the rotation columns give w x X with w = (r2, r3, r1);
  // the strain columns the symmetric strain tensor times X.
  const Point c(1., 2., 3.), x(1.5, 1.2, 3.7), X = x - c;
  const auto  T = displacement_matrix(c, x);
  Vector12    d = Vector12::Zero();
  d[3]          = 0.3;  // r1, about z
  d[4]          = -0.2; // r2, about x
  d[5]          = 0.7;  // r3, about y
  EXPECT_LT((T * d - Point(-0.2, 0.7, 0.3).cross(X)).norm(), 1e-15);
  d.setZero();
  d.tail<6>() << 1e-3, 2e-3, 3e-3, 4e-3, 5e-3, 6e-3;
  Eigen::Matrix3d E;
  E << 1e-3, 2e-3, 3e-3, 2e-3, 2e-3, 2.5e-3, 3e-3, 2.5e-3, 3e-3;
  EXPECT_LT((T * d - E * X).norm(), 1e-17);

  // Mass matrix against a quadrature that is exact for T^T T (degree 2):
  // the 4-point rule on each tetrahedron of a fan from the vertex mean,
  // for a non-convex block away from the origin.
  const Polyhedron poly = transformed(
    make_prism(l_polygon(), 0., 1.5),
    Eigen::AngleAxisd(0.4, Point(1., 1., 0.).normalized()).toRotationMatrix(),
    Point(10., -20., 30.));
  const auto     m   = poly.moments();
  const double   rho = 2500.;
  const Matrix12 M   = mass_matrix(m, rho);
  Matrix12       Mq  = Matrix12::Zero();
  const Point    o   = poly.vertex_mean();
  const double   a = 0.5854101966249685, b = 0.1381966011250105;
  for (const auto &f : poly.faces)
    for (std::size_t k = 1; k + 1 < f.size(); ++k)
      {
        const Point  p[4] = {o,
                             poly.vertices[f[0]],
                             poly.vertices[f[k]],
                             poly.vertices[f[k + 1]]};
        const double V
          = (p[1] - p[0]).dot((p[2] - p[0]).cross(p[3] - p[0])) / 6.;
        for (int q = 0; q < 4; ++q)
          {
            Point x = Point::Zero();
            for (int r = 0; r < 4; ++r)
              x += (r == q ? a : b) * p[r];
            const auto Tq = displacement_matrix(m.centroid, x);
            Mq += rho * V / 4. * Tq.transpose() * Tq;
          }
      }
  const double mass_error = (M - Mq).norm() / M.norm();
  std::printf("mass matrix against 4-point quadrature: %.2e relative\n",
              mass_error);
  EXPECT_LT(mass_error, 1e-13);
  EXPECT_LT((M - M.transpose()).norm(), 1e-14 * M.norm());
  EXPECT_GT(Eigen::SelfAdjointEigenSolver<Matrix12>(M).eigenvalues().minCoeff(),
            0.);
  // Rotation block = the inertia tensor J = rho (tr S I - S), in the
  // order (about z, about x, about y).
  const Eigen::Matrix3d J
    = rho * (m.second.trace() * Eigen::Matrix3d::Identity() - m.second);
  const int perm[3] = {2, 0, 1};
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j)
      EXPECT_NEAR(M(3 + i, 3 + j), J(perm[i], perm[j]), 1e-12 * J.norm());

  // Elasticity: the compliance C^-1 of uniaxial stress gives sigma / E and
  // -nu sigma / E; shear modulus E / (2 (1 + nu)).
  const Material mat{2700., 3e10, 0.2, 1};
  const Matrix6  C = elasticity_matrix(mat);
  Vector6        s = Vector6::Zero();
  s[1]             = 1e6;
  const Vector6 e  = C.ldlt().solve(s);
  EXPECT_NEAR(e[1], 1e6 / 3e10, 1e-18);
  EXPECT_NEAR(e[0], -0.2 * 1e6 / 3e10, 1e-18);
  EXPECT_NEAR(e[2], -0.2 * 1e6 / 3e10, 1e-18);
  EXPECT_NEAR(C(4, 4), 3e10 / 2.4, 1e-5);
}



// ---------------------------------------------------------------------------
// Contact-free stepping.

TEST(Dda3dFreeBlocks, RigidRotationKeepsVolumeAndGivesNoStrain)
{
  // 90 deg about an oblique axis in 1000 steps, (a) prescribed increments,
  // (b) by the angular velocity of a free block (dynamic scheme); the
  // block is the non-convex L prism, at UTM coordinates in (b).
  const Point           axis  = Point(1., 2., 3.).normalized();
  const double          angle = pi / 2.;
  const int             n     = 1000;
  const Eigen::Matrix3d R = Eigen::AngleAxisd(angle, axis).toRotationMatrix();
  const Polyhedron      L = make_prism(l_polygon(), 0., 1.5);
  {
    FreeBlocks  blocks(one_block(L), FreeStepControls());
    Vector12    d  = Vector12::Zero();
    const Point w  = (angle / n) * axis;
    d[3]           = w.z();
    d[4]           = w.x();
    d[5]           = w.y();
    const Point c0 = blocks.scene().blocks[0].polyhedron.moments().centroid;
    const auto  initial = blocks.scene().blocks[0].polyhedron;
    for (int k = 0; k < n; ++k)
      blocks.apply_increment(0, d);
    const auto &block   = blocks.scene().blocks[0];
    const auto [dv, dx] = rotation_errors(
      initial, block.polyhedron, R, c0, block.polyhedron.moments().centroid);
    std::printf("prescribed rotation: volume change %.2e, vertices off the "
                "exact rotation %.2e (x size), strain %.1e\n",
                dv,
                dx,
                block.strain.norm());
    EXPECT_LT(dv, 1e-9);
    EXPECT_LT(dx, 1e-12);
    EXPECT_EQ(block.strain.norm(), 0.);
  }
  {
    BlockSystem s = one_block(
      transformed(L, Eigen::Matrix3d::Identity(), Point(5e5, 4e6, 0.)));
    const Point w           = (angle / 1.) * axis; // 1 s
    s.blocks[0].velocity[3] = w.z();
    s.blocks[0].velocity[4] = w.x();
    s.blocks[0].velocity[5] = w.y();
    FreeStepControls ctrl;
    ctrl.dt = 1. / n;
    FreeBlocks   blocks(s, ctrl);
    const auto   initial = blocks.scene().blocks[0].polyhedron;
    const Point  c0      = initial.moments().centroid;
    const double e0      = blocks.kinetic_energy();
    for (int k = 0; k < n; ++k)
      blocks.step();
    const auto &block   = blocks.scene().blocks[0];
    const auto [dv, dx] = rotation_errors(
      initial, block.polyhedron, R, c0, block.polyhedron.moments().centroid);
    const double de = std::abs(blocks.kinetic_energy() - e0) / e0;
    std::printf("spinning block (dt = 1 ms, at UTM): volume change %.2e, "
                "vertices off the exact rotation %.2e (x size), strain "
                "%.1e, centroid drift %.1e m, kinetic energy change %.1e\n",
                dv,
                dx,
                block.strain.cwiseAbs().maxCoeff(),
                blocks.displacement(0).norm(),
                de);
    EXPECT_LT(dv, 1e-9);
    EXPECT_LT(dx, 1e-9);
    EXPECT_LT(block.strain.cwiseAbs().maxCoeff(), 1e-12);
    EXPECT_LT(block.stress.cwiseAbs().maxCoeff(), 1e-12 * 1e10);
    EXPECT_LT(blocks.displacement(0).norm(), 1e-9);
    EXPECT_LT(de, 1e-9);
  }
}



TEST(Dda3dFreeBlocks, FreeFallAndSeismicLoadingFollowTheConstantAcceleration)
{
  // The scheme integrates a constant acceleration exactly
  // (D = v dt + a dt^2 / 2, v' = 2 D / dt - v = v + a dt, and about the
  // centroid the translations decouple from the rotations and strains),
  // so the error is round-off, ~ steps x 1e-16: the 1e-6 holds
  // with a wide margin.
  const Polyhedron tet = make_tetrahedron(Point(0., 0., 0.),
                                          Point(1., 0., 0.),
                                          Point(0., 2., 0.),
                                          Point(0., 0., 3.));
  const double     g   = 9.80665;
  // Free fall with a horizontal initial velocity; then seismic loading by
  // a 3-component ground acceleration (0.3, -0.2, 0.1) g.
  for (const bool seismic : {false, true})
    {
      BlockSystem s                  = one_block(tet);
      s.gravity                      = Point(0., 0., -g);
      s.blocks[0].velocity.head<3>() = Point(0.5, 0., 0.);
      FreeStepControls ctrl;
      ctrl.dt         = 1e-3;
      const Point a_g = Point(0.3, -0.2, 0.1) * g;
      if (seismic)
        ctrl.ground_acceleration = [a_g](double) { return a_g; };
      FreeBlocks blocks(s, ctrl);
      for (int k = 0; k < 1000; ++k)
        blocks.step();
      const double t     = blocks.time();
      const Point  a     = s.gravity - (seismic ? a_g : Point::Zero());
      const Point  exact = Point(0.5, 0., 0.) * t + 0.5 * a * t * t;
      const double error
        = (blocks.displacement(0) - exact).norm() / exact.norm();
      std::printf("%s: displacement after %.3f s %.6f m, relative error "
                  "%.2e (bound 1e-6); rotation %.1e rad, strain %.1e\n",
                  seismic ? "seismic loading" : "free fall",
                  t,
                  blocks.displacement(0).norm(),
                  error,
                  blocks.scene().blocks[0].velocity.segment<3>(3).norm(),
                  blocks.scene().blocks[0].strain.cwiseAbs().maxCoeff());
      EXPECT_LT(error, 1e-6);
      EXPECT_LT(blocks.scene().blocks[0].strain.cwiseAbs().maxCoeff(), 1e-15);
    }
}



TEST(Dda3dFreeBlocks, StaticElasticResponse)
{
  const double E = 1e10, nu = 0.25, rho = 2700., g = 9.80665;
  // (a) Uniaxial stress: a free unit cube pulled by +-f on two opposite
  // face centres. The generalised force f a on eps_x balances V C eps, so
  // eps = C^-1 (f / A) e_x: sigma / E along x, -nu sigma / E across.
  // The geometry is updated each step (the arm and volume grow with the
  // strain), so the small-strain values hold to O(eps) = 1e-6 relative.
  {
    const double f = 1e4; // N, sigma = 1e4 Pa, eps = 1e-6
    BlockSystem  s
      = one_block(make_box(Point::Zero(), Point::Ones()), rho, E, nu);
    s.load_points.push_back({0, Point(1., 0.5, 0.5), Point(f, 0., 0.)});
    s.load_points.push_back({0, Point(0., 0.5, 0.5), Point(-f, 0., 0.)});
    FreeStepControls ctrl;
    ctrl.dt      = 1.;
    ctrl.dynamic = 0.;
    FreeBlocks blocks(s, ctrl);
    for (int k = 0; k < 10; ++k)
      blocks.step();
    const auto  &b       = blocks.scene().blocks[0];
    const double ex      = f / E;
    const double e_axial = std::abs(b.strain[0] - ex) / ex;
    const double e_lat   = std::max(std::abs(b.strain[1] + nu * ex),
                                  std::abs(b.strain[2] + nu * ex))
                         / (nu * ex);
    const double e_stress = std::abs(b.stress[0] - f) / f;
    std::printf("uniaxial stress: eps_x off sigma/E by %.2e, eps_y, eps_z "
                "off -nu sigma/E by %.2e, sigma_x off f/A by %.2e (bound "
                "1e-5); last increment %.1e\n",
                e_axial,
                e_lat,
                e_stress,
                blocks.last_increment(0).norm());
    EXPECT_LT(e_axial, 1e-5);
    EXPECT_LT(e_lat, 1e-5);
    EXPECT_LT(e_stress, 1e-5);
    EXPECT_LT(b.stress.tail<3>().cwiseAbs().maxCoeff(), 1e-9 * f);
    EXPECT_LT(b.stress.segment<2>(1).cwiseAbs().maxCoeff(), 1e-5 * f);
  }
  // (b) A 1 m cube hanging from a fixed point at the centre of its top
  // face, under gravity. The spring carries m g: the point sinks by
  // m g / p. The spring force at the arm h / 2 above the centroid loads
  // eps_z by m g h / 2, so sigma_z = rho g h / 2 (the mean stress of a
  // hanging column), eps_z = sigma_z / E, eps_x = eps_y = -nu eps_z, and
  // the centroid sinks by m g / p + eps_z h / 2.
  {
    const double p = 1e10;
    BlockSystem  s
      = one_block(make_box(Point::Zero(), Point::Ones()), rho, E, nu);
    s.gravity = Point(0., 0., -g);
    s.fixed_points.push_back({0, Point(0.5, 0.5, 1.), Point::Zero()});
    s.measurement_points.push_back({0, Point(0.5, 0.5, 1.), Point::Zero()});
    FreeStepControls ctrl;
    ctrl.dt            = 1.;
    ctrl.dynamic       = 0.;
    ctrl.fixed_penalty = p;
    FreeBlocks blocks(s, ctrl);
    for (int k = 0; k < 20; ++k)
      blocks.step();
    const auto  &b    = blocks.scene().blocks[0];
    const double mg   = rho * g;
    const double sz   = rho * g / 2.;
    const double ez   = sz / E;
    const double sink = mg / p;
    const double e_top
      = std::abs(-(blocks.measurement_point(0).z() - 1.) - sink) / sink;
    const double e_cent
      = std::abs(-blocks.displacement(0).z() - (sink + ez / 2.))
        / (sink + ez / 2.);
    const double e_sz = std::abs(b.stress[2] - sz) / sz;
    const double e_ez = std::abs(b.strain[2] - ez) / ez;
    const double e_ex = std::abs(b.strain[0] + nu * ez) / (nu * ez);
    std::printf("hanging block: top point sinks %.4e m (m g / p off by "
                "%.2e), centroid off by %.2e, sigma_z off rho g h / 2 by "
                "%.2e, eps_z %.2e, eps_x %.2e (bound 1e-5)\n",
                sink,
                e_top,
                e_cent,
                e_sz,
                e_ez,
                e_ex);
    EXPECT_LT(e_top, 1e-5);
    EXPECT_LT(e_cent, 1e-5);
    EXPECT_LT(e_sz, 1e-5);
    EXPECT_LT(e_ez, 1e-5);
    EXPECT_LT(e_ex, 1e-5);
  }
}



// ---------------------------------------------------------------------------
// Block file and bad input.

namespace
{
  const char *cube_faces = "face 0 2 3 1\n"
                           "face 4 5 7 6\n"
                           "face 0 1 5 4\n"
                           "face 2 6 7 3\n"
                           "face 0 4 6 2\n"
                           "face 1 3 7 5\n";

  std::string
  cube_vertices(const double top_corner_z = 1.)
  {
    std::string s;
    for (int k = 0; k < 8; ++k)
      s += "vertex " + std::to_string(k & 1) + " "
           + std::to_string((k >> 1) & 1) + " "
           + (k == 7 ? std::to_string(top_corner_z)
                     : std::to_string((k >> 2) & 1))
           + "\n";
    return s;
  }

  /// The message of the InputError that parsing @p text throws ("" if
  /// none).
  std::string
  error_of(const std::string &text)
  {
    try
      {
        parse_block_text(text, "bad.dda3d");
      }
    catch (const InputError &e)
      {
        return e.what();
      }
    return "";
  }
} // namespace



TEST(Dda3dInput, BlockFileReadsWritesAndNamesBadInput)
{
  // A good file: a cube (lines 1-16) with a fixed, a load and a
  // measurement point; written back and read again, the same block.
  const std::string good = "material 1 2700 1e10 0.25\n"
                           "block 7 1\n"
                           + cube_vertices() + cube_faces
                           + "fixed 7 0.5 0.5 0\n"
                             "load 7 0.5 0.5 1 0 0 -100\n"
                             "measure 7 0.5 0.5 0.5\n"
                             "velocity 7 1 0 0 0 0 0.1\n";
  const BlockSystem s = parse_block_text(good, "good.dda3d");
  ASSERT_EQ(s.blocks.size(), 1u);
  EXPECT_NEAR(s.blocks[0].polyhedron.signed_volume(), 1., 1e-15);
  EXPECT_EQ(s.fixed_points.size(), 1u);
  EXPECT_EQ(s.blocks[0].velocity[3], 0.1); // wz -> r1 (about z)
  const BlockSystem again = parse_block_text(block_text(s), "again.dda3d");
  EXPECT_EQ(again.blocks[0].polyhedron.vertices,
            s.blocks[0].polyhedron.vertices);
  EXPECT_EQ(again.blocks[0].polyhedron.faces, s.blocks[0].polyhedron.faces);
  EXPECT_EQ(again.load_points.size(), 1u);

  struct Bad
  {
    const char              *what;
    std::string              text;
    std::vector<std::string> expected;
  };
  const std::string head = "material 1 2700 1e10 0.25\nblock 7 1\n";
  std::string       open_faces(cube_faces);
  open_faces.erase(open_faces.rfind("face")); // drop the x = 1 face
  std::string flipped(cube_faces);
  flipped.replace(flipped.find("face 0 1 5 4"), 12, "face 4 5 1 0");
  const std::string      inward = "face 1 3 2 0\nface 6 7 5 4\nface 4 5 1 0\n"
                                  "face 3 7 6 2\nface 2 6 4 0\nface 5 7 3 1\n";
  const std::vector<Bad> cases  = {
     {"not closed",
      head + cube_vertices() + open_faces,
      {"bad.dda3d", "line 11", "block 7", "face 0", "edge 3-1", "not closed"}},
     {"one face listed clockwise",
      head + cube_vertices() + flipped,
      {"line 13", "block 7", "face 2", "clockwise"}},
     {"inward normals",
      head + cube_vertices() + inward,
      {"line 11", "block 7", "face 0", "inward normals"}},
     {"non-planar face",
      head + cube_vertices(1.01) + cube_faces,
      {"line 12", "block 7", "face 1", "not planar"}},
     {"zero density",
      "material 1 0 1e10 0.25\nblock 7 1\n" + cube_vertices() + cube_faces,
      {"line 1", "material 1", "block 7", "density"}},
     {"negative density",
      "material 1 -2700 1e10 0.25\nblock 7 1\n" + cube_vertices() + cube_faces,
      {"line 1", "block 7", "density"}},
     {"fixed point outside",
      head + cube_vertices() + cube_faces + "fixed 7 2 0.5 0.5\n",
      {"line 17", "outside block 7"}},
     {"bad vertex index",
      head + cube_vertices() + "face 0 2 3 9\n" + cube_faces,
      {"line 11", "block 7", "face 0", "vertex index 9"}},
     {"unknown keyword",
      head + "vertx 0 0 0\n",
      {"line 3", "unknown keyword 'vertx'"}},
     {"Poisson's ratio",
      "material 1 2700 1e10 0.5\n",
      {"line 1", "material 1", "Poisson"}}};
  for (const auto &c : cases)
    {
      const std::string message = error_of(c.text);
      std::printf("%-26s -> %s\n", c.what, message.c_str());
      for (const auto &e : c.expected)
        EXPECT_NE(message.find(e), std::string::npos)
          << c.what << ": '" << e << "' not in '" << message << "'";
    }
}



namespace
{
  /// The blocks of the output tests: a non-convex prism (id 1) and a
  /// tetrahedron (id 2).
  BlockSystem
  output_blocks()
  {
    BlockSystem s = one_block(make_prism(l_polygon(), 0., 1.5));
    Block       t = s.blocks[0];
    t.id          = 2;
    t.polyhedron  = make_tetrahedron(Point(3., 0., 0.),
                                    Point(4., 0., 0.),
                                    Point(3., 2., 0.),
                                    Point(3., 0., 3.));
    s.blocks.push_back(t);
    validate_and_prepare(s);
    return s;
  }
} // namespace



TEST(Dda3dOutput, PolyhedraVtuRoundTrip)
{
  // Two blocks (a non-convex prism and a tetrahedron) at UTM coordinates:
  // the VTU's points and its faces / faceoffsets arrays rebuild the same
  // polyhedra (volumes to 1e-12 with the 17-digit ASCII), one
  // VTK_POLYHEDRON (42) per block.
  BlockSystem       s = output_blocks();
  const Point       origin(5e5, 4e6, 0.);
  const std::string vtu  = blocks_vtu(s, origin);
  auto              data = [&](const std::string &name) {
    const auto start = vtu.find('>', vtu.find("Name=\"" + name + "\"")) + 1;
    std::istringstream in(
      vtu.substr(start, vtu.find("</DataArray>", start) - start));
    std::vector<double> values;
    for (double v; in >> v;)
      values.push_back(v);
    return values;
  };
  const auto         p0 = vtu.find('>', vtu.find("<Points>") + 9) + 1;
  std::istringstream pin(vtu.substr(p0, vtu.find("</DataArray>", p0) - p0));
  std::vector<Point> points;
  for (double x, y, z; pin >> x >> y >> z;)
    points.emplace_back(x, y, z);
  EXPECT_EQ(points.size(), 12u + 4u);
  const auto types = data("types");
  EXPECT_EQ(types, std::vector<double>({42., 42.}));
  const auto faces   = data("faces");
  const auto offsets = data("faceoffsets");
  ASSERT_EQ(offsets.size(), 2u);
  EXPECT_EQ(offsets.back(), double(faces.size()));
  std::size_t k = 0;
  for (std::size_t c = 0; c < 2; ++c)
    {
      Polyhedron p;
      p.vertices = points;
      for (auto &v : p.vertices)
        v -= origin;
      const int n_faces = int(faces[k++]);
      for (int f = 0; f < n_faces; ++f)
        {
          std::vector<int> face(int(faces[k++]));
          for (auto &i : face)
            i = int(faces[k++]);
          p.faces.push_back(face);
        }
      EXPECT_EQ(double(k), offsets[c]);
      const double V = s.blocks[c].polyhedron.signed_volume();
      EXPECT_NEAR(p.signed_volume(), V, 1e-12 * V) << "block " << c;
    }
  EXPECT_EQ(data("block_id"), std::vector<double>({1., 2.}));
  EXPECT_EQ(data("stress").size(), 12u);
}



TEST(Dda3dOutput, Hdf5SnapshotIsTheBlocksClosedSurfaces)
{
  // The blocks of PolyhedraVtuRoundTrip (a non-convex prism and a
  // tetrahedron at UTM coordinates) through the HDF5 writer and reader of
  // large scenes: one polygon cell per face, each with its block's fields.
  // The faces of each block, read back, must enclose its volume by the
  // divergence theorem (V = sum over the faces' fan triangles of
  // a . (b x c) / 6, about the block's first point so that the UTM offset
  // does not cancel): to 1e-9 of V, the 17 digits of the coordinates at
  // 4e6 m against a 1 m block; faces of the wrong orientation or a missing
  // one would change V by O(1).
  BlockSystem s         = output_blocks();
  s.blocks[1].stress[4] = 7.5e5;
  const Point       origin(5e5, 4e6, 0.);
  const std::string path
    = (std::filesystem::temp_directory_path()
       / ("rockdda-dda3d-hdf5-" + std::to_string(::getpid()) + ".h5"))
        .string();
  dda::Snapshot contacts;
  contacts.lines = true;
  dda::write_snapshot_hdf5(path, 0.25, blocks_snapshot(s, origin), contacts);
  const dda::Snapshot back = dda::read_snapshot_hdf5(path, "blocks");
  EXPECT_DOUBLE_EQ(dda::read_snapshot_time(path), 0.25);
  std::filesystem::remove(path);
  const std::size_t n_faces
    = s.blocks[0].polyhedron.faces.size() + s.blocks[1].polyhedron.faces.size();
  ASSERT_EQ(back.n_cells(), n_faces);
  const auto field = [&](const std::string &name) {
    for (const auto &f : back.fields)
      if (f.name == name)
        return f;
    ADD_FAILURE() << "no field " << name;
    return dda::SnapshotField{};
  };
  const auto id     = field("block_id");
  const auto stress = field("stress");
  ASSERT_EQ(id.integer.size(), n_faces);
  ASSERT_EQ(stress.real.size(), 6 * n_faces);
  std::map<int, double> volume;
  std::map<int, Point>  reference;
  std::int64_t          first = 0;
  for (std::size_t c = 0; c < back.n_cells(); ++c)
    {
      const auto point = [&](const std::int64_t k) {
        return Point(back.xyz[3 * k], back.xyz[3 * k + 1], back.xyz[3 * k + 2]);
      };
      const int b = id.integer[c];
      if (!reference.count(b))
        reference[b] = point(first);
      const Point o = reference[b];
      for (std::int64_t k = first + 1; k + 1 < back.offsets[c]; ++k)
        volume[b]
          += (point(first) - o).dot((point(k) - o).cross(point(k + 1) - o))
             / 6.;
      EXPECT_EQ(stress.real[6 * c + 4], b == 2 ? 7.5e5 : 0.) << "face " << c;
      first = back.offsets[c];
    }
  for (const auto &b : s.blocks)
    {
      const double V = b.polyhedron.signed_volume();
      std::printf("block %d: volume %.15g m^3 from its faces, %.15g m^3\n",
                  b.id,
                  volume[b.id],
                  V);
      EXPECT_NEAR(volume[b.id], V, 1e-9 * V) << "block " << b.id;
    }
}



// ---------------------------------------------------------------------------
// Contacts: detection, Mohr-Coulomb springs, open-close iteration.

namespace
{
  /// The polyhedron @p p rotated by @p R about the origin and shifted.
  Polyhedron
  moved(const Polyhedron &p, const Eigen::Matrix3d &R, const Point &shift)
  {
    return transformed(p, R, shift);
  }

  /// Number of candidates of each type.
  std::pair<int, int>
  count_types(const std::vector<ContactCandidate> &c)
  {
    int vf = 0, ee = 0;
    for (const auto &x : c)
      (x.type == ContactType::vertex_face ? vf : ee)++;
    return {vf, ee};
  }

  /// Result of the block-on-incline scene.
  struct InclineRun
  {
    /// Displacement of the slider's centroid down the slope, and its
    /// largest component across the slope (m).
    double along = 0., across = 0.;
    /// Sum of the normal forces at the last and the previous step (N), the
    /// slider's weight (N).
    double normal = 0., normal_previous = 0., weight = 0.;
    /// Largest energy balance over the run (J) and m g size (J).
    double max_balance = -1e300, energy_scale = 0.;
    int    cuts = 0, steps = 0;
  };

  /**
   * A 1 m cube (rho 2700, E 10 GPa) on a clamped 6 x 3 x 1 m base whose
   * top is the plane z = 0 rotated by @p alpha_deg about y (dipping
   * towards +x), then rotated by @p R and shifted by @p shift; friction
   * @p phi_deg.
   */
  test_scenes::InclineScene
  slider_scene(const double           alpha_deg,
               const double           phi_deg,
               const Eigen::Matrix3d &R     = Eigen::Matrix3d::Identity(),
               const Point           &shift = Point::Zero())
  {
    return test_scenes::incline_scene(alpha_deg,
                                      phi_deg,
                                      Point(-3., -1.5, -1.),
                                      Point(3., 1.5, 0.),
                                      Point(-2., -0.5, 0.),
                                      Point(-1., 0.5, 1.),
                                      {2700., 1e10, 0.25, 1},
                                      R,
                                      shift);
  }

  /**
   * The slider_scene() run with penalty 1e11 N/m (10 E x 1 m), dt @p dt,
   * to @p t_end.
   */
  InclineRun
  run_incline(const double           alpha_deg,
              const double           phi_deg,
              const double           t_end,
              const double           dt,
              const Eigen::Matrix3d &R     = Eigen::Matrix3d::Identity(),
              const Point           &shift = Point::Zero(),
              const std::function<void(EngineControls &)> &tune = {})
  {
    const auto             Sc = slider_scene(alpha_deg, phi_deg, R, shift);
    const Eigen::Matrix3d &Q  = Sc.frame;
    const BlockSystem     &s  = Sc.system;
    EngineControls         c;
    c.dt                 = dt;
    c.law.normal_penalty = 1e11;
    if (tune)
      tune(c);
    Engine     engine(s, c);
    InclineRun out;
    out.weight       = 2700. * 9.80665;
    out.energy_scale = out.weight * 1.;
    while (engine.time() < t_end - 1e-9)
      {
        engine.advance_to(std::min(t_end, engine.time() + dt));
        out.max_balance = std::max(out.max_balance, engine.energy().balance());
        out.cuts += engine.statistics().cuts;
        ++out.steps;
        out.normal_previous = out.normal;
        out.normal          = 0.;
        for (const auto &ct : engine.contacts())
          out.normal += ct.state == ContactState::open ? 0. : ct.normal_force;
      }
    EXPECT_TRUE(engine.clamped(0));
    const Point down = Q * Point::UnitX(), across = Q * Point::UnitY();
    const Point d = engine.displacement(1);
    out.along     = d.dot(down);
    out.across    = std::abs(d.dot(across));
    return out;
  }
} // namespace



TEST(Dda3dContacts, BroadPhaseFindsExactlyTheOverlappingPairs)
{
  // 400 random boxes of mixed sizes (and one huge one) against the O(N^2)
  // check.
  std::mt19937                           rng(7);
  std::uniform_real_distribution<double> u(0., 20.), e(0.1, 2.);
  std::vector<BoundingBox>               boxes;
  for (int k = 0; k < 400; ++k)
    {
      BoundingBox b;
      b.lo = Point(u(rng), u(rng), u(rng));
      b.hi = b.lo + Point(e(rng), e(rng), e(rng));
      boxes.push_back(b);
    }
  boxes.push_back({Point(-1., -1., -1.), Point(21., 21., 0.5)});
  boxes.push_back({Point(0., 0., 0.), Point(1., 1., 1.)});
  boxes.push_back({Point(1., 0., 0.), Point(2., 1., 1.)}); // touching
  const auto                       pairs = broad_phase(boxes);
  std::vector<std::pair<int, int>> brute;
  for (int i = 0; i < int(boxes.size()); ++i)
    for (int j = i + 1; j < int(boxes.size()); ++j)
      if (!((boxes[i].hi.array() < boxes[j].lo.array()).any()
            || (boxes[j].hi.array() < boxes[i].lo.array()).any()))
        brute.emplace_back(i, j);
  std::printf("broad phase: %zu pairs (brute force %zu)\n",
              pairs.size(),
              brute.size());
  EXPECT_EQ(pairs, brute);
}



TEST(Dda3dContacts, NarrowPhaseContactTypesAndEntranceRules)
{
  DetectionTolerances tol;
  const Polyhedron    base = make_box(Point(-2., -2., -1.), Point(2., 2., 0.));
  // A small box on a large one: its 4 bottom corners on the top face.
  {
    const Polyhedron top = make_box(Point(-0.5, -0.5, 0.), Point(0.5, 0.5, 1.));
    const auto       c   = detect_contacts({&base, &top}, tol);
    EXPECT_EQ(count_types(c), std::make_pair(4, 0));
    for (const auto &x : c)
      {
        EXPECT_EQ(x.i, 1);
        EXPECT_NEAR(x.gap, 0., 1e-15);
        EXPECT_NEAR((x.normal - Point::UnitZ()).norm(), 0., 1e-15);
      }
  }
  // Flush equal boxes (vertex-vertex at every corner): one contact per
  // corner, not the 3 faces at each corner of either block.
  {
    const Polyhedron a = make_box(Point(0., 0., 0.), Point(1., 1., 1.));
    const Polyhedron b = make_box(Point(0., 0., 1.), Point(1., 1., 2.));
    const auto       c = detect_contacts({&a, &b}, tol);
    EXPECT_EQ(count_types(c), std::make_pair(4, 0));
    for (const auto &x : c)
      EXPECT_NEAR(std::abs(x.normal.z()), 1., 1e-15);
  }
  // The same box turned 45 deg about z on the other: the 8 crossings of
  // the edges (edge-edge, normal +z), no corner on a face.
  {
    const Polyhedron a = make_box(Point(-0.5, -0.5, -1.), Point(0.5, 0.5, 0.));
    Eigen::Matrix3d  Rz;
    Rz = Eigen::AngleAxisd(pi / 4., Point::UnitZ());
    const Polyhedron b
      = moved(make_box(Point(-0.5, -0.5, 0.), Point(0.5, 0.5, 1.)),
              Rz,
              Point::Zero());
    const auto c = detect_contacts({&a, &b}, tol);
    EXPECT_EQ(count_types(c), std::make_pair(0, 8));
    for (const auto &x : c)
      {
        EXPECT_NEAR(x.gap, 0., 1e-15);
        // out of the lower block (j) towards the upper (i)
        EXPECT_NEAR((x.normal * (x.i == 1 ? 1. : -1.) - Point::UnitZ()).norm(),
                    0.,
                    1e-12);
      }
  }
  // Two boxes crossing edge on edge (rotated 90 deg about each other's
  // edge direction, like crossed beams on their edges): one edge-edge
  // contact with the normal along the cross product; then penetrated by
  // 1 mm: the gap is -1 mm.
  for (const double pen : {0., 1e-3})
    {
      Eigen::Matrix3d Rx, Ry;
      Rx                 = Eigen::AngleAxisd(pi / 4., Point::UnitX());
      Ry                 = Eigen::AngleAxisd(pi / 4., Point::UnitY());
      const double     h = std::sqrt(0.5);
      const Polyhedron a
        = moved(make_box(Point(-2., -0.5, -0.5), Point(2., 0.5, 0.5)),
                Rx,
                Point(0., 0., -h + pen / 2.));
      const Polyhedron b
        = moved(make_box(Point(-0.5, -2., -0.5), Point(0.5, 2., 0.5)),
                Ry,
                Point(0., 0., h - pen / 2.));
      const auto c = detect_contacts({&a, &b}, tol);
      ASSERT_EQ(count_types(c), std::make_pair(0, 1));
      EXPECT_NEAR(c[0].gap, -pen, 1e-14);
      EXPECT_NEAR(std::abs(c[0].normal.z()), 1., 1e-14);
      EXPECT_NEAR(c[0].p.norm(), pen / 2., 1e-14);
    }
  // A tetrahedron's apex 1 mm into the top face: a penetrated vertex-face
  // contact (the apex's edges enter the face); the same apex 1 mm above.
  for (const double z : {-1e-3, 1e-3})
    {
      const Polyhedron t = make_tetrahedron(Point(0., 0., z),
                                            Point(1., 0., 1.),
                                            Point(-0.5, 0.8, 1.),
                                            Point(-0.5, -0.8, 1.));
      const auto       c = detect_contacts({&base, &t}, tol);
      ASSERT_EQ(count_types(c), std::make_pair(1, 0));
      EXPECT_NEAR(c[0].gap, z, 1e-15);
      EXPECT_GT(c[0].score, 0.);
    }
  // Far apart: nothing.
  {
    const Polyhedron t = make_box(Point(-0.5, -0.5, 1.), Point(0.5, 0.5, 2.));
    EXPECT_TRUE(detect_contacts({&base, &t}, tol).empty());
  }
}



TEST(Dda3dContacts, BlockOnInclineBelowTheFrictionAngleSlides)
{
  // alpha = 30 deg, phi = 20 deg: x(t) = 1/2 g (sin a - cos a tan phi) t^2.
  // Shi's scheme integrates a constant acceleration exactly and friction
  // is implicit through the open-close iteration, so the error is the
  // start-up transient (the penalty compresses by W / p = 2.6e-7 m and the
  // first step's state changes), far below the 1 % asked.
  const double a = 30. * pi / 180., phi = 20. * pi / 180.;
  const double exact
    = 0.5 * 9.80665 * (std::sin(a) - std::cos(a) * std::tan(phi));
  const auto   r = run_incline(30., 20., 1., 0.005);
  const double e = std::abs(r.along - exact) / exact;
  std::printf("incline 30/20: slide %.9f m, exact %.9f m, rel. error %.2e, "
              "across %.2e m, normal force / weight cos a %.6f, %d steps, "
              "%d cuts, max balance %.2e J (m g size %.2e J)\n",
              r.along,
              exact,
              e,
              r.across,
              r.normal / (r.weight * std::cos(a)),
              r.steps,
              r.cuts,
              r.max_balance,
              r.energy_scale);
  EXPECT_LT(e, 1e-2);
  EXPECT_LT(r.across, 1e-9);
  // Energy: Shi's scheme and friction may only dissipate.
  EXPECT_LT(r.max_balance, 1e-6 * r.energy_scale);
}



TEST(Dda3dContacts, IterationKnobsKeepTheInclineSolutions)
{
  // The optional parts of the open-close iteration, written once for both
  // engines and off by default in 3D: the exact line search
  // (dda/line_search.h), the relaxed friction iteration
  // (dda::FrictionRelaxation) and inexact CG solves confirmed by an exact
  // one (Inexact solve factor 1000). With each, the block on the incline
  // still slides by 1/2 g (sin a - cos a tan phi) t^2 within 1 % below the
  // friction angle and stays within 1e-6 m above it, and the ledger never
  // gains energy.
  const double a = 30. * pi / 180., phi = 20. * pi / 180.;
  const double exact
    = 0.5 * 9.80665 * (std::sin(a) - std::cos(a) * std::tan(phi));
  const Eigen::Matrix3d I = Eigen::Matrix3d::Identity();
  const std::vector<
    std::pair<const char *, std::function<void(EngineControls &)>>>
    knobs{{"line search", [](EngineControls &c) { c.line_search = true; }},
          {"friction relaxation",
           [](EngineControls &c) { c.friction_relaxation = true; }},
          {"inexact CG", [](EngineControls &c) {
             c.solver.type    = dda::SolverType::iterative;
             c.inexact_factor = 1000.;
           }}};
  for (const auto &[name, tune] : knobs)
    {
      SCOPED_TRACE(name);
      const auto slides
        = run_incline(30., 20., 1., 0.005, I, Point::Zero(), tune);
      const auto stays
        = run_incline(20., 30., 1., 0.005, I, Point::Zero(), tune);
      const double e = std::abs(slides.along - exact) / exact;
      std::printf("%s: incline 30/20 slide %.9f m (exact %.9f m, error "
                  "%.2e, %d cuts), 20/30 %.2e m\n",
                  name,
                  slides.along,
                  exact,
                  e,
                  slides.cuts,
                  stays.along);
      EXPECT_LT(e, 1e-2);
      EXPECT_LT(std::abs(stays.along), 1e-6);
      EXPECT_LT(slides.max_balance, 1e-6 * slides.energy_scale);
      EXPECT_LT(stays.max_balance, 1e-6 * stays.energy_scale);
    }
}



TEST(Dda3dContacts, AnOutputTimeDoesNotShortenTheTimeStep)
{
  // The step control shared with 2D (dda::TimeStepControl): a step
  // shortened to land on an output time does not shorten the steps after
  // it. The slider of the test above is advanced to 0.3 dt (one short
  // step), then by one dt per advance_to() call for 0.5 s: each call must
  // take exactly one step of dt, and the slide still follows
  // 1/2 g (sin a - cos a tan phi) t^2 within 1 %. (Before the control was
  // shared, the 3D engine grew its next step from the shortened one: each
  // call then took 2-3 steps of 0.3-0.5 dt for the rest of the run.)
  const double   a = 30. * pi / 180., phi = 20. * pi / 180., dt = 0.005;
  const auto     Sc = slider_scene(30., 20.);
  EngineControls c;
  c.dt                 = dt;
  c.law.normal_penalty = 1e11;
  Engine engine(Sc.system, c);
  engine.advance_to(0.3 * dt);
  EXPECT_EQ(engine.n_steps, 1ul);
  EXPECT_EQ(engine.time_step(), dt);
  const int calls = 100;
  for (int k = 0; k < calls; ++k)
    engine.advance_to(engine.time() + dt);
  EXPECT_EQ(engine.n_steps, 1ul + calls);
  EXPECT_EQ(engine.n_cuts, 0ul);
  const double t = engine.time();
  const double exact
    = 0.5 * 9.80665 * (std::sin(a) - std::cos(a) * std::tan(phi)) * t * t;
  const double along = engine.displacement(1).dot(Sc.frame * Point::UnitX());
  std::printf("incline 30/20 from an output at 0.3 dt: %lu steps to t = %.4f "
              "s, slide %.9f m, exact %.9f m\n",
              engine.n_steps,
              t,
              along,
              exact);
  EXPECT_NEAR(along, exact, 1e-2 * exact);
}



TEST(Dda3dContacts, FixedPointSpringIsInTheEnergyLedger)
{
  // A free unit cube held at its centroid by one fixed point (not clamped:
  // it needs 3) on a soft spring p = m omega^2, omega = 10 rad/s, set off
  // at v0 = 0.1 m/s: a harmonic oscillator, 1/2 m v^2 + 1/2 p x^2 = 1/2 m
  // v0^2. The ledger shared with 2D (dda::EnergyLedger) books the spring
  // (its `fixed` term): over half a period (omega dt = 0.01) the balance
  // never rises above its start and falls only by the scheme's numerical
  // dissipation (Newmark gamma = 1, damping ratio omega dt / 4: pi omega
  // dt / 2 = 1.6 % of the energy over half a period; measured 1.57 %,
  // bound 3 %). Without the term the balance fell by the whole 1/2 m v0^2
  // at the quarter period, where the energy is all in the spring.
  BlockSystem  s = one_block(make_box(Point(0., 0., 0.), Point(1., 1., 1.)));
  const double m = 2700., omega = 10., v0 = 0.1, dt = 1e-3;
  s.blocks[0].velocity.head<3>() = Point(v0, 0., 0.);
  s.fixed_points.push_back({0, Point(0.5, 0.5, 0.5), Point::Zero()});
  EngineControls c;
  c.dt            = dt;
  c.fixed_penalty = m * omega * omega;
  Engine       engine(s, c);
  const double k0 = 0.5 * m * v0 * v0, b0 = engine.energy().balance();
  double       rise = 0., fall = 0., spring_max = 0.;
  while (engine.time() < pi / omega - 1e-9)
    {
      engine.advance_to(engine.time() + dt);
      const auto e = engine.energy();
      rise         = std::max(rise, e.balance() - b0);
      fall         = std::max(fall, b0 - e.balance());
      spring_max   = std::max(spring_max, e.fixed);
    }
  std::printf("fixed-point oscillator: spring energy up to %.4f of 1/2 m v0^2,"
              " balance rose by %.1e and fell by %.2e of it\n",
              spring_max / k0,
              rise / k0,
              fall / k0);
  EXPECT_GT(spring_max, 0.95 * k0);
  EXPECT_LT(rise, 1e-9 * k0);
  EXPECT_LT(fall, 0.03 * k0);
}



TEST(Dda3dContacts, BlockOnInclineAboveTheFrictionAngleStays)
{
  // alpha = 20 deg, phi = 30 deg: the block must stay. What it may move is
  // the elastic compliance of the contact springs and of the block under
  // its own weight: W sin(a) / (4 p_s) = 2.3e-8 m (shear springs, 4
  // corners) plus the shear strain of the block, ~W sin(a) / (G A) x h/2 =
  // 4.5e-7 m at the centroid, below the 1e-6 m asked.
  const auto r = run_incline(20., 30., 1., 0.005);
  std::printf("incline 20/30: displacement down the slope %.3e m, across "
              "%.2e m, %d steps, %d cuts\n",
              r.along,
              r.across,
              r.steps,
              r.cuts);
  EXPECT_LT(std::abs(r.along), 1e-6);
}



TEST(Dda3dContacts, BlockRestingOnAFixedBlockCarriesItsWeight)
{
  // alpha = 0: the normal forces carry the weight; no energy is gained.
  // The contact mode is stiff (omega dt = sqrt(4 p / m) dt = 60), where
  // Shi's update v' = 2 D / dt - v leaves a residual velocity that changes
  // sign every step (amplification -1 as omega dt -> infinity): the force
  // of one step is W +- 2 m v / dt (measured 1e-4 W), and the mean of two
  // consecutive steps is W + m (v_k+1 - v_k-1) / (2 dt): the slow part of
  // the start-up transient (the block's elastic vibration), 1.7e-6 W at
  // 1 s; bound 1e-5 W.
  const auto   r    = run_incline(0., 30., 1., 0.005);
  const double mean = 0.5 * (r.normal + r.normal_previous);
  std::printf("resting block: normal force / weight - 1 = %.3e (last step), "
              "%.3e (mean of the last two), settlement %.3e m, max balance "
              "%.2e J (m g size %.2e J)\n",
              r.normal / r.weight - 1.,
              mean / r.weight - 1.,
              r.along,
              r.max_balance,
              r.energy_scale);
  EXPECT_NEAR(mean / r.weight, 1., 1e-5);
  EXPECT_NEAR(r.normal / r.weight, 1., 1e-3);
  // Energy: never above its initial 0 beyond round-off.
  EXPECT_LT(r.max_balance, 1e-9 * r.energy_scale);
}



TEST(Dda3dContacts, InclineInUtmCoordinatesAndRotatedGivesTheSameAnswer)
{
  // The 30/20 incline moved to UTM (5e5, 4e6, 0), rotated (37 deg about z,
  // then 10 deg about x; gravity rotated with it), and both. The engine
  // works about a local origin (an exact shift) and nothing in it depends
  // on the frame: a shift or a rotation alone changes the slide by
  // round-off (bound 1e-9 m). Rotated coordinates at UTM are rounded to
  // ulp(4e6) = 4.7e-10 m, which perturbs the geometry (initial gaps
  // +-3e-11 m, the mirror symmetry) at that level; the slide depends on
  // the geometry at first order, so the bound is 1e-8 m (20 ulp). New
  // contacts count as closed within the round-off of the global
  // coordinates (4 eps |origin|), otherwise half the corners started
  // open and the start-up transient changed the slide by 1.5e-4 m.
  Eigen::Matrix3d R;
  R = Eigen::AngleAxisd(37. * pi / 180., Point::UnitZ())
      * Eigen::AngleAxisd(10. * pi / 180., Point::UnitX());
  const Point utm(5e5, 4e6, 0.);
  const auto  r0 = run_incline(30., 20., 1., 0.005);
  const auto  rs
    = run_incline(30., 20., 1., 0.005, Eigen::Matrix3d::Identity(), utm);
  const auto   rr = run_incline(30., 20., 1., 0.005, R);
  const auto   rb = run_incline(30., 20., 1., 0.005, R, utm);
  const double a = 30. * pi / 180., phi = 20. * pi / 180.;
  const double exact
    = 0.5 * 9.80665 * (std::sin(a) - std::cos(a) * std::tan(phi));
  std::printf("incline: slide %.12f m; at UTM %.3e m different, rotated "
              "%.3e m, both %.3e m (%.2e relative; against the exact "
              "%.2e and %.2e)\n",
              r0.along,
              rs.along - r0.along,
              rr.along - r0.along,
              rb.along - r0.along,
              (rb.along - r0.along) / r0.along,
              (r0.along - exact) / exact,
              (rb.along - exact) / exact);
  EXPECT_LT(std::abs(rs.along - r0.along), 1e-9);
  EXPECT_LT(std::abs(rr.along - r0.along), 1e-9);
  EXPECT_LT(std::abs(rb.along - r0.along), 1e-8);
  EXPECT_LT(rb.across, 1e-6);
}



TEST(Dda3dContacts, SymmetricWedgeSlidesAlongTheIntersectionLine)
{
  // A triangular prism in a V-trough: planes through the trough's axis at
  // beta = 30 deg to the horizontal across it, the axis plunging psi = 30
  // deg towards +x, friction phi = 15 deg on both. Rigid-block answer
  // (analytical::slide_3d, double-face sliding; the same as the closed form
  // a = g (sin psi - cos psi tan phi / cos beta)): 1.14 m at 1 s. Two
  // clamped trough blocks, the prism (E 10 GPa, p = 1e11 N/m), dt 5 ms.
  // Measured: 3.0e-6. Before the sliding direction of a face group was
  // corrected within the step, the first step slid along the locked
  // springs' trial force, which in a wedge includes the wedging across the
  // axis: an error first order in dt (2.8e-3, 1.4e-3, 7.1e-4 at dt = 5,
  // 2.5, 1.25 ms). Bound 1e-3 (the issue asks 1 %): ten times the start-up
  // error of the incline (7.5e-5). Energy: at most 1e-5 of the energy
  // released (measured 2e-6: the contact energy of the last iteration).
  const double beta = 30. * pi / 180., psi = 30. * pi / 180.;
  const double phi_deg = 15., L = 1., w = 0.5;
  const double tb = std::tan(beta);
  const Point  nA(0., -std::sin(beta), std::cos(beta)),
    nB(0., std::sin(beta), std::cos(beta));
  BlockSystem s;
  s.materials.push_back({2700., 1e10, 0.25, 1});
  dda::JointMaterial joint;
  joint.friction_deg = phi_deg;
  s.joints.push_back(joint);
  Eigen::Matrix3d R;
  R        = Eigen::AngleAxisd(psi, Point::UnitY());
  auto add = [&](const Polyhedron &p, const int id) {
    Block b;
    b.id         = id;
    b.material   = 0;
    b.polyhedron = moved(p, R, Point::Zero());
    s.blocks.push_back(b);
  };
  // Trough block A (y >= 0, below plane A) and B (mirror).
  add(clip_convex(make_box(Point(-1., 0., -1.),
                           Point(L + 2., 2. * w, 2. * w * tb)),
                  {{nA, 0.}}),
      1);
  add(clip_convex(make_box(Point(-1., -2. * w, -1.),
                           Point(L + 2., 0., 2. * w * tb)),
                  {{nB, 0.}}),
      2);
  // The wedge: above both planes, below z = w tan(beta).
  add(clip_convex(make_box(Point(0., -w, 0.), Point(L, w, w * tb)),
                  {{-nA, 0.}, {-nB, 0.}}),
      3);
  for (const int b : {0, 1})
    for (const Point &p :
         {Point(0., 0.5, -0.5), Point(2., 0.5, -0.5), Point(1., 0.8, -0.8)})
      s.fixed_points.push_back(
        {b, R * Point(p.x(), b == 0 ? p.y() : -p.y(), p.z()), Point::Zero()});
  EngineControls c;
  c.dt                 = 0.005;
  c.law.normal_penalty = 1e11;
  Engine engine(s, c);
  double max_balance = -1e300;
  int    cuts        = 0;
  while (engine.time() < 1. - 1e-9)
    {
      engine.advance_to(std::min(1., engine.time() + c.dt));
      max_balance = std::max(max_balance, engine.energy().balance());
      cuts += engine.statistics().cuts;
    }
  const Point d = engine.displacement(2);

  // The analytical wedge: the planes' dip and dip direction (x east,
  // y north) from their upward normals in the scene.
  analytical::Sliding3dOptions o;
  o.wedge    = true;
  auto plane = [&](const Point &n_local) {
    const Point              n = R * n_local;
    analytical::SlidingPlane p;
    p.dip_deg           = std::acos(n.z()) * 180. / pi;
    p.dip_direction_deg = std::atan2(n.x(), n.y()) * 180. / pi;
    if (p.dip_direction_deg < 0.)
      p.dip_direction_deg += 360.;
    p.friction = analytical::FrictionLaw::coulomb_deg(phi_deg);
    EXPECT_LT(
      (analytical::plane_normal(p.dip_deg, p.dip_direction_deg) - n).norm(),
      1e-12);
    return p;
  };
  o.plane1    = plane(nA);
  o.plane2    = plane(nB);
  o.time_step = 1e-3;
  o.duration  = 1.;
  const auto exact
    = analytical::slide_3d([](double) { return Eigen::Vector3d(0., 0., -1.); },
                           o);
  const double a_closed
    = 9.80665
      * (std::sin(psi)
         - std::cos(psi) * std::tan(phi_deg * pi / 180.) / std::cos(beta));
  const double e
    = (d - exact.final_displacement).norm() / exact.final_displacement.norm();
  std::printf("wedge: DDA (%.6f, %.6f, %.6f) m, slide_3d (%.6f, %.6f, %.6f) m "
              "(mode %s; closed form %.6f m), rel. error %.2e, %d cuts, "
              "max balance %.2e J of %.2e J released, contacts o/s/l %d %d "
              "%d\n",
              d.x(),
              d.y(),
              d.z(),
              exact.final_displacement.x(),
              exact.final_displacement.y(),
              exact.final_displacement.z(),
              analytical::to_string(exact.final_mode),
              0.5 * a_closed,
              e,
              cuts,
              max_balance,
              -2700. * engine.scene().blocks[2].polyhedron.moments().volume
                * 9.80665 * d.z(),
              engine.statistics().open,
              engine.statistics().sliding,
              engine.statistics().locked);
  EXPECT_EQ(exact.final_mode, analytical::SlidingMode::wedge);
  EXPECT_NEAR(exact.final_displacement.norm(), 0.5 * a_closed, 1e-6 * a_closed);
  EXPECT_LT(e, 1e-3);
  const double released = -engine.scene().materials[0].density
                          * engine.scene().blocks[2].polyhedron.moments().volume
                          * 9.80665 * d.z();
  EXPECT_LT(max_balance, 1e-5 * released);
}



namespace
{
  /// The scene of a tetrahedral wedge (joints 1, 2, slope face, height 1 m,
  /// E = 10 GPa) in its clamped trough (wedge_in_trough_scene()), friction
  /// @p phi_deg on both joints.
  BlockSystem
  wedge_scene(const WedgePlanes &planes, const double phi_deg)
  {
    dda::JointMaterial joint;
    joint.friction_deg = phi_deg;
    return wedge_in_trough_scene(make_wedge_in_trough(planes, 1., 0.5),
                                 {2700., 1e10, 0.25, 1},
                                 joint);
  }
} // namespace



TEST(Dda3dContacts, HoekBrayWedgeStartsToSlideAtTheLimitFrictionAngle)
{
  // Hoek & Bray's asymmetric wedge (Rock Slope Engineering, the wedge
  // example: joints 45/105 and 70/235, slope face 65/185, here with a
  // horizontal top; height 1 m). Limit equilibrium with both joints in
  // contact and phi on both: the weight W (0, 0, -1) is held by
  // N1 n1 + N2 n2 + F e = W (0, 0, 1), e down the line of intersection, so
  // F = W e_z and the factor of safety (N1 + N2) tan(phi) / |F| is 1 at
  // tan(phi_LE) = |F| / (N1 + N2), solved here in closed form (and checked
  // against analytical::critical_friction_angle_wedge(), which bisects the
  // static test of slide_3d()).
  const double j1 = 45., d1 = 105., j2 = 70., d2 = 235.;
  const Point  n1 = analytical::plane_normal(j1, d1),
              n2  = analytical::plane_normal(j2, d2);
  Point e         = n1.cross(n2).normalized();
  if (e.z() > 0.)
    e = -e;
  Eigen::Matrix3d A;
  A << n1, n2, e;
  const Point  NF = A.partialPivLu().solve(Point(0., 0., 1.));
  const double phi_le
    = std::atan(std::abs(NF[2]) / (NF[0] + NF[1])) * 180. / pi;
  ASSERT_GT(NF[0], 0.); // both joints in contact
  ASSERT_GT(NF[1], 0.);
  const double phi_yield
    = analytical::critical_friction_angle_wedge(j1, d1, j2, d2, 0., 0.);
  EXPECT_NEAR(phi_yield, phi_le, 1e-9);

  // "Slides": the wedge's centroid moves more than delta in T = 0.4 s after
  // 20 static settling steps. A wedge that holds moves by the elastic
  // compliance of its contact springs, at most W / k_s (its whole weight on
  // one shear spring, k_s = 0.4 p) = 6e-8 m here; delta = 100 W / k_s. A
  // wedge that slides accelerates along e at a = g (|F| - tan(phi) (N1 +
  // N2)) and moves a T^2 / 2: at phi_LE - 0.5 deg that is 100 delta or
  // more (checked below), so the switch of the criterion lies within
  // about 0.01 deg of the DDA wedge's own limit angle. Bisection to 0.01
  // deg. Measured: 21.948 deg against phi_LE = 21.913 deg (0.035 deg; 12 runs
  // of 80 steps, 0.2 s).
  const double T = 0.4, g = 9.80665, p = 1e11;
  auto         run = [&](const double phi) {
    BlockSystem    s = wedge_scene({j1, d1, j2, d2, 65., 185.}, phi);
    EngineControls c;
    c.dt                 = 0.005;
    c.law.normal_penalty = p;
    Engine engine(s, c);
    engine.settle(20);
    engine.advance_to(T);
    return engine.displacement(2);
  };
  const BlockSystem probe = wedge_scene({j1, d1, j2, d2, 65., 185.}, 30.);
  const double      W = 2700. * probe.blocks[2].polyhedron.moments().volume * g;
  const double      delta = 100. * W / (0.4 * p);
  auto              accel = [&](const double phi_deg) {
    return g
           * (std::abs(NF[2])
              - std::tan(phi_deg * pi / 180.) * (NF[0] + NF[1]));
  };
  ASSERT_GT(0.5 * accel(phi_le - 0.5) * T * T, 100. * delta);

  // Bisection on phi in DDA, from a bracket of +-4 deg about phi_LE.
  double      lo = phi_le - 4., hi = phi_le + 4.; // lo slides, hi holds
  const auto  start = std::chrono::steady_clock::now();
  const Point d_lo = run(lo), d_hi = run(hi);
  ASSERT_GT(d_lo.norm(), delta);
  ASSERT_LT(d_hi.norm(), delta);
  // The wedge slides along the line of intersection (both joints).
  EXPECT_GT(d_lo.normalized().dot(e), 1. - 1e-6);
  int runs = 2;
  while (hi - lo > 0.01)
    {
      const double mid                    = 0.5 * (lo + hi);
      (run(mid).norm() > delta ? lo : hi) = mid;
      ++runs;
    }
  const double phi_dda = 0.5 * (lo + hi);
  const double wall
    = std::chrono::duration<double>(std::chrono::steady_clock::now() - start)
        .count();
  std::printf("Hoek-Bray wedge 45/105, 70/235: N1 = %.4f W, N2 = %.4f W, "
              "|F| = %.4f W, phi_LE = %.4f deg (yield.h %.4f deg); DDA "
              "limit %.3f deg (bracket %.3f-%.3f), difference %.3f deg, "
              "delta %.2e m, slide at phi_LE - 4 deg %.4f m (rigid wedge %.4f "
              "m; along the line: %.8f), at phi_LE + 4 deg %.2e m; %d runs, "
              "%.1f s\n",
              NF[0],
              NF[1],
              std::abs(NF[2]),
              phi_le,
              phi_yield,
              phi_dda,
              lo,
              hi,
              phi_dda - phi_le,
              delta,
              d_lo.norm(),
              0.5 * accel(phi_le - 4.) * T * T,
              d_lo.normalized().dot(e),
              d_hi.norm(),
              runs,
              wall);
  EXPECT_NEAR(phi_dda, phi_le, 0.5);
  // The slide 4 deg below the limit against the rigid wedge's a T^2 / 2
  // (constant acceleration from rest after settling: Shi's scheme
  // integrates it exactly; 1 % as the issue asks of the wedge).
  const double rigid = 0.5 * accel(phi_le - 4.) * T * T;
  EXPECT_NEAR(d_lo.norm(), rigid, 0.01 * rigid);
}



TEST(Dda3dContacts, LightWedgeOnStiffContactsYieldsAtTheYieldAcceleration)
{
  // The shaking-table wedge (joints 51.4/065.8 and 51.4/295.2, height 0.1
  // m: 0.78 kg, W = 7.7 N; E = 200 GPa), phi = 26.754 deg (k_y = 0.14 g
  // along the line's trend 000.5), under a constant horizontal inertial
  // load k_y -+ 0.01 g down the line (loading mode) for 0.3 s after 20
  // settling steps, at penalties of 1e10 N/m to 1e13 N/m (the thesis's 10
  // GN/m to 1e3 x). Below k_y the wedge holds (elastic slip only: W /
  // k_s < 2e-9 m); above it slides at the rigid wedge's acceleration a =
  // g (|F| - tan(phi) (N1 + N2)) (the closed-form wedge statics, as in
  // HoekBrayWedgeStartsToSlideAtTheLimitFrictionAngle), within 2 % of
  // a T^2 / 2 = 3.6 mm. The state check's force tolerance was once
  // k_n x 1e-12 x the block size: 0.2 N = 2.6 % of W per contact at
  // 1e12 N/m, and the wedge held at k_y + 0.01 g (slide 0 at 1e12 and
  // 1e13 N/m).
  const double phi = 26.754, az = 0.5 * pi / 180., g = 9.80665, T = 0.3;
  const Point  n1 = analytical::plane_normal(51.4, 65.8),
              n2  = analytical::plane_normal(51.4, 295.2);
  Point e         = n1.cross(n2).normalized();
  if (e.z() > 0.)
    e = -e;
  const Point     h(std::sin(az), std::cos(az), 0.);
  Eigen::Matrix3d A;
  A << n1, n2, e;
  const double ky = 0.14;
  ASSERT_NEAR(
    analytical::critical_friction_angle_wedge(51.4, 65.8, 51.4, 295.2, 0.5, ky),
    phi,
    1e-3);
  dda::JointMaterial joint;
  joint.friction_deg      = phi;
  const BlockSystem scene = wedge_in_trough_scene(
    make_wedge_in_trough({51.4, 65.8, 51.4, 295.2, 80., 0.5}, 0.1, 0.1),
    {1700., 2e11, 0.25, 1},
    joint);
  for (const double p : {1e10, 1e12, 1e13})
    for (const double dk : {-0.01, 0.01})
      {
        const double k = ky + dk;
        // Rigid wedge: N1 n1 + N2 n2 + F e = -(k h - z).
        const Point  x = A.partialPivLu().solve(-(k * h - Point::UnitZ()));
        const double a = std::max(
          0., g * (std::abs(x[2]) - std::tan(phi * pi / 180.) * (x[0] + x[1])));
        EngineControls c;
        c.dt                  = 0.005;
        c.law.normal_penalty  = p;
        c.ground_acceleration = [&](double) { return Point(-k * g * h); };
        Engine engine(scene, c);
        engine.settle(20);
        engine.advance_to(T);
        const Point  d     = engine.displacement(2);
        const double rigid = 0.5 * a * T * T;
        std::printf("light wedge, penalty %.0e N/m, k = k_y %+.2f g: slide "
                    "%.4e m along the line (rigid wedge %.4e m), %.1e m "
                    "across\n",
                    p,
                    dk,
                    d.dot(e),
                    rigid,
                    (d - d.dot(e) * e).norm());
        if (dk < 0.)
          EXPECT_LT(d.norm(), 1e-6) << p;
        else
          EXPECT_NEAR(d.dot(e), rigid, 0.02 * rigid) << p;
      }
}



TEST(Dda3dContacts, FaceGroupSticksAndSlidesAsARigidBlock)
{
  // A 1 m cube (rho 2700, W = 26.5 kN) on a clamped level base, friction 30
  // deg, pushed by a horizontal load F at its centroid (0.5 m above the
  // base) for 0.3 s: its 4 corner springs form one face group. The load's
  // moment F / 2 shifts the normal forces to W / 4 +- F / 4 (front, rear)
  // while the equal corner springs share the shear, F / 4 each: from F =
  // mu W / (1 + mu) on, the rear corners carry more than their own
  // strength mu (W - F) / 4, although the face as a whole (sum of the
  // strengths mu W) holds the cube up to F = mu W; the cube tips only at F
  // = W. A rigid block: at F = 0.95 mu W it sticks: it may move by the
  // elastic F / (4 p_s) + ~F / (G A) x 1/2 = 1.8e-6 m (1e10 N/m), twice
  // that under the suddenly applied load, and by the start-up transient of
  // Shi's scheme in the stiff contact modes; bound 1e-4 m, 1 % of what a 5
  // % overload slides in the same time. At F = 1.05 mu W it slides at a =
  // (F - mu W) / m, x = a T^2 / 2 = 12.7 mm, within 1 % (the contacts'
  // elastic slip and the start-up transient are below 1e-5 m). Physics at
  // every accepted step: all 4 corners closed, none in tension beyond its
  // force tolerance, the group's shear resultant within Mohr-Coulomb,
  // |sum F_s| <= mu sum N + 4 tolerances. No flip-flop: no step is cut and
  // none needs more than the state-change budget (12 open-close
  // iterations). Each corner against its own strength alone (printed, not
  // asserted), the cube at 1e13 N/m and 0.95 mu W slid 1.9 mm, its corners
  // opened at some step and steps took up to 23 iterations.
  const double mu = std::tan(30. * pi / 180.), g = 9.80665, T = 0.3;
  const double m = 2700., W = m * g, tolerance = 1e-4 * W;
  const auto   scene = test_scenes::incline_scene(0.,
                                                30.,
                                                Point(-3., -1.5, -1.),
                                                Point(3., 1.5, 0.),
                                                Point(-0.5, -0.5, 0.),
                                                Point(0.5, 0.5, 1.));
  for (const bool group : {true, false})
    for (const double p : {1e10, 1e11, 1e12, 1e13})
      for (const double ratio : {0.95, 1.05})
        {
          BlockSystem s = scene.system;
          s.load_points.push_back(
            {1, Point(0., 0., 0.5), Point(ratio * mu * W, 0., 0.)});
          EngineControls c;
          c.dt                  = 0.005;
          c.law.normal_penalty  = p;
          c.face_group_friction = group;
          Engine engine(s, c);
          int    max_iterations = 0, closed_min = 4;
          double tension = 0., excess = -1e300;
          bool   failed = false;
          try
            {
              while (engine.time() < T - 1e-9)
                {
                  engine.advance_to(std::min(T, engine.time() + c.dt));
                  max_iterations = std::max(max_iterations,
                                            engine.statistics().iterations
                                              + 100 * engine.statistics().cuts);
                  Point  shear   = Point::Zero();
                  double normal  = 0.;
                  int    closed  = 0;
                  for (const auto &ct : engine.contacts())
                    if (ct.state != ContactState::open)
                      {
                        tension = std::max(tension, -ct.normal_force);
                        shear += ct.shear_force;
                        normal += ct.normal_force;
                        ++closed;
                      }
                  closed_min = std::min(closed_min, closed);
                  excess     = std::max(excess, shear.norm() - mu * normal);
                }
            }
          catch (const dda::DdaFailure &e)
            {
              failed = true;
              std::printf("  failed: %s\n", e.what());
            }
          const double x = engine.displacement(1).x();
          const double rigid
            = ratio > 1. ? 0.5 * (ratio - 1.) * mu * g * T * T : 0.;
          std::printf("face group, %s, penalty %.0e N/m, F = %.2f mu W: slide "
                      "%.6e m (rigid block %.6e m), at most %d open-close "
                      "iterations per step (+100 per cut), %d closed corners "
                      "at least, tension %.1e W, |sum F_s| - mu sum N = %.1e "
                      "W\n",
                      group ? "shared strength" : "per corner",
                      p,
                      ratio,
                      x,
                      rigid,
                      max_iterations,
                      closed_min,
                      tension / W,
                      excess / W);
          if (!group)
            continue; // the per-corner rule: printed for comparison
          ASSERT_FALSE(failed) << p;
          if (ratio < 1.)
            EXPECT_LT(engine.displacement(1).norm(), 1e-4) << p;
          else
            EXPECT_NEAR(x, rigid, 0.01 * rigid) << p;
          EXPECT_EQ(closed_min, 4) << p;
          EXPECT_LE(tension, tolerance) << p;
          EXPECT_LE(excess, 4. * tolerance) << p;
          EXPECT_LE(max_iterations, c.max_open_close) << p;
        }
}



TEST(Dda3dOutput, ContactsVtuMatchesTheEngine)
{
  // The 30/20 incline after 1 s (200 steps): one line cell per contact of the
  // engine, with its state, blocks, forces and detection points; the file
  // is the 2D engine's binary format (read back by tests/unit/vtu_reader.h).
  const auto sc
    = slider_scene(30., 20., Eigen::Matrix3d::Identity(), Point(5e5, 4e6, 0.));
  EngineControls c;
  c.dt = 0.005;
  Engine engine(sc.system, c);
  engine.advance_to(1.);
  const auto &contacts = engine.contacts();
  ASSERT_EQ(contacts.size(), 4u);
  const test::Vtu vtu(contacts_vtu(engine));
  EXPECT_NE(vtu.text.find("<VTKFile type=\"UnstructuredGrid\""),
            std::string::npos);
  EXPECT_NE(vtu.text.find("NumberOfCells=\"4\""), std::string::npos);
  EXPECT_NE(vtu.text.find("0 open, 1 sliding, 2 locked"), std::string::npos);
  const auto xyz   = vtu["Points"].values<double>();
  const auto state = vtu["state"].values<std::int32_t>();
  const auto type  = vtu["type"].values<std::int32_t>();
  const auto bi    = vtu["block_i"].values<std::int32_t>();
  const auto bj    = vtu["block_j"].values<std::int32_t>();
  const auto gap   = vtu["normal_gap"].values<double>();
  const auto fn    = vtu["normal_force"].values<double>();
  const auto fs    = vtu["shear_force"].values<double>();
  ASSERT_EQ(xyz.size(), 6 * contacts.size());
  ASSERT_EQ(state.size(), contacts.size());
  ASSERT_EQ(fs.size(), 3 * contacts.size());
  double normal_sum = 0.;
  for (std::size_t k = 0; k < contacts.size(); ++k)
    {
      const auto &ct = contacts[k];
      EXPECT_EQ(state[k], int(ct.state));
      EXPECT_EQ(type[k], 0); // the slider's corners on the base's top
      EXPECT_EQ(bi[k], 2);
      EXPECT_EQ(bj[k], 1);
      EXPECT_EQ(gap[k], ct.geometry.gap);
      EXPECT_EQ(fn[k], ct.normal_force);
      for (int d = 0; d < 3; ++d)
        {
          EXPECT_EQ(fs[3 * k + d], ct.shear_force[d]);
          // Global coordinates: the local origin added back.
          EXPECT_EQ(xyz[6 * k + d], ct.geometry.p[d] + engine.origin()[d]);
          EXPECT_EQ(xyz[6 * k + 3 + d], ct.geometry.q[d] + engine.origin()[d]);
        }
      normal_sum += ct.state == ContactState::open ? 0. : fn[k];
    }
  // The file's normal forces carry the block's weight normal to the slope
  // within the start-up transient's residual (1.1e-4 at 1 s in
  // BlockOnInclineBelowTheFrictionAngleSlides; 6.6e-3 at 0.1 s): 1e-3.
  EXPECT_NEAR(normal_sum / (2700. * 9.80665 * std::cos(pi / 6.)), 1., 1e-3);
}



TEST(Dda3dSolvers, IterativeMatchesDirectAndThreadsDoNotMatter)
{
  // A 4 x 4 running-bond wall of 2 x 1 x 1 m bricks (18 and the clamped
  // base) shaken in loading mode (0.9 g at 5 Hz along the wall, 0.3 g at
  // 7 Hz across it), 80 dynamic steps of 1 ms: the top bricks start to
  // slide (tan 35 deg = 0.7 < 0.9) while the rest rocks on its springs.
  // The 12x12-block CG (D-ILU and block-Jacobi, the 2D engine's
  // LinearSolverOf<dofs>) must give the direct solver's block positions:
  // CG stops at a relative residual of 1e-8 (SolverOptions::tolerance), so
  // each step's increment (at most 1e-2 L, the displacement limit) is off
  // by ~1e-8 of it, and 80 steps add up to at most ~1e-8 L while the
  // contact states follow the same path (a state that flips differently
  // moves a brick by its elastic slip, ~W / k_s = 1e-6 m, or more).
  // Bound: 1e-8 L (measured: 1.9e-11 m D-ILU, 1.1e-12 m Jacobi; 5e-13 m
  // before the spin of a face in planar contact was resisted: a brick
  // whose side contacts are open is in planar contact). On 1 and 2 threads
  // (the D-ILU's two subdomains swept in parallel, ordering forced from 3
  // blocks on) the positions must agree bit for bit. So must they on a
  // 10 x 10 wall (106 blocks, ~1,100 contacts), whose contact detection,
  // kinematics and state checks run in chunks (128 contacts, 32 block
  // pairs) on the solver's threads, and so does the assembly of the
  // contact springs (8 blocks, 32 pairs of blocks: each diagonal block,
  // load and off-diagonal block summed by one chunk in contact order):
  // from 8 chunks on they run concurrently (TaskTeam), and the chunks write
  // disjoint data joined in order.
  const BlockSystem small_wall = test_scenes::brick_wall(4, 4);
  const double      L          = 1.; // the bricks' smallest dimension (m)
  struct Result
  {
    std::vector<Point> vertices;
    double             moved     = 0.;
    unsigned long      cg        = 0;
    int                separator = 0, sliding = 0, contacts = 0;
    /// Pairs of blocks in contact in the last step (off-diagonal blocks).
    int pairs = 0;
  };
  auto run = [&](const BlockSystem        &wall,
                 const dda::SolverType     type,
                 const dda::Preconditioner preconditioner,
                 const int                 threads,
                 const int                 subdomain_limit) {
    EngineControls c;
    c.dt                  = 1e-3;
    c.law.normal_penalty  = 1e11;
    c.ground_acceleration = [](const double t) {
      return Point(0.9 * 9.80665 * std::sin(2. * pi * 5. * t),
                   0.3 * 9.80665 * std::sin(2. * pi * 7. * t),
                   0.);
    };
    c.solver.type            = type;
    c.solver.preconditioner  = preconditioner;
    c.solver.threads         = threads;
    c.solver.subdomain_limit = subdomain_limit;
    Engine engine(wall, c);
    Result r;
    for (int k = 0; k < 80; ++k)
      {
        engine.step();
        r.cg += engine.statistics().solver_iterations;
      }
    EXPECT_EQ(engine.linear_solver().type(), type);
    for (const auto &b : engine.scene().blocks)
      for (const auto &v : b.polyhedron.vertices)
        r.vertices.push_back(v);
    for (std::size_t b = 0; b < wall.blocks.size(); ++b)
      r.moved = std::max(r.moved, engine.displacement(b).norm());
    std::set<std::pair<int, int>> pairs;
    for (const auto &ct : engine.contacts())
      if (!engine.clamped(ct.geometry.i) && !engine.clamped(ct.geometry.j))
        pairs.emplace(std::min(ct.geometry.i, ct.geometry.j),
                      std::max(ct.geometry.i, ct.geometry.j));
    r.pairs     = static_cast<int>(pairs.size());
    r.separator = engine.linear_solver().separator_size();
    r.sliding   = engine.statistics().sliding;
    r.contacts  = engine.statistics().open + engine.statistics().sliding
                 + engine.statistics().locked;
    return r;
  };
  auto difference = [](const Result &a, const Result &b) {
    double d = 0.;
    for (std::size_t k = 0; k < a.vertices.size(); ++k)
      d = std::max(d, (a.vertices[k] - b.vertices[k]).norm());
    return d;
  };
  const Result direct = run(small_wall,
                            dda::SolverType::direct,
                            dda::Preconditioner::block_dilu,
                            1,
                            300);
  std::printf("direct: largest centroid displacement %.3e m, %d sliding "
              "contacts at the end\n",
              direct.moved,
              direct.sliding);
  EXPECT_GT(direct.moved, 1e-5 * L); // the wall moves: the test can fail
  EXPECT_GT(direct.sliding, 0);
  EXPECT_EQ(direct.cg, 0u);
  for (const auto preconditioner :
       {dda::Preconditioner::block_dilu, dda::Preconditioner::block_jacobi})
    {
      const Result cg
        = run(small_wall, dda::SolverType::iterative, preconditioner, 1, 300);
      const double d = difference(direct, cg);
      std::printf("iterative (%s): %lu CG iterations, max vertex difference "
                  "from direct %.3e m\n",
                  preconditioner == dda::Preconditioner::block_dilu
                    ? "block-dilu"
                    : "block-jacobi",
                  cg.cg,
                  d);
      EXPECT_GT(cg.cg, 0u);
      EXPECT_LT(d, 1e-8 * L);
    }
  // The D-ILU CG on @p threads, two subdomains from @p limit blocks on.
  auto dilu = [&](const BlockSystem &w, const int threads, const int limit) {
    return run(w,
               dda::SolverType::iterative,
               dda::Preconditioner::block_dilu,
               threads,
               limit);
  };
  const Result one = dilu(small_wall, 1, 3);
  const Result two = dilu(small_wall, 2, 3);
  std::printf("two subdomains, separator of %d blocks: 1 vs 2 threads "
              "differ by %.3e m, from direct by %.3e m\n",
              one.separator,
              difference(one, two),
              difference(direct, one));
  EXPECT_GT(one.separator, 0);
  EXPECT_EQ(difference(one, two), 0.);
  EXPECT_LT(difference(direct, one), 1e-8 * L);

  const BlockSystem large_wall = test_scenes::brick_wall(10, 10);
  const Result      one_large  = dilu(large_wall, 1, 300);
  const Result      two_large  = dilu(large_wall, 2, 300);
  std::printf("106 blocks, %d contacts, %d pairs, %d sliding, largest "
              "displacement %.3e m: 1 vs 2 threads differ by %.3e m\n",
              one_large.contacts,
              one_large.pairs,
              one_large.sliding,
              one_large.moved,
              difference(one_large, two_large));
  // The loops do run on threads: >= 8 chunks of contacts, of blocks and of
  // pairs of blocks in contact.
  EXPECT_GE(one_large.contacts, 8 * 128);
  EXPECT_GE(large_wall.blocks.size(), 8u * 8u);
  EXPECT_GE(one_large.pairs, 8 * 32);
  EXPECT_GT(one_large.moved, 1e-5 * L);
  EXPECT_GT(one_large.sliding, 0);
  EXPECT_EQ(difference(one_large, two_large), 0.);
}



// Force continuity at lock, the rule of both engines (dda::lock_anchor(),
// doc/theory/dda.md "Force continuity at lock"; the 2D test is
// DdaRelockEnergy.ShakenStackNeverGainsEnergy): three 1 m x 1 m x 0.5 m
// boxes stacked on a clamped base (each shifted 0.1 m in x from the one
// below), friction 30 deg, joints with a shear stiffness in series with the
// penalty, shaken in loading mode by 1.5 g at 3 Hz horizontally and a
// vertical 7 Hz component. Their contacts slide into steps and lock while
// their normal forces swing within the step. A contact that locks takes the
// spring of the step's start; the time integration only dissipates, so the
// ledger's balance may not rise in a step beyond its residue across
// lock/slide changes. The bound is the 2D test's, 1 % of the energy in
// play.
TEST(Dda3dContacts, ShakenStackNeverGainsEnergyAtRelock)
{
  for (const auto &[joint_shear, vertical, dt] :
       {std::tuple{1e7, 0.9, 2e-3}, std::tuple{1e8, 0.6, 1e-3}})
    {
      SCOPED_TRACE("joint shear " + std::to_string(joint_shear) + " Pa/m");
      BlockSystem s;
      s.materials.push_back({2700., 1e10, 0.25, 1});
      dda::JointMaterial j;
      j.friction_deg    = 30.;
      j.shear_stiffness = joint_shear;
      s.joints.push_back(j);
      test_scenes::add_box_block(s, Point(-3., -2., -1.), Point(3., 2., 0.));
      for (const auto &v : s.blocks[0].polyhedron.vertices)
        s.fixed_points.push_back({0, v, Point::Zero()});
      for (int k = 0; k < 3; ++k)
        test_scenes::add_box_block(s,
                                   Point(-0.5 + 0.1 * k, -0.5, 0.5 * k),
                                   Point(0.5 + 0.1 * k, 0.5, 0.5 * k + 0.5));
      s.gravity = Point(0., 0., -9.80665);
      EngineControls c;
      c.dt                  = dt;
      c.law.normal_penalty  = 1e12;
      const double g        = 9.80665;
      const double v        = vertical;
      c.ground_acceleration = [g, v](const double t) {
        return Point(1.5 * g * std::sin(2. * pi * 3. * t),
                     0.,
                     v * g * std::sin(2. * pi * 7. * t + 0.3));
      };
      Engine       engine(s, c);
      double       worst_gain = -1e300;
      unsigned int relocks    = 0;
      while (engine.time() < 1.5 - 1e-9)
        {
          const double before = engine.energy().balance();
          engine.advance_to(engine.time() + dt);
          const auto e = engine.energy();
          worst_gain = std::max(worst_gain, (e.balance() - before) / e.scale());
          for (const auto &ct : engine.contacts())
            relocks += ct.state_at_start == ContactState::sliding
                       && ct.state == ContactState::locked;
        }
      std::printf("3D shaken stack, joint shear %.0e Pa/m: %u relocks, "
                  "largest gain of the balance in a step %.2e of the energy "
                  "in play\n",
                  joint_shear,
                  relocks,
                  worst_gain);
      EXPECT_GT(relocks, 10u);
      EXPECT_LE(worst_gain, 1e-2);
    }
}
