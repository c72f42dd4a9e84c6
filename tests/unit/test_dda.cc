/**
 * @file
 * Verification of the 2D DDA engine (issue 3): exact geometry and block
 * matrices, rigid rotation, free fall, block on an incline, Newmark sliding
 * in both seismic modes, stack at rest, elastic column, impact, stability
 * at the extremes, bad input.
 */
#include <rockdda/analytical/newmark.h>
#include <rockdda/dda/assembler.h>
#include <rockdda/dda/block_file.h>
#include <rockdda/dda/block_matrices.h>
#include <rockdda/dda/block_partition.h>
#include <rockdda/dda/contact_detection.h>
#include <rockdda/dda/engine.h>
#include <rockdda/io/error.h>

#include <Eigen/Dense>
#include <gtest/gtest.h>

#include "dda_test_scenes.h"
#include <algorithm>
#include <cmath>
#include <memory>
#include <random>
#include <tuple>

using namespace rockdda;
using namespace rockdda::dda;
using namespace rockdda::dda::test_scenes;


// ---------------------------------------------------------------------------
// Exact geometry and block matrices.

TEST(DdaGeometry, MomentsRectangleTriangleLShape)
{
  // Rectangle w x h about its centroid: sxx = h w^3/12, syy = w h^3/12.
  {
    const BlockMoments m = block_moments(rectangle(1., 2., 3., 2.));
    EXPECT_NEAR(m.area, 6., 1e-13);
    EXPECT_NEAR(m.centroid.x(), 2.5, 1e-13);
    EXPECT_NEAR(m.centroid.y(), 3., 1e-13);
    EXPECT_NEAR(m.sxx, 2. * 27. / 12., 1e-12);
    EXPECT_NEAR(m.syy, 3. * 8. / 12., 1e-12);
    EXPECT_NEAR(m.sxy, 0., 1e-12);
  }
  // Right triangle (0,0), (b,0), (0,h): about the centroid
  // sxx = b^3 h/36, syy = b h^3/36, sxy = -b^2 h^2/72.
  {
    Polygon      p;
    const double b = 3., h = 2.;
    p.vertices           = {Point(0, 0), Point(b, 0), Point(0, h)};
    const BlockMoments m = block_moments(p);
    EXPECT_NEAR(m.area, 3., 1e-13);
    EXPECT_NEAR(m.centroid.x(), 1., 1e-13);
    EXPECT_NEAR(m.centroid.y(), 2. / 3., 1e-13);
    EXPECT_NEAR(m.sxx, b * b * b * h / 36., 1e-12);
    EXPECT_NEAR(m.syy, b * h * h * h / 36., 1e-12);
    EXPECT_NEAR(m.sxy, -b * b * h * h / 72., 1e-12);
  }
  // L-shape = [0,2]x[0,1] + [0,1]x[1,2]: area 3, centroid (5/6, 5/6);
  // integral x^2 = 8/3 + 1/3 = 3, integral xy = 1 + 3/4 = 7/4.
  {
    Polygon p;
    p.vertices           = {Point(0, 0),
                            Point(2, 0),
                            Point(2, 1),
                            Point(1, 1),
                            Point(1, 2),
                            Point(0, 2)};
    const BlockMoments m = block_moments(p);
    EXPECT_NEAR(m.area, 3., 1e-13);
    EXPECT_NEAR(m.centroid.x(), 5. / 6., 1e-13);
    EXPECT_NEAR(m.centroid.y(), 5. / 6., 1e-13);
    EXPECT_NEAR(m.sxx, 3. - 3. * 25. / 36., 1e-12);
    EXPECT_NEAR(m.syy, 3. - 3. * 25. / 36., 1e-12);
    EXPECT_NEAR(m.sxy, 7. / 4. - 3. * 25. / 36., 1e-12);
    // Agrees with the shared Polygon helper.
    const Eigen::Vector3d c = p.central_second_moments();
    EXPECT_NEAR(c[1], m.sxx, 1e-12);
    EXPECT_NEAR(c[0], m.syy, 1e-12);
    EXPECT_NEAR(c[2], m.sxy, 1e-12);
  }
}

TEST(DdaGeometry, MassAndStiffnessSubmatrices)
{
  // The mass matrix equals rho * integral T^T T, checked by 2D Gauss
  // quadrature over a rectangle (T is linear, so 2 points are exact).
  const Polygon      r     = rectangle(-1., 0.5, 2., 3.);
  const BlockMoments m     = block_moments(r);
  const double       rho   = 2500.;
  const Matrix6      M     = mass_matrix(m, rho);
  Matrix6            Q     = Matrix6::Zero();
  const double       gp[2] = {-1. / std::sqrt(3.), 1. / std::sqrt(3.)};
  for (double a : gp)
    for (double b : gp)
      {
        const Point p(0. + a * 1., 2. + b * 1.5);
        const auto  T = displacement_matrix(m.centroid, p);
        Q += rho * (2. * 3. / 4.) * T.transpose() * T;
      }
  EXPECT_LT((M - Q).norm(), 1e-9 * M.norm());
  EXPECT_LT((M - M.transpose()).norm(), 1e-12 * M.norm());
  EXPECT_GT(Eigen::SelfAdjointEigenSolver<Matrix6>(M).eigenvalues().minCoeff(),
            0.);
  // Plane stress elasticity; uniaxial stress sigma_x gives eps_y = -nu eps_x.
  BlockMaterial         mat{2700., 2e10, 0.2, false};
  const Eigen::Matrix3d C   = elasticity_matrix(mat);
  const Eigen::Vector3d eps = C.inverse() * Eigen::Vector3d(1e6, 0., 0.);
  EXPECT_NEAR(eps[0], 1e6 / 2e10, 1e-18);
  EXPECT_NEAR(eps[1], -0.2 * 1e6 / 2e10, 1e-18);
  EXPECT_NEAR(C(2, 2), 2e10 / (2. * 1.2), 1e-3);
  // Plane strain: sigma_z = nu (sigma_x + sigma_y); with eps_y = 0 under
  // sigma_x, C(0,0) = E (1 - nu)/((1 + nu)(1 - 2 nu)).
  mat.plane_strain = true;
  EXPECT_NEAR(elasticity_matrix(mat)(0, 0), 2e10 * 0.8 / (1.2 * 0.6), 1.);
}

TEST(DdaGeometry, RigidRotationKeepsAreaExactly)
{
  // 90 degrees in 1000 steps of the finite-rotation update.
  Polygon      p  = rectangle(0.3, -0.2, 2., 0.5);
  const double a0 = block_moments(p).area;
  Vector6      d  = Vector6::Zero();
  d[2]            = 0.5 * M_PI / 1000.;
  for (int s = 0; s < 1000; ++s)
    {
      const Point c = block_moments(p).centroid;
      for (auto &v : p.vertices)
        v = move_point(c, d, v);
    }
  EXPECT_NEAR(block_moments(p).area / a0, 1., 1e-9);
  // The long side now points along y.
  EXPECT_NEAR(std::abs((p.vertices[1] - p.vertices[0]).y()), 2., 1e-9);
}

// ---------------------------------------------------------------------------
// Single blocks.


TEST(DdaSingleBlock, FreeFall)
{
  BlockSystem s = one_material_scene();
  add_block(s, rectangle(0., 0., 1., 1.));
  Controls c               = controls(0.01, 1., 1e11);
  c.max_displacement_ratio = 1.;
  DdaSystem dda(s, c);
  dda.run_until(1.);
  const double exact = -0.5 * g_earth;
  EXPECT_NEAR(dda.centroid_displacement(0).y() / exact, 1., 1e-6);
  EXPECT_NEAR(dda.centroid_displacement(0).x(), 0., 1e-12);
  EXPECT_NEAR(dda.system().blocks[0].velocity[1] / -g_earth, 1., 1e-9);
}

TEST(DdaSingleBlock, RigidRotationInEngine)
{
  // A free block spinning at pi/2 rad/s for 1 s in 1000 steps: area kept to
  // 1e-9 and no strain.
  BlockSystem s = one_material_scene();
  add_block(s, rectangle(0., 0., 2., 1.));
  s.gravity                = Point::Zero();
  s.blocks[0].velocity[2]  = 0.5 * M_PI;
  Controls c               = controls(1e-3, 1., 1e11);
  c.max_displacement_ratio = 1.;
  const double a0          = s.blocks[0].polygon.area();
  DdaSystem    dda(s, c);
  dda.run_until(1.);
  EXPECT_EQ(dda.n_steps, 1000u);
  EXPECT_NEAR(dda.system().blocks[0].polygon.area() / a0, 1., 1e-9);
  EXPECT_LT(dda.system().blocks[0].strain.norm(), 1e-12);
  EXPECT_NEAR(dda.system().blocks[0].rotation, 0.5 * M_PI, 1e-9);
  const auto &v = dda.system().blocks[0].polygon.vertices;
  EXPECT_NEAR((v[1] - v[0]).x(), 0., 1e-9);
  EXPECT_NEAR((v[1] - v[0]).y(), 2., 1e-9);
}

namespace
{
  /// Sliding distance on a 30 deg incline after 1 s, friction 20 deg.
  double
  incline_error(double penalty, double dt)
  {
    const double alpha = M_PI / 6., phi = 20.;
    DdaSystem    dda(incline_scene(alpha, phi), controls(dt, 1., penalty));
    dda.run_until(1.);
    const double exact
      = 0.5 * g_earth
        * (std::sin(alpha) - std::cos(alpha) * std::tan(phi * M_PI / 180.));
    return std::abs(along_slope(dda, 1, alpha) - exact) / exact;
  }
} // namespace

TEST(DdaSingleBlock, InclineSliding)
{
  // d = g/2 (sin a - cos a tan phi) t^2; documented: E = 10 GPa, 1 m block,
  // dt = 0.01 s, penalty 1e11 N/m (10 E). The error falls with the penalty
  // until it reaches a floor of ~1e-6 (benchmarks/dda-scaling).
  const double e7  = incline_error(1e7, 1e-2);
  const double e8  = incline_error(1e8, 1e-2);
  const double e9  = incline_error(1e9, 1e-2);
  const double e11 = incline_error(1e11, 1e-2);
  std::printf("incline error: p=1e7 %.3e, 1e8 %.3e, 1e9 %.3e, 1e11 %.3e\n",
              e7,
              e8,
              e9,
              e11);
  EXPECT_LT(e11, 0.01);
  EXPECT_LT(e9, e8);
  EXPECT_LT(e8, e7);
}

TEST(DdaSingleBlock, InclineSticking)
{
  const double alpha = M_PI / 6.;
  BlockSystem  scene = incline_scene(alpha, 35.);
  const auto   v0    = scene.blocks[1].polygon.vertices;
  DdaSystem    dda(scene, controls(1e-3, 1., 1e11));
  dda.run_until(1.);
  // Slip at the contact: the along-slope motion of the two base vertices
  // of the block (the centroid also moves by the elastic shear of the
  // block, m g sin(a) h / (2 G A) ~ 1.6e-6 m for E = 10 GPa).
  const Point s_dir(std::cos(alpha), -std::sin(alpha));
  for (int k : {0, 1})
    EXPECT_LT(std::abs((dda.system().origin
                        + dda.system().blocks[1].polygon.vertices[k] - v0[k])
                         .dot(s_dir)),
              1e-6);
  for (const auto &c : dda.contacts())
    EXPECT_NE(c.state, ContactState::sliding);
}

TEST(DdaSingleBlock, ShearPenaltySetOnItsOwnGivesTheElasticSlip)
{
  // Key 'Shear penalty' (dda::ContactLaw::fixed_shear_penalty): the shear
  // springs take it instead of the ratio x the normal penalty. A 1 m block
  // (W = 2700 g = 26.5 kN/m) sticking on a 30 deg incline (phi = 35 deg),
  // static steps: its two base corners share the slope's load W sin(a)
  // equally (equal springs, the same height on a uniformly strained
  // block), so each slips elastically by W sin(a) / (2 p_s) = 6.6e-5 m at
  // p_s = 1e8 N/m, and 400 times less with the default ratio (0.4 x 1e11
  // N/m). What else could move them along the slope, the tilt on the
  // unequal normal forces, is second order (measured: both within 1e-6).
  const double alpha = M_PI / 6.;
  for (const double ps : {1e8, 0.})
    {
      BlockSystem scene = incline_scene(alpha, 35.);
      const auto  v0    = scene.blocks[1].polygon.vertices;
      // Static steps of 0.1 s: the inertia term 2 M / dt^2 = 5.4e5 N/m is
      // far below the springs, so each step ends at equilibrium.
      Controls c                = controls(0.1, 0., 1e11);
      c.law.fixed_shear_penalty = ps;
      DdaSystem dda(scene, c);
      dda.run_until(1.);
      const double W = 2700. * g_earth;
      const double expected
        = W * std::sin(alpha) / (2. * (ps > 0. ? ps : 0.4 * 1e11));
      const Point s_dir(std::cos(alpha), -std::sin(alpha));
      double      slip = 0.;
      for (int k : {0, 1})
        slip += 0.5
                * (dda.system().origin
                   + dda.system().blocks[1].polygon.vertices[k] - v0[k])
                    .dot(s_dir);
      std::printf("shear penalty %.0e N/m: base corners slip %.6e m, "
                  "W sin(a) / (2 p_s) = %.6e m\n",
                  ps,
                  slip,
                  expected);
      EXPECT_NEAR(slip / expected, 1., 1e-3);
      for (const auto &ct : dda.contacts())
        EXPECT_EQ(ct.state, ContactState::locked);
    }
}

TEST(DdaSingleBlock, StrainDampingDampsTheStrainModeNotTheSlide)
{
  // A soft 1 m block (E = 10 MPa, rho = 2700 kg/m^3) on a 30 deg incline,
  // started on uncompressed springs: its uniform-strain mode on the base,
  // omega ~ (3 E / (rho h^2))^1/2 = 105 rad/s, rings. Shi's scheme damps it
  // at ~omega dt / 4 = 0.026 (dt = 1 ms): its energy falls by ~e^-5.5 in
  // 1 s. A strain damping eta = 2e-2 s (ratio eta omega / 2 = 1.05,
  // overdamped: the slow root decays at >= 70 1/s) leaves none of it.
  const double alpha = M_PI / 6.;
  auto         run   = [&](const double phi, const double eta) {
    BlockSystem s         = incline_scene(alpha, phi);
    s.materials[0].young  = 1e7;
    Controls c            = controls(1e-3, 1., 1e11);
    c.strain_damping      = eta;
    auto         dda      = std::make_unique<DdaSystem>(s, c);
    const double balance0 = dda->energy().balance();
    double       kinetic  = 0.;
    for (int k = 90; k <= 100; ++k)
      {
        dda->run_until(0.01 * k);
        kinetic = std::max(kinetic, dda->kinetic_energy());
      }
    return std::make_tuple(std::move(dda), kinetic, balance0);
  };
  // Resting (phi = 35 deg): the largest kinetic energy in [0.9, 1] s.
  const auto [rest0, k0, b0] = run(35., 0.);
  const auto [rest1, k1, b1] = run(35., 2e-2);
  // Sliding (phi = 20 deg): d = g/2 (sin a - cos a tan phi) t^2 at 1 s.
  const auto [slide, k2, b2] = run(20., 2e-2);
  const double exact
    = 0.5 * g_earth * (std::sin(alpha) - std::cos(alpha) * std::tan(M_PI / 9.));
  const double d = along_slope(*slide, 1, alpha);
  std::printf("2D strain damping: resting block's kinetic energy in [0.9, 1] "
              "s %.3e J/m undamped, %.3e J/m damped; damped slide %.6f m "
              "(exact %.6f), dissipated %.3e J/m\n",
              k0,
              k1,
              d,
              exact,
              slide->energy().damping);
  EXPECT_GT(k0, 0.);
  EXPECT_LT(k1, 1e-3 * k0);
  EXPECT_LT(std::abs(d - exact), 0.01 * exact);
  EXPECT_EQ(rest0->energy().damping, 0.);
  for (const auto *dda : {rest1.get(), slide.get()})
    {
      const EnergyLedger e = dda->energy();
      EXPECT_GT(e.damping, 0.);
      // Dissipated, never created: the balance only falls.
      EXPECT_LT(e.balance(), (dda == slide.get() ? b2 : b1) + 1e-9 * e.scale());
    }
}

// ---------------------------------------------------------------------------
// Newmark sliding with DDA, both seismic modes (Kamai & Hatzor 2008).

namespace
{
  /// Block on a 20 deg plane dipping towards -x (so positive ground
  /// acceleration, towards +x, drives it downslope), friction 30 deg, under
  /// a(t) = A g sin(2 pi f t) for 2 s (default A = 0.5, f = 1 Hz). Returns
  /// {DDA, exact} downslope displacement relative to the base.
  std::pair<double, double>
  newmark_case(SeismicInput::Mode mode,
               double             penalty,
               double             dt,
               unsigned int       settle_steps = 0,
               double             frequency    = 1.,
               double             A            = 0.5)
  {
    const double alpha = 20. * M_PI / 180., phi = 30.;
    const double omega = 2. * M_PI * frequency, T = 2.;
    BlockSystem  s      = incline_scene(-alpha, phi);
    s.seismic.mode      = mode;
    s.seismic.g         = g_earth;
    s.seismic.record.dt = 1e-3;
    for (int k = 0; k <= static_cast<int>(T / 1e-3) + 1; ++k)
      s.seismic.record.acceleration.push_back(A * std::sin(omega * k * 1e-3));
    Controls  c = controls(dt, 1., penalty);
    DdaSystem dda(s, c);
    if (settle_steps > 0)
      dda.settle(settle_steps);
    dda.run_until(T);
    // Downslope direction: (-cos a, -sin a).
    const Point  down(-std::cos(alpha), -std::sin(alpha));
    const double d
      = (dda.centroid_displacement(1) - dda.centroid_displacement(0)).dot(down);
    const double exact
      = g_earth
        * (std::cos(alpha) + std::tan(phi * M_PI / 180.) * std::sin(alpha))
        * analytical::harmonic_sliding_displacement(
          A, omega, std::tan(phi * M_PI / 180. - alpha), T);
    return {d, exact};
  }
} // namespace

TEST(DdaNewmark, InertialLoadingMode)
{
  // Documented: penalty 1e11 N/m (10 E), dt = 1e-3 s.
  const auto [d, exact]
    = newmark_case(SeismicInput::Mode::inertial, 1e11, 1e-3);
  std::printf("Newmark inertial: DDA %.6f m, exact %.6f m, error %.3e\n",
              d,
              exact,
              std::abs(d - exact) / exact);
  EXPECT_GT(exact, 0.05);
  EXPECT_LT(std::abs(d - exact) / exact, 0.05);
}

TEST(DdaNewmark, DisplacementMode)
{
  const auto [d, exact]
    = newmark_case(SeismicInput::Mode::displacement, 1e11, 1e-3);
  std::printf("Newmark displacement: DDA %.6f m, exact %.6f m, error %.3e\n",
              d,
              exact,
              std::abs(d - exact) / exact);
  EXPECT_LT(std::abs(d - exact) / exact, 0.05);
}

// Twenty stick-slip episodes (0.5 g at 10 Hz for 2 s): a contact that stops
// sliding locks at the friction force it carried (force continuity), so no
// spurious slip of ~strength / shear penalty accumulates per episode. With
// a shear spring that restarts from zero at each lock the error was 1.1e-3
// (DDA ahead of the rigid-block solution); with force continuity and the
// force criteria of the contact states the error scatters by +-5e-4 with
// the time step (-5.5e-4, 1.6e-4, 4.7e-4 at dt = 1, 0.5, 0.25 ms: the
// timing of the 20 lock events), so the bound is 1e-3.
TEST(DdaNewmark, ManyStickSlipEpisodes)
{
  const auto [d, exact]
    = newmark_case(SeismicInput::Mode::inertial, 1e11, 1e-3, 0, 10., 0.5);
  std::printf("Newmark 10 Hz: DDA %.6f m, exact %.6f m, error %.3e\n",
              d,
              exact,
              std::abs(d - exact) / exact);
  EXPECT_GT(exact, 0.05);
  EXPECT_LT(std::abs(d - exact) / exact, 1e-3);
}

// ---------------------------------------------------------------------------
// Many blocks.

namespace
{
  /// n blocks of w x h stacked on a wider fixed base.
  BlockSystem
  stack_scene(int n, double w, double h, double phi = 30.)
  {
    BlockSystem s    = one_material_scene(2700., 1e10, 0.25, phi);
    const int   base = add_block(s, rectangle(-w, -1., 3. * w, 1.));
    for (int k = 0; k < n; ++k)
      add_block(s, rectangle(0., k * h, w, h));
    fix_block(s, base);
    return s;
  }
} // namespace

TEST(DdaManyBlocks, StackAtRest)
{
  // Static mode (dynamic control 0), 1000 steps of 0.01 s. The blocks first
  // settle by the contact and elastic compression (~1e-5 m); the drift is
  // measured from step 100 to step 1000. Both linear solvers.
  for (auto type : {SolverType::direct, SolverType::iterative})
    {
      Controls c    = controls(0.01, 0., 1e11);
      c.solver.type = type;
      DdaSystem dda(stack_scene(10, 1., 1.), c);
      for (int k = 0; k < 100; ++k)
        dda.step();
      std::vector<Polygon> settled;
      for (const auto &b : dda.system().blocks)
        settled.push_back(b.polygon);
      for (int k = 0; k < 900; ++k)
        dda.step();
      double drift = 0.;
      for (std::size_t b = 0; b < settled.size(); ++b)
        for (std::size_t v = 0; v < settled[b].vertices.size(); ++v)
          drift = std::max(drift,
                           (dda.system().blocks[b].polygon.vertices[v]
                            - settled[b].vertices[v])
                             .norm());
      EXPECT_EQ(dda.solver_type(), type);
      std::printf("stack drift %.3e m\n", drift);
      EXPECT_LT(drift, 1e-6);
      // One contact per corner per interface, all locked.
      EXPECT_EQ(dda.contacts().size(), 20u);
      for (const auto &c : dda.contacts())
        EXPECT_EQ(c.state, ContactState::locked);
      // The bottom block's mean vertical stress carries 9.5 block weights (9
      // above and half its own): rho g (9 + 1/2) h.
      const double expected = -2700. * g_earth * 9.5;
      EXPECT_NEAR(dda.system().blocks[1].stress[1] / expected, 1., 0.01);
    }
}

TEST(DdaManyBlocks, ElasticColumn)
{
  // Five 2 m blocks: each block's mean strain eps_y = -rho g z_c / E, z_c
  // the depth of its centroid below the top; eps_x = -nu eps_y (plane
  // stress, free sides). The joints are frictionless so that they do not
  // restrain the Poisson expansion (with friction the locked shear springs
  // do, and the blocks carry a horizontal stress).
  const int    n = 5;
  const double h = 2., E = 1e10, nu = 0.25;
  DdaSystem    dda(stack_scene(n, 1., h, 0.), controls(0.01, 0., 1e12));
  dda.run_until(2.);
  for (int k = 0; k < n; ++k)
    {
      const double depth = (n - k - 0.5) * h;
      const double eps   = -2700. * g_earth * depth / E;
      const auto  &b     = dda.system().blocks[1 + k];
      EXPECT_NEAR(b.strain[1] / eps, 1., 0.01) << "block " << k;
      EXPECT_NEAR(b.strain[0] / (-nu * eps), 1., 0.01) << "block " << k;
    }
}

TEST(DdaManyBlocks, FrictionlessImpact)
{
  // A 1 m block dropped from 0.5 m onto a fixed block, dynamic mode, no
  // friction. Penetration stays below 1e-3 m (the elastic penalty
  // compression m v^2 = 2 p delta^2 gives 3.6e-4 m), and the total energy
  // (kinetic + gravity + strain + contact springs) never exceeds its
  // initial value by more than 1 % of m g h per impact.
  BlockSystem s    = one_material_scene(2700., 1e10, 0.25, 0.);
  const int   base = add_block(s, rectangle(-1., -1., 3., 1.));
  add_block(s, rectangle(0., 0.5, 1., 1.));
  fix_block(s, base);
  Controls c               = controls(1e-3, 1., 1e11);
  c.max_displacement_ratio = 0.05;
  DdaSystem    dda(s, c);
  const double mgh   = 2700. * g_earth * 0.5;
  double       e_max = -1e300, min_y = 1e300;
  int          impacts    = 0;
  bool         in_contact = false;
  while (dda.time() < 2.)
    {
      dda.step();
      const double e = dda.kinetic_energy() + dda.potential_energy()
                       + dda.strain_energy() + dda.contact_energy();
      e_max = std::max(e_max, e);
      for (const auto &v : dda.system().blocks[1].polygon.vertices)
        min_y = std::min(min_y, v.y() + dda.system().origin.y());
      bool closed = false;
      for (const auto &ct : dda.contacts())
        closed = closed || ct.state != ContactState::open;
      if (closed && !in_contact)
        ++impacts;
      in_contact = closed;
    }
  std::printf("impact: %d impacts, max energy growth %.3e m g h, min y %.3e\n",
              impacts,
              e_max / mgh,
              min_y);
  EXPECT_GE(impacts, 1);
  EXPECT_LE(e_max, 0.01 * mgh * impacts);
  EXPECT_GT(min_y, -1e-3);
}

// ---------------------------------------------------------------------------
// Stability at the extremes: every case completes with finite results or
// stops with a DdaFailure whose message is a diagnosis; never NaN, never a
// hang (the step limit bounds the work).

namespace
{
  struct ExtremeCase
  {
    const char *name;
    double      penalty_over_E, dt, phi, size, aspect;
  };

  /// A block of size x (size / aspect) on a fixed base (30 deg incline).
  std::string
  run_extreme(const ExtremeCase &c, bool &finished)
  {
    const double E = 1e10;
    const double w = c.size, h = c.size / c.aspect;
    BlockSystem  s     = one_material_scene(2700., E, 0.25, c.phi);
    const double alpha = M_PI / 6.;
    const int    base
      = add_block(s, rotated(rectangle(-2. * w, -w, 4. * w, w), -alpha));
    add_block(s, rotated(rectangle(-0.5 * w, 0., w, h), -alpha));
    fix_block(s, base);
    Controls ctrl  = controls(c.dt, 1., c.penalty_over_E * E);
    ctrl.max_steps = 2000;
    finished       = false;
    try
      {
        DdaSystem dda(s, ctrl);
        dda.run_until(std::min(200 * c.dt, 0.5));
        finished = true;
        for (const auto &b : dda.system().blocks)
          {
            for (const auto &v : b.polygon.vertices)
              if (!v.allFinite())
                return "non-finite vertex";
            if (!b.velocity.allFinite() || !b.stress.allFinite())
              return "non-finite state";
          }
        return "ok after " + std::to_string(dda.n_steps) + " steps, "
               + std::to_string(dda.n_cuts) + " cuts";
      }
    catch (const DdaFailure &e)
      {
        return std::string("stopped: ") + e.what();
      }
  }
} // namespace

TEST(DdaStability, ExtremeParameters)
{
  const ExtremeCase cases[] = {
    {"reference", 10., 1e-3, 20., 1., 1.},
    {"penalty 1e-3 E", 1e-3, 1e-3, 20., 1., 1.},
    {"penalty 1e3 E", 1e3, 1e-3, 20., 1., 1.},
    {"dt 1e-6 s", 10., 1e-6, 20., 1., 1.},
    {"dt 1e-1 s", 10., 1e-1, 20., 1., 1.},
    {"friction 0 deg", 10., 1e-3, 0., 1., 1.},
    {"friction 89 deg", 10., 1e-3, 89., 1., 1.},
    {"size 1 mm", 10., 1e-3, 20., 1e-3, 1.},
    {"size 100 m", 10., 1e-3, 20., 100., 1.},
    {"aspect 1000:1 (flat)", 10., 1e-3, 20., 1., 1000.},
    {"aspect 1:1000 (tall)", 10., 1e-3, 20., 1e-3, 1e-3},
    {"all large", 1e3, 1e-1, 89., 100., 1000.},
    {"all small", 1e-3, 1e-6, 0., 1e-3, 1.},
  };
  for (const auto &c : cases)
    {
      bool              finished = false;
      const std::string result   = run_extreme(c, finished);
      std::printf("  %-22s %s\n", c.name, result.c_str());
      if (finished)
        EXPECT_EQ(result.substr(0, 2), "ok") << c.name;
      else
        EXPECT_NE(result.find("step"), std::string::npos) << c.name;
    }
}

// ---------------------------------------------------------------------------
// Bad input: each error names the block.

namespace
{
  std::string
  construction_error(const BlockSystem &s)
  {
    try
      {
        DdaSystem dda(s, controls(1e-3, 1., 1e11));
      }
    catch (const InputError &e)
      {
        return e.what();
      }
    return "";
  }
} // namespace

TEST(DdaBadInput, ClockwisePolygonIsReversedWithWarning)
{
  BlockSystem s = one_material_scene();
  Polygon     p = rectangle(0., 0., 1., 1.);
  std::reverse(p.vertices.begin(), p.vertices.end());
  add_block(s, p);
  DdaSystem dda(s, controls(1e-3, 1., 1e11));
  ASSERT_EQ(dda.warnings().size(), 1u);
  EXPECT_NE(dda.warnings()[0].find("block 0"), std::string::npos);
  EXPECT_GT(dda.system().blocks[0].polygon.signed_area(), 0.);
}

TEST(DdaBadInput, SelfIntersectingOverlapDensityMaterial)
{
  {
    BlockSystem s = one_material_scene();
    add_block(s, rectangle(0., 0., 1., 1.));
    Polygon bow;
    bow.vertices = {Point(2, 0), Point(3, 1), Point(3, 0), Point(2, 1)};
    add_block(s, bow);
    const std::string e = construction_error(s);
    EXPECT_NE(e.find("block 1"), std::string::npos) << e;
    EXPECT_NE(e.find("self-intersecting"), std::string::npos) << e;
  }
  {
    BlockSystem s = one_material_scene();
    add_block(s, rectangle(0., 0., 1., 1.));
    add_block(s, rectangle(0.5, 0.5, 1., 1.));
    const std::string e = construction_error(s);
    EXPECT_NE(e.find("overlaps"), std::string::npos) << e;
    EXPECT_NE(e.find("block 0"), std::string::npos) << e;
    EXPECT_NE(e.find("block 1"), std::string::npos) << e;
  }
  {
    BlockSystem s = one_material_scene(0.);
    add_block(s, rectangle(0., 0., 1., 1.));
    const std::string e = construction_error(s);
    EXPECT_NE(e.find("block 0"), std::string::npos) << e;
    EXPECT_NE(e.find("density"), std::string::npos) << e;
  }
  {
    BlockSystem s = one_material_scene();
    add_block(s, rectangle(0., 0., 1., 1.));
    add_block(s, rectangle(2., 0., 1., 1.), -1);
    const std::string e = construction_error(s);
    EXPECT_NE(e.find("block 1: has no material"), std::string::npos) << e;
  }
}

// ---------------------------------------------------------------------------
// Contact detection.

TEST(DdaContacts, BroadPhaseMatchesAllPairs)
{
  // A staggered brick wall: the grid finds exactly the pairs that the
  // O(N^2) check finds.
  std::vector<Polygon> walls;
  for (int r = 0; r < 12; ++r)
    for (int c = 0; c < 15; ++c)
      walls.push_back(rectangle(c * 2. + (r % 2), r * 1., 2., 1.));
  const double                     d     = 0.05;
  const auto                       pairs = candidate_pairs(walls, d);
  std::vector<std::pair<int, int>> brute;
  for (int i = 0; i < static_cast<int>(walls.size()); ++i)
    for (int j = i + 1; j < static_cast<int>(walls.size()); ++j)
      {
        const auto a = walls[i].bounding_box(), b = walls[j].bounding_box();
        if (a[0] - d <= b[2] && b[0] - d <= a[2] && a[1] - d <= b[3]
            && b[1] - d <= a[3])
          brute.emplace_back(i, j);
      }
  EXPECT_EQ(pairs, brute);
}

TEST(DdaContacts, EqualWidthStackHasNoDuplicates)
{
  // Two equal squares on top of each other: exactly one contact per
  // corner; the vertex's wedge is never behind the edge.
  std::vector<Polygon> p = {rectangle(0, 0, 1, 1), rectangle(0, 1, 1, 1)};
  DetectionOptions     o;
  o.search_distance = 0.01;
  const auto c      = detect_contacts(p, o);
  ASSERT_EQ(c.size(), 2u);
  for (const auto &k : c)
    {
      EXPECT_NEAR(std::abs(k.normal.y()), 1., 1e-12);
      EXPECT_NEAR(k.gap, 0., 1e-12);
    }
  // A concave L-shaped block does not initiate contacts from its reflex
  // corner: a square sitting in its notch touches with its own vertices.
  Polygon L;
  L.vertices             = {Point(0, 0),
                            Point(2, 0),
                            Point(2, 1),
                            Point(1, 1),
                            Point(1, 2),
                            Point(0, 2)};
  std::vector<Polygon> q = {L, rectangle(1, 1, 1, 1)};
  for (const auto &k : detect_contacts(q, o))
    EXPECT_FALSE(k.block_i == 0 && k.vertex == 3);
}

TEST(DdaNewmark, SmallTimeStep)
{
  // At dt = 1e-4 s the contact vibration (period 2 pi sqrt(m / 2p) = 0.7 ms
  // at p = 1e11 N/m) is resolved and barely damped by the scheme. With the
  // friction force lagged by one open-close iteration the block then rocks
  // on its corners and loses friction (20-75 % error); iterating the
  // friction to agree with the normal force fixes it, with or without a
  // static settling phase before t = 0.
  for (unsigned int settle : {0u, 20u})
    {
      const auto [d, exact]
        = newmark_case(SeismicInput::Mode::inertial, 1e11, 1e-4, settle);
      std::printf("Newmark dt 1e-4, %u settling steps: DDA %.6f m, exact "
                  "%.6f m, error %.3e\n",
                  settle,
                  d,
                  exact,
                  std::abs(d - exact) / exact);
      EXPECT_LT(std::abs(d - exact) / exact, 0.05);
    }
}

TEST(DdaBlockFile, ParsesEveryKeywordAndNamesBadLines)
{
  const std::string text = "# comment\n"
                           "material 1 2700 1e10 0.25 plane-strain\n"
                           "joint 2 25 1e5 0\n"
                           "block 10 1 2  0 0 1 0 1 1 0 1  # a square\n"
                           "block 11 1 2  0 1 1 1 1 2 0 2\n"
                           "fixed-block 10\n"
                           "fixed 11 0 2\n"
                           "load 11 0.5 2 0 -1000\n"
                           "measure 11 0.5 1.5\n"
                           "velocity 11 1 0 0.5\n";
  const BlockSystem s    = parse_block_text(text, "scene");
  ASSERT_EQ(s.blocks.size(), 2u);
  EXPECT_TRUE(s.materials[0].plane_strain);
  EXPECT_EQ(s.joints[0].friction_deg, 25.);
  EXPECT_EQ(s.blocks[1].id, 11);
  EXPECT_EQ(s.fixed_points.size(), 5u);
  EXPECT_EQ(s.load_points.size(), 1u);
  EXPECT_EQ(s.measurement_points.size(), 1u);
  EXPECT_EQ(s.blocks[1].velocity[2], 0.5);
  try
    {
      parse_block_text("material 1 2700 1e10 0.25\nblok 1 1 0 0 0\n", "f");
      FAIL();
    }
  catch (const InputError &e)
    {
      EXPECT_NE(std::string(e.what()).find("line 2"), std::string::npos);
    }
  try
    {
      parse_block_text("material 1 2700 1e10 0.25\nblock 3 1 0 0 0 1 0\n", "f");
      FAIL();
    }
  catch (const InputError &e)
    {
      EXPECT_NE(std::string(e.what()).find("at least 3 vertices"),
                std::string::npos);
    }
}

// A run resumed from a checkpoint continues bit for bit: 20 dynamic steps
// of a sliding, rocking wall, checkpoint, 20 more steps; a fresh engine
// restored from the checkpoint takes the same 20 steps to the same vertex
// coordinates, velocities, stresses and contact states (exactly: every
// evolving quantity is stored as raw doubles). A checkpoint of another
// scene or a truncated one is rejected with a message naming the source.
TEST(DdaCheckpoint, ResumedRunIsIdentical)
{
  BlockSystem s    = one_material_scene(2700., 1e10, 0.25, 20.);
  const int   base = add_block(s, rectangle(-2., -1., 14., 1.));
  fix_block(s, base);
  for (int r = 0; r < 4; ++r)
    for (int c = 0; c < 5; ++c)
      add_block(s, rectangle(2. * c + (r % 2), r * 1., 2., 1.));
  s.gravity = Point(4., -g_earth);
  MeasurementPoint mp;
  mp.block = 6;
  mp.point = Point(1.5, 1.5);
  s.measurement_points.push_back(mp);
  const Controls c = controls(1e-3, 1., 1e11);

  DdaSystem original(s, c);
  for (int k = 0; k < 20; ++k)
    original.step();
  const std::string saved = original.checkpoint();
  for (int k = 0; k < 20; ++k)
    original.step();

  DdaSystem resumed(s, c);
  resumed.restore(saved, "test checkpoint");
  EXPECT_EQ(resumed.n_steps, 20u);
  for (int k = 0; k < 20; ++k)
    resumed.step();

  EXPECT_EQ(resumed.time(), original.time());
  EXPECT_EQ(resumed.n_steps, original.n_steps);
  double sliding = 0.;
  for (std::size_t b = 0; b < s.blocks.size(); ++b)
    {
      const Block &x = original.system().blocks[b];
      const Block &y = resumed.system().blocks[b];
      for (std::size_t v = 0; v < x.polygon.vertices.size(); ++v)
        EXPECT_EQ(x.polygon.vertices[v], y.polygon.vertices[v]);
      EXPECT_EQ(x.velocity, y.velocity);
      EXPECT_EQ(x.stress, y.stress);
      sliding = std::max(sliding, original.centroid_displacement(b).norm());
    }
  ASSERT_EQ(resumed.contacts().size(), original.contacts().size());
  unsigned n_sliding = 0;
  for (std::size_t k = 0; k < original.contacts().size(); ++k)
    {
      EXPECT_EQ(resumed.contacts()[k].state, original.contacts()[k].state);
      EXPECT_EQ(resumed.contacts()[k].xi_ref, original.contacts()[k].xi_ref);
      n_sliding += original.contacts()[k].state == ContactState::sliding;
    }
  EXPECT_EQ(resumed.system().measurement_points[0].point,
            original.system().measurement_points[0].point);
  std::printf("resumed run: %zu contacts (%u sliding), largest displacement "
              "%.3e m, identical\n",
              original.contacts().size(),
              n_sliding,
              sliding);
  EXPECT_GT(sliding, 1e-4); // the wall moves: the test is not trivial

  // Another scene (one block fewer) and a truncated file are rejected.
  BlockSystem other = s;
  other.blocks.pop_back();
  DdaSystem different(other, c);
  try
    {
      different.restore(saved, "run/checkpoint.bin");
      FAIL();
    }
  catch (const InputError &e)
    {
      EXPECT_NE(std::string(e.what()).find("run/checkpoint.bin"),
                std::string::npos);
      EXPECT_NE(std::string(e.what()).find("another scene"), std::string::npos);
    }
  DdaSystem same(s, c);
  EXPECT_THROW(same.restore(saved.substr(0, saved.size() / 2), "half"),
               InputError);
  EXPECT_THROW(same.restore("not a checkpoint", "text"), InputError);
  // A rejected checkpoint leaves the engine as it was.
  EXPECT_EQ(same.time(), 0.);
  EXPECT_EQ(same.n_steps, 0u);
}

namespace
{
  /// A block matrix on an m x m grid of blocks of @p dofs unknowns: a
  /// random SPD diagonal block each (0.1 R R^T + 0.01 I, scaled by
  /// 10^(decades b / n) over the blocks), each block coupled to its right
  /// and upper neighbours (and, with @p diagonals, its upper-right one) by
  /// @p springs random springs k (e - h)(e - h)^T, and a random load.
  template <int dofs>
  std::pair<BlockSparseMatrixOf<dofs>, Eigen::VectorXd>
  random_grid(const int          m,
              const unsigned int seed,
              const bool         diagonals,
              const double       decades,
              const int          springs)
  {
    using Dense                        = Eigen::Matrix<double, dofs, dofs>;
    using Vec                          = Eigen::Matrix<double, dofs, 1>;
    const int                        n = m * m;
    std::mt19937                     rng(seed);
    std::normal_distribution<double> normal;
    auto                             random_vector = [&]() {
      Vec v;
      for (int c = 0; c < dofs; ++c)
        v[c] = normal(rng);
      return v;
    };
    std::vector<std::pair<int, int>> pairs;
    for (int i = 0; i < m; ++i)
      for (int j = 0; j < m; ++j)
        {
          if (j + 1 < m)
            pairs.emplace_back(i * m + j, i * m + j + 1);
          if (i + 1 < m)
            pairs.emplace_back(i * m + j, (i + 1) * m + j);
          if (diagonals && i + 1 < m && j + 1 < m)
            pairs.emplace_back(i * m + j, (i + 1) * m + j + 1);
        }
    std::sort(pairs.begin(), pairs.end());
    BlockSparseMatrixOf<dofs> K;
    K.reinit(n, pairs);
    for (int b = 0; b < n; ++b)
      {
        Dense R;
        for (int c = 0; c < dofs; ++c)
          R.col(c) = random_vector();
        K.diag[b] = std::pow(10., decades * b / n)
                    * (0.1 * R * R.transpose() + 0.01 * Dense::Identity());
      }
    for (std::size_t k = 0; k < pairs.size(); ++k)
      for (int spring = 0; spring < springs; ++spring)
        {
          const Vec e = random_vector(), h = random_vector();
          K.diag[pairs[k].first] += e * e.transpose();
          K.diag[pairs[k].second] += h * h.transpose();
          K.off[k] -= e * h.transpose();
        }
    Eigen::VectorXd f(dofs * n);
    for (int b = 0; b < n; ++b)
      f.template segment<dofs>(dofs * b) = random_vector();
    return {K, f};
  }
} // namespace

TEST(DdaSolvers, SubdomainOrderingIsExactAndThreadIndependent)
{
  // A 24 x 24 grid of blocks, each coupled to its four neighbours by a
  // random spring matrix, plus a random SPD diagonal: the D-ILU CG in the
  // natural order and in the two-subdomain order (separator last) on one
  // and on two threads solves K x = f to its tolerance (checked against
  // the direct solver); one and two threads give bit-identical results;
  // the separator is one BFS level (at most one grid diagonal, 47 blocks).
  const int m = 24, n = m * m;
  const auto [K, f] = random_grid<6>(m, 7, false, 0., 2);

  SolverOptions direct_options;
  direct_options.type = SolverType::direct;
  LinearSolver direct(direct_options);
  direct.new_pattern(K);
  Eigen::VectorXd exact;
  ASSERT_TRUE(direct.solve(K, f, exact));
  const double scale = exact.norm();

  std::vector<Eigen::VectorXd> solutions;
  for (const auto &[limit, threads] : {std::make_pair(1000000, 1),
                                       std::make_pair(10, 1),
                                       std::make_pair(10, 2)})
    {
      SolverOptions o;
      o.type            = SolverType::iterative;
      o.tolerance       = 1e-10;
      o.subdomain_limit = limit;
      o.threads         = threads;
      LinearSolver cg(o);
      cg.new_pattern(K);
      Eigen::VectorXd x = Eigen::VectorXd::Zero(6 * n);
      ASSERT_TRUE(cg.solve(K, f, x));
      const double error = (x - exact).norm() / scale;
      std::printf("subdomain limit %d, %u thread(s): separator %d blocks, "
                  "%d CG iterations, relative error %.2e\n",
                  limit,
                  cg.n_threads(),
                  cg.separator_size(),
                  cg.last_iterations(),
                  error);
      // CG stops at 1e-10 of the preconditioned residual; the condition
      // number (~1e3) allows 1e-7 in the solution.
      EXPECT_LT(error, 1e-7);
      if (limit == 10)
        {
          EXPECT_GT(cg.separator_size(), 0);
          EXPECT_LE(cg.separator_size(), 2 * m - 1);
          EXPECT_EQ(cg.n_threads(), static_cast<unsigned>(threads));
        }
      else
        EXPECT_EQ(cg.separator_size(), 0);
      // A second solve with the same matrix reuses the preconditioner.
      Eigen::VectorXd x2 = Eigen::VectorXd::Zero(6 * n);
      ASSERT_TRUE(cg.solve(K, f, x2, true));
      EXPECT_EQ((x2 - x).norm(), 0.);
      solutions.push_back(x);
    }
  EXPECT_EQ((solutions[1] - solutions[2]).norm(), 0.);
}

namespace
{
  /// The direct solver on a random m x m grid of blocks of @p dofs
  /// unknowns (random SPD diagonals plus random spring couplings, the
  /// pattern of a contact graph): returns the backward error
  /// |K x - f| / (|K|_F |x|) and whether an indefinite pivot is refused.
  template <int dofs>
  std::pair<double, bool>
  direct_solver_on_random_grid(const int m)
  {
    const int n = m * m;
    auto [K, f] = random_grid<dofs>(m, 11, true, 6., 1);
    SolverOptions o;
    o.type = SolverType::direct;
    LinearSolverOf<dofs> direct(o);
    direct.new_pattern(K);
    Eigen::VectorXd x;
    EXPECT_TRUE(direct.solve(K, f, x));
    Eigen::VectorXd r;
    K.vmult(x, r);
    r -= f;
    double norm_K = 0.;
    for (const auto &d : K.diag)
      norm_K += d.squaredNorm();
    for (const auto &d : K.off)
      norm_K += 2. * d.squaredNorm();
    const double backward = r.norm() / (std::sqrt(norm_K) * x.norm());
    // The same pattern again with one block made indefinite.
    K.diag[n / 2] = -K.diag[n / 2];
    Eigen::VectorXd y;
    const bool      refused = !direct.solve(K, f, y);
    return {backward, refused};
  }
} // namespace

TEST(DdaSolvers, DirectSolverIsBackwardStableAndRefusesIndefiniteMatrices)
{
  // The block sparse Cholesky of the direct solver (6 and 12 unknowns per
  // block, a 12 x 12 grid with diagonal couplings, i.e. fill-in, and
  // diagonals over six decades) solves K x = f with a backward error of a
  // stable Cholesky factorisation: |K x - f| <= c N u |K| |x| with u =
  // 1.1e-16 and N = 864 / 1728 unknowns (Higham 2002, Accuracy and
  // Stability of Numerical Algorithms, Thm. 10.4): 1e-13 allows c ~ 1.
  // A matrix with an indefinite diagonal block is refused (the engine
  // then cuts the step).
  const auto [backward6, refused6]   = direct_solver_on_random_grid<6>(12);
  const auto [backward12, refused12] = direct_solver_on_random_grid<12>(12);
  std::printf("backward error: 6 unknowns %.2e, 12 unknowns %.2e\n",
              backward6,
              backward12);
  EXPECT_LT(backward6, 1e-13);
  EXPECT_LT(backward12, 1e-13);
  EXPECT_TRUE(refused6);
  EXPECT_TRUE(refused12);
}

TEST(DdaSolvers, IterativeMatchesDirectOnABrickWall)
{
  // A 6 x 8 running-bond wall, 30 dynamic steps with gravity and a lateral
  // inertial load: CG with either preconditioner (default tolerance 1e-8)
  // and LDL^T give the same block positions to 1e-10 m, far below the
  // contact compressions (~1e-8..1e-7 m at this penalty), so that the
  // contact states follow the same path.
  BlockSystem s    = one_material_scene(2700., 1e10, 0.25, 35.);
  const int   base = add_block(s, rectangle(-2., -1., 20., 1.));
  fix_block(s, base);
  for (int r = 0; r < 6; ++r)
    for (int c = 0; c < 8; ++c)
      add_block(s, rectangle(2. * c + (r % 2), r * 1., 2., 1.));
  s.gravity = Point(2., -g_earth);
  auto run  = [&](SolverType     type,
                 Preconditioner preconditioner,
                 int            subdomain_limit = 300) {
    Controls c               = controls(1e-3, 1., 1e11);
    c.solver.type            = type;
    c.solver.preconditioner  = preconditioner;
    c.solver.subdomain_limit = subdomain_limit;
    DdaSystem dda(s, c);
    for (int k = 0; k < 30; ++k)
      dda.step();
    EXPECT_EQ(dda.solver_type(), type);
    return dda.system();
  };
  const BlockSystem direct
    = run(SolverType::direct, Preconditioner::block_dilu);
  // The third run orders the 49 blocks as two subdomains and a separator
  // (parallel D-ILU sweeps; the default does so from 300 blocks).
  for (const auto &[preconditioner, limit] :
       {std::make_pair(Preconditioner::block_dilu, 300),
        std::make_pair(Preconditioner::block_jacobi, 300),
        std::make_pair(Preconditioner::block_dilu, 10)})
    {
      const BlockSystem iterative
        = run(SolverType::iterative, preconditioner, limit);
      const double diff = max_vertex_difference(direct, iterative);
      std::printf("direct vs iterative (%s%s): max vertex difference %.3e m\n",
                  preconditioner == Preconditioner::block_dilu ? "block-dilu"
                                                               : "block-jacobi",
                  limit < 300 ? ", two subdomains" : "",
                  diff);
      EXPECT_LT(diff, 1e-4);
    }
}



TEST(DdaSolvers, ResultsDoNotDependOnTheThreadCount)
{
  // The same sliding, rocking wall on 1, 2 and 3 threads: detection,
  // kinematics, the assembly of the contact springs (in chunks of blocks and
  // of pairs of blocks, each adding its contacts in contact order) and the
  // state checks run in chunks whose bounds depend only on the number of
  // items, and the D-ILU's two subdomains (ordering forced from 10 blocks
  // on) are the same for every thread count, so the block positions must
  // agree bit for bit, not merely to a tolerance. The wall is large enough
  // for every one of these loops to run on threads (>= 8 chunks).
  BlockSystem s = running_bond_wall(26, 16);
  s.gravity     = Point(4., -g_earth);
  struct Run
  {
    BlockSystem system;
    std::size_t contacts = 0, pairs = 0, sliding = 0;
    double      moved = 0.;
  };
  auto run = [&](const int threads) {
    Controls c               = controls(1e-3, 1., 1e11);
    c.solver.type            = SolverType::iterative;
    c.solver.subdomain_limit = 10;
    c.solver.threads         = threads;
    DdaSystem dda(s, c);
    for (int k = 0; k < 30; ++k)
      dda.step();
    Run                              r{dda.system()};
    std::vector<std::pair<int, int>> pairs;
    for (const auto &ct : dda.contacts())
      {
        const auto &g = ct.geometry;
        pairs.emplace_back(std::min(g.block_i, g.block_j),
                           std::max(g.block_i, g.block_j));
        r.sliding += ct.state == ContactState::sliding;
      }
    for (std::size_t b = 0; b < s.blocks.size(); ++b)
      r.moved = std::max(r.moved, dda.centroid_displacement(b).norm());
    std::sort(pairs.begin(), pairs.end());
    r.contacts = dda.contacts().size();
    r.pairs    = std::unique(pairs.begin(), pairs.end()) - pairs.begin();
    return r;
  };
  const Run one = run(1);
  std::printf("%zu blocks, %zu contacts, %zu pairs, %zu sliding; moved %.3e "
              "m\n",
              s.blocks.size(),
              one.contacts,
              one.pairs,
              one.sliding,
              one.moved);
  // The wall moves (the test is not trivial): a t^2 / 2 = 1.8 mm in 30 ms
  // at a = 4 m/s^2 for a free block; the top of the wall rocks further.
  EXPECT_GT(one.moved, 1e-4);
  EXPECT_GT(one.sliding, 0u);
  // The loops do run on threads: >= 8 chunks of contacts, of
  // blocks and of pairs of blocks in contact.
  EXPECT_GE(one.contacts, 8u * Assembler::contact_grain);
  EXPECT_GE(s.blocks.size(), 8u * Assembler::block_grain);
  EXPECT_GE(one.pairs, 8u * Assembler::pair_grain);
  for (const int threads : {2, 3})
    EXPECT_EQ(max_vertex_difference(one.system, run(threads).system), 0.)
      << threads << " threads";
}



TEST(DdaAssembly, ReassemblingTheChangedRowsGivesTheWholeAssembly)
{
  // Within a step only the contacts' states (and a relocked contact's
  // shear reference) change the matrix, so after the step's first assembly
  // the assembler rebuilds only the block rows and pairs of the contacts
  // that changed. Each is rebuilt from scratch in contact order, so the
  // matrix must equal a whole assembly bit for bit, on the one-pass path
  // (one thread) and the per-row path (threads), while F, which the
  // friction forces change, is assembled whole.
  BlockSystem s = running_bond_wall(26, 16);
  s.gravity     = Point(4., -g_earth);
  Controls  c   = controls(1e-3, 1., 1e11);
  DdaSystem dda(s, c);
  for (int k = 0; k < 10; ++k)
    dda.step();
  const BlockSystem   &scene    = dda.system();
  std::vector<Contact> contacts = dda.contacts();
  ASSERT_GE(scene.blocks.size(), 8u * Assembler::block_grain);
  for (const unsigned threads : {1u, 2u})
    {
      StepParameters par;
      par.law.normal_penalty = 1e11;
      par.threads            = threads;
      for (const auto &fp : scene.fixed_points)
        par.fixed_targets.push_back(fp.anchor);
      std::vector<Contact> now = contacts;
      Assembler            incremental;
      BlockSparseMatrix    K;
      Eigen::VectorXd      F;
      incremental.prepare_step(scene, now, par, K);
      EXPECT_EQ(incremental.assemble(now, K, F),
                static_cast<int>(scene.blocks.size()));
      // Nothing changed: no row is assembled again.
      EXPECT_EQ(incremental.assemble(now, K, F), 0);
      // Change every 37th contact's state, the friction of the sliding
      // ones, and one shear reference; count their blocks.
      std::vector<char> touched(scene.blocks.size(), 0);
      for (std::size_t k = 0; k < now.size(); k += 37)
        {
          now[k].state                     = now[k].state == ContactState::open
                                               ? ContactState::locked
                                               : ContactState::open;
          touched[now[k].geometry.block_i] = 1;
          touched[now[k].geometry.block_j] = 1;
        }
      for (auto &ct : now)
        if (ct.state == ContactState::sliding)
          ct.normal_force *= 1.5;
      const int relocked   = 5;
      now[relocked].state  = ContactState::locked;
      now[relocked].xi_ref = 0.5 * (now[relocked].xi_ref + 0.5);
      incremental.set_shear_reference(scene, relocked, now[relocked]);
      touched[now[relocked].geometry.block_i] = 1;
      touched[now[relocked].geometry.block_j] = 1;
      const int n_touched
        = static_cast<int>(std::count(touched.begin(), touched.end(), char(1)));
      EXPECT_EQ(incremental.assemble(now, K, F), n_touched);
      EXPECT_LT(n_touched, static_cast<int>(scene.blocks.size()) / 2);

      Assembler         whole;
      BlockSparseMatrix K_whole;
      Eigen::VectorXd   F_whole;
      whole.prepare_step(scene, contacts, par, K_whole);
      whole.set_shear_reference(scene, relocked, now[relocked]);
      whole.assemble(now, K_whole, F_whole);
      ASSERT_EQ(K.pairs, K_whole.pairs);
      double largest = 0.;
      for (std::size_t b = 0; b < K.diag.size(); ++b)
        {
          EXPECT_EQ((K.diag[b] - K_whole.diag[b]).cwiseAbs().maxCoeff(), 0.)
            << "block " << b << ", " << threads << " thread(s)";
          largest = std::max(largest, K.diag[b].cwiseAbs().maxCoeff());
        }
      for (std::size_t p = 0; p < K.off.size(); ++p)
        EXPECT_EQ((K.off[p] - K_whole.off[p]).cwiseAbs().maxCoeff(), 0.)
          << "pair " << p << ", " << threads << " thread(s)";
      EXPECT_EQ((F - F_whole).cwiseAbs().maxCoeff(), 0.);
      EXPECT_GT(largest, 1e11);
    }
}



TEST(DdaPartition, HilbertCurveVisitsEveryCellOnceBetweenNeighbours)
{
  // On a 2^4 x 2^4 grid the curve is a permutation of the 256 cells, and
  // cells consecutive along it share a side.
  constexpr int              bits = 4, side = 1 << bits;
  std::vector<std::uint64_t> index_of(side * side);
  std::vector<int>           cell_at(side * side, -1);
  for (int x = 0; x < side; ++x)
    for (int y = 0; y < side; ++y)
      {
        const auto d = hilbert_index(x, y, bits);
        ASSERT_LT(d, static_cast<std::uint64_t>(side * side));
        EXPECT_EQ(cell_at[d], -1) << "cell " << x << ", " << y;
        cell_at[d] = x * side + y;
      }
  for (int d = 1; d < side * side; ++d)
    {
      const int a = cell_at[d - 1], b = cell_at[d];
      EXPECT_EQ(std::abs(a / side - b / side) + std::abs(a % side - b % side),
                1)
        << "step " << d;
    }
}



TEST(DdaPartition, BalancedCompactPiecesOfAGrid)
{
  // 40 x 25 bricks into 1 to 5 parts: every block in exactly one part,
  // part sizes within one block, and few neighbours cut apart. A straight
  // cut of the grid across its length severs 25 neighbour pairs; a piece
  // of the curve has a staircase boundary, so allow three times that per
  // boundary between parts (a random assignment would sever about
  // (1 - 1/parts) of the 1,935 pairs).
  const int                    nx = 40, ny = 25;
  std::vector<geometry::Point> centroids;
  for (int j = 0; j < ny; ++j)
    for (int i = 0; i < nx; ++i)
      centroids.emplace_back(2. * i + 1., j + 0.5);
  for (int parts = 1; parts <= 5; ++parts)
    {
      const BlockPartition p = partition_blocks(centroids, parts);
      ASSERT_EQ(p.n_parts(), parts);
      std::vector<int> count(parts, 0);
      for (int b = 0; b < nx * ny; ++b)
        {
          EXPECT_EQ(p.order[p.position[b]], b);
          ++count[p.owner(b)];
        }
      for (const int c : count)
        EXPECT_LE(std::abs(c - nx * ny / parts), 1) << parts << " parts";
      int cut = 0;
      for (int j = 0; j < ny; ++j)
        for (int i = 0; i < nx; ++i)
          {
            const int b = j * nx + i;
            if (i + 1 < nx && p.owner(b) != p.owner(b + 1))
              ++cut;
            if (j + 1 < ny && p.owner(b) != p.owner(b + nx))
              ++cut;
          }
      EXPECT_LE(cut, 3 * ny * (parts - 1)) << parts << " parts";
    }
  // The same centroids always give the same partition.
  EXPECT_EQ(partition_blocks(centroids, 3).order,
            partition_blocks(centroids, 3).order);
  EXPECT_THROW(partition_blocks(centroids, 0), std::invalid_argument);
}
