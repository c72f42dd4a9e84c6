// Tests of the analytical thermal ratchet model (Pasten 2012; thesis
// Ch. 5.4, Eqs. 5.1-5.6 and 5.9): each equation against a value computed by
// hand, the homogenisation limit, the thresholds, the trends and the
// reproduction of thesis Fig. 5-13 (issue 13, item 1).

#include <rockdda/analytical/ratchet.h>
#include <rockdda/io/error.h>

#include <gtest/gtest.h>

#include "test_files.h"
#include <cmath>
#include <limits>
#include <string>
#include <vector>

using namespace rockdda::analytical;
using rockdda::InputError;

using namespace rockdda::test_files;

namespace
{
  /// Masada Block 1 (Table 5-2, L_B 7 m, H 15 m, wedge 200 mm).
  RatchetInput
  block1()
  {
    return RatchetInput();
  }

  /// @p n values evenly spaced from @p a to @p b.
  std::vector<double>
  range(const double a, const double b, const unsigned int n = 21)
  {
    std::vector<double> v;
    for (unsigned int i = 0; i < n; ++i)
      v.push_back(a + (b - a) * i / (n - 1.));
    return v;
  }

} // namespace



// Eq. 5.1: D_T = 1.7 / (2600 * 810) = 8.0722e-7 m^2/s;
// D_T t_exp / 2 = 8.0722e-7 * 15552000 / 2 = 6.27692 m^2; S_d = 2.50538 m
// (thesis: 2.5 m).
TEST(RatchetAnalytical, SkinDepthEq51)
{
  const double D = thermal_diffusivity(1.7, 2600., 810.);
  EXPECT_NEAR(D, 8.0722e-7, 1e-11);
  EXPECT_NEAR(skin_depth(D, 180. * 86400., 7.), 2.50538, 1e-5);
  EXPECT_NEAR(skin_depth(D,
                         180. * 86400.,
                         std::numeric_limits<double>::infinity()),
              2.50538,
              1e-5);
  // t* = 2 * 7^2 / D_T = 1.214e8 s (3.85 years) > 180 days: not homogenised.
  EXPECT_NEAR(homogenisation_time(7., D), 1.21405e8, 1e3);
  EXPECT_FALSE(ratchet(block1()).homogenised);
}



// The homogenisation limit: a 1 m slab has t* = 2 / D_T = 2.4776e6 s
// (28.7 days) < 180 days, so S_d = L / 2 = 0.5 m. Just below t*, Eq. 5.1
// holds: sqrt(D_T t* / 2) = L.
TEST(RatchetAnalytical, HomogenisationLimit)
{
  const double D     = thermal_diffusivity(1.7, 2600., 810.);
  const double tstar = homogenisation_time(1., D);
  EXPECT_NEAR(tstar, 2.47765e6, 10.);
  EXPECT_DOUBLE_EQ(skin_depth(D, 180. * 86400., 1.), 0.5);
  EXPECT_DOUBLE_EQ(skin_depth(D, 1.0001 * tstar, 1.), 0.5);
  EXPECT_NEAR(skin_depth(D, 0.9999 * tstar, 1.), 1., 1e-4);

  RatchetInput in       = block1();
  in.block_length       = 1.;
  in.wedge_length       = 0.;
  const RatchetResult r = ratchet(in);
  EXPECT_TRUE(r.homogenised);
  EXPECT_DOUBLE_EQ(r.skin_depth, 0.5);
  // delta_T = alpha Delta T_p (2 beta L / 2) = 8e-6 * 18 * 0.45 = 6.48e-5 m.
  EXPECT_NEAR(r.thermal_displacement, 6.48e-5, 1e-15);
}



// Eq. 5.2: 8e-6 * 18 * (0.2 + 2 * 0.45 * 2.5) = 1.44e-4 * 2.45 = 3.528e-4 m.
TEST(RatchetAnalytical, ThermalDisplacementEq52)
{
  EXPECT_NEAR(thermal_displacement(8e-6, 18., 0.2, 0.45, 2.5), 3.528e-4, 1e-16);
  EXPECT_DOUBLE_EQ(thermal_displacement(0., 18., 0.2, 0.45, 2.5), 0.);
}



// Eq. 5.3 with gamma = 25000 N/m^3, L_B 7, H 15, eta 19, phi 41:
// tan 19 = 0.344328, H - 3.5 tan 19 = 13.794853;
// tan 41 cos 19 - sin 19 = 0.869287 * 0.945519 - 0.325568 = 0.496359;
// F = 25000 * 7 * 13.794853 * 0.496359 = 1.198259e6 N/m.
TEST(RatchetAnalytical, MaxForceEq53)
{
  EXPECT_NEAR(max_force(25000., 7., 15., 19., 41.), 1.198259e6, 1.);
  // Limit equilibrium: eta = phi gives 0, steeper gives < 0.
  EXPECT_NEAR(max_force(25000., 7., 15., 41., 41.), 0., 1e-9);
  EXPECT_LT(max_force(25000., 7., 15., 45., 41.), 0.);
  // Flat plane: F = gamma L_B H tan(phi) = 25000 * 7 * 15 * tan 41.
  EXPECT_NEAR(max_force(25000., 7., 15., 0., 41.),
              25000. * 7. * 15. * 0.869287,
              2.);
}



// Eq. 5.4: F = 1e6 N/m, cos 19 = 0.945519:
// 1e6 * 0.945519 / (15 * 40e9) * (0.2 + 3.5) = 1.575865e-6 * 3.7
// = 5.830698e-6 m.
TEST(RatchetAnalytical, ElasticDisplacementEq54)
{
  EXPECT_NEAR(elastic_displacement(1e6, 19., 15., 40e9, 0.2, 7.),
              5.830698e-6,
              1e-12);
}



// Eq. 5.5: 1e6 * 0.945519 / (1e9 * 7) = 1.350741e-4 m.
TEST(RatchetAnalytical, JointDisplacementEq55)
{
  EXPECT_NEAR(joint_displacement(1e6, 19., 1e9, 7.), 1.350741e-4, 1e-10);
}



// Eq. 5.6: 3e-4 - 1e-5 - 1e-4 = 1.9e-4; no ratchet when the sum of the
// elastic parts exceeds the expansion.
TEST(RatchetAnalytical, PlasticDisplacementEq56)
{
  EXPECT_NEAR(plastic_displacement(3e-4, 1e-5, 1e-4), 1.9e-4, 1e-18);
  EXPECT_EQ(plastic_displacement(1e-4, 1e-5, 1e-4), 0.);
  EXPECT_EQ(plastic_displacement(1.1e-4, 1e-5, 1e-4), 0.);
}



// Eq. 5.9, thesis Fig. 5-11B: dL 0.14 mm, dT 9 K, L_B 1.6 m, S_d 2.5 m:
// beta 0.45: 1.4e-4 / ((0.8 + 1.125) * 9) = 1.4e-4 / 17.325 = 8.0808e-6;
// beta 0.7:  1.4e-4 / ((0.8 + 1.75) * 9)  = 1.4e-4 / 22.95  = 6.1002e-6.
TEST(RatchetAnalytical, ThermalExpansionFromFieldCycleEq59)
{
  const double a45
    = thermal_expansion_from_field_cycle(1.4e-4, 9., 1.6, .45, 2.5);
  const double a70
    = thermal_expansion_from_field_cycle(1.4e-4, 9., 1.6, .7, 2.5);
  EXPECT_NEAR(a45, 8.0808e-6, 1e-10);
  EXPECT_NEAR(a70, 6.1002e-6, 1e-10);
  EXPECT_NEAR(a45, 8e-6, 0.02 * 8e-6);
  EXPECT_NEAR(a70, 6e-6, 0.02 * 6e-6);
  // Inverse of the forward relation dL = alpha (L_B / 2 + beta S_d) dT.
  EXPECT_NEAR(a45 * (0.8 + 0.45 * 2.5) * 9., 1.4e-4, 1e-18);
  EXPECT_THROW(thermal_expansion_from_field_cycle(1.4e-4, 0., 1.6, .45, 2.5),
               InputError);
  EXPECT_THROW(thermal_expansion_from_field_cycle(1.4e-4, 9., 1.6, 0., 2.5),
               InputError);
  EXPECT_THROW(thermal_expansion_from_field_cycle(-1e-4, 9., 1.6, .45, 2.5),
               InputError);
}



// ratchet() is Eqs. 5.1-5.6 put together; Block 1 with a 200 mm wedge:
// delta_T 0.3535 mm, delta_sigma 0.0071 mm, delta_j 0.1651 mm,
// delta_p 0.1813 mm per cycle.
TEST(RatchetAnalytical, Block1Combined)
{
  const RatchetInput  in = block1();
  const RatchetResult r  = ratchet(in);
  const double        F  = max_force(2600. * 9.80665, 7., 15., 19., 41.);
  EXPECT_DOUBLE_EQ(r.max_force, F);
  EXPECT_DOUBLE_EQ(r.thermal_displacement,
                   thermal_displacement(8e-6, 18., 0.2, 0.45, r.skin_depth));
  EXPECT_DOUBLE_EQ(r.elastic_displacement,
                   elastic_displacement(F, 19., 15., 40e9, 0.2, 7.));
  EXPECT_DOUBLE_EQ(r.joint_displacement, joint_displacement(F, 19., 1e9, 7.));
  EXPECT_NEAR(r.thermal_displacement, 3.53497e-4, 1e-9);
  EXPECT_NEAR(r.elastic_displacement, 7.1257e-6, 1e-10);
  EXPECT_NEAR(r.joint_displacement, 1.650733e-4, 1e-10);
  EXPECT_NEAR(r.plastic_displacement, 1.812982e-4, 1e-10);
  EXPECT_DOUBLE_EQ(r.excess, r.plastic_displacement);
}



// Trends (the signs the coupled study must reproduce): delta_p rises with
// the wedge length, alpha, Delta T_p and beta; F_max grows with friction, so
// delta_j grows and delta_p falls; F_max falls with the slope, so delta_p
// rises.
TEST(RatchetAnalytical, MonotonicTrends)
{
  const RatchetInput base   = block1();
  const auto         rising = [&](double RatchetInput::     *member,
                          const std::vector<double> &values,
                          const int                  sign) {
    const auto r = ratchet_sweep(base, member, values);
    for (std::size_t i = 1; i < r.size(); ++i)
      {
        EXPECT_GT(
          sign * (r[i].plastic_displacement - r[i - 1].plastic_displacement),
          0.)
          << "at value " << values[i];
      }
    return r;
  };
  rising(&RatchetInput::wedge_length, range(0., 0.2), 1);
  rising(&RatchetInput::thermal_expansion, range(4e-6, 1.2e-5), 1);
  rising(&RatchetInput::temperature_change, range(10., 30.), 1);
  rising(&RatchetInput::beta, range(0.3, 1.), 1);
  const auto friction
    = rising(&RatchetInput::friction_angle_deg, range(35., 45.), -1);
  const auto slope = rising(&RatchetInput::slope_deg, range(10., 25.), 1);
  for (std::size_t i = 1; i < friction.size(); ++i)
    {
      EXPECT_GT(friction[i].max_force, friction[i - 1].max_force);
      EXPECT_GT(friction[i].joint_displacement,
                friction[i - 1].joint_displacement);
      EXPECT_LT(slope[i].max_force, slope[i - 1].max_force);
    }
  // d delta_p / d L_W = alpha Delta T_p - F_max cos(eta) / (H E): the
  // expansion of the wedge less its elastic shortening.
  const auto   w = ratchet_sweep(base, &RatchetInput::wedge_length, {0., 0.2});
  const double F = w[0].max_force;
  EXPECT_NEAR((w[1].plastic_displacement - w[0].plastic_displacement) / 0.2,
              8e-6 * 18. - F * std::cos(19. * M_PI / 180.) / (15. * 40e9),
              1e-15);
}



// Delta T_p* = (delta_sigma + delta_j) / (alpha (L_W + 2 beta S_d)): for
// Block 1 (0.0071 + 0.1651) mm / (8e-6 * (0.2 + 0.9 * 2.50538)) = 8.768 K
// peak to peak (amplitude 4.38 K).
TEST(RatchetAnalytical, ThresholdTemperatureChange)
{
  RatchetInput in = block1();
  const double dt = threshold_temperature_change(in);
  EXPECT_NEAR(dt, 8.7683, 1e-4);
  in.temperature_change  = dt;
  const RatchetResult at = ratchet(in);
  EXPECT_NEAR(at.excess, 0., 1e-12 * at.thermal_displacement);
  in.temperature_change = 0.999 * dt;
  EXPECT_EQ(ratchet(in).plastic_displacement, 0.);
  in.temperature_change = 1.001 * dt;
  EXPECT_GT(ratchet(in).plastic_displacement, 0.);
  // No expansion, no ratchet at any temperature.
  in.thermal_expansion = 0.;
  EXPECT_EQ(threshold_temperature_change(in),
            std::numeric_limits<double>::infinity());
}



// phi*: delta_T = delta_sigma + delta_j solved for phi; Block 1: 54.88 deg.
// Above it the block stays put even when pushed.
TEST(RatchetAnalytical, ThresholdFrictionAngle)
{
  RatchetInput in  = block1();
  const double phi = threshold_friction_angle(in);
  EXPECT_NEAR(phi, 54.8835, 1e-4);
  in.friction_angle_deg  = phi;
  const RatchetResult at = ratchet(in);
  EXPECT_NEAR(at.excess, 0., 1e-12 * at.thermal_displacement);
  in.friction_angle_deg = phi + 0.01;
  EXPECT_EQ(ratchet(in).plastic_displacement, 0.);
  in.friction_angle_deg = phi - 0.01;
  EXPECT_GT(ratchet(in).plastic_displacement, 0.);
  // Independent of the input friction angle; without expansion the
  // threshold is the slope itself (any stable block stays put).
  in.friction_angle_deg = 30.;
  EXPECT_NEAR(threshold_friction_angle(in), phi, 1e-12);
  in.thermal_expansion = 0.;
  EXPECT_NEAR(threshold_friction_angle(in), 19., 1e-12);
}



// Thesis Fig. 5-13 (L_B 7 m, H 15 m, eta 19, phi 41, Delta T_p 18 K):
// beta 0.45, alpha 8e-6: 0.181-0.210 mm/yr; beta 0.7, alpha 6e-6:
// 0.238-0.260 mm/yr for wedges of 0-200 mm. By hand (S_d 2.50538 m,
// delta_sigma + delta_j = 0.1718 mm at L_W 0):
//   8e-6 * 18 * 0.9 * 2.50538 = 0.3247 mm - 0.1718 = 0.1529 mm;
//   6e-6 * 18 * 1.4 * 2.50538 = 0.3788 mm - 0.1718 = 0.2070 mm;
// and +(alpha Delta T_p - F cos(eta) / (H E)) * 0.2 m = +0.0284 / +0.0212 mm
// at 200 mm. Within 20 % of the thesis (12-16 % low; doc/theory/ratchet.md:
// the thesis's Fig. 5-9 cross-section carries a ~17 % smaller F_max).
TEST(RatchetAnalytical, Figure513Reproduction)
{
  struct Curve
  {
    double beta, alpha, thesis_0, thesis_200, ours_0, ours_200;
  };
  for (const Curve &c : {Curve{0.45, 8e-6, 0.181, 0.210, 0.1529, 0.1813},
                         Curve{0.7, 6e-6, 0.238, 0.260, 0.2070, 0.2282}})
    {
      RatchetInput in      = block1();
      in.beta              = c.beta;
      in.thermal_expansion = c.alpha;
      const auto r = ratchet_sweep(in, &RatchetInput::wedge_length, {0., 0.2});
      const double rate_0   = 1e3 * r[0].plastic_displacement;
      const double rate_200 = 1e3 * r[1].plastic_displacement;
      EXPECT_NEAR(rate_0, c.ours_0, 1e-4);
      EXPECT_NEAR(rate_200, c.ours_200, 1e-4);
      EXPECT_NEAR(rate_0, c.thesis_0, 0.2 * c.thesis_0);
      EXPECT_NEAR(rate_200, c.thesis_200, 0.2 * c.thesis_200);
      // The rise over 200 mm of wedge matches the thesis to its 3 digits
      // (0.029 and 0.022 mm/yr).
      EXPECT_NEAR(rate_200 - rate_0, c.thesis_200 - c.thesis_0, 1.5e-3);
    }
}



// Bad input names the key and the valid range.
TEST(RatchetAnalytical, BadInput)
{
  RatchetInput in      = block1();
  in.thermal_expansion = -1e-6;
  EXPECT_NE(error_of([&]() {
              ratchet(in);
            }).find("'Ratchet analytical/Thermal expansion coefficient'"),
            std::string::npos);
  in      = block1();
  in.beta = 0.;
  EXPECT_NE(error_of([&]() { ratchet(in); }).find("0 < beta <= 1"),
            std::string::npos);
  in.beta = 1.5;
  EXPECT_NE(error_of([&]() { ratchet(in); }).find("0 < beta <= 1"),
            std::string::npos);
  in                         = block1();
  in.slope_deg               = 41.;
  const std::string unstable = error_of([&]() { ratchet(in); });
  EXPECT_NE(unstable.find("'Ratchet analytical/Slope'"), std::string::npos);
  EXPECT_NE(unstable.find("not stable without the crack"), std::string::npos);
  in              = block1();
  in.block_length = 100.;
  EXPECT_NE(error_of([&]() { ratchet(in); }).find("H > L_B tan(slope) / 2"),
            std::string::npos);
  in              = block1();
  in.wedge_length = -0.1;
  EXPECT_THROW(ratchet(in), InputError);
  in                    = block1();
  in.temperature_change = -1.;
  EXPECT_THROW(ratchet(in), InputError);
  in                       = block1();
  in.joint_shear_stiffness = 0.;
  EXPECT_THROW(ratchet(in), InputError);
  in               = block1();
  in.exposure_time = std::nan("");
  EXPECT_THROW(ratchet(in), InputError);
  in           = block1();
  in.slope_deg = 50.;
  EXPECT_THROW(threshold_friction_angle(in), InputError);
}
