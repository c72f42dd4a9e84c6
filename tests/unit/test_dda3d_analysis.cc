/**
 * @file
 * 3D DDA scene checks and the analysis type "dda3d" (issue 17): overlap at
 * t = 0, the block on an incline run through the analysis type
 * (statistics.csv, summary, VTU series), the seismic loading and
 * displacement modes, the thesis's Fig. 4-2A/B against
 * analytical::slide_3d, and checkpoints (a resumed run is bit for bit the
 * uninterrupted one).
 */
#include <rockdda/analytical/sliding3d.h>
#include <rockdda/analytical/yield.h>
#include <rockdda/dda3d/analyses.h>
#include <rockdda/dda3d/block_file.h>
#include <rockdda/dda3d/engine.h>
#include <rockdda/dda3d/generators.h>
#include <rockdda/io/binary_stream.h>
#include <rockdda/io/error.h>

#include <deal.II/base/parameter_handler.h>

#include <Eigen/Geometry>
#include <gtest/gtest.h>

#include "dda3d_test_scenes.h"
#include "test_files.h"
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>
#include <string>
#include <vector>

using namespace rockdda;
using namespace rockdda::dda3d;
using rockdda::test_files::error_of;

namespace
{
  const double pi = std::acos(-1.);

  /// @p p rotated by @p R and shifted by @p shift.
  Polyhedron
  moved(Polyhedron p, const Eigen::Matrix3d &R, const Point &shift)
  {
    for (auto &v : p.vertices)
      v = R * v + shift;
    return p;
  }

  /// Two blocks (ids 1 and 2) of one material and one joint.
  BlockSystem
  two_blocks(const Polyhedron &a, const Polyhedron &b)
  {
    BlockSystem s;
    s.materials.push_back({2700., 1e10, 0.25, 1});
    s.joints.push_back(dda::JointMaterial());
    Block x;
    x.material   = 0;
    x.id         = 1;
    x.polyhedron = a;
    Block y      = x;
    y.id         = 2;
    y.polyhedron = b;
    s.blocks     = {x, y};
    return s;
  }

  std::string
  engine_error(const BlockSystem &s)
  {
    EngineControls c;
    return error_of([&]() { Engine e(s, c); });
  }

  /**
   * The frame of a plane with dip @p dip_deg and dip direction
   * @p dip_direction_deg: columns down the dip line, along strike, and the
   * upward normal (x east, y north, z up).
   */
  Eigen::Matrix3d
  plane_frame(const double dip_deg, const double dip_direction_deg)
  {
    const double    d = dip_deg * pi / 180., b = dip_direction_deg * pi / 180.;
    const Point     e1(std::sin(b) * std::cos(d),
                   std::cos(b) * std::cos(d),
                   -std::sin(d));
    const Point     e3 = analytical::plane_normal(dip_deg, dip_direction_deg);
    Eigen::Matrix3d Q;
    Q << e1, e3.cross(e1), e3;
    return Q;
  }

  /**
   * Block-file text of a cube of edge @p s on a clamped 8 x 4 x 1 m base
   * whose top is the plane (dip, dip direction), 2 m up the dip line from
   * the origin, with a measurement point at its centroid; material
   * (rho, E, nu), joint friction @p phi.
   */
  std::string
  incline_blocks(const double dip,
                 const double dip_direction,
                 const double phi,
                 const double rho,
                 const double E,
                 const double s = 1.)
  {
    const Eigen::Matrix3d Q = plane_frame(dip, dip_direction);
    // The scene's fixed points are replaced by 'fixed-block 1' below.
    BlockSystem sys = test_scenes::incline_scene(0.,
                                                 phi,
                                                 Point(-4., -2., -1.),
                                                 Point(4., 2., 0.),
                                                 Point(-2. - s / 2, -s / 2, 0.),
                                                 Point(-2. + s / 2, s / 2, s),
                                                 {rho, E, 0.25, 1},
                                                 Q)
                        .system;
    sys.fixed_points.clear();
    std::string text = block_text(sys);
    char        line[256];
    const Point m = Q * Point(-2., 0., s / 2);
    std::snprintf(line,
                  sizeof(line),
                  "fixed-block 1\nmeasure 2 %.17g %.17g %.17g\n",
                  m.x(),
                  m.y(),
                  m.z());
    return text + line;
  }

  /// Summary of a dda3d run: quantity -> value.
  using Summary = std::map<std::string, double>;

  /// The rows of a CSV table of numbers, keyed by its header.
  std::vector<std::map<std::string, double>>
  read_table(const std::filesystem::path &file)
  {
    std::ifstream            in(file);
    std::string              line, cell;
    std::vector<std::string> head;
    std::getline(in, line);
    std::istringstream h(line);
    while (std::getline(h, cell, ','))
      head.push_back(cell);
    std::vector<std::map<std::string, double>> rows;
    while (std::getline(in, line))
      {
        std::istringstream r(line);
        auto              &row = rows.emplace_back();
        for (std::size_t k = 0; k < head.size() && std::getline(r, cell, ',');
             ++k)
          row[head[k]] = std::atof(cell.c_str());
      }
    return rows;
  }

  /// Run "dda3d" on @p prm_text in the folder @p dir (kept: its output
  /// folder "out" may hold a checkpoint); returns summary.csv's values,
  /// @p wall the wall time of parsing and running (s).
  Summary
  run_dda3d_in(const std::filesystem::path &dir,
               const std::string           &prm_text,
               double                      *wall = nullptr)
  {
    auto  analyses = make_analyses();
    auto &a        = *analyses.front();
    EXPECT_EQ(a.name(), "dda3d");
    const auto        start   = std::chrono::steady_clock::now();
    const io::Summary summary = test_files::run_analysis_in(a, dir, prm_text);
    if (wall)
      *wall = std::chrono::duration<double>(std::chrono::steady_clock::now()
                                            - start)
                .count();
    std::istringstream in(summary.csv());
    std::string        line;
    Summary            s;
    std::getline(in, line);
    while (std::getline(in, line))
      {
        const auto c1 = line.find(','), c2 = line.find(',', c1 + 1);
        s[line.substr(0, c1)]
          = std::atof(line.substr(c1 + 1, c2 - c1 - 1).c_str());
      }
    return s;
  }

  /**
   * Run the analysis type "dda3d" on the parameter text @p prm_text (the
   * "DDA 3d" and "Ground motion" sections) with the block file text
   * @p blocks in a scratch folder @p name; returns summary.csv's values.
   * @p wall receives the run's wall time (s), @p history the rows of
   * statistics.csv.
   */
  Summary
  run_dda3d(const std::string                          &name,
            const std::string                          &blocks,
            const std::string                          &prm_text,
            double                                     *wall    = nullptr,
            std::vector<std::map<std::string, double>> *history = nullptr)
  {
    const auto dir = test_files::scratch(name);
    test_files::write_file(dir / "scene.blocks", blocks);
    const Summary s = run_dda3d_in(dir, prm_text, wall);
    // The output files exist (written atomically through OutputDirectory).
    EXPECT_TRUE(std::ifstream(dir / "out" / "statistics.csv").good());
    if (history)
      *history = read_table(dir / "out" / "statistics.csv");
    return s;
  }

  /// Parameter text of a dda3d run on scene.blocks.
  std::string
  dda3d_prm(const double       end_time,
            const double       dt,
            const double       penalty,
            const std::string &extra = "")
  {
    std::ostringstream p;
    p.precision(17);
    p << "subsection DDA 3d\n"
      << "  set Block file = scene.blocks\n"
      << "  set End time = " << end_time << "\n"
      << "  set Time step = " << dt << "\n"
      << "  set Contact penalty = " << penalty << "\n"
      << "  set Output interval = 0\n"
      << extra << "end\n";
    return p.str();
  }

  /// The shaking table of thesis Sec. 4.6-4.7.2: the wedge on joints
  /// 51.4/065.8 and 51.4/295.2 in its trough (clamped; margin @p margin m)
  /// under a slope face 80/000.5, Table 4-1's material, joint friction
  /// @p phi (deg); and the input: a 2 Hz sinusoid of 0.21 g along 000.5
  /// with a linear ramp of @p ramp s, @p record s long, sampled at 5 ms and
  /// low-passed at 2.5 Hz (order 4, zero phase), read as the dda3d analysis
  /// reads it (loading mode) for a run of @p end_time s at @p dt s.
  struct ShakingTable
  {
    BlockSystem           scene;
    std::string           ground;
    dda3d::SeismicInput3d input;
  };

  /// Parameter text of a dda3d run of the shaking table (20 settling
  /// steps, statistics every 0.01 s, the ground motion along 000.5 in
  /// @p mode) with @p extra keys.
  std::string
  shaking_table_prm(const double       end_time,
                    const double       dt,
                    const double       penalty,
                    const std::string &mode,
                    const std::string &extra = "")
  {
    return dda3d_prm(end_time,
                     dt,
                     penalty,
                     "  set Settling steps = 20\n  set Statistics interval = "
                     "0.01\n  set Seismic input = "
                       + mode
                       + "\n  set Seismic source = ground motion\n  set "
                         "Ground motion azimuth = 0.5\n"
                       + extra);
  }

  ShakingTable
  shaking_table(const double phi,
                const double margin,
                const double ramp,
                const double record,
                const double end_time,
                const double dt)
  {
    std::ostringstream ground;
    ground << "subsection Ground motion\n"
           << "  set Source = harmonic\n  set Harmonic amplitude = 0.21\n"
           << "  set Harmonic frequency = 2\n"
           << "  set Harmonic ramp duration = " << ramp
           << "\n  set Duration = " << record
           << "\n  set Time step = 0.005\n  subsection Processing\n"
           << "    set Low-pass corner = 2.5\n    set Filter order = 4\n"
           << "  end\nend\n";
    dda::JointMaterial joint;
    joint.friction_deg = phi;
    ShakingTable t{
      wedge_in_trough_scene(
        make_wedge_in_trough({51.4, 65.8, 51.4, 295.2, 80., 0.5}, 0.1, margin),
        {1700., 2e11, 0.25, 1},
        joint),
      ground.str(),
      {}};
    dealii::ParameterHandler prm;
    auto                     analyses = make_analyses();
    analyses.front()->declare_parameters(prm);
    prm.parse_input_from_string(t.ground
                                + "subsection DDA 3d\n  set Seismic input = "
                                  "loading\n  set Seismic source = ground "
                                  "motion\n  set Ground motion azimuth = "
                                  "0.5\nend\n");
    t.input = parse_seismic_input(prm, "test.prm", end_time, dt, 9.80665);
    return t;
  }

  /// The rigid wedge on @p p1 and @p p2 (analytical::slide_3d, steps of
  /// 1e-4 s, output every 0.01 s) under the shaking table's input for
  /// @p duration s.
  analytical::Sliding3dResult
  rigid_wedge(const analytical::SlidingPlane &p1,
              const analytical::SlidingPlane &p2,
              const ShakingTable             &table,
              const double                    duration)
  {
    analytical::Sliding3dOptions o;
    o.wedge           = true;
    o.plane1          = p1;
    o.plane2          = p2;
    o.time_step       = 1e-4;
    o.duration        = duration;
    o.output_interval = 0.01;
    return analytical::slide_3d(
      [&](const double t) {
        return Eigen::Vector3d(Point(0., 0., -1.)
                               - table.input.acceleration(t) / 9.80665);
      },
      o);
  }
} // namespace



TEST(Dda3dScene, OverlapAtStartIsRejectedNamingBothBlocks)
{
  const Polyhedron base = make_box(Point(0., 0., 0.), Point(2., 2., 1.));
  // Resting on it (touching), and sunk 0.1 m into it.
  EXPECT_EQ(engine_error(two_blocks(
              base, make_box(Point(0.5, 0.5, 1.), Point(1.5, 1.5, 2.)))),
            "");
  const std::string e = engine_error(
    two_blocks(base, make_box(Point(0.5, 0.5, 0.9), Point(1.5, 1.5, 1.9))));
  std::printf("overlap message: %s\n", e.c_str());
  EXPECT_NE(e.find("block 1 overlaps block 2 at t = 0 by 0.1 m"),
            std::string::npos)
    << e;
  // Crossed beams 1 mm into each other: no vertex of either is inside the
  // other (edges cross faces); the separating-axis test finds it.
  {
    const Polyhedron a = make_box(Point(-2., -0.1, -0.2), Point(2., 0.1, 0.));
    const Polyhedron b = make_box(Point(-0.1, -2., -1e-3), Point(0.1, 2., 0.2));
    const std::string m = engine_error(two_blocks(a, b));
    EXPECT_NE(m.find("block 1 overlaps block 2 at t = 0 by 0.001 m"),
              std::string::npos)
      << m;
    const Polyhedron c = make_box(Point(-0.1, -2., 0.), Point(0.1, 2., 0.2));
    EXPECT_EQ(engine_error(two_blocks(a, c)), "");
  }
  // Round-off (1e-9 of the size) is allowed; at UTM coordinates too.
  {
    const Point utm(5e5, 4e6, 100.);
    const auto  s = two_blocks(moved(base, Eigen::Matrix3d::Identity(), utm),
                              moved(make_box(Point(0.5, 0.5, 1. - 1e-9),
                                             Point(1.5, 1.5, 2.)),
                                    Eigen::Matrix3d::Identity(),
                                    utm));
    EXPECT_EQ(engine_error(s), "");
  }
  // A non-convex block (an L prism) with a box in its notch: touching is
  // fine, 5 cm into the leg is not.
  {
    geometry::Polygon L;
    L.vertices = {{0., 0.}, {2., 0.}, {2., 1.}, {1., 1.}, {1., 2.}, {0., 2.}};
    const Polyhedron l = make_prism(L, 0., 1.);
    EXPECT_EQ(engine_error(
                two_blocks(l, make_box(Point(1., 1., 0.), Point(2., 2., 1.)))),
              "");
    const std::string m = engine_error(
      two_blocks(l, make_box(Point(0.95, 1.2, 0.2), Point(1.9, 1.9, 0.8))));
    EXPECT_NE(m.find("block 1 overlaps block 2"), std::string::npos) << m;
  }
  // Through the block file and the analysis: the file and both ids.
  {
    const auto  dir = test_files::scratch("dda3d-overlap");
    BlockSystem s
      = two_blocks(base, make_box(Point(0.5, 0.5, 0.9), Point(1.5, 1.5, 1.9)));
    s.blocks[0].id = 7;
    s.blocks[1].id = 9;
    test_files::write_file(dir / "scene.blocks", block_text(s));
    const std::string prm_file = (dir / "run.prm").string();
    const std::string text     = dda3d_prm(1., 0.01, 1e10);
    test_files::write_file(prm_file, text);
    auto                     analyses = make_analyses();
    dealii::ParameterHandler prm;
    analyses.front()->declare_parameters(prm);
    prm.parse_input_from_string(text);
    const std::string m
      = error_of([&]() { analyses.front()->parse_parameters(prm, prm_file); });
    EXPECT_NE(m.find("scene.blocks"), std::string::npos) << m;
    EXPECT_NE(m.find("block 7 overlaps block 9"), std::string::npos) << m;
  }
}



TEST(Dda3dAnalysis, BadInputNamesFileKeyAndRange)
{
  const auto dir = test_files::scratch("dda3d-bad");
  test_files::write_file(dir / "scene.blocks",
                         incline_blocks(20., 90., 30., 1000., 2e7));
  const std::string prm_file = (dir / "run.prm").string();
  auto              error    = [&](const std::string &text) {
    test_files::write_file(prm_file, text);
    auto                     analyses = make_analyses();
    dealii::ParameterHandler prm;
    analyses.front()->declare_parameters(prm);
    return error_of([&]() {
      try
        {
          prm.parse_input_from_string(text);
        }
      catch (const dealii::ExceptionBase &e)
        {
          throw InputError(e.what());
        }
      analyses.front()->parse_parameters(prm, prm_file);
    });
  };
  std::string m = error(dda3d_prm(1., 0.01, 1e10, "  set Block file =\n"));
  EXPECT_NE(m.find("'DDA 3d/Block file' is empty"), std::string::npos) << m;
  m = error(dda3d_prm(1e9, 1e-3, 1e10));
  EXPECT_NE(m.find("'DDA 3d/Time step'"), std::string::npos) << m;
  EXPECT_NE(m.find("at most 1e+08"), std::string::npos) << m;
  // A value outside the declared range is refused while the file is read
  // (the pattern names the key and the range).
  m = error(
    dda3d_prm(1., 0.01, 1e10, "  set Maximum displacement ratio = 0\n"));
  EXPECT_NE(m.find("Maximum displacement ratio"), std::string::npos) << m;
  EXPECT_NE(m.find("0 < x <= 1"), std::string::npos) << m;
  // The sanity check's penetration bound, a key of both analyses: beyond
  // 10 % of a block the penalty method's overlap is no longer a contact.
  m = error(dda3d_prm(1., 0.01, 1e10, "  set Penetration limit = 0.5\n"));
  EXPECT_NE(m.find("Penetration limit"), std::string::npos) << m;
  EXPECT_NE(m.find("0 < x <= 0.1"), std::string::npos) << m;
  m = error(dda3d_prm(1.,
                      0.01,
                      1e10,
                      "  set Seismic input = loading\n"
                      "  set Ground acceleration = sin(t; 0\n"));
  EXPECT_NE(m.find("'DDA 3d/Ground acceleration'"), std::string::npos) << m;
}



TEST(Dda3dAnalysis, InclineSlidesAsTheClosedFormThroughTheAnalysisType)
{
  // A 1 m cube (rho 2700, E 10 GPa) on a 30/090 plane, phi = 20 deg:
  // d = g/2 (sin a - cos a tan phi) t^2 = 0.906098 m at 1 s down the dip
  // (+x, -z), nothing along strike. Penalty 1e11 N/m, dt 5 ms (the engine
  // test measures 7.5e-5 at these settings: the start-up transient).
  const double a = 30. * pi / 180., phi = 20. * pi / 180., g = 9.80665;
  const double d_exact = 0.5 * g * (std::sin(a) - std::cos(a) * std::tan(phi));
  const auto   s
    = run_dda3d("dda3d-incline",
                incline_blocks(30., 90., 20., 2700., 1e10),
                dda3d_prm(1., 0.005, 1e11, "  set Output interval = 0.25\n"));
  const Point  u(s.at("mp1_ux"), s.at("mp1_uy"), s.at("mp1_uz"));
  const Point  down(std::cos(a), 0., -std::sin(a));
  const double along = u.dot(down), across = std::abs(u.y());
  const double error = std::abs(along - d_exact) / d_exact;
  std::printf("dda3d incline: along %.6f m (exact %.6f), error %.2e, across "
              "%.1e m, normal %.1e m, energy created %.2e J, %g steps\n",
              along,
              d_exact,
              error,
              across,
              std::abs((u - along * down).norm()),
              s.at("energy_created_max"),
              s.at("steps"));
  EXPECT_NEAR(s.at("final_time"), 1., 1e-12);
  EXPECT_LT(error, 1e-3);
  EXPECT_LT(across, 1e-9);
  // Shi's scheme may only lose energy (up to the ledger's round-off):
  // the contact springs' trial energy, m g h x 1e-6.
  EXPECT_LT(s.at("energy_created_max"), 2700. * g * 1e-6);
}



namespace
{
  /// "(ux, uy, uz) m, analytical (...) m, error e" of a displacement @p u
  /// against @p exact (the relative error of the vector).
  std::string
  against_exact(const Point &u, const Point &exact)
  {
    char line[200];
    std::snprintf(line,
                  sizeof(line),
                  "(%.5f, %.2e, %.5f) m, analytical (%.5f, %.2e, %.5f) m, "
                  "error %.2e",
                  u.x(),
                  u.y(),
                  u.z(),
                  exact.x(),
                  exact.y(),
                  exact.z(),
                  (u - exact).norm() / exact.norm());
    return line;
  }

  /// slide_3d on one plane under r(t) (g) with time step @p dt: the final
  /// displacement (m).
  Point
  analytical_slide(const double                                  dip,
                   const double                                  dip_direction,
                   const double                                  phi,
                   const std::function<Eigen::Vector3d(double)> &r,
                   const double                                  duration,
                   const double                                  dt)
  {
    analytical::Sliding3dOptions o;
    o.plane1.dip_deg           = dip;
    o.plane1.dip_direction_deg = dip_direction;
    o.plane1.friction          = analytical::FrictionLaw::coulomb_deg(phi);
    o.time_step                = dt;
    o.duration                 = duration;
    o.output_interval          = duration;
    return analytical::slide_3d(r, o).final_displacement;
  }
} // namespace



TEST(Dda3dSeismic, DisplacementModeMovesTheFoundationByTheDoubleIntegral)
{
  // a_g = (0.1 sin(2 pi t), -0.05 sin(pi t), 0.02 sin(4 pi t)) g: the
  // clamped base follows u_g = A g (t / w - sin(w t) / w^2) per component
  // (from rest); a block resting on it is carried along (phi = 40 deg on a
  // flat base: 0.1 g < tan 40 g).
  const double g = 9.80665, T = 1.;
  const Point  A(0.1, -0.05, 0.02), w(2. * pi, pi, 4. * pi);
  std::string  blocks = incline_blocks(0., 90., 40., 2700., 1e10);
  // A second measurement point, on the base.
  blocks += "measure 1 0 0 -0.5\n";
  const auto s
    = run_dda3d("dda3d-displacement-mode",
                blocks,
                dda3d_prm(T,
                          0.005,
                          1e11,
                          "  set Seismic input = displacement\n"
                          "  set Ground acceleration = 0.1*sin(2*pi*t); "
                          "-0.05*sin(pi*t); 0.02*sin(4*pi*t)\n"));
  Point exact;
  for (int d = 0; d < 3; ++d)
    exact[d] = A[d] * g * (T / w[d] - std::sin(w[d] * T) / (w[d] * w[d]));
  const Point base(s.at("mp2_ux"), s.at("mp2_uy"), s.at("mp2_uz"));
  const Point ground(s.at("ground_ux"), s.at("ground_uy"), s.at("ground_uz"));
  const Point block(s.at("mp1_ux"), s.at("mp1_uy"), s.at("mp1_uz"));
  std::printf("displacement mode: base %.3e m from the closed form (ground "
              "integral %.3e), block - base %.3e m\n",
              (base - exact).norm(),
              (ground - exact).norm(),
              (block - base).norm());
  // The piecewise-linear integral of the expression sampled at dt / 20:
  // O((dt / 20)^2 w^2) of the displacement.
  EXPECT_LT((ground - exact).norm(), 1e-6 * exact.norm());
  EXPECT_LT((base - exact).norm(), 1e-6 * exact.norm());
  // The block sticks: it moves with the base up to the contact springs'
  // elastic response (m a / k_s ~ 2700 x 1 / 4e10 ~ 1e-7 m).
  EXPECT_LT((block - base).norm(), 1e-5);
}



TEST(Dda3dSeismic, LoadingAndDisplacementModesAgreeWithSliding3d)
{
  // A 1 m cube (rho = 1000 kg/m^3, E = 20 GPa: rigid next to its contact
  // springs) on a plane 20/090, phi = 30 deg, settled by 20 static steps,
  // under a 2 Hz harmonic of 0.35 g along x (azimuth 090) with a 2 s
  // linear ramp, low-passed at 2.5 Hz (Butterworth, order 4, padding
  // kept), for 4 s; the Ground motion section's record drives both modes.
  // The block slides down the dip in pulses when the ground accelerates
  // up the dip by more than about g sin(phi - alpha) / cos(phi) = 0.2 g.
  const std::string ground = "subsection Ground motion\n"
                             "  set Source = harmonic\n"
                             "  set Harmonic amplitude = 0.35\n"
                             "  set Harmonic frequency = 2\n"
                             "  set Harmonic ramp duration = 2\n"
                             "  set Duration = 4\n"
                             "  set Time step = 0.005\n"
                             "  subsection Processing\n"
                             "    set Low-pass corner = 2.5\n"
                             "    set Filter order = 4\n"
                             "  end\n"
                             "end\n";
  const double      dt = 0.002, T = 4., penalty = 1e11;
  const std::string blocks = incline_blocks(20., 90., 30., 1000., 2e10);
  std::map<std::string, Point> slip;
  for (const std::string mode : {"loading", "displacement"})
    {
      const auto s = run_dda3d("dda3d-mode-" + mode,
                               blocks,
                               ground
                                 + dda3d_prm(T,
                                             dt,
                                             penalty,
                                             "  set Settling steps = 20\n"
                                             "  set Seismic input = "
                                               + mode
                                               + "\n  set Seismic source = "
                                                 "ground motion\n"
                                                 "  set Ground motion "
                                                 "azimuth = 90\n"));
      Point      u(s.at("mp1_ux"), s.at("mp1_uy"), s.at("mp1_uz"));
      if (mode == "displacement")
        u -= Point(s.at("ground_ux"), s.at("ground_uy"), s.at("ground_uz"));
      slip[mode] = u;
    }
  // The analytical solution under the same processed record.
  dealii::ParameterHandler prm;
  auto                     analyses = make_analyses();
  analyses.front()->declare_parameters(prm);
  prm.parse_input_from_string(
    ground
    + "subsection DDA 3d\n  set Seismic input = loading\n  set Seismic "
      "source = ground motion\nend\n");
  const auto  in    = parse_seismic_input(prm, "test.prm", T, dt, 9.80665);
  const Point exact = analytical_slide(
    20.,
    90.,
    30.,
    [&](const double t) {
      return Eigen::Vector3d(Point(0., 0., -1.) - in.acceleration(t) / 9.80665);
    },
    T,
    1e-4);
  for (const auto &[mode, u] : slip)
    std::printf("%s mode: slip %s\n",
                mode.c_str(),
                against_exact(u, exact).c_str());
  // Measured: 3.7e-3 (loading) and 3.7e-3 (displacement) of the 4.5 cm
  // slip (3.5e-3 and 2.7e-3 before the spin of a face in planar contact
  // was resisted), 7e-3 - 1.2e-2 at a penalty of 1e10 N/m: the contact
  // springs' compliance, ~1 / penalty. 1 % holds at 1e11 N/m.
  ASSERT_GT(exact.norm(), 0.04);
  for (const auto &[mode, u] : slip)
    EXPECT_LT((u - exact).norm(), 0.01 * exact.norm()) << mode;
  EXPECT_LT((slip["loading"] - slip["displacement"]).norm(),
            0.005 * exact.norm());
}



namespace
{
  /**
   * Thesis Fig. 4-2A (@p b false) or 4-2B: a 1 m cube of rho = 1000 kg/m^3
   * and Young's modulus @p E on a plane 20/090, phi = 30 deg, settled by 20
   * static steps, under r = [0.5 sin 10t, 0, -1] g (A) or
   * [0.5 sin 10t, 0.5 sin 5t, -1] g (B) for 2 pi s in the loading mode
   * (a_g = gravity - r) at time step @p dt and penalty @p penalty, with the
   * extra keys @p extra. Prints and returns the relative error of the final
   * displacement vector against sliding3d's; @p summary receives the run's.
   */
  double
  fig4_2_error(const bool         b,
               const double       E,
               const double       dt,
               const double       penalty,
               const std::string &extra,
               Summary           *summary = nullptr)
  {
    double            wall = 0.;
    const std::string expr
      = std::string("  set Ground acceleration = -0.5*sin(10*t); ")
        + (b ? "-0.5*sin(5*t)" : "0") + "; 0\n";
    const auto  s = run_dda3d(std::string(b ? "dda3d-fig4-2b" : "dda3d-fig4-2a")
                               + (E < 1e9 ? "-table4-1" : ""),
                             incline_blocks(20., 90., 30., 1000., E),
                             dda3d_prm(2. * pi,
                                       dt,
                                       penalty,
                                       "  set Settling steps = 20\n"
                                        "  set Seismic input = loading\n"
                                         + expr + extra),
                             &wall);
    const Point u(s.at("mp1_ux"), s.at("mp1_uy"), s.at("mp1_uz"));
    const Point exact = analytical_slide(
      20.,
      90.,
      30.,
      [b](const double t) {
        return Eigen::Vector3d(0.5 * std::sin(10. * t),
                               b ? 0.5 * std::sin(5. * t) : 0.,
                               -1.);
      },
      2. * pi,
      1e-4);
    const double error = (u - exact).norm() / exact.norm();
    std::printf("Fig. 4-2%c (E = %g Pa): DDA %s, %.2f s wall, %g steps\n",
                b ? 'B' : 'A',
                E,
                against_exact(u, exact).c_str(),
                wall,
                s.at("steps"));
    EXPECT_GT(exact.norm(), 1.);
    if (summary)
      *summary = s;
    return error;
  }
} // namespace



TEST(Dda3dSeismic, ThesisFig4_2AAndBAgainstSliding3d)
{
  // Thesis Fig. 4-2 at Table 4-1's dt = 0.01 s. With E = 20 GPa (a rigid
  // block, as the analytical solution assumes) and a penalty of 1e10 N/m
  // the final displacement vector is within 1.4e-3 (A) and 1.7e-3 (B) of
  // the analytical one (benchmarks/dda3d: 7e-4 - 5e-3 for 1e9 - 1e11 N/m
  // and dt = 1 - 10 ms).
  for (const bool b : {false, true})
    EXPECT_LT(fig4_2_error(b, 2e10, 0.01, 1e10, ""), 0.01);
}



TEST(Dda3dSeismic, ThesisFig4_2AAndBWithTable4_1BlockAgainstSliding3d)
{
  // Thesis Fig. 4-2 with Table 4-1's block (E = 20 MPa, nu = 0.25, rho =
  // 1000 kg/m^3), penalty 1e10 N/m, dt = 5 ms (the thesis's 10 ms gives
  // 1.15 % (A) and 0.90 % (B); 5 ms 0.61 % and 0.84 %; 2.5 ms 0.59 % and
  // 0.81 %). Undamped, the block's
  // uniform-strain mode on its base (omega = (3 E A / m L)^1/2 = 245
  // rad/s) is self-excited by the sliding friction: it grows within
  // 0.5 s to corners lifting off (benchmarks/dda3d/README.md: 1.7 - 25 %
  // error, growing as dt falls). A Kelvin-Voigt strain damping of eta =
  // 5e-3 s (ratio eta omega / 2 = 0.61 at that mode, 0.025 at the 10 rad/s
  // input) suppresses it. (The figures 5.7e-3 - 8.5e-3 over dt = 1 - 10
  // ms measured before the shared step control were at a finer step than
  // stated: after a cut the engine never grew back to dt.) The E = 20 GPa
  // block: 1.2e-3 - 2.2e-3 over dt = 2.5 - 10 ms. The target: 1 %.
  for (const bool b : {false, true})
    {
      Summary      s;
      const double error = fig4_2_error(
        b, 2e7, 0.005, 1e10, "  set Strain damping = 5e-3\n", &s);
      EXPECT_LT(error, 0.01);
      // The damping dissipates (the ledger books it) and no energy is
      // created: the balance never rises above its start by more than the
      // ledger's round-off, 1e-6 m g L.
      EXPECT_GT(s.at("damping_dissipation"), 0.);
      EXPECT_LT(s.at("energy_created_max"), 1e-6 * 1000. * 9.80665);
    }
}



TEST(Dda3dAnalysis, StrainDampingLeavesASlidingBlockAlone)
{
  // Table 4-1's soft block (E = 20 MPa) on a 20/090 plane with phi = 10
  // deg slides under gravity as a rigid block: d = g/2 (sin a - cos a tan
  // phi) t^2 at 1 s. Its strain is constant while it slides, so a strain
  // damping (here eta = 5e-2 s, ten times the Fig. 4-2 setting) must
  // neither change the slide (beyond the start-up transient of the
  // shear strain, 1e-4 of it) nor dissipate more than that transient's
  // strain energy (rho g L / 2)^2 L^3 / E ~ 1 J against the ~3 kJ of
  // friction work.
  const double a = 20. * pi / 180., phi = 10. * pi / 180., g = 9.80665;
  const double d_exact = 0.5 * g * (std::sin(a) - std::cos(a) * std::tan(phi));
  const Point  down(std::cos(a), 0., -std::sin(a));
  std::map<bool, Summary> s;
  for (const bool damped : {false, true})
    s[damped]
      = run_dda3d(damped ? "dda3d-incline-damped" : "dda3d-incline-undamped",
                  incline_blocks(20., 90., 10., 1000., 2e7),
                  dda3d_prm(1.,
                            0.005,
                            1e10,
                            std::string("  set Settling steps = 20\n")
                              + (damped ? "  set Strain damping = 5e-2\n"
                                        : "")));
  auto along = [&](const Summary &x) {
    return Point(x.at("mp1_ux"), x.at("mp1_uy"), x.at("mp1_uz")).dot(down);
  };
  std::printf("soft block on an incline: %.6f m undamped, %.6f m damped, "
              "exact %.6f m; damping dissipation %.3e J, friction %.3e J\n",
              along(s[false]),
              along(s[true]),
              d_exact,
              s[true].at("damping_dissipation"),
              s[true].at("friction_dissipation"));
  EXPECT_LT(std::abs(along(s[true]) - d_exact), 0.01 * d_exact);
  EXPECT_LT(std::abs(along(s[true]) - along(s[false])), 1e-4 * d_exact);
  EXPECT_EQ(s[false].at("damping_dissipation"), 0.);
  EXPECT_GT(s[true].at("damping_dissipation"), 0.);
  EXPECT_LT(s[true].at("damping_dissipation"), 1.);
  EXPECT_LT(s[true].at("energy_created_max"), 1e-6 * 1000. * g);
}



TEST(Dda3dSeismic,
     ShakingTableWedgeYieldsAtTheYieldAccelerationAndSlidesAsSliding3d)
{
  // Thesis Sec. 4.6-4.7.2: the wedge on joints 51.4/065.8 and 51.4/295.2
  // (make_wedge_in_trough(): height 0.1 m under a slope face 80/000.5, the
  // trough clamped), Table 4-1's material (E = 200 GPa, nu = 0.25, rho =
  // 1700 kg/m^3) and dt = 0.005 s, shaken along the line of intersection
  // (000.5) by a 2 Hz sinusoid of 0.21 g with a 5 s linear ramp, low-passed
  // at 2.5 Hz (order 4, zero phase: 0.194 g at 2 Hz; the padding of 1.2 s
  // kept), in the loading and the displacement mode. The friction angle is
  // chosen as the thesis chose it: the one that makes the acceleration at
  // the observed onset of sliding, 0.14 g, critical (26.754 deg here; the
  // thesis's 30 deg holds this wedge up to 0.207 g, above the filtered
  // 0.194 g). Penalty 4e10 N/m (the thesis's largest convergent one),
  // the whole 20 s record (+ 2.4 s of padding): 30 slip pulses, 17 cm.
  // The documented setting (parameter-files/dda3d-shaking-table.prm):
  // stiff-mode velocity and a shear penalty of 1e9 N/m (0.05 E L, L = 0.1
  // m) independent of the normal one; run at the thesis's largest convergent
  // normal penalty, 4e10 N/m, and at 1e3 x it, 4e13 N/m, in a trough 0.3 m
  // longer than the wedge (the 17 cm slide stays on it). Measured: onset at the
  // analytical 5.100 s, history error 0.21 % / 0.20 % (loading / displacement)
  // at 4e10 N/m and 0.20 % / 0.91 % at 4e13 N/m, 4480 steps without a cut. With
  // the shear penalty tied to the normal one (0.4 p: 1.6e10 - 1.6e13 N/m, up to
  // 800 E L) the locked shear springs hold the wedge's elastic deformation as a
  // self-stress that wedges it into the trough (normal forces 2-3 % above the
  // rigid wedge's at the onset): each pulse starts late, and the error grew
  // to 2.8-53 % with step cuts (benchmarks/dda3d-shaking-table, "Shear
  // penalty"). The bound 2 % is the measured error's upper end over 1e10 - 4e13
  // N/m in both modes (1.2 % at 1e10 N/m) plus the stick-slip's sensitivity to
  // round-off.
  const double g = 9.80665, k_onset = 0.14, az = 0.5;
  const double phi = analytical::critical_friction_angle_wedge(
    51.4, 65.8, 51.4, 295.2, az, k_onset);
  analytical::SlidingPlane p1, p2;
  p1.dip_deg = p2.dip_deg = 51.4;
  p1.dip_direction_deg    = 65.8;
  p2.dip_direction_deg    = 295.2;
  p1.friction = p2.friction = analytical::FrictionLaw::coulomb_deg(phi);
  const double ky           = analytical::wedge_yield_acceleration(p1, p2, az);
  EXPECT_NEAR(ky, k_onset, 1e-8);

  const double       record = 20., T = record + 2.4, dt = 0.005, shear = 1e9;
  const ShakingTable table  = shaking_table(phi, 0.3, 5., record, T, dt);
  const BlockSystem &scene  = table.scene;
  const std::string &ground = table.ground;
  const auto        &in     = table.input;
  const double       mass = 1700. * scene.blocks[2].polyhedron.moments().volume;

  // The analytical rigid wedge under the processed input.
  const auto            exact = rigid_wedge(p1, p2, table, T);
  const Eigen::Vector3d end   = exact.final_displacement;
  // The input's component that drives the wedge down the line: the
  // inertial load -a_g along the shaking axis (g).
  const Point axis(std::sin(az * pi / 180.), std::cos(az * pi / 180.), 0.);
  auto        drive
    = [&](const double t) { return -in.acceleration(t).dot(axis) / g; };
  double t_yield = 0.;
  while (drive(t_yield) < ky)
    t_yield += 1e-4;

  // "Sliding": a slide beyond delta = 1e-4 m, 100 x the elastic slip of
  // the contact springs under the whole driving force at the onset (m g
  // (sin(27.6 deg) + 0.14) / k_s: 4.8e-9 m at k_s = 1e9 N/m).
  const double delta = 1e-4;
  ASSERT_LT(100. * mass * g * 0.62 / shear, delta);
  double t_exact = -1.;
  for (std::size_t k = 0; k < exact.time.size() && t_exact < 0.; ++k)
    if (exact.displacement[k].norm() > delta)
      t_exact = exact.time[k];
  std::printf("shaking-table wedge: phi = %.3f deg (0.14 g critical), k_y = "
              "%.4f g, first reached at %.3f s; analytical onset (%.0e m) "
              "%.3f s (input %.4f g), slide %.4f m at %.1f s; wedge mass "
              "%.3f kg\n",
              phi,
              ky,
              t_yield,
              delta,
              t_exact,
              drive(t_exact),
              end.norm(),
              T,
              mass);
  ASSERT_GT(end.norm(), 0.01);

  const std::string blocks = block_text(scene);
  const std::string setting
    = "  set Shear penalty = 1e9\n  set Stiff mode velocity = true\n";
  for (const double penalty : {4e10, 4e13})
    for (const std::string mode : {"loading", "displacement"})
      {
        double                                     wall = 0.;
        std::vector<std::map<std::string, double>> rows;
        const auto                                 s
          = run_dda3d("dda3d-shaking-" + mode,
                      blocks,
                      ground + shaking_table_prm(T, dt, penalty, mode, setting),
                      &wall,
                      &rows);
        // The slide (relative to the ground) against the analytical one at
        // the same times (both every 0.01 s).
        double t_onset = -1., error = 0., before_yield = 0.;
        Point  u = Point::Zero();
        for (const auto &r : rows)
          {
            const double t = r.at("time_s");
            u = Point(r.at("mp1_ux_m"), r.at("mp1_uy_m"), r.at("mp1_uz_m"));
            if (mode == "displacement")
              u -= Point(r.at("ground_ux_m"),
                         r.at("ground_uy_m"),
                         r.at("ground_uz_m"));
            if (t_onset < 0. && u.norm() > delta)
              t_onset = t;
            if (t < t_yield)
              before_yield = std::max(before_yield, u.norm());
            const std::size_t k = std::min(exact.time.size() - 1,
                                           std::size_t(std::llround(t / 0.01)));
            error = std::max(error, (u - exact.displacement[k]).norm());
          }
        error /= end.norm();
        const double error_end = (u - end).norm() / end.norm();
        std::printf("%s mode (penalty %.0e N/m): onset %.3f s (input %.4f g; "
                    "k_y %.4f g), slide before k_y is first reached %.2e m, "
                    "slide %.4f m (analytical %.4f m), error at the end "
                    "%.2e, largest over the history %.2e (of the final "
                    "slide), %g steps, %g cuts, %.1f s wall\n",
                    mode.c_str(),
                    penalty,
                    t_onset,
                    drive(t_onset),
                    ky,
                    before_yield,
                    u.norm(),
                    end.norm(),
                    error_end,
                    error,
                    s.at("steps"),
                    s.at("time_step_cuts"),
                    wall);
        // No slide before the input first reaches the yield acceleration,
        // and the onset within 0.02 s (4 steps) of the analytical one.
        EXPECT_LT(before_yield, delta) << mode << penalty;
        EXPECT_NEAR(t_onset, t_exact, 0.02) << mode << penalty;
        // The history within 2 % of the final slide.
        EXPECT_LT(error, 0.02) << mode << penalty;
      }
}



TEST(Dda3dSeismic, ShakingTableWedgeRunsOutWithVelocityWeakeningAsSliding3d)
{
  // Thesis Sec. 4.7.3 and 4.8: the shaking-table wedge of the test above
  // (phi = 26.754 deg, critical at 0.14 g; 0.21 g at 2 Hz low-passed at
  // 2.5 Hz; loading mode; penalty 4e10 N/m), with a 1 s ramp instead of
  // 5 s so that the slip pulses are full from the first (the smallest
  // pulses near the onset are where DDA's stick-slip is sensitive), the
  // first 3.5 s of the record, dt = 1 ms, a trough margin of 1.5 m for
  // the run-out, and the steady-state velocity-dependent friction mu(V) =
  // tan(phi) + (A - B) ln(max(V, V_min) / V0) of the keys "Friction
  // velocity dependence", "Reference slip rate" and "Minimum slip rate"
  // (the parameter file's path). A - B = -0.0174 (the thesis's fit to all
  // its data, Fig. 4-10), V0 = V_min = 1e-5 m/s (within the slow direct
  // shear tests' 2e-6 - 1e-4 m/s): at rest the friction is tan(phi), so
  // the onset is the constant-friction one; above 2.4 cm/s mu falls below
  // tan(20.23 deg), the wedge's limit without shaking, so a pulse that
  // fast does not stop: the wedge accelerates away. With A - B = 0 the
  // run is the constant-friction run bit for bit.
  // The documented shaking-table setting (Shear penalty 1e9 N/m, Stiff
  // mode velocity): 3500 steps, no cut. Measured: constant friction 12.4
  // mm against sliding3d's 12.4 mm, history error 0.19 %; weakening 0.556
  // m against 0.564 m, 1.5 % (at dt = 0.5 ms: 0.17 % and 2.0 %). The
  // weakening run's deficit is the slip rate's lag of one step: in the
  // first steps of a pulse from rest the friction's logarithm is far off
  // (doc/theory/dda3d.md). (Before the shared step control, the engine
  // shrank its step to every output time and grew it back from there, so
  // after a cut it never returned to dt: the engine defaults then took
  // 10,817 steps with 171 cuts here, 3 x the nominal count, and gave 0.38
  // %; at the nominal dt they give 5.3 % with 145 cuts.)
  const double az = 0.5, v0 = 1e-5;
  const double phi = analytical::critical_friction_angle_wedge(
    51.4, 65.8, 51.4, 295.2, az, 0.14);
  const double record = 12., T = 3.5, dt = 1e-3, penalty = 4e10;
  // The documented setting's shear spring and end-of-step velocity
  // (parameter-files/dda3d-shaking-table.prm).
  const std::string documented
    = "  set Shear penalty = 1e9\n  set Stiff mode velocity = true\n";
  const ShakingTable table  = shaking_table(phi, 1.5, 1., record, T, dt);
  const std::string &ground = table.ground;
  const std::string  blocks = block_text(table.scene);

  // The rigid wedge under the processed input, with either law.
  const auto slide = [&](const double a_minus_b) {
    analytical::SlidingPlane p1, p2;
    p1.dip_deg = p2.dip_deg     = 51.4;
    p1.dip_direction_deg        = 65.8;
    p2.dip_direction_deg        = 295.2;
    analytical::FrictionLaw law = analytical::FrictionLaw::coulomb_deg(phi);
    if (a_minus_b != 0.)
      {
        law.type      = analytical::FrictionLaw::Type::steady_state;
        law.a_minus_b = a_minus_b;
        law.v0        = v0;
        law.v_cutoff  = v0;
      }
    p1.friction = p2.friction = law;
    return rigid_wedge(p1, p2, table, T);
  };

  struct Run
  {
    std::string name, keys;
    double      a_minus_b;
  };
  std::ostringstream law;
  law.precision(17);
  law << "  set Reference slip rate = " << v0
      << "\n  set Minimum slip rate = " << v0 << "\n";
  const std::vector<Run> runs
    = {{"constant", "", 0.},
       {"A-B=0", "  set Friction velocity dependence = 0\n" + law.str(), 0.},
       {"A-B=-0.0174",
        "  set Friction velocity dependence = -0.0174\n" + law.str(),
        -0.0174}};
  std::map<std::string, std::vector<Point>>  history;
  std::map<std::string, double>              final_slide, exact_final, errors;
  std::map<std::string, std::vector<double>> cycles, exact_cycles;
  for (const auto &run : runs)
    {
      const auto                                 exact = slide(run.a_minus_b);
      double                                     wall  = 0.;
      std::vector<std::map<std::string, double>> rows;
      const auto                                 s = run_dda3d(
        "dda3d-rate-" + run.name,
        blocks,
        ground
          + shaking_table_prm(T, dt, penalty, "loading", documented + run.keys),
        &wall,
        &rows);
      double error = 0.;
      Point  u     = Point::Zero();
      for (const auto &r : rows)
        {
          u = Point(r.at("mp1_ux_m"), r.at("mp1_uy_m"), r.at("mp1_uz_m"));
          history[run.name].push_back(u);
          const std::size_t k
            = std::min(exact.time.size() - 1,
                       std::size_t(std::llround(r.at("time_s") / 0.01)));
          error = std::max(error, (u - exact.displacement[k]).norm());
          // The slide at the end of each cycle (2 Hz) from 1 s on.
          const long n = std::llround(r.at("time_s") / 0.01);
          if (n >= 100 && n % 50 == 0)
            {
              cycles[run.name].push_back(u.norm());
              exact_cycles[run.name].push_back(exact.displacement[k].norm());
            }
        }
      const double end      = exact.final_displacement.norm();
      final_slide[run.name] = u.norm();
      exact_final[run.name] = end;
      error /= end;
      std::printf("%s: slide %.4f m (sliding3d %.4f m, largest speed %.3f "
                  "m/s), error at the end %.2e, largest over the history "
                  "%.2e (of the final slide), %g steps, %g cuts, %.1f s "
                  "wall\n",
                  run.name.c_str(),
                  u.norm(),
                  end,
                  exact.max_speed,
                  (u - exact.final_displacement).norm() / end,
                  error,
                  s.at("steps"),
                  s.at("time_step_cuts"),
                  wall);
      errors[run.name] = error;
      std::printf("  slide at the end of each cycle from 1 s (m; sliding3d):");
      for (std::size_t c = 0; c < cycles[run.name].size(); ++c)
        std::printf(" %.4f (%.4f)",
                    cycles[run.name][c],
                    exact_cycles[run.name][c]);
      std::printf("\n");
    }
  // A - B = 0 is the constant-friction run, bit for bit.
  ASSERT_EQ(history["A-B=0"].size(), history["constant"].size());
  for (std::size_t k = 0; k < history["constant"].size(); ++k)
    EXPECT_EQ(history["A-B=0"][k], history["constant"][k]) << k;
  // Constant friction: the staircase of the test above, each step short
  // of the rigid wedge's by DDA's per-pulse deficit (2-8 %).
  EXPECT_LT(errors["constant"], 0.08);
  // Velocity weakening: the run-out tracks sliding3d with the same law
  // within 2 % of its final slide over the whole history.
  EXPECT_LT(errors["A-B=-0.0174"], 0.02);
  // It accelerates away: the slide of each cycle grows (the constant-
  // friction staircase has steps of a few mm), in DDA as in sliding3d,
  // and the run-out is many times the constant-friction slide.
  const auto &w = cycles["A-B=-0.0174"], &we = exact_cycles["A-B=-0.0174"];
  ASSERT_GE(w.size(), 4u);
  for (std::size_t c = w.size() - 3; c + 1 < w.size(); ++c)
    {
      EXPECT_GT(w[c + 1] - w[c], w[c] - w[c - 1]) << c;
      EXPECT_GT(we[c + 1] - we[c], we[c] - we[c - 1]) << c;
    }
  EXPECT_GT(exact_final["A-B=-0.0174"], 20. * exact_final["constant"]);
  EXPECT_GT(final_slide["A-B=-0.0174"], 20. * final_slide["constant"]);
}



// A 3D run resumed from a checkpoint continues bit for bit (issue 17,
// checkpoints as in 2D): the shaking-table wedge, settled by 20 static
// steps and shaken in the loading mode (0.5 g at 4 Hz along the line of
// intersection, friction 30 deg: it slides and sticks) to 0.1 s (stuck,
// its locked contacts' shear springs stretched), checkpoint, on to 0.3 s
// (it slides, sticks again); a fresh engine of the same scene (not settled)
// restored from the checkpoint takes the same steps to the same vertex
// coordinates, velocities, stresses, contact states, shear references and
// forces, energy ledger and counters, exactly. A checkpoint of another
// scene, a truncated one and the 2D engine's are rejected naming the
// source, leaving the engine as it was.
TEST(Dda3dCheckpoint, ResumedRunIsIdentical)
{
  dda::JointMaterial joint;
  joint.friction_deg      = 30.;
  const BlockSystem scene = wedge_in_trough_scene(
    make_wedge_in_trough({51.4, 65.8, 51.4, 295.2, 80., 0.5}, 0.1, 0.1),
    {1700., 2e11, 0.25, 1},
    joint);
  EngineControls c;
  c.dt                 = 1e-3;
  c.law.normal_penalty = 4e10;
  const Point axis(std::sin(0.5 * pi / 180.), std::cos(0.5 * pi / 180.), 0.);
  c.ground_acceleration = [axis](const double t) {
    return Point(0.5 * 9.80665 * std::sin(8. * pi * t) * axis);
  };
  Engine original(scene, c);
  original.settle(20);
  while (original.time() < 0.1)
    original.step();
  const std::string   saved    = original.checkpoint();
  const unsigned long n_before = original.n_steps;
  const double        t_saved  = original.time();
  // Steps with a sliding contact (the run is not trivial).
  unsigned long sliding_steps = 0, locked_at_checkpoint = 0;
  for (const Contact &x : original.contacts())
    locked_at_checkpoint
      += x.state == ContactState::locked && x.shear_force.norm() > 0.;
  while (original.time() < 0.3)
    {
      original.step();
      sliding_steps += original.statistics().sliding > 0;
    }
  const unsigned long n_after = original.n_steps - n_before;

  Engine resumed(scene, c);
  resumed.restore(saved, "test checkpoint");
  EXPECT_EQ(resumed.n_steps, n_before);
  for (unsigned long k = 0; k < n_after; ++k)
    resumed.step();

  EXPECT_EQ(resumed.time(), original.time());
  EXPECT_EQ(resumed.time_step(), original.time_step());
  EXPECT_EQ(resumed.n_steps, original.n_steps);
  EXPECT_EQ(resumed.n_cuts, original.n_cuts);
  EXPECT_EQ(resumed.n_iterations, original.n_iterations);
  for (std::size_t b = 0; b < scene.blocks.size(); ++b)
    {
      const Block &x = original.scene().blocks[b];
      const Block &y = resumed.scene().blocks[b];
      EXPECT_EQ(x.polyhedron.vertices, y.polyhedron.vertices);
      EXPECT_EQ(x.velocity, y.velocity);
      EXPECT_EQ(x.stress, y.stress);
      EXPECT_EQ(x.strain, y.strain);
      EXPECT_EQ(original.displacement(b), resumed.displacement(b));
    }
  ASSERT_EQ(resumed.contacts().size(), original.contacts().size());
  for (std::size_t k = 0; k < original.contacts().size(); ++k)
    {
      const Contact &x = original.contacts()[k], &y = resumed.contacts()[k];
      EXPECT_EQ(x.state, y.state);
      EXPECT_EQ(x.reference, y.reference);
      EXPECT_EQ(x.slide_direction, y.slide_direction);
      EXPECT_EQ(x.normal_force, y.normal_force);
      EXPECT_EQ(x.shear_force, y.shear_force);
      EXPECT_EQ(x.slip_rate, y.slip_rate);
    }
  const Energy ex = original.energy(), ey = resumed.energy();
  for (const auto &[a, b] : {std::pair{ex.kinetic, ey.kinetic},
                             {ex.strain, ey.strain},
                             {ex.contact, ey.contact},
                             {ex.potential, ey.potential},
                             {ex.friction, ey.friction},
                             {ex.load_work, ey.load_work}})
    EXPECT_EQ(a, b);
  const double slide = original.displacement(2).norm();
  std::printf("dda3d resumed run: checkpoint at t = %.4f s after %lu steps, "
              "%lu locked contacts under shear, %lu more steps to %.4f s (%lu "
              "with a sliding contact, %lu cuts in all); %zu contacts, wedge "
              "displaced %.3e m, friction work "
              "%.3e J: identical\n",
              t_saved,
              n_before,
              locked_at_checkpoint,
              n_after,
              original.time(),
              sliding_steps,
              original.n_cuts,
              original.contacts().size(),
              slide,
              ex.friction);
  EXPECT_GT(sliding_steps, 10u); // the wedge slides and sticks
  EXPECT_GT(locked_at_checkpoint, 0u);
  EXPECT_GT(slide, 1e-4);

  // Another scene (the slider on an incline), a truncated file, the 2D
  // engine's checkpoint: rejected, naming the source.
  Engine            other(test_scenes::incline_scene(30.,
                                          20.,
                                          Point(-4., -2., -1.),
                                          Point(4., 2., 0.),
                                          Point(-1., -0.5, 0.),
                                          Point(0., 0.5, 1.))
                 .system,
               c);
  const std::string m1
    = error_of([&]() { other.restore(saved, "run/checkpoint.bin"); });
  EXPECT_NE(m1.find("run/checkpoint.bin"), std::string::npos) << m1;
  EXPECT_NE(m1.find("another scene"), std::string::npos) << m1;
  Engine            same(scene, c);
  const std::string m2 = error_of(
    [&]() { same.restore(saved.substr(0, saved.size() / 2), "half.bin"); });
  EXPECT_NE(m2.find("half.bin: the checkpoint is "), std::string::npos) << m2;
  io::BinaryWriter w2d;
  w2d.put_header("rockdda DDA checkpoint", 8);
  const std::string m3 = error_of([&]() { same.restore(w2d.bytes, "2d.bin"); });
  EXPECT_NE(m3.find("2d.bin: not a rockdda DDA 3d checkpoint"),
            std::string::npos)
    << m3;
  // A rejected checkpoint leaves the engine as it was.
  EXPECT_EQ(same.time(), 0.);
  EXPECT_EQ(same.n_steps, 0u);
  EXPECT_TRUE(same.contacts().empty());
}



namespace
{
  std::string
  file_text(const std::filesystem::path &file)
  {
    std::ifstream      in(file, std::ios::binary);
    std::ostringstream s;
    s << in.rdbuf();
    return s.str();
  }
} // namespace



// The analysis type continues a checkpointed run bit for bit, as the 2D
// one does (tests/regression/run_resume.cmake): the shaking-table wedge
// (friction 20 deg: it slides; 20 settling steps, skipped on resume) run
// to 1 s at once, and to 0.5 s with checkpoints every 0.25 s then resumed
// to 1 s (settings the same, 'Resume' = true): statistics.csv, the VTU
// series' blocks.pvd and contacts.pvd and every summary value but the
// wall time are identical. Resume without a checkpoint, a damaged
// checkpoint and one of another run are rejected naming the key or file.
TEST(Dda3dCheckpoint, AnalysisResumesBitForBit)
{
  const double       T = 1., dt = 0.005, penalty = 4e10;
  const ShakingTable table  = shaking_table(20., 0.1, 0.5, 2., T, dt);
  const std::string  blocks = block_text(table.scene);
  auto               prm    = [&](const double end, const bool resume) {
    return table.ground
           + shaking_table_prm(end,
                               dt,
                               penalty,
                               "loading",
                               "  set Output interval = 0.25\n"
                                                "  set Checkpoint interval = 0.25\n"
                                                "  set Resume = "
                                 + std::string(resume ? "true" : "false")
                                 + "\n");
  };
  const auto full = test_files::scratch("dda3d-resume-full");
  const auto part = test_files::scratch("dda3d-resume-part");
  for (const auto &d : {full, part})
    test_files::write_file(d / "scene.blocks", blocks);
  Summary a = run_dda3d_in(full, prm(T, false));
  run_dda3d_in(part, prm(0.5, false));
  ASSERT_TRUE(std::filesystem::exists(part / "out" / "checkpoint.bin"));
  Summary b = run_dda3d_in(part, prm(T, true));
  for (const char *f : {"statistics.csv", "blocks.pvd", "contacts.pvd"})
    EXPECT_EQ(file_text(full / "out" / f), file_text(part / "out" / f)) << f;
  a.erase("wall_time");
  b.erase("wall_time");
  EXPECT_EQ(a, b);
  EXPECT_EQ(a.at("final_time"), T);
  const auto rows         = read_table(full / "out" / "statistics.csv");
  int        sliding_rows = 0;
  for (const auto &r : rows)
    sliding_rows += r.at("contacts_sliding") > 0.;
  std::printf("dda3d resumed analysis: %zu rows (%d with sliding contacts), "
              "%g steps, wedge at %.4e m: identical\n",
              rows.size(),
              sliding_rows,
              a.at("steps"),
              a.at("max_block_displacement"));
  EXPECT_GT(sliding_rows, 0);

  // Resume without a checkpoint: the key and the file.
  const auto  none = test_files::scratch("dda3d-resume-none");
  std::string m    = error_of([&]() {
    test_files::write_file(none / "scene.blocks", blocks);
    run_dda3d_in(none, prm(T, true));
  });
  EXPECT_NE(m.find("key 'DDA 3d/Resume' is true but there is no checkpoint"),
            std::string::npos)
    << m;
  // A damaged checkpoint (cut short) and one of another run (another time
  // step): errors naming the file.
  const std::string bytes = file_text(part / "out" / "checkpoint.bin");
  test_files::write_file(part / "out" / "checkpoint.bin",
                         bytes.substr(0, bytes.size() - 100));
  m = error_of([&]() { run_dda3d_in(part, prm(T, true)); });
  EXPECT_NE(m.find((part / "out" / "checkpoint.bin").string()),
            std::string::npos)
    << m;
  EXPECT_NE(m.find("truncated"), std::string::npos) << m;
  test_files::write_file(part / "out" / "checkpoint.bin", bytes);
  m = error_of([&]() {
    run_dda3d_in(part,
                 table.ground
                   + shaking_table_prm(
                     T, 0.004, penalty, "loading", "  set Resume = true\n"));
  });
  EXPECT_NE(m.find((part / "out" / "checkpoint.bin").string()),
            std::string::npos)
    << m;
  EXPECT_NE(m.find("written for another run"), std::string::npos) << m;
}
