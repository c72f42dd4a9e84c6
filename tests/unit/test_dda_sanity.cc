/**
 * @file
 * A DDA run never ends silently on a physically impossible state (issue 11,
 * item 2): a penalty too low for the load, a Young's modulus in the wrong
 * units, a record in the wrong units. Each gets a warning naming the
 * plausible value before the run, and a run that goes wrong stops with a
 * diagnosis instead of completing. On the code before issue 11 all three
 * ran to the end without a word (block 4.67 m through the incline; every
 * block dropped 19.6 m; PGA 407 g).
 */
#include <rockdda/dda/block_matrices.h>
#include <rockdda/dda/engine.h>

#include <gtest/gtest.h>

#include "dda_test_scenes.h"
#include <cmath>
#include <string>

using namespace rockdda;
using namespace rockdda::dda;
using namespace rockdda::dda::test_scenes;

namespace
{
  constexpr double deg = M_PI / 180.;

  bool
  any_contains(const std::vector<std::string> &list, const std::string &text)
  {
    for (const auto &s : list)
      if (s.find(text) != std::string::npos)
        return true;
    return false;
  }

  /// Run @p dda to @p end and return the failure message ("" if none).
  std::string
  failure_of(DdaSystem &dda, const double end)
  {
    try
      {
        dda.run_until(end);
      }
    catch (const DdaFailure &e)
      {
        return e.what();
      }
    return "";
  }
} // namespace



TEST(DdaSanity, PenaltyTooLowForTheLoadStopsWithADiagnosis)
{
  // 1 m block (26.5 kN/m) on a 30 deg incline, friction 40 deg (stable),
  // penalty 1e5 N/m: it would sink 0.26 m per metre... through the base.
  DdaSystem dda(incline_scene(30. * deg, 40.), controls(1e-3, 1., 1e5));
  EXPECT_TRUE(any_contains(dda.warnings(), "contact penalty"));
  const std::string why = failure_of(dda, 1.);
  std::printf("penalty 1e5: %s\n", why.c_str());
  EXPECT_NE(why.find("penetrates"), std::string::npos) << why;
  EXPECT_NE(why.find("penalty"), std::string::npos) << why;
  // The same scene at a sound penalty runs and stays put.
  DdaSystem sound(incline_scene(30. * deg, 40.), controls(1e-3, 1., 1e11));
  EXPECT_FALSE(any_contains(sound.warnings(), "contact penalty"));
  EXPECT_EQ(failure_of(sound, 0.2), "");
  EXPECT_LT(std::abs(along_slope(sound, 1, 30. * deg)), 1e-5);
}



TEST(DdaSanity, YoungsModulusInTheWrongUnitsStopsWithADiagnosis)
{
  // E = 10 Pa (meant as 10 GPa): the blocks would flatten under their own
  // weight.
  BlockSystem s        = incline_scene(0., 40.);
  s.materials[0].young = 10.;
  DdaSystem dda(s, controls(1e-3, 1., 1e11));
  EXPECT_TRUE(any_contains(dda.warnings(), "Young's modulus"));
  const std::string why = failure_of(dda, 1.);
  std::printf("E = 10 Pa: %s\n", why.c_str());
  EXPECT_NE(why.find("Young's modulus"), std::string::npos) << why;
}



TEST(DdaSanity, RecordInTheWrongUnitsIsFlagged)
{
  // A record in cm/s^2 read as g: a 4 m/s^2 (0.41 g) peak becomes 407 g.
  BlockSystem s         = incline_scene(20. * deg, 40.);
  s.seismic.mode        = SeismicInput::Mode::inertial;
  s.seismic.record.name = "cm-per-s2.txt";
  s.seismic.record.dt   = 1e-2;
  for (int k = 0; k < 100; ++k)
    s.seismic.record.acceleration.push_back(400. * std::sin(0.3 * k));
  DdaSystem dda(s, controls(1e-3, 1., 1e11));
  EXPECT_TRUE(any_contains(dda.warnings(), "cm/s^2")) << dda.warnings().size();
  for (const auto &w : dda.warnings())
    std::printf("warning: %s\n", w.c_str());
  // A plausible record gives no such warning.
  for (auto &a : s.seismic.record.acceleration)
    a /= 981.;
  DdaSystem plausible(s, controls(1e-3, 1., 1e11));
  EXPECT_FALSE(any_contains(plausible.warnings(), "cm/s^2"));
}



TEST(DdaSanity, AutomaticPenaltyKeepsPenetrationSmall)
{
  // 'Contact penalty = auto': at least 10 E x 1 m, and stiff enough that
  // the heaviest block sinks by at most 1e-4 of its size under its own
  // weight; the plausibility check then has nothing to say. A 40 m x 20 m
  // block of E = 0.1 GPa needs more than 10 E.
  for (const double size : {1., 40.})
    {
      BlockSystem s = incline_scene(0., 40., size, 0.5 * size, 4. * size);
      s.materials[0].young = 1e8;
      const double p       = automatic_penalty(s, g_earth);
      const double weight  = 2700. * 0.5 * size * size * g_earth;
      EXPECT_GE(p, 10. * 1e8);
      if (size > 10.)
        EXPECT_GT(p, 10. * 1e8);
      const double b_size = block_size(s.blocks[1].polygon);
      EXPECT_LE(weight / p, 1e-4 * b_size * (1. + 1e-12));
      DdaSystem dda(s, controls(1e-3, 1., p));
      EXPECT_FALSE(any_contains(dda.warnings(), "contact penalty")) << size;
      std::printf("block %g m: automatic penalty %.3e N/m, sinks %.2e of "
                  "its size\n",
                  size,
                  p,
                  weight / p / b_size);
    }
}
