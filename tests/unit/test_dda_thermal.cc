/**
 * @file
 * Thermoelastic checks of the DDA eigenstrain load (issue 13): a free block
 * heated uniformly expands by alpha dT L without stress; a block confined
 * between fixed walls develops the plane-stress or plane-strain thermal
 * stress; a free beam cut into bonded triangles, with a temperature that
 * varies linearly across it, bends by the closed-form curvature alpha grad T
 * (second order in the triangle size) and equals the constant-strain
 * triangle (CST) finite-element solution of the same triangulation.
 */
#include <rockdda/dda/block_matrices.h>
#include <rockdda/dda/engine.h>

#include <Eigen/Dense>
#include <Eigen/Sparse>
#include <gtest/gtest.h>

#include "dda_test_scenes.h"
#include <array>
#include <cmath>
#include <vector>

using namespace rockdda;
using namespace rockdda::dda;
using namespace rockdda::dda::test_scenes;

namespace
{
  constexpr double young = 4e10, nu = 0.2, alpha = 8e-6, dT = 9.;

  /// A scene without gravity: one material (plane strain or stress).
  BlockSystem
  weightless_scene(const bool plane_strain)
  {
    BlockSystem s               = one_material_scene(2600., young, nu, 41.);
    s.materials[0].plane_strain = plane_strain;
    s.gravity                   = Point::Zero();
    return s;
  }

  /// Quasi-static controls: static steps of 1 s (the inertia term 2 M /
  /// dt^2 is 1e-7 of the stiffness of a metre-sized block).
  Controls
  quasi_static(const double penalty)
  {
    Controls c = controls(1., 0., penalty);
    return c;
  }

  /// A block L x H (index 1) between two fixed frictionless walls (0 and
  /// 2), taller than the block: x is held, y free.
  BlockSystem
  confined_scene(const bool plane_strain, const double L, const double H)
  {
    BlockSystem s            = weightless_scene(plane_strain);
    s.joints[0].friction_deg = 0.;
    const int w1             = add_block(s, rectangle(-1., -1., 1., H + 2.));
    add_block(s, rectangle(0., 0., L, H));
    const int w2 = add_block(s, rectangle(L, -1., 1., H + 2.));
    fix_block(s, w1);
    fix_block(s, w2);
    return s;
  }

  /// Set the same free thermal strain alpha dT on every block that is not
  /// fixed and take @p steps static steps.
  void
  heat_uniformly(DdaSystem               &dda,
                 const std::vector<char> &heated,
                 const unsigned int       steps)
  {
    std::vector<Eigen::Vector3d> e(dda.system().blocks.size(),
                                   Eigen::Vector3d::Zero());
    for (std::size_t b = 0; b < e.size(); ++b)
      if (heated[b] != 0)
        e[b] = thermal_eigenstrain(
          dda.system().materials[dda.system().blocks[b].material], alpha * dT);
    dda.set_eigenstrains(e);
    for (unsigned int k = 0; k < steps; ++k)
      dda.step();
  }

  /// Triangles of an nx x ny grid of a beam L x h: each cell is cut along
  /// alternating diagonals (a pattern with 4 and 8 triangles at the nodes).
  std::vector<std::array<Point, 3>>
  triangulated_beam(const double L, const double h, const int nx, const int ny)
  {
    std::vector<std::array<Point, 3>> t;
    const double                      dx = L / nx, dy = h / ny;
    for (int i = 0; i < nx; ++i)
      for (int j = 0; j < ny; ++j)
        {
          const Point a(i * dx, j * dy), b((i + 1) * dx, j * dy),
            c((i + 1) * dx, (j + 1) * dy), d(i * dx, (j + 1) * dy);
          if ((i + j) % 2 == 0)
            {
              t.push_back({{a, b, c}});
              t.push_back({{a, c, d}});
            }
          else
            {
              t.push_back({{a, b, d}});
              t.push_back({{b, c, d}});
            }
        }
    return t;
  }

  /// Curvature -v'' of the least-squares parabola v(x) through the
  /// deflections @p v at the abscissae @p x.
  double
  fitted_curvature(const std::vector<double> &x, const std::vector<double> &v)
  {
    Eigen::MatrixXd a(x.size(), 3);
    Eigen::VectorXd r(x.size());
    for (std::size_t k = 0; k < x.size(); ++k)
      {
        a.row(k) << 1., x[k], x[k] * x[k];
        r[k] = v[k];
      }
    return -2. * a.colPivHouseholderQr().solve(r)[2];
  }

  /**
   * The constant-strain-triangle (CST) finite-element solution of the same
   * free beam (plane stress, eigenstrain of each triangle at its centroid,
   * three displacement components fixed against rigid motion): the
   * curvature of its mid-line.
   */
  double
  cst_curvature(const std::vector<std::array<Point, 3>> &triangles,
                const double                             h,
                const double                             gradient)
  {
    // Nodes by position (the grid's vertices are exact binary fractions).
    std::vector<Point> nodes;
    auto               node = [&nodes](const Point &p) {
      for (std::size_t k = 0; k < nodes.size(); ++k)
        if ((nodes[k] - p).norm() < 1e-12)
          return static_cast<int>(k);
      nodes.push_back(p);
      return static_cast<int>(nodes.size() - 1);
    };
    const double    c = young / (1. - nu * nu);
    Eigen::Matrix3d elastic;
    elastic << c, c * nu, 0., c * nu, c, 0., 0., 0., c * (1. - nu) / 2.;
    std::vector<Eigen::Triplet<double>> k;
    std::vector<std::array<int, 3>>     ids;
    for (const auto &t : triangles)
      ids.push_back({{node(t[0]), node(t[1]), node(t[2])}});
    const int       n = 2 * static_cast<int>(nodes.size());
    Eigen::VectorXd f = Eigen::VectorXd::Zero(n);
    for (std::size_t e = 0; e < triangles.size(); ++e)
      {
        const auto  &p    = triangles[e];
        const double area = 0.5
                            * ((p[1] - p[0]).x() * (p[2] - p[0]).y()
                               - (p[1] - p[0]).y() * (p[2] - p[0]).x());
        Eigen::Matrix<double, 3, 6> b = Eigen::Matrix<double, 3, 6>::Zero();
        for (int m = 0; m < 3; ++m)
          {
            const Point &q = p[(m + 1) % 3], &r = p[(m + 2) % 3];
            const double by = q.y() - r.y(), bx = r.x() - q.x();
            b(0, 2 * m)     = by / (2. * area);
            b(1, 2 * m + 1) = bx / (2. * area);
            b(2, 2 * m)     = bx / (2. * area);
            b(2, 2 * m + 1) = by / (2. * area);
          }
        const double          yc = (p[0].y() + p[1].y() + p[2].y()) / 3.;
        const Eigen::Vector3d eps
          = alpha * gradient * (yc - 0.5 * h) * Eigen::Vector3d(1., 1., 0.);
        const Eigen::Matrix<double, 6, 6> ke
          = area * b.transpose() * elastic * b;
        const Eigen::Matrix<double, 6, 1> fe
          = area * b.transpose() * elastic * eps;
        for (int r = 0; r < 6; ++r)
          {
            const int gr = 2 * ids[e][r / 2] + r % 2;
            f[gr] += fe[r];
            for (int s = 0; s < 6; ++s)
              k.emplace_back(gr, 2 * ids[e][s / 2] + s % 2, ke(r, s));
          }
      }
    // Rigid motion: fix the node at (0, 0) and the vertical motion of the
    // node at the right end of the bottom face (a large diagonal term).
    int right = 0;
    for (std::size_t m = 0; m < nodes.size(); ++m)
      if (nodes[m].y() == 0. && nodes[m].x() > nodes[right].x())
        right = static_cast<int>(m);
    const int origin = node(Point(0., 0.));
    for (const int d : {2 * origin, 2 * origin + 1, 2 * right + 1})
      k.emplace_back(d, d, 1e6 * young);
    Eigen::SparseMatrix<double> km(n, n);
    km.setFromTriplets(k.begin(), k.end());
    const Eigen::VectorXd u
      = Eigen::SimplicialLDLT<Eigen::SparseMatrix<double>>(km).solve(f);
    std::vector<double> x, v;
    for (std::size_t m = 0; m < nodes.size(); ++m)
      if (std::abs(nodes[m].y() - 0.5 * h) < 1e-12)
        {
          x.push_back(nodes[m].x());
          v.push_back(u[2 * m + 1]);
        }
    return fitted_curvature(x, v);
  }
} // namespace



// A free block, heated uniformly, expands by alpha dT L (plane stress) or
// (1 + nu) alpha dT L (plane strain: the out-of-plane strain is held at
// zero) with no stress. The quasi-static step leaves a residual of the
// inertia term, 1e-7 per step; after 3 steps the error is round-off.
TEST(DdaThermal, FreeBlockExpandsWithoutStress)
{
  for (const bool plane_strain : {false, true})
    {
      BlockSystem s = weightless_scene(plane_strain);
      add_block(s, rectangle(100., 50., 7., 15.));
      DdaSystem dda(s, quasi_static(40. * young));
      heat_uniformly(dda, {1}, 3);
      const auto  &p        = dda.system().blocks[0].polygon.vertices;
      const double expected = (plane_strain ? 1. + nu : 1.) * alpha * dT;
      const double width    = (p[1] - p[0]).norm();
      const double height   = (p[3] - p[0]).norm();
      EXPECT_NEAR(width / 7. - 1., expected, 1e-6 * expected);
      EXPECT_NEAR(height / 15. - 1., expected, 1e-6 * expected);
      EXPECT_LT(dda.system().blocks[0].stress.norm(),
                1e-6 * young * alpha * dT);
      // The centroid stays put (no load but the eigenstrain).
      EXPECT_LT(dda.centroid_displacement(0).norm(), 1e-9 * 15.);
    }
}



// A free block whose eigenstrain cycles (24 static steps per cycle, 50
// cycles, amplitude 1e-3) returns to the same size at the end of every
// cycle: eigenstrain_step applies the change multiplicatively, so its sides
// are 1 + e times their initial length whatever the path. Applied as the
// difference e - a to the current geometry, each cycle shortened them by
// half the sum of the squared increments, 24 (4e-3 / 24)^2 / 2 = 3.3e-7
// per cycle: 1.7e-5 after 50 cycles (Block 1's top tilted by 7.5e-9 m per
// year). Within a step a static step lags the exact size by the inertia
// term's share, 2 M / (dt^2 A E) = 2.4e-6 of the increment (2.6e-4):
// 6.3e-10 (measured 6.04e-10, asserted 1e-9).
TEST(DdaThermal, CycledFreeBlockDoesNotDrift)
{
  BlockSystem s = weightless_scene(false);
  add_block(s, rectangle(100., 50., 7., 15.));
  DdaSystem    dda(s, quasi_static(40. * young));
  const double amplitude = 1e-3;
  double       worst = 0., first_cycle = 0., last_cycle = 0.;
  for (int k = 1; k <= 24 * 50; ++k)
    {
      const double e = amplitude * std::sin(2. * M_PI * k / 24.);
      dda.set_eigenstrains({thermal_eigenstrain(s.materials[0], e)});
      dda.step();
      const auto  &p     = dda.system().blocks[0].polygon.vertices;
      const double error = (p[1] - p[0]).norm() / 7. - (1. + e);
      worst              = std::max({worst,
                                     std::abs(error),
                                     std::abs((p[3] - p[0]).norm() / 15. - (1. + e))});
      if (k == 24)
        first_cycle = error;
      last_cycle = error;
    }
  EXPECT_LT(worst, 1e-9);
  EXPECT_LT(std::abs(last_cycle - first_cycle), 1e-12); // measured 8e-14
}



// A block between two fixed frictionless walls (x confined, y free) develops
// sigma_x = -E alpha dT (plane stress) or -E alpha dT / (1 - nu) (plane
// strain), reduced by the compliance of the contact springs in series:
// each face carries two vertex springs p, so a face force sigma H shortens
// the block by 2 sigma H / (2 p) = sigma H / p, and
// sigma = sigma_0 / (1 + E' H / (p L)), E' = E (stress) or E / (1 - nu^2)
// (strain). Asserted within 1 % of sigma_0 with a penalty of 1000 E' (the
// series correction is then 1e-3) and within 1e-6 of the series formula.
TEST(DdaThermal, ConfinedBlockDevelopsThermalStress)
{
  for (const bool plane_strain : {false, true})
    {
      const double      L = 7., H = 15.;
      const BlockSystem s       = confined_scene(plane_strain, L, H);
      const int         b       = 1;
      const double      e_plane = plane_strain ? young / (1. - nu * nu) : young;
      const double      p       = 1000. * e_plane;
      DdaSystem         dda(s, quasi_static(p));
      heat_uniformly(dda, {0, 1, 0}, 6);
      // The stress takes the eigenstrain as the logarithmic strain
      // log(1 + e) of the free stretch 1 + e (e = alpha dT, or (1 + nu)
      // alpha dT in plane strain; doc/theory/dda.md, "Strain update"):
      // sigma_0 = -E' log(1 + e) = -E alpha dT (1 - e / 2 + ...) in plane
      // stress, -E alpha dT / (1 - nu) (...) in plane strain, the linear
      // results to 4e-5.
      const double free_strain = (plane_strain ? 1. + nu : 1.) * alpha * dT;
      const double sigma_0     = -e_plane * std::log1p(free_strain);
      const double series      = sigma_0 / (1. + e_plane * H / (p * L));
      const auto  &stress      = dda.system().blocks[b].stress;
      EXPECT_NEAR(stress[0], sigma_0, 0.01 * std::abs(sigma_0));
      EXPECT_NEAR(stress[0], series, 1e-6 * std::abs(sigma_0));
      EXPECT_NEAR(stress[1], 0., 1e-6 * std::abs(sigma_0));
      EXPECT_NEAR(stress[2], 0., 1e-6 * std::abs(sigma_0));
      // The ledger counts the eigenstrain's work, -A sigma_mid . d eps*,
      // with the area at the start of the step, while the stored strain
      // energy uses the block's area now, larger by the area strain
      // (1 + nu) alpha dT at most: that is the small-strain ledger's only
      // error here (a created energy would be of the order of the scale).
      const EnergyLedger e = dda.energy();
      EXPECT_LE(e.balance(), 2. * (1. + nu) * alpha * dT * e.scale());
      EXPECT_GT(e.strain, 0.);
    }
}



// A block confined between two fixed frictionless walls (x held, y free)
// under a cycled eigenstrain e(t) (24 static steps per cycle, amplitude
// 1e-3, 40 cycles): its height follows e (1 + nu) (plane stress) and returns
// to the same value at the end of every cycle. The elastic (Poisson) part of
// each step's strain is not a thermal ratio: with the stress adding the
// increments d themselves, a cycle returned the stress to its start while
// the shape, a product of the stretches 1 + d, shrank by
// 1 - sum d^2 / 2 - sum a d (a the thermal ratios), (nu + nu^2 / 2) sum de^2
// ~ 1e-7 of the height per cycle (measured: 2.9e-5 m from cycle 1 to 40;
// the ratchet's crack closed by 1.6e-9 m a year so). With the stress adding
// log(1 + d), it is a function of the shape, and the shape returns with it:
// asserted 1e-12 of the height between cycles 1 and 40.
TEST(DdaThermal, ConfinedCycledBlockDoesNotDrift)
{
  const double      L = 7., H = 15.;
  const BlockSystem s = confined_scene(false, L, H);
  const int         b = 1;
  DdaSystem         dda(s, quasi_static(1000. * young));
  const double      amplitude = 1e-3;
  const auto        height    = [&]() {
    const auto &p = dda.system().blocks[b].polygon.vertices;
    return 0.5 * ((p[3] - p[0]).norm() + (p[2] - p[1]).norm());
  };
  double first_cycle = 0., last_cycle = 0., swing = 0.;
  for (int k = 1; k <= 24 * 40; ++k)
    {
      const double e = amplitude * std::sin(2. * M_PI * k / 24.);
      dda.set_eigenstrains({Eigen::Vector3d::Zero(),
                            thermal_eigenstrain(s.materials[0], e),
                            Eigen::Vector3d::Zero()});
      dda.step();
      if (k == 6)
        swing = height() / H - 1.;
      if (k == 24)
        first_cycle = height();
      last_cycle = height();
    }
  // The quarter cycle's height: (1 + nu) e less the walls' compliance.
  EXPECT_NEAR(swing, (1. + nu) * amplitude, 1e-3 * amplitude);
  EXPECT_LT(std::abs(last_cycle - first_cycle), 1e-12 * H);
}



// A free beam (L x h = 4 m x 1 m, plane stress, weightless) cut into bonded
// triangles (square cells of h / n, halved along alternating diagonals),
// with a temperature varying linearly across it (gradient g; each triangle
// takes the eigenstrain of its centroid), bends by kappa = alpha g (a
// linear temperature in a free beam is stress-free: Timoshenko & Goodier,
// Theory of Elasticity, thermal stress in beams). A first-order block carries
// one uniform strain, so a triangle is exactly a CST element and bonded
// triangles (vertex-to-edge springs at the shared nodes) are a CST mesh in the
// penalty limit: the DDA curvature must equal the CST finite-element curvature
// of the same mesh up to the penalty compliance (E / p = 1e-2 of a node's
// relative motion; measured 6e-6 to 3e-5 relative, asserted 1e-3), and converge
// to alpha g at second order in h / n (the CST mesh converges at O(h^2) in this
// stress-free problem: measured errors 15.5 %, 4.3 %, 1.1 % for n = 4, 8, 16).
// The issue asks for 2 % at the finest. (Rectangular sub-blocks cannot do this:
// opposite faces of a first-order block stay parallel, so a grid of rectangles
// only bends by the penalty's compliance, kappa / (alpha g) = 0.007 at p = 1000
// E for n = 8: doc/theory/coupling.md.)
TEST(DdaThermal, TriangulatedBeamBendsByAlphaGradT)
{
  const double L = 4., h = 1., gradient = 10. / h; // 10 K across the beam
  const double kappa = alpha * gradient;
  std::vector<double> error;
  for (const int n : {4, 8, 16})
    {
      const auto  triangles = triangulated_beam(L, h, 4 * n, n);
      BlockSystem s         = weightless_scene(false);
      s.joints[0].cohesion  = 1e12; // bonded: never opens or slides
      s.joints[0].tensile   = 1e12;
      for (const auto &t : triangles)
        add_block(s, polygon({t[0], t[1], t[2]}));
      // The direct solver: CG's residual (1e-8) does not resolve the rigid
      // modes, whose only stiffness here is the inertia term 2 M / dt^2,
      // 1e-11 of the contacts'.
      Controls c    = quasi_static(100. * young);
      c.solver.type = SolverType::direct;
      DdaSystem                    dda(s, c);
      std::vector<Eigen::Vector3d> e;
      for (const auto &t : triangles)
        e.push_back(thermal_eigenstrain(
          s.materials[0],
          alpha * gradient
            * ((t[0].y() + t[1].y() + t[2].y()) / 3. - 0.5 * h)));
      dda.set_eigenstrains(e);
      // Four static steps: the beam has bent after the second (later steps
      // change the curvature by < 1e-6 of it). No force but the contacts'
      // acts on the free beam, so in a static step the inertia terms
      // (2 / dt^2) M_b D_b balance the contacts' net force and moment. Each
      // contact's two forces act at one point (the vertex), so the moment of
      // sum_b M_b D_b about any point is zero up to the solve's round-off,
      // eps x the condition 1e11 of the rigid modes: measured 2e-6 to 4e-5
      // of the bending step's scale in that step, 1e-10 after it; asserted
      // 1e-4 and, summed over the three later steps, 1e-6. (With block j's
      // point at the vertex's projection on the edge, a gap away, each shear
      // pair was a couple: the beam turned as a rigid body by 8e-8 rad per
      // step for n = 4, a moment of 2.5e-3, 6e-4, 1.6e-4 of the bending
      // step's scale in every later step for n = 4, 8, 16.)
      double bending_scale = 0., later = 0.;
      for (int k = 0; k < 4; ++k)
        {
          std::vector<BlockMoments> start;
          Point                     C = Point::Zero();
          for (const auto &b : dda.system().blocks)
            {
              start.push_back(block_moments(b.polygon));
              C += start.back().centroid / double(s.blocks.size());
            }
          dda.step();
          double moment = 0., scale = 0.;
          for (std::size_t b = 0; b < start.size(); ++b)
            {
              const Vector6 f = mass_matrix(start[b], s.materials[0].density)
                                * dda.last_increments().segment<6>(6 * b);
              const Point r = start[b].centroid - C;
              moment += r.x() * f[1] - r.y() * f[0] + f[2];
              scale += std::abs(r.x() * f[1]) + std::abs(r.y() * f[0])
                       + std::abs(f[2]);
            }
          if (k == 0)
            {
              bending_scale = scale;
              EXPECT_LT(std::abs(moment), 1e-4 * scale) << "n = " << n;
            }
          else
            later += std::abs(moment);
        }
      EXPECT_LT(later, 1e-6 * bending_scale) << "n = " << n;
      std::vector<double> x, v;
      for (std::size_t b = 0; b < s.blocks.size(); ++b)
        for (std::size_t m = 0; m < 3; ++m)
          {
            const Point &p0 = s.blocks[b].polygon.vertices[m];
            if (std::abs(p0.y() - 0.5 * h) < 1e-12)
              {
                x.push_back(p0.x());
                v.push_back(dda.system().blocks[b].polygon.vertices[m].y()
                            - p0.y());
              }
          }
      const double dda_kappa = fitted_curvature(x, v);
      const double cst_kappa = cst_curvature(triangles, h, gradient);
      EXPECT_NEAR(dda_kappa, cst_kappa, 1e-3 * cst_kappa) << "n = " << n;
      error.push_back(std::abs(dda_kappa / kappa - 1.));
    }
  EXPECT_LT(error.back(), 0.02);
  // Second order: each halving of the triangles divides the error by > 3.
  EXPECT_GT(error[0] / error[1], 3.);
  EXPECT_GT(error[1] / error[2], 3.);
}



namespace
{
  /// The thermal ratchet reduced to its mechanism: a block (L x H) on a
  /// fixed flat base, a fixed cliff whose face leans back by (w_t - w_b) over
  /// H, and (optionally) a wedge between them. The block is cooled by
  /// -dT_w and warmed back, in static steps; returns per cycle the
  /// block's centroid slip, the wedge's descent times the crack's taper and
  /// the energy ledger's gain over the cycle.
  struct RatchetCycle
  {
    double slip, descent_x_taper, ledger_gain, scale;
  };

  std::vector<RatchetCycle>
  minimal_ratchet(const bool   wedge,
                  const double penalty,
                  const int    cycles,
                  const Point &shift = Point::Zero())
  {
    const double L = 4., H = 4., wt = 0.1, wb = 0.02;
    BlockSystem  s    = one_material_scene(2600., young, nu, 40.);
    const int    base = add_block(s, rectangle(-2., -1., L + 4., 1.));
    fix_block(s, base);
    // The cliff's face: x = -wb - (wt - wb) y / H.
    const auto xc = [&](const double y) { return -wb - (wt - wb) * y / H; };
    const int  cliff
      = add_block(s, polygon({{-2., 0.}, {xc(0.), 0.}, {xc(H), H}, {-2., H}}));
    fix_block(s, cliff);
    const int blk = add_block(s, rectangle(0., 0., L, H));
    const int w
      = wedge ? add_block(
          s, polygon({{xc(2.5), 2.5}, {0., 2.5}, {0., 3.5}, {xc(3.5), 3.5}}))
              : -1;
    for (auto &b : s.blocks)
      b.polygon = translated(b.polygon, shift);
    for (auto &f : s.fixed_points)
      f.point += shift;
    Controls c       = controls(1., 0., penalty);
    c.max_iterations = 30;
    c.cycle_limit    = 24;
    DdaSystem dda(s, c);
    dda.settle(50);
    const double tolerance   = 1e-9 * H;
    const auto   equilibrate = [&](const double free_strain) {
      std::vector<Eigen::Vector3d> e(dda.system().blocks.size(),
                                     Eigen::Vector3d::Zero());
      e[blk] = thermal_eigenstrain(dda.system().materials[0], free_strain);
      dda.set_eigenstrains(e);
      for (int k = 0; k < 5000; ++k)
        {
          const StepReport r = dda.step();
          if (r.max_displacement <= tolerance && r.cuts == 0)
            return;
        }
      ADD_FAILURE() << "no equilibrium";
    };
    std::vector<RatchetCycle> out;
    double                    last = 0., last_descent = 0.;
    for (int k = 0; k < cycles; ++k)
      {
        const double e0 = dda.energy().balance();
        for (int j = 1; j <= 20; ++j)
          equilibrate(-alpha * 10. * 0.5 * (1. - std::cos(M_PI * j / 10.)));
        const double x = dda.centroid_displacement(blk)[0];
        const double d
          = wedge ? -dda.centroid_displacement(w)[1] * (wt - wb) / H : 0.;
        const auto e = dda.energy();
        out.push_back(
          {x - last, d - last_descent, e.balance() - e0, e.scale()});
        last         = x;
        last_descent = d;
      }
    return out;
  }
} // namespace



// Pasten's ratchet in its simplest exact form. A block on a flat base with
// uniform friction contracts about its centre: cooled by dT its back face
// retreats by alpha dT L / 2 (plane stress here), and a wedge falls into
// the gap (descent = retreat / taper). Warmed back, the block cannot
// expand backwards past the wedge: all of its expansion goes forward, and
// its centre advances by the retreat. The slip per cycle is alpha dT L / 2
// less the elastic shortening by the force that drags the block over its
// base (mu W L / (2 E H) = 4 um, 2.6 %), and never more than the retreat.
// The first three cycles are the wedge's seating (the block lags the wedge
// by up to 7e-6 m and catches up); from the fourth on the slip equals the
// wedge's descent times the taper, up to the change of the block's elastic
// length between the ends of two cycles, which the drag bounds: mu W L /
// (2 E H) = 4.3 um, 2.7 % of the retreat (measured within 1.2e-7 m here and
// 3.0e-6 m in UTM coordinates: which end takes how much of a contraction
// is round-off sensitive, see below). The static path splits each contraction
// between the two ends only to within a few per cent (cycles of 1.53-1.57e-4
// m, and at 100 E one of 0.98e-4 in ten), hence 10 % for the mean. It does
// not depend on the penalty (10 and 100 x E) or on where the scene sits,
// nothing slips without the wedge, and no cycle creates energy.
TEST(DdaThermal, WedgeRatchetAdvancesByTheBackFacesRetreat)
{
  const double exact = alpha * 10. * 4. / 2.;
  // The drag's elastic shortening mu W L / (2 E H), L = H = 4 m.
  const double shortening
    = std::tan(40. * M_PI / 180.) * 2600. * g_earth * 4. * 4. / (2. * young);
  for (const double penalty : {10. * young, 100. * young})
    {
      const auto cycles = minimal_ratchet(true, penalty, 7);
      double     mean   = 0.;
      for (std::size_t k = 0; k < cycles.size(); ++k)
        {
          const auto &c = cycles[k];
          EXPECT_LE(c.ledger_gain, 1e-9 * c.scale) << k;
          if (k < 3)
            continue;
          mean += c.slip / (cycles.size() - 3);
          EXPECT_NEAR(c.slip, c.descent_x_taper, shortening) << k;
          EXPECT_GT(c.slip, 0.) << k;
          EXPECT_LT(c.slip, exact * (1. + 1e-3)) << k;
        }
      EXPECT_NEAR(mean, exact, 0.1 * exact) << penalty;
    }
  for (const auto &c : minimal_ratchet(false, 10. * young, 3))
    EXPECT_LT(std::abs(c.slip), 0.01 * exact);
  // The same scene in UTM coordinates (the engine works relative to a
  // local origin) ratchets by the same law. Not cycle by cycle: the
  // coordinates' representation moves the vertices by ~1e-11 m, and how a
  // frictional block splits its contraction between its two ends in the
  // static path is that sensitive (measured: cycle 1 agrees to 5e-4, cycle
  // 2 differs by 8 %). So the ratchet law, not the sequence, is compared.
  const auto utm  = minimal_ratchet(true, 10. * young, 7, Point(5e5, 4e6));
  double     mean = 0.;
  for (std::size_t k = 3; k < utm.size(); ++k)
    {
      mean += utm[k].slip / (utm.size() - 3);
      EXPECT_NEAR(utm[k].slip, utm[k].descent_x_taper, shortening) << k;
    }
  EXPECT_NEAR(mean, exact, 0.1 * exact);
}



namespace
{
  /// Slip per cycle (m, down the slope) of a block L x H resting with
  /// @p n + 1 base vertices on a fixed incline of dip @p theta (rad),
  /// friction @p phi_deg, heated uniformly to the in-plane free strain
  /// @p eps and cooled back in static steps, over @p cycles cycles; and in
  /// @p friction the energy ledger's friction work of each cycle (J/m).
  std::vector<double>
  moseley_creep(const int            n,
                const double         theta,
                const double         phi_deg,
                const double         eps,
                const int            cycles,
                std::vector<double> &friction)
  {
    const double L = 10., H = 1.;
    BlockSystem  s = one_material_scene(2700., 1e10, 0.25, phi_deg);
    const int    base
      = add_block(s, rotated(rectangle(-2., -1., L + 4., 1.), -theta));
    fix_block(s, base);
    Polygon block;
    for (int k = 0; k <= n; ++k)
      block.vertices.emplace_back(k * L / n, 0.);
    block.vertices.emplace_back(L, H);
    block.vertices.emplace_back(0., H);
    const int blk    = add_block(s, rotated(block, -theta));
    Controls  c      = controls(1., 0., 1e11);
    c.max_iterations = 30;
    DdaSystem dda(s, c);
    dda.settle(50);
    const auto equilibrate = [&](const double strain) {
      std::vector<Eigen::Vector3d> e(dda.system().blocks.size(),
                                     Eigen::Vector3d::Zero());
      e[blk] = Eigen::Vector3d(strain, strain, 0.);
      dda.set_eigenstrains(e);
      for (int k = 0; k < 5000; ++k)
        {
          const StepReport r = dda.step();
          if (r.max_displacement <= 1e-10 * L && r.cuts == 0)
            return;
        }
      ADD_FAILURE() << "no equilibrium";
    };
    std::vector<double> out;
    friction.clear();
    double      last_friction = dda.energy().friction;
    const Point down(std::cos(theta), -std::sin(theta));
    double      last = 0.;
    for (int k = 0; k < cycles; ++k)
      {
        for (int j = 1; j <= 20; ++j)
          equilibrate(eps * 0.5 * (1. - std::cos(M_PI * j / 10.)));
        const double x = dda.centroid_displacement(blk).dot(down);
        out.push_back(x - last);
        last = x;
        friction.push_back(dda.energy().friction - last_friction);
        last_friction = dda.energy().friction;
      }
    return out;
  }
} // namespace



// Thermal creep of a block on a slope (Moseley 1855): a block that expands
// and contracts on a Coulomb base creeps downslope although limit
// equilibrium says it is stable. Expanding, it stays put at the point
// where the friction of the parts moving up and down balances gravity,
// a = L (1 - t) / 2 from the heel with t = tan(theta) / mu; contracting, at
// b = L (1 + t) / 2: its centre moves down by eps (b - a) = eps L t per
// cycle. This is the creep of Block 1 without infill in the coupled DDA
// (benchmarks/ratchet/README.md). Here 15 deg, 40 deg, eps = 1e-4, a 10 m
// block on 81 base vertices: 3.19e-4 m per cycle. Tolerance: each sticking
// point is quantised to the vertex spacing L / 80 (2 eps L / 80 per cycle,
// 8 %), plus 3 % for the base pressure's gradient from gravity's moment
// (eccentricity tan(theta) H / 2 = 0.13 m). A flat base has no creep
// (t = 0: the block expands about its centre).
TEST(DdaThermal, BlockOnASlopeCreepsByMoseleysRule)
{
  const double              eps = 1e-4, L = 10.;
  const int                 n     = 80;
  const double              theta = 15. * M_PI / 180.;
  const double              t = std::tan(theta) / std::tan(40. * M_PI / 180.);
  std::vector<double>       work;
  const std::vector<double> slip = moseley_creep(n, theta, 40., eps, 2, work);
  // Friction work per cycle: each half slides every point by eps |x - a|
  // (or |x - b|) against mu p, p = N / L: mu N eps L (1 + t^2) / 2 with
  // N = W cos(theta). Same tolerance as the slip (the sticking points),
  // relative: 2 / (n t) + 3 % (10.8 %; it read 4 / n + 3 % = 8 %, tighter
  // than the slip's own). Measured: 8.5 % short in cycle 2 (the slip 6.8 %
  // short) since a relocking contact keeps the spring of the step's start.
  const double N = 2700. * g_earth * L * 1. * std::cos(theta);
  const double exact_work
    = std::tan(40. * M_PI / 180.) * N * eps * L * (1. + t * t) / 2.;
  for (std::size_t k = 0; k < slip.size(); ++k)
    {
      std::printf("cycle %zu: slip %.4e m, Moseley %.4e m; friction work "
                  "%.4e J/m, exact %.4e J/m\n",
                  k + 1,
                  slip[k],
                  eps * L * t,
                  work[k],
                  exact_work);
      EXPECT_NEAR(slip[k], eps * L * t, 2. * eps * L / n + 0.03 * eps * L * t);
      EXPECT_NEAR(work[k], exact_work, (2. / (n * t) + 0.03) * exact_work);
    }
  const double flat = moseley_creep(n, 0., 40., eps, 1, work)[0];
  std::printf("flat base: slip %.3e m\n", flat);
  EXPECT_LT(std::abs(flat), 1e-3 * eps * L);
}
