/**
 * @file
 * The ParaView output of dda (issue 11, item 7), read back with a small
 * reader of the format written (vtu_reader.h: base64, zlib, header_type
 * UInt64): binary
 * files, the user's material ids, the stress tensor equal to the engine's,
 * contacts with both block ids, normal gap, shear slip, forces and state.
 */
#include <rockdda/dda/block_file.h>
#include <rockdda/dda/engine.h>
#include <rockdda/dda/vtu_output.h>

#include <gtest/gtest.h>

#include "dda_test_scenes.h"
#include "vtu_reader.h"
#include <cmath>
#include <cstdint>
#include <string>
#include <vector>

using namespace rockdda;
using namespace rockdda::dda;
using namespace rockdda::dda::test_scenes;
using rockdda::test::Array;
using rockdda::test::Vtu;

namespace
{
  /// Block 20 (material 3) on a fixed base (block 10, material 7) and
  /// block 30 (material 7) on block 20: user ids that are not indices.
  const char *const two_materials = "material 7 2700 1e10 0.25 plane-stress\n"
                                    "material 3 2500 2e10 0.2 plane-strain\n"
                                    "joint 5 30 0 0\n"
                                    "block 10 7 5  -1 -1  3 -1  3 0  -1 0\n"
                                    "fixed-block 10\n"
                                    "block 20 3 5  0 0  1 0  1 1  0 1\n"
                                    "block 30 7 5  0 1  1 1  1 2  0 2\n";
} // namespace



TEST(DdaVtu, BlocksBinaryWithUserMaterialIdsAndStressTensor)
{
  BlockSystem scene = parse_block_text(two_materials, "two-materials");
  DdaSystem   dda(scene, controls(0.01, 0., 1e11));
  for (int k = 0; k < 5; ++k)
    dda.step();
  const Vtu vtu(blocks_vtu(dda));
  EXPECT_EQ(vtu.text.find("format=\"ascii\""), std::string::npos);
  EXPECT_EQ(vtu.word, 8u);
#ifdef DEAL_II_WITH_ZLIB
  EXPECT_TRUE(vtu.compressed);
#endif
  const auto &blocks = dda.system().blocks;
  ASSERT_EQ(blocks.size(), 3u);

  const auto ids      = vtu["block_id"].values<std::int32_t>();
  const auto material = vtu["material"].values<std::int32_t>();
  EXPECT_EQ(vtu["material"].type, "Int32");
  EXPECT_EQ(ids, (std::vector<std::int32_t>{10, 20, 30}));
  EXPECT_EQ(material, (std::vector<std::int32_t>{7, 3, 7}));

  const Array &stress = vtu["stress"];
  EXPECT_EQ(stress.components, 6);
  EXPECT_EQ(stress.attributes.at("ComponentName0"), "XX");
  EXPECT_EQ(stress.attributes.at("ComponentName3"), "XY");
  EXPECT_EQ(stress.attributes.at("ComponentName5"), "XZ");
  const auto s = stress.values<double>();
  ASSERT_EQ(s.size(), 18u);
  for (std::size_t b = 0; b < blocks.size(); ++b)
    {
      EXPECT_EQ(s[6 * b + 0], blocks[b].stress[0]);
      EXPECT_EQ(s[6 * b + 1], blocks[b].stress[1]);
      EXPECT_EQ(s[6 * b + 2], 0.);
      EXPECT_EQ(s[6 * b + 3], blocks[b].stress[2]);
      EXPECT_EQ(s[6 * b + 4], 0.);
      EXPECT_EQ(s[6 * b + 5], 0.);
    }
  // Block 20 carries block 30: compressed vertically.
  EXPECT_LT(s[6 * 1 + 1], 0.);

  // The points are the vertices, in order; offsets close each polygon.
  const auto xyz     = vtu["Points"].values<double>();
  const auto offsets = vtu["offsets"].values<std::int64_t>();
  EXPECT_EQ(offsets, (std::vector<std::int64_t>{4, 8, 12}));
  std::size_t k = 0;
  for (const auto &b : blocks)
    for (const auto &v : b.polygon.vertices)
      {
        EXPECT_EQ(xyz[3 * k], dda.system().origin.x() + v.x());
        EXPECT_EQ(xyz[3 * k + 1], dda.system().origin.y() + v.y());
        EXPECT_EQ(xyz[3 * k + 2], 0.);
        ++k;
      }
  const auto displacement = vtu["displacement"].values<double>();
  for (std::size_t b = 0; b < blocks.size(); ++b)
    EXPECT_EQ(displacement[3 * b + 1],
              dda.centroid_displacement(static_cast<int>(b)).y());
}



TEST(DdaVtu, ContactsCarryBlockIdsGapSlipForcesState)
{
  BlockSystem    scene = parse_block_text(two_materials, "two-materials");
  const Controls c     = controls(0.01, 0., 1e11);
  DdaSystem      dda(scene, c);
  for (int k = 0; k < 5; ++k)
    dda.step();
  const Vtu   vtu(contacts_vtu(dda));
  const auto &contacts = dda.contacts();
  ASSERT_FALSE(contacts.empty());
  EXPECT_EQ(vtu.text.find("format=\"ascii\""), std::string::npos);
  // The state codes are named in the file.
  EXPECT_NE(vtu.text.find("0 open, 1 sliding, 2 locked"), std::string::npos);

  const auto state  = vtu["state"].values<std::int32_t>();
  const auto vb     = vtu["vertex_block"].values<std::int32_t>();
  const auto eb     = vtu["edge_block"].values<std::int32_t>();
  const auto gap    = vtu["normal_gap"].values<double>();
  const auto slip   = vtu["shear_slip"].values<double>();
  const auto fn     = vtu["normal_force"].values<double>();
  const auto fs     = vtu["shear_force"].values<double>();
  const auto normal = vtu["normal"].values<double>();
  ASSERT_EQ(state.size(), contacts.size());
  ASSERT_EQ(slip.size(), contacts.size());
  const auto &blocks   = dda.system().blocks;
  int         base_top = 0, closed = 0;
  for (std::size_t k = 0; k < contacts.size(); ++k)
    {
      const auto &ct = contacts[k];
      EXPECT_EQ(state[k], static_cast<int>(ct.state));
      EXPECT_EQ(vb[k], blocks[ct.geometry.block_i].id);
      EXPECT_EQ(eb[k], blocks[ct.geometry.block_j].id);
      EXPECT_EQ(fn[k], ct.normal_force);
      EXPECT_EQ(fs[k], ct.shear_force);
      EXPECT_NEAR(std::hypot(normal[3 * k], normal[3 * k + 1]), 1., 1e-14);
      // The pairs touching in this scene: 20 on 10 and 30 on 20.
      const std::pair<int, int> pair(std::min(vb[k], eb[k]),
                                     std::max(vb[k], eb[k]));
      EXPECT_TRUE(pair == std::make_pair(10, 20)
                  || pair == std::make_pair(20, 30))
        << vb[k] << " " << eb[k];
      if (ct.state == ContactState::open)
        continue;
      ++closed;
      // Closed at rest: locked, compressed, penetration = force / penalty.
      EXPECT_EQ(state[k], 2);
      EXPECT_LT(gap[k], 0.);
      EXPECT_GT(fn[k], 0.);
      EXPECT_NEAR(-gap[k] * c.law.normal_penalty, fn[k], 1e-3 * fn[k]);
      // Locked: the shear slip is the elastic displacement of the shear
      // spring, which carries the shear force.
      EXPECT_NEAR(std::abs(fs[k]),
                  c.law.shear_penalty() * std::abs(slip[k]),
                  1e-3 * std::abs(fs[k]) + 1e-9 * fn[k]);
      base_top += eb[k] == 10 && vb[k] == 20;
    }
  EXPECT_GE(closed, 4);
  // Both bottom corners of block 20 press on the base's top edge.
  EXPECT_EQ(base_top, 2);
  // The two corners of block 20 carry its and block 30's weight
  // (2700 + 2500) kg/m^3 x 1 m^2 x g.
  double total = 0.;
  for (std::size_t k = 0; k < contacts.size(); ++k)
    if (vb[k] == 20 && eb[k] == 10)
      total += fn[k];
  EXPECT_NEAR(total, (2700. + 2500.) * g_earth, 1e-3 * total);
}



TEST(DdaVtu, SlidingContactReportsItsSlip)
{
  // A 1 m block sliding down a 30 deg incline with 10 deg friction: the
  // shear slip of its sliding contacts is the distance slid in the last
  // step (a sliding contact's shear reference is its position at the
  // start of the step).
  const double alpha = 30. * M_PI / 180.;
  DdaSystem    dda(incline_scene(alpha, 10.), controls(1e-3, 1., 1e11));
  for (int k = 0; k < 199; ++k)
    dda.step();
  const double before = along_slope(dda, 1, alpha);
  dda.step();
  const double slid = along_slope(dda, 1, alpha) - before;
  ASSERT_GT(slid, 1e-4);
  const Vtu  vtu(contacts_vtu(dda));
  const auto state   = vtu["state"].values<std::int32_t>();
  const auto slip    = vtu["shear_slip"].values<double>();
  int        sliding = 0;
  for (std::size_t k = 0; k < state.size(); ++k)
    if (state[k] == 1)
      {
        ++sliding;
        EXPECT_NEAR(std::abs(slip[k]), slid, 0.02 * slid);
      }
  EXPECT_EQ(sliding, 2);
}
