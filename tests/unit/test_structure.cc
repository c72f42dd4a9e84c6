// Tests of the structure subsystem: exact block cutting, trace generators,
// structure statistics and bad input.
#include <rockdda/io/error.h>
#include <rockdda/structure/block_cutter.h>
#include <rockdda/structure/block_output.h>
#include <rockdda/structure/generators.h>
#include <rockdda/structure/statistics.h>

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <iostream>
#include <map>
#include <numeric>
#include <sstream>
#include <tuple>

using namespace rockdda;
using namespace rockdda::structure;

namespace
{
  Polygon
  rectangle(const double x0, const double y0, const double x1, const double y1)
  {
    Polygon p;
    p.vertices = {Point(x0, y0), Point(x1, y0), Point(x1, y1), Point(x0, y1)};
    return p;
  }

  TaggedSegment
  joint(const double x0,
        const double y0,
        const double x1,
        const double y1,
        const int    set = 0)
  {
    return {Point(x0, y0), Point(x1, y1), {EdgeKind::joint, set}};
  }

  /// Every interior block edge must be matched by the reverse edge of
  /// exactly one other block when T-junction vertices are kept (conforming
  /// blocks): no overlaps, no gaps. Boundary and excavation edges are
  /// unmatched. Where distinct exact vertices round to (nearly) one double
  /// point, edges shorter than @p tiny (m) may stay unmatched: such a gap
  /// is below double resolution. Returns the number of unmatched interior
  /// edges longer than @p tiny.
  std::size_t
  unmatched_interior_edges(const BlockSet &set, const double tiny = 0.)
  {
    std::map<std::pair<std::size_t, std::size_t>, int> count;
    for (const Block &b : set.blocks)
      for (std::size_t i = 0; i < b.vertex_ids.size(); ++i)
        count[{b.vertex_ids[i], b.vertex_ids[(i + 1) % b.vertex_ids.size()]}]
          += 1;
    std::size_t bad = 0;
    for (const Block &b : set.blocks)
      for (std::size_t i = 0; i < b.vertex_ids.size(); ++i)
        {
          const std::size_t a = b.vertex_ids[i],
                            c = b.vertex_ids[(i + 1) % b.vertex_ids.size()];
          const EdgeKind k    = b.edge_tags[i].kind;
          if (k == EdgeKind::boundary || k == EdgeKind::excavation)
            continue;
          if ((count[{a, c}] != 1 || count[{c, a}] != 1)
              && (set.vertices[a] - set.vertices[c]).norm() > tiny)
            ++bad;
        }
    return bad;
  }
} // namespace

// A square cut by k horizontal and m vertical through-going lines gives
// (k+1)(m+1) blocks; lines are exactly representable, so the areas add up
// to rounding (1e-12 relative).
TEST(BlockCutter, GridGivesExpectedBlockCount)
{
  for (const auto &[k, m] :
       std::vector<std::pair<int, int>>{{0, 0}, {1, 1}, {3, 5}, {10, 7}})
    {
      std::vector<TaggedSegment> s;
      for (int i = 1; i <= k; ++i)
        s.push_back(joint(-1., i / (k + 1.), 2., i / (k + 1.), 0));
      for (int j = 1; j <= m; ++j)
        s.push_back(joint(j / (m + 1.), -1., j / (m + 1.), 2., 1));
      const BlockSet b = cut_blocks(rectangle(0, 0, 1, 1), {}, s);
      EXPECT_EQ(b.blocks.size(), std::size_t((k + 1) * (m + 1)));
      EXPECT_NEAR(b.total_block_area(), 1., 1e-12);
      for (const Block &blk : b.blocks)
        {
          EXPECT_EQ(blk.polygon.vertices.size(), 4u);
          EXPECT_GT(blk.polygon.signed_area(), 0.);
        }
    }
}

// A line ending inside a block is dangling: it adds no block.
TEST(BlockCutter, DanglingLineAddsNoBlock)
{
  const BlockSet b = cut_blocks(rectangle(0, 0, 2, 1),
                                {},
                                {joint(1, -1, 1, 2),
                                 joint(0.2, 0.5, 0.7, 0.5),
                                 joint(1.5, 0.5, 3, 0.5)});
  // The vertical line makes 2 blocks; the second horizontal one reaches the
  // boundary at x = 2 and the vertical line? No: it starts at x = 1.5,
  // inside the right block, so it dangles too.
  EXPECT_EQ(b.blocks.size(), 2u);
  EXPECT_NEAR(b.total_block_area(), 2., 1e-12);
  EXPECT_GE(b.n_dangling_edges, 2u);
  for (const Block &blk : b.blocks)
    EXPECT_EQ(blk.polygon.vertices.size(), 4u); // collinear vertices removed
}

// Joints through an existing vertex and along an existing edge.
TEST(BlockCutter, DegenerateJointsAreExact)
{
  // Both diagonals pass exactly through the corners and the centre; a joint
  // lies along the bottom boundary and another one overlaps a diagonal.
  const BlockSet b = cut_blocks(rectangle(0, 0, 1, 1),
                                {},
                                {joint(0, 0, 1, 1),
                                 joint(0, 1, 1, 0, 1),
                                 joint(-1, 0, 2, 0, 2),
                                 joint(0.25, 0.25, 0.75, 0.75, 3)});
  EXPECT_EQ(b.blocks.size(), 4u);
  EXPECT_NEAR(b.total_block_area(), 1., 1e-15);
  for (const Block &blk : b.blocks)
    {
      EXPECT_EQ(blk.polygon.vertices.size(), 3u);
      EXPECT_NEAR(blk.polygon.area(), 0.25, 1e-15);
      // The edge along the bottom keeps the boundary tag (priority).
      for (std::size_t i = 0; i < 3; ++i)
        {
          if (blk.polygon.vertices[i].y() == 0.
              && blk.polygon.vertices[(i + 1) % 3].y() == 0.)
            {
              EXPECT_EQ(blk.edge_tags[i].kind, EdgeKind::boundary);
            }
        }
    }
  // Neighbours share the centre vertex exactly.
  EXPECT_EQ(b.vertices.size(), 5u);
  EXPECT_EQ(unmatched_interior_edges(b), 0u);
}

// A block floating inside another (a closed joint loop touching nothing)
// and an excavation touched by no joint: the faces with holes are split by
// vertical "split" cuts, nothing is lost.
TEST(BlockCutter, FacesWithHoles)
{
  std::vector<TaggedSegment> s = {joint(1, 1, 2, 1),
                                  joint(2, 1, 2, 2),
                                  joint(2, 2, 1, 2),
                                  joint(1, 2, 1, 1)};
  const BlockSet             b
    = cut_blocks(rectangle(0, 0, 6, 3), {rectangle(4, 1, 5, 2)}, s);
  EXPECT_EQ(b.n_holes_split, 2u);
  EXPECT_NEAR(b.excavated_area, 1., 1e-14);
  EXPECT_NEAR(b.total_block_area() + b.excavated_area, 18., 1e-13);
  bool has_split = false, has_excavation = false;
  for (const Block &blk : b.blocks)
    for (const EdgeTag &t : blk.edge_tags)
      {
        has_split |= t.kind == EdgeKind::split;
        has_excavation |= t.kind == EdgeKind::excavation;
      }
  EXPECT_TRUE(has_split);
  EXPECT_TRUE(has_excavation);
  // The floating block is one of the blocks.
  EXPECT_EQ(std::count_if(b.blocks.begin(),
                          b.blocks.end(),
                          [](const Block &blk) {
                            return std::abs(blk.polygon.area() - 1.) < 1e-14;
                          }),
            1);
}

// An excavation crossed by joints: faces inside it are dropped.
TEST(BlockCutter, ExcavationRemovesFaces)
{
  std::vector<TaggedSegment> s;
  for (int i = 1; i < 10; ++i)
    s.push_back(joint(i, -1, i, 11));
  for (int i = 1; i < 10; ++i)
    s.push_back(joint(-1, i + 0.5, 11, i + 0.5, 1));
  const BlockSet b
    = cut_blocks(rectangle(0, 0, 10, 10), {rectangle(3.2, 0, 6.8, 3)}, s);
  EXPECT_NEAR(b.excavated_area, 3.6 * 3., 1e-12);
  EXPECT_NEAR(b.total_block_area() + b.excavated_area, 100., 1e-12);
}


namespace
{
  /// A random trace network for seed @p seed with about @p n segments:
  /// even seeds two Shi-Goodman sets at random dips, odd seeds short random
  /// segments (up to 3 steps) with endpoints on a coarse grid (many exact
  /// coincidences: collinear overlaps, traces through vertices and along
  /// edges).
  std::vector<TaggedSegment>
  random_network(const unsigned int seed,
                 const std::size_t  n,
                 const double       size)
  {
    Random                                 r(seed);
    std::uniform_real_distribution<double> u(0., 1.);
    std::vector<TaggedSegment>             s;
    if (seed % 2 == 0)
      {
        for (int set = 0; s.size() < n; ++set)
          {
            JointSetParameters p;
            p.dip                  = 180. * u(r);
            p.mean_length          = size * (0.05 + 0.3 * u(r));
            p.mean_bridge          = p.mean_length * u(r);
            p.degree_of_randomness = u(r);
            // Spacing such that this set gives about n/2 segments.
            p.mean_spacing
              = size * size * 1.4 / (0.5 * n * (p.mean_length + p.mean_bridge));
            for (const auto &t : generate_joint_set(
                   p, set, Eigen::Vector4d(0, 0, size, size), r))
              if (s.size() < n)
                s.push_back(t);
          }
      }
    else
      {
        const double                       h = size / 16.;
        std::uniform_int_distribution<int> g(-1, 17), dg(-3, 3);
        while (s.size() < n)
          {
            const int x = g(r), y = g(r);
            s.push_back({Point(x * h, y * h),
                         Point((x + dg(r)) * h, (y + dg(r)) * h),
                         {EdgeKind::joint, int(s.size() % 3)}});
          }
      }
    return s;
  }
} // namespace

// Area conservation for 100 random networks of 50 to 5,000 segments: block
// areas + excavated + dropped = domain area (1e-9 relative: only the final
// rounding of exact vertices to double enters), every block
// counter-clockwise, and every interior edge shared with exactly one
// neighbour in reverse (conforming blocks): no overlaps and no gaps.
TEST(BlockCutter, AreaConservationRandomNetworks)
{
  for (unsigned int seed = 0; seed < 100; ++seed)
    {
      const std::size_t n    = 50 + 50 * seed;
      const double      size = 20.;
      const auto        s    = random_network(seed, n, size);
      CutOptions        options;
      options.remove_all_collinear = false;
      if (seed % 3 == 0)
        {
          options.sliver_area  = 1e-3;
          options.sliver_angle = 5. * M_PI / 180.;
        }
      std::vector<Polygon> excavations;
      if (seed % 4 < 2)
        excavations.push_back(rectangle(7.3, 0., 12.1, 4.05));
      const BlockSet b
        = cut_blocks(rectangle(0, 0, size, size), excavations, s, options);
      const double total
        = b.total_block_area() + b.excavated_area + b.dropped_area;
      ASSERT_NEAR(total / (size * size), 1., 1e-9) << "seed " << seed;
      for (const Block &blk : b.blocks)
        {
          std::ostringstream os;
          for (std::size_t i = 0; i < blk.polygon.vertices.size(); ++i)
            os << "(" << blk.polygon.vertices[i].transpose() << ") "
               << to_string(blk.edge_tags[i].kind) << " ";
          ASSERT_GT(blk.polygon.signed_area(), 0.)
            << "seed " << seed << ": " << os.str();
        }
      ASSERT_EQ(unmatched_interior_edges(b, 1e-12 * size), 0u)
        << "seed " << seed;
      if (!excavations.empty())
        {
          ASSERT_NEAR(b.excavated_area, 4.8 * 4.05, 1e-12);
        }
    }
}

// Slivers: a joint nearly parallel to and very close to another makes a
// thin block, which is merged into its neighbour across the longest shared
// edge; with merging off it is only counted.
TEST(BlockCutter, SliverMerged)
{
  std::vector<TaggedSegment> s
    = {joint(-1, 0.5, 3, 0.5), joint(-1, 0.5 + 1e-3, 3, 0.5 + 1e-3, 1)};
  CutOptions o;
  o.sliver_area         = 1e-2;
  const BlockSet merged = cut_blocks(rectangle(0, 0, 2, 1), {}, s, o);
  EXPECT_EQ(merged.blocks.size(), 2u);
  EXPECT_EQ(merged.n_slivers_merged, 1u);
  EXPECT_NEAR(merged.total_block_area(), 2., 1e-12);
  o.merge_slivers     = false;
  const BlockSet kept = cut_blocks(rectangle(0, 0, 2, 1), {}, s, o);
  EXPECT_EQ(kept.blocks.size(), 3u);
  EXPECT_EQ(kept.n_slivers_remaining, 1u);
}

// The width test: a vertical joint 5 cm from the right edge of a 10 m x 1 m
// domain cuts a 0.05 m x 1 m strip (area 0.05 m^2, all angles 90 deg: no
// area or angle test at usual settings catches it). Its width is exactly
// 0.05 m; a 0.1 m width threshold merges it into its neighbour, which then
// spans the whole domain; the cut counts it under the width test only.
TEST(BlockCutter, NarrowStripMergedByWidth)
{
  const std::vector<TaggedSegment> s = {joint(9.95, -1, 9.95, 2)};
  CutOptions                       o;
  o.sliver_area         = 1e-3;
  o.sliver_angle        = 2. * M_PI / 180.;
  const BlockSet before = cut_blocks(rectangle(0, 0, 10, 1), {}, s, o);
  ASSERT_EQ(before.blocks.size(), 2u);
  double narrowest = 1e300;
  for (const auto &b : before.blocks)
    narrowest = std::min(narrowest, b.polygon.min_width());
  EXPECT_NEAR(narrowest, 0.05, 1e-12);
  o.sliver_width       = 0.1;
  const BlockSet after = cut_blocks(rectangle(0, 0, 10, 1), {}, s, o);
  ASSERT_EQ(after.blocks.size(), 1u);
  EXPECT_EQ(after.n_slivers_merged, 1u);
  EXPECT_EQ(after.n_slivers_by_width, 1u);
  EXPECT_EQ(after.n_slivers_by_area + after.n_slivers_by_angle, 0u);
  EXPECT_NEAR(after.blocks[0].polygon.min_width(), 1., 1e-12);
  EXPECT_NEAR(after.total_block_area(), 10., 1e-12);
}

// Minimum width: a rectangle's smaller side, a triangle's smallest height,
// invariant under rotation.
TEST(Polygon, MinWidth)
{
  geometry::Polygon r;
  r.vertices = {{0., 0.}, {3., 0.}, {3., 0.2}, {0., 0.2}};
  EXPECT_NEAR(r.min_width(), 0.2, 1e-15);
  geometry::Polygon t;
  t.vertices = {{0., 0.}, {4., 0.}, {0., 3.}};
  // heights: 3 (on 4), 4 (on 3), 12/5 (on the hypotenuse 5)
  EXPECT_NEAR(t.min_width(), 2.4, 1e-14);
  const double c = std::cos(0.7), sn = std::sin(0.7);
  for (auto &v : t.vertices)
    v = geometry::Point(c * v.x() - sn * v.y(), sn * v.x() + c * v.y());
  EXPECT_NEAR(t.min_width(), 2.4, 1e-14);
}

// Fixed boundary blocks: on a 3 x 2 grid of 1 m squares, 'bottom' fixes
// the 3 blocks of the bottom row, 'sides' the 4 blocks touching x = 0 or
// x = 3, both together 5 (the bottom middle and the four corners' columns),
// and a region polygon around the top-middle centroid adds that block.
TEST(BlockCutter, BoundaryBlocksForDda)
{
  const std::vector<TaggedSegment> s
    = {joint(1, -1, 1, 3), joint(2, -1, 2, 3), joint(-1, 1, 4, 1)};
  const BlockSet b = cut_blocks(rectangle(0, 0, 3, 2), {}, s, CutOptions());
  ASSERT_EQ(b.blocks.size(), 6u);
  auto centroids = [&](const std::vector<std::size_t> &list) {
    std::vector<std::pair<double, double>> c;
    for (const std::size_t i : list)
      c.emplace_back(b.blocks[i].polygon.centroid().x(),
                     b.blocks[i].polygon.centroid().y());
    std::sort(c.begin(), c.end());
    return c;
  };
  using C = std::vector<std::pair<double, double>>;
  EXPECT_EQ(centroids(boundary_blocks(b, true, false)),
            (C{{0.5, 0.5}, {1.5, 0.5}, {2.5, 0.5}}));
  EXPECT_EQ(centroids(boundary_blocks(b, false, true)),
            (C{{0.5, 0.5}, {0.5, 1.5}, {2.5, 0.5}, {2.5, 1.5}}));
  EXPECT_EQ(boundary_blocks(b, true, true).size(), 5u);
  geometry::Polygon region;
  region.vertices = {{1.2, 1.2}, {1.8, 1.2}, {1.8, 1.8}, {1.2, 1.8}};
  EXPECT_EQ(boundary_blocks(b, true, true, region).size(), 6u);
  EXPECT_TRUE(boundary_blocks(b, false, false).empty());
  // The DDA block file lists them as fixed blocks.
  const std::string text
    = dda_block_file_text(b, boundary_blocks(b, true, false));
  std::size_t n = 0;
  for (std::size_t p = text.find("fixed-block "); p != std::string::npos;
       p             = text.find("fixed-block ", p + 1))
    ++n;
  EXPECT_EQ(n, 3u);
}

// Shi & Goodman sets: L, b and s are uniform in [mean (1 - DR),
// mean (1 + DR)]; over ~10^4 samples the means are within 5 % (the
// sampling error is ~0.3 %), no value leaves the DR band and the standard
// deviation is DR mean / sqrt(3) within 5 %.
TEST(Generators, ShiGoodmanStatistics)
{
  JointSetParameters p;
  p.dip                  = 60.;
  p.mean_length          = 5.;
  p.mean_bridge          = 2.;
  p.mean_spacing         = 0.54;
  p.degree_of_randomness = 0.5;
  Random                                r(7);
  std::vector<std::vector<std::size_t>> lines;
  const auto                            s
    = generate_joint_set(p, 0, Eigen::Vector4d(0, 0, 150, 150), r, &lines);
  const Point d(std::cos(M_PI / 3.), std::sin(M_PI / 3.)), n(-d.y(), d.x());
  std::vector<double> L, b, sp;
  double              previous_offset = 0.;
  bool                first           = true;
  for (const auto &line : lines)
    {
      if (line.empty())
        continue;
      const double offset = n.dot(s[line[0]].a);
      if (!first)
        sp.push_back(offset - previous_offset);
      first           = false;
      previous_offset = offset;
      for (std::size_t i = 0; i < line.size(); ++i)
        {
          L.push_back((s[line[i]].b - s[line[i]].a).norm());
          if (i > 0)
            b.push_back(d.dot(s[line[i]].a - s[line[i - 1]].b));
        }
    }
  ASSERT_GT(L.size(), 5000u);
  auto check =
    [&](const std::vector<double> &v, const double mean, const char *what) {
      const double m   = std::accumulate(v.begin(), v.end(), 0.) / v.size();
      double       var = 0.;
      for (const double x : v)
        var += (x - m) * (x - m);
      const double sd = std::sqrt(var / (v.size() - 1));
      EXPECT_NEAR(m / mean, 1., 0.05) << what;
      EXPECT_NEAR(sd / (0.5 * mean / std::sqrt(3.)), 1., 0.05) << what;
      EXPECT_GE(*std::min_element(v.begin(), v.end()), 0.5 * mean * (1. - 1e-9))
        << what;
      EXPECT_LE(*std::max_element(v.begin(), v.end()), 1.5 * mean * (1. + 1e-9))
        << what;
    };
  check(L, 5., "length");
  check(b, 2., "bridge");
  check(sp, 0.54, "spacing");
}

// DR = 0 gives a regular pattern.
TEST(Generators, ZeroRandomnessIsRegular)
{
  JointSetParameters p;
  p.dip                  = 0.;
  p.degree_of_randomness = 0.;
  Random     r(3);
  const auto s = generate_joint_set(p, 0, Eigen::Vector4d(0, 0, 30, 10), r);
  for (const auto &t : s)
    EXPECT_NEAR((t.b - t.a).norm(), 5., 1e-12);
}

namespace
{
  double
  normal_cdf(const double x)
  {
    return 0.5 * std::erfc(-x / std::sqrt(2.));
  }

  /// Kolmogorov distribution tail Q(lambda) = P(sqrt(n) D > lambda).
  double
  kolmogorov_q(const double lambda)
  {
    double q = 0.;
    for (int j = 1; j < 200; ++j)
      q += 2. * std::pow(-1., j - 1) * std::exp(-2. * j * j * lambda * lambda);
    return std::clamp(q, 0., 1.);
  }
} // namespace

// Bed thicknesses of the layered generator follow the truncated lognormal
// law (thesis: mean 10^0 m, deviation 10^-0.2 m, minimum 0.7 m): one-sample
// KS test on 2,000 beds at p > 0.01.
TEST(Generators, BedThicknessKolmogorovSmirnov)
{
  LayeredParameters p;
  p.confined_joints = false;
  Random     r(11);
  const auto net = generate_layered(p, 0, Eigen::Vector4d(0, 0, 10, 3000), r);
  ASSERT_GE(net.thicknesses.size(), 2000u);
  std::vector<double> t(net.thicknesses.begin(),
                        net.thicknesses.begin() + 2000);
  std::sort(t.begin(), t.end());
  const auto [mu, sigma] = p.log_parameters();
  const double f0        = normal_cdf((std::log(p.min_thickness) - mu) / sigma);
  double       D         = 0.;
  const double n         = t.size();
  for (std::size_t i = 0; i < t.size(); ++i)
    {
      EXPECT_GE(t[i], p.min_thickness);
      const double F
        = (normal_cdf((std::log(t[i]) - mu) / sigma) - f0) / (1. - f0);
      D = std::max({D, std::abs(F - i / n), std::abs((i + 1) / n - F)});
    }
  const double sn     = std::sqrt(n);
  const double pvalue = kolmogorov_q((sn + 0.12 + 0.11 / sn) * D);
  EXPECT_GT(pvalue, 0.01) << "D = " << D;
  // The same test rejects the untruncated law (the test has power).
  double D_untruncated = 0.;
  for (std::size_t i = 0; i < t.size(); ++i)
    {
      const double F = normal_cdf((std::log(t[i]) - mu) / sigma);
      D_untruncated  = std::max(D_untruncated, std::abs(F - (i + 1) / n));
    }
  EXPECT_LT(kolmogorov_q((sn + 0.12 + 0.11 / sn) * D_untruncated), 0.01);
}

// Joints confined to beds: the median spacing in each bed equals
// thickness / FSI within 10 % (about 1,000 joints per bed, sampling error of
// the median ~1 %), and every joint spans exactly its bed.
TEST(Generators, MedianSpacingIsThicknessOverFsi)
{
  LayeredParameters p;
  p.fsi = 1.3;
  Random     r(5);
  const auto net = generate_layered(p, 0, Eigen::Vector4d(0, 0, 1000, 12), r);
  ASSERT_GE(net.thicknesses.size(), 5u);
  for (std::size_t k = 0; k < net.thicknesses.size(); ++k)
    {
      const auto         &x = net.joint_positions[k];
      std::vector<double> sp;
      for (std::size_t i = 1; i < x.size(); ++i)
        sp.push_back(x[i] - x[i - 1]);
      std::nth_element(sp.begin(), sp.begin() + sp.size() / 2, sp.end());
      EXPECT_NEAR(sp[sp.size() / 2] / (net.thicknesses[k] / p.fsi), 1., 0.1)
        << "bed " << k;
    }
}

namespace
{
  /// The coarse Table 3-1 domain (thesis Fig. 3-4 scaled down) with its bed
  /// sequence; returns (block count, mean width) of the DL model with L, b.
  std::pair<double, double>
  table_model(const double          L,
              const double          b,
              const LayeredNetwork &beds,
              const Polygon        &domain,
              const unsigned int    seed)
  {
    JointSetParameters p;
    p.dip                  = 90.;
    p.mean_length          = L;
    p.mean_bridge          = b;
    p.mean_spacing         = 0.54;
    p.degree_of_randomness = 0.5;
    Random r(seed);
    auto   s = generate_joint_set(p, 0, domain.bounding_box(), r);
    s.insert(s.end(), beds.bedding.begin(), beds.bedding.end());
    const BlockSet blocks = cut_blocks(domain, {}, s);
    double         w      = 0.;
    for (const Block &blk : blocks.blocks)
      w += block_width(blk, 0.);
    return {double(blocks.blocks.size()), w / blocks.blocks.size()};
  }
} // namespace

// Thesis Table 3-1 trends at coarse size (40 m x 20 m, common random
// numbers): the block count decreases with b at each L, increases with L at
// equal b, and the mean block width increases with b/L (Fig. 3-6).
TEST(Table31, TrendsCoarse)
{
  const Polygon     domain = rectangle(0, 0, 40, 20);
  LayeredParameters lp;
  Random            r(1);
  const auto        beds = generate_layered(lp, 1, domain.bounding_box(), r);
  std::map<std::pair<int, int>, std::pair<double, double>> m;
  for (const int L : {5, 10, 15})
    for (int i = 1; i <= 5; ++i)
      m[{L, L / 5 * i}] = table_model(L, L / 5 * i, beds, domain, 100);
  auto count = [&](const int L, const int b) { return m[{L, b}].first; };
  for (const int L : {5, 10, 15})
    for (int i = 1; i < 5; ++i)
      {
        EXPECT_GT(count(L, L / 5 * i), count(L, L / 5 * (i + 1)))
          << "L " << L << " b " << L / 5 * i;
      }
  EXPECT_LT(count(5, 2), count(10, 2));
  EXPECT_LT(count(5, 4), count(10, 4));
  EXPECT_LT(count(5, 3), count(15, 3));
  EXPECT_LT(count(10, 6), count(15, 6));
  // Width against b/L: Spearman rank correlation over the 15 models.
  std::vector<std::pair<double, double>> xy;
  for (const auto &[k, v] : m)
    xy.emplace_back(double(k.second) / k.first, v.second);
  auto ranks = [](std::vector<double> v) {
    std::vector<double> r(v.size());
    for (std::size_t i = 0; i < v.size(); ++i)
      for (std::size_t j = 0; j < v.size(); ++j)
        r[i] += (v[j] < v[i]) + 0.5 * (v[j] == v[i] && i != j);
    return r;
  };
  std::vector<double> x, y;
  for (const auto &[a, c] : xy)
    {
      x.push_back(a);
      y.push_back(c);
    }
  const auto   rx = ranks(x), ry = ranks(y);
  const double mx  = std::accumulate(rx.begin(), rx.end(), 0.) / rx.size();
  const double my  = std::accumulate(ry.begin(), ry.end(), 0.) / ry.size();
  double       sxy = 0., sxx = 0., syy = 0.;
  for (std::size_t i = 0; i < rx.size(); ++i)
    {
      sxy += (rx[i] - mx) * (ry[i] - my);
      sxx += (rx[i] - mx) * (rx[i] - mx);
      syy += (ry[i] - my) * (ry[i] - my);
    }
  EXPECT_GT(sxy / std::sqrt(sxx * syy), 0.8);
}

// Bad input gets a clear InputError.
TEST(BadInput, ClearErrors)
{
  Polygon bow;
  bow.vertices = {Point(0, 0), Point(1, 1), Point(1, 0), Point(0, 1)};
  EXPECT_THROW(cut_blocks(bow, {}, {}), InputError);
  EXPECT_THROW(cut_blocks(rectangle(0, 0, 1, 1), {rectangle(2, 2, 3, 3)}, {}),
               InputError);
  JointSetParameters p;
  p.mean_spacing = -0.5;
  EXPECT_THROW(p.check("set 1"), InputError);
  p.mean_spacing         = 0.5;
  p.degree_of_randomness = 1.5;
  EXPECT_THROW(p.check("set 1"), InputError);
  try
    {
      p.check("set 1");
    }
  catch (const InputError &e)
    {
      EXPECT_NE(std::string(e.what()).find("[0, 1]"), std::string::npos);
    }
  LayeredParameters lp;
  lp.min_thickness = 30.;
  Random r(1);
  EXPECT_THROW(generate_layered(lp, 0, Eigen::Vector4d(0, 0, 50, 20), r),
               InputError);
}

// The block file round-trips bit for bit (17 significant digits), keeps the
// edge tags, and a malformed file names its line.
TEST(BlockFile, RoundTripAndErrors)
{
  std::vector<TaggedSegment> s
    = {joint(0.1, -1, 0.7, 2, 0),
       joint(-1, 1. / 3., 2, 0.4, 1),
       {Point(-1, 0.8), Point(2, 0.8), {EdgeKind::bedding, 0}}};
  const BlockSet b
    = cut_blocks(rectangle(0, 0, 1, 1), {rectangle(0.2, 0.5, 0.4, 0.6)}, s);
  const BlockSet r = parse_block_file(block_file_text(b), "test");
  ASSERT_EQ(r.blocks.size(), b.blocks.size());
  ASSERT_EQ(r.vertices.size(), b.vertices.size());
  for (std::size_t i = 0; i < b.vertices.size(); ++i)
    EXPECT_TRUE(r.vertices[i] == b.vertices[i]);
  for (std::size_t k = 0; k < b.blocks.size(); ++k)
    {
      EXPECT_EQ(r.blocks[k].vertex_ids, b.blocks[k].vertex_ids);
      for (std::size_t i = 0; i < b.blocks[k].edge_tags.size(); ++i)
        EXPECT_TRUE(r.blocks[k].edge_tags[i] == b.blocks[k].edge_tags[i]);
    }
  try
    {
      parse_block_file("rockdda-blocks 1\nvertices 3\n0 0 0\n1 1 0\n2 0 1\n"
                       "blocks 1\nblock 0 3\n0 joint 0\n1 crack 0\n2 joint 0\n",
                       "bad.txt");
      FAIL() << "no error";
    }
  catch (const InputError &e)
    {
      EXPECT_NE(std::string(e.what()).find("bad.txt:9"), std::string::npos)
        << e.what();
      EXPECT_NE(std::string(e.what()).find("crack"), std::string::npos);
    }
}

// 3D option: rectangular fractures in each bed cut by a vertical trace
// plane. With the intensity set from FSI, the median trace spacing along
// the section is thickness / FSI within 10 % (Poisson crossings, ~4,000
// per bed: the sample median's relative error is 1 / (ln 2 sqrt(n)) ~ 2 %), for
// fractures normal to the section and for strikes spread +- 40 deg at an
// oblique section.
TEST(Generators, ThreeDTraceSpacingMatchesFsi)
{
  for (const auto &[strike, spread, azimuth] :
       std::vector<std::tuple<double, double, double>>{{90., 0., 0.},
                                                       {70., 40., 10.}})
    {
      LayeredParameters p;
      p.three_d         = true;
      p.fracture_strike = strike;
      p.strike_spread   = spread;
      p.section_azimuth = azimuth;
      p.fracture_length = 3.;
      Random     r(17);
      const auto net
        = generate_layered(p, 0, Eigen::Vector4d(0, 0, 4000, 6), r);
      std::vector<double> ratios;
      for (std::size_t k = 0; k < net.thicknesses.size(); ++k)
        {
          const auto         &x = net.joint_positions[k];
          std::vector<double> sp;
          for (std::size_t i = 1; i < x.size(); ++i)
            sp.push_back(x[i] - x[i - 1]);
          ASSERT_GT(sp.size(), 200u);
          std::nth_element(sp.begin(), sp.begin() + sp.size() / 2, sp.end());
          EXPECT_NEAR(sp[sp.size() / 2] / (net.thicknesses[k] / p.fsi), 1., 0.1)
            << "bed " << k << " strike " << strike;
        }
    }
  // Fractures parallel to the trace plane leave no traces: an error.
  LayeredParameters p;
  p.three_d         = true;
  p.fracture_strike = 0.;
  EXPECT_THROW(p.check("layered"), InputError);
}
