/**
 * @file
 * One geometry of Masada Block 1 (analytical::Block1Section, thesis Eq.
 * 5.3, doc/theory/block1.md): its polygon has the area L_B (H - L_B
 * tan(eta) / 2) of Eq. 5.3 with H the front face, and every model of the
 * block takes that polygon: the seismic scene of 'calibrate',
 * 'earthquakes' and 'compare', the coupled ratchet scene (the union of its
 * slices and foot), the analytical ratchet's weight, and the defaults of
 * every analysis's 'Block length', 'Block height' and 'Slope' keys.
 * Analytical identities: the tolerances are round-off (a few ulps of the
 * numbers involved), not measured values.
 */
#include <rockdda/analytical/analyses.h>
#include <rockdda/analytical/block1.h>
#include <rockdda/analytical/ratchet.h>
#include <rockdda/coupling/analyses.h>
#include <rockdda/coupling/block1_seismic.h>
#include <rockdda/coupling/ratchet_scene.h>

#include <deal.II/base/parameter_handler.h>

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <memory>
#include <string>
#include <utility>
#include <vector>

using namespace rockdda;
using analytical::Block1Section;
using geometry::Point;

namespace
{
  constexpr double pi = 3.14159265358979323846;

  /// Eq. 5.3's cross-section, written out.
  double
  eq_5_3_area(const double L, const double H, const double eta_deg)
  {
    return L * (H - 0.5 * L * std::tan(eta_deg * pi / 180.));
  }

  /// Sections: Block 1 (7 m, 15 m, 19 deg) and others.
  std::vector<Block1Section>
  sections()
  {
    return {Block1Section(),
            Block1Section{3., 5., 0.},
            Block1Section{10., 12., 30.},
            Block1Section{2., 40., 44.}};
  }

  /// Expect @p a and @p b to be the same point within @p tol (m).
  void
  expect_same_point(const Point &a, const Point &b, const double tol)
  {
    EXPECT_NEAR(a[0], b[0], tol) << a.transpose() << " vs " << b.transpose();
    EXPECT_NEAR(a[1], b[1], tol) << a.transpose() << " vs " << b.transpose();
  }
} // namespace



// The defaults are the thesis's Block 1 (5.2.2, Table 5-2): 15 m high,
// 7 m long, on a bedding plane dipping 19 deg.
TEST(Block1Geometry, DefaultsAreTheThesisBlock)
{
  const Block1Section b;
  EXPECT_EQ(b.length, 7.);
  EXPECT_EQ(b.height, 15.);
  EXPECT_EQ(b.slope_deg, 19.);
  // L_B (H - L_B tan 19 / 2) = 96.564 m^2 (the back-face reading of H gave
  // L_B (H + L_B tan 19 / 2) = 113.4 m^2).
  EXPECT_NEAR(b.area(), 96.56397, 1e-5);
}



// The polygon's area (shoelace) is Eq. 5.3's L_B (H - L_B tan(eta) / 2):
// H is the front (downslope) face, the back face is H - L_B tan(eta), both
// vertical, the top horizontal, the base on the bedding plane.
TEST(Block1Geometry, PolygonAreaIsEquation53)
{
  for (const auto &b : sections())
    {
      const double exact = eq_5_3_area(b.length, b.height, b.slope_deg);
      EXPECT_NEAR(b.area(), exact, 1e-14 * exact);
      for (const Point heel : {Point(0., 0.), Point(0.02, -0.0069)})
        {
          const auto p = b.polygon(heel);
          ASSERT_EQ(p.vertices.size(), 4u);
          EXPECT_GT(p.signed_area(), 0.); // counter-clockwise
          EXPECT_NEAR(p.area(), exact, 1e-13 * exact);
          const auto &v = p.vertices;
          expect_same_point(v[0], heel, 0.);
          const double t = std::tan(b.slope_deg * pi / 180.);
          // Base on the bedding plane through the heel, dipping eta.
          EXPECT_NEAR(v[1][0] - v[0][0], b.length, 1e-14 * b.length);
          EXPECT_NEAR(v[1][1] - v[0][1], -b.length * t, 1e-14 * b.length);
          // Front face H, back face H - L_B tan(eta), both vertical; top
          // horizontal.
          EXPECT_EQ(v[2][0], v[1][0]);
          EXPECT_EQ(v[3][0], v[0][0]);
          EXPECT_NEAR(v[2][1] - v[1][1], b.height, 1e-14 * b.height);
          EXPECT_NEAR(v[3][1] - v[0][1], b.back_height(), 1e-14 * b.height);
          EXPECT_NEAR(b.back_height(),
                      b.height - b.length * t,
                      1e-14 * b.height);
          EXPECT_NEAR(v[3][1], v[2][1], 1e-14 * b.height);
        }
      const Point d = b.downslope();
      EXPECT_NEAR(d.norm(), 1., 1e-15);
      EXPECT_NEAR(std::atan2(-d[1], d[0]) * 180. / pi, b.slope_deg, 1e-12);
    }
}



// The analytical ratchet (Eqs. 5.3-5.5) takes the section's area: F_max =
// gamma A (tan(phi) cos(eta) - sin(eta)) with A = Block1Section::area(),
// and RatchetInput's defaults are the section's.
TEST(Block1Geometry, AnalyticalRatchetUsesTheSection)
{
  const analytical::RatchetInput in;
  const Block1Section            b;
  EXPECT_EQ(in.section().length, b.length);
  EXPECT_EQ(in.section().height, b.height);
  EXPECT_EQ(in.section().slope_deg, b.slope_deg);
  const double eta   = in.slope_deg * pi / 180.;
  const double phi   = in.friction_angle_deg * pi / 180.;
  const double gamma = in.density * in.gravity;
  const double f_max = gamma * eq_5_3_area(b.length, b.height, b.slope_deg)
                       * (std::tan(phi) * std::cos(eta) - std::sin(eta));
  EXPECT_NEAR(analytical::ratchet(in).max_force, f_max, 1e-13 * f_max);
  analytical::RatchetInput other;
  other.set_section(Block1Section{3., 5., 10.});
  EXPECT_EQ(other.block_length, 3.);
  EXPECT_EQ(other.block_height, 5.);
  EXPECT_EQ(other.slope_deg, 10.);
}



// The seismic scene ('calibrate', 'earthquakes', 'compare') is the section
// with its heel at the origin, vertex for vertex.
TEST(Block1Geometry, SeismicSceneIsTheSection)
{
  for (const auto &b : sections())
    {
      coupling::Block1Geometry g;
      static_cast<Block1Section &>(g) = b;
      if (!(b.slope_deg < 45.))
        continue;
      const auto scene
        = coupling::make_block1_seismic_scene(g, coupling::Block1Materials());
      const auto &v = scene.blocks.blocks[scene.block].polygon.vertices;
      const auto  p = b.polygon().vertices;
      ASSERT_EQ(v.size(), p.size());
      for (std::size_t i = 0; i < p.size(); ++i)
        expect_same_point(v[i], p[i], 0.);
      expect_same_point(scene.downslope, b.downslope(), 0.);
    }
}



// The coupled ratchet scene's block (its slices and its foot) is the same
// section, translated so that its heel lies on the bedding plane at the
// crack's bottom width from the cliff: the slices' areas add up to Eq. 5.3
// and the heel, toe and back-top corners and the front-top corner are the
// section's. With and without slices, with and without infill.
TEST(Block1Geometry, RatchetSceneIsTheSection)
{
  for (const auto &b : sections())
    for (const unsigned int slices : {0u, 1u, 4u})
      {
        if (b.back_height() < 1.) // the 10 % back face and the foot
          continue;
        coupling::RatchetGeometry g;
        g.block           = b;
        g.slices          = slices;
        g.crack_top_width = std::min(g.crack_top_width, 0.4 * b.length);
        // An infill that fits every section (it does not touch the block's
        // polygon).
        g.infill_top_depth = 0.3 * b.back_height();
        g.infill_height    = 0.3 * b.back_height();
        const auto scene
          = coupling::make_ratchet_scene(g, coupling::RatchetMaterials());
        const auto &blocks = scene.blocks.blocks;
        double      area   = 0.;
        for (const int i : scene.block_slices)
          area += blocks[i].polygon.area();
        const double exact = eq_5_3_area(b.length, b.height, b.slope_deg);
        EXPECT_NEAR(area, exact, 1e-12 * exact)
          << b.length << " " << b.height << " " << b.slope_deg << " " << slices;
        const double wb = g.crack_bottom_width;
        const auto   p
          = b.polygon(Point(wb, -wb * std::tan(b.slope_deg * pi / 180.)))
              .vertices;
        const auto vertex = [&](const std::pair<int, int> &v) {
          return blocks[v.first].polygon.vertices[v.second];
        };
        const double tol = 1e-12 * b.height;
        expect_same_point(vertex(scene.heel), p[0], tol);
        expect_same_point(vertex(scene.toe), p[1], tol);
        expect_same_point(vertex(scene.back_top), p[3], tol);
        // The front-top corner: the last slice's top-right vertex.
        expect_same_point(
          blocks[scene.block_slices[slices > 0 ? scene.block_slices.size() - 2
                                               : 0]]
            .polygon.vertices[2],
          p[2],
          tol);
        expect_same_point(scene.downslope, b.downslope(), 0.);
        // The crack: wb wide at the bedding plane, wt at the top.
        const auto foot = vertex(scene.cliff_foot),
                   top  = vertex(scene.cliff_top);
        EXPECT_NEAR(p[0][0] - foot[0], wb, tol);
        EXPECT_NEAR(p[3][0] - top[0], g.crack_top_width, tol);
        EXPECT_NEAR(top[1], p[3][1], tol);
      }
}



// Every analysis of Block 1 declares the same defaults for its 'Block
// length', 'Block height' and 'Slope' keys: those of Block1Section.
TEST(Block1Geometry, AnalysesShareTheDefaults)
{
  const std::vector<std::pair<std::string, std::string>> users{
    {"ratchet", "Ratchet"},
    {"calibrate", "Calibration"},
    {"earthquakes", "Earthquakes"},
    {"compare", "Compare"},
    {"ratchet-analytical", "Ratchet analytical"}};
  auto list = coupling::make_analyses();
  for (auto &a : analytical::make_analyses())
    list.push_back(std::move(a));
  const Block1Section b;
  unsigned int        found = 0;
  for (const auto &a : list)
    for (const auto &[name, section] : users)
      if (a->name() == name)
        {
          ++found;
          dealii::ParameterHandler prm;
          a->declare_parameters(prm);
          prm.enter_subsection(section);
          EXPECT_EQ(prm.get_double("Block length"), b.length) << name;
          EXPECT_EQ(prm.get_double("Block height"), b.height) << name;
          EXPECT_EQ(prm.get_double("Slope"), b.slope_deg) << name;
          prm.leave_subsection();
        }
  EXPECT_EQ(found, users.size());
}
