/**
 * @file
 * From the block cutter to the DDA engine: edge tags become per-edge joint
 * materials, and a contact on a tagged edge obeys that edge's friction.
 */
#include <rockdda/dda/block_file.h>
#include <rockdda/dda/engine.h>
#include <rockdda/structure/block_cutter.h>
#include <rockdda/structure/block_output.h>

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <sstream>

using namespace rockdda;

TEST(CutToDda, EdgeTagsBecomeJointMaterials)
{
  // A 2 m square cut by one horizontal joint of set 0 at y = 1 m.
  geometry::Polygon domain;
  domain.vertices = {{0., 0.}, {2., 0.}, {2., 2.}, {0., 2.}};
  structure::TaggedSegment joint;
  joint.a        = {-1., 1.};
  joint.b        = {3., 1.};
  joint.tag.kind = structure::EdgeKind::joint;
  joint.tag.set  = 0;
  const auto cut = structure::cut_blocks(domain, {}, {joint});
  ASSERT_EQ(cut.blocks.size(), 2u);

  const dda::BlockSystem scene
    = dda::parse_block_text(structure::dda_block_file_text(cut), "cut.dda");
  ASSERT_EQ(scene.blocks.size(), 2u);
  // Joint materials in the file: 1 (boundary) and 10 (set 0), in this order.
  ASSERT_EQ(scene.joints.size(), 2u);
  for (const auto &b : scene.blocks)
    {
      const auto &v = b.polygon.vertices;
      ASSERT_EQ(b.edge_joints.size(), v.size());
      for (std::size_t k = 0; k < v.size(); ++k)
        {
          const auto &p = v[k], &q = v[(k + 1) % v.size()];
          const bool  on_joint
            = std::abs(p.y() - 1.) < 1e-12 && std::abs(q.y() - 1.) < 1e-12;
          EXPECT_EQ(b.edge_joints[k], on_joint ? 1 : 0)
            << "edge " << k << " of block " << b.id;
        }
    }
}



namespace
{
  /// Scene text: a fixed base (20 m x 1 m) and a 1 m block on it, both
  /// rotated by -alpha; every block's own joint is 45 deg, but the base's
  /// top edge is tagged with joint 2 (phi_edge). @p clockwise lists the base
  /// vertices clockwise (the reader reverses them and must keep the tags).
  std::string
  incline_text(const double alpha, const double phi_edge, const bool clockwise)
  {
    auto rot = [alpha](double x, double y) {
      return std::make_pair(x * std::cos(alpha) + y * std::sin(alpha),
                            -x * std::sin(alpha) + y * std::cos(alpha));
    };
    std::ostringstream s;
    s.precision(17);
    s << "material 1 2700 1e10 0.25 plane-stress\n"
      << "joint 1 45 0 0\njoint 2 " << phi_edge << " 0 0\n";
    // Base corners counter-clockwise: (-10,-1) (10,-1) (10,0) (-10,0); the
    // top edge is edge 2 (from (10,0) to (-10,0)).
    std::vector<std::pair<double, double>> base
      = {rot(-10., -1.), rot(10., -1.), rot(10., 0.), rot(-10., 0.)};
    std::vector<int> tags = {1, 1, 2, 1};
    if (clockwise)
      {
        // vertices reversed; edge k of the reversed list is the old edge
        // n - 2 - k (mod n)
        std::reverse(base.begin(), base.end());
        tags = {2, 1, 1, 1};
      }
    s << "block 0 1 1";
    for (const auto &[x, y] : base)
      s << " " << x << " " << y;
    s << "\nedge-joints 0";
    for (const int t : tags)
      s << " " << t;
    s << "\nblock 1 1 1";
    for (const auto &[x, y] :
         {rot(-0.5, 0.), rot(0.5, 0.), rot(0.5, 1.), rot(-0.5, 1.)})
      s << " " << x << " " << y;
    s << "\nfixed-block 0\n";
    return s.str();
  }

  /// Slide of block 1 along the incline after 1 s.
  double
  slide(const std::string &text, const double alpha)
  {
    dda::Controls c;
    c.time_step              = 1e-2;
    c.dynamic                = 1.;
    c.law.normal_penalty     = 1e11;
    c.max_displacement_ratio = 0.01;
    dda::DdaSystem dda(dda::parse_block_text(text, "incline.dda"), c);
    dda.run_until(1.);
    return dda.centroid_displacement(1).dot(
      geometry::Point(std::cos(alpha), -std::sin(alpha)));
  }
} // namespace



TEST(CutToDda, TaggedEdgeFrictionGovernsSliding)
{
  // 30 deg incline; the blocks' own joints (45 deg) would hold the block,
  // the tagged base edge (20 deg) lets it slide:
  // d = g/2 (sin a - cos a tan 20) t^2. Same 1 % as the DDA incline test
  // (documented penalty 1e11 N/m, dt = 0.01 s; measured error there ~1e-6).
  const double alpha = M_PI / 6.;
  const double exact
    = 0.5 * 9.80665 * (std::sin(alpha) - std::cos(alpha) * std::tan(M_PI / 9.));
  for (const bool clockwise : {false, true})
    {
      const double d = slide(incline_text(alpha, 20., clockwise), alpha);
      EXPECT_NEAR(d / exact, 1., 0.01) << (clockwise ? "clockwise" : "ccw");
    }
  // With the tagged edge at 45 deg too, the block stays put.
  EXPECT_LT(std::abs(slide(incline_text(alpha, 45., false), alpha)), 1e-4);
}
