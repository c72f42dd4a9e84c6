/**
 * @file
 * The ParaView output of heat (issue 11, item 7): compressed binary VTU
 * with the heat flux q = -lambda grad T (W/m^2), read back with
 * vtu_reader.h and checked against 1-D steady conduction through two
 * blocks of different conductivity.
 */
#include <rockdda/thermal/heat_solver.h>
#include <rockdda/thermal/verification.h>

#include <deal.II/base/config.h>

#include <gtest/gtest.h>

#include "heat_test_scenes.h"
#include "vtu_reader.h"
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

using namespace rockdda;
using namespace rockdda::thermal;
using rockdda::test::Vtu;

namespace
{
  Block
  rectangle(const double                    x0,
            const double                    x1,
            const std::vector<std::string> &tags)
  {
    Block b;
    b.name      = "rectangle";
    b.vertices  = {{{x0, 0.}}, {{x1, 0.}}, {{x1, 1.}}, {{x0, 1.}}};
    b.edge_tags = tags; // bottom, right, top, left
    return b;
  }
} // namespace



// Steady conduction through [0, l1] (lambda1) and [l1, l1 + l2] (lambda2)
// in perfect contact, T_L and T_R held at the ends, the long sides
// adiabatic: q = (T_L - T_R) / (l1/lambda1 + l2/lambda2) along +x in both
// blocks. The profile is piecewise linear, which FE_Q(2) represents
// exactly, so after the transient has decayed (backward Euler with dt =
// one diffusion time, 60 steps: see Heat.JointConductanceSteadyState) the
// flux of every output point equals q up to round-off amplified by the
// condition number (~1e-8 q) and the single precision of deal.II's VTU
// values (6e-8 relative); the tolerance 1e-6 q leaves a margin.
TEST(HeatVtu, HeatFluxOfSteadyConduction)
{
  const double   l1 = 1., l2 = 1.5, lambda1 = 1.7, lambda2 = 0.8;
  const double   tl = 30., tr = 10.;
  HeatParameters p;
  Material       m1 = masada_dolomite(), m2 = masada_dolomite();
  m1.name         = "left";
  m1.conductivity = lambda1;
  m2.name         = "right";
  m2.conductivity = lambda2;
  p.materials     = {m1, m2};
  Block b1 = rectangle(0., l1, {"adiabatic", "joint", "adiabatic", "left end"});
  Block b2
    = rectangle(l1, l1 + l2, {"adiabatic", "right end", "adiabatic", "joint"});
  b2.material           = 1;
  p.blocks              = {b1, b2};
  p.boundary_conditions = test_scenes::fixed_end_temperatures(tl, tr);
  p.joint_contact       = HeatParameters::JointContact::perfect;
  p.degree              = 2;
  p.coarse_cell_size    = 0.25;
  p.initial_temperature = 0.5 * (tl + tr);
  p.stepper             = TimeStepper::backward_euler;
  const double kappa    = m2.diffusivity();
  p.time_step           = (l1 + l2) * (l1 + l2) / kappa;
  HeatSolver solver(p);
  solver.advance_to(60. * p.time_step);

  const Vtu vtu(solver.vtu());
  // Binary, and compressed when deal.II has zlib (deal.II writes Float32).
  for (const std::string name :
       {"Points", "connectivity", "temperature", "heat_flux", "block"})
    EXPECT_EQ(vtu[name].attributes.at("format"), "binary") << name;
#ifdef DEAL_II_WITH_ZLIB
  EXPECT_TRUE(vtu.compressed);
#endif
  const auto &flux = vtu["heat_flux"];
  ASSERT_EQ(flux.components, 3);
  ASSERT_EQ(flux.type, "Float32");
  const auto   q       = flux.values<float>();
  const auto   xyz     = vtu["Points"].values<float>();
  const double q_exact = (tl - tr) / (l1 / lambda1 + l2 / lambda2);
  ASSERT_EQ(q.size(), xyz.size());
  ASSERT_GT(q.size(), 0u);
  double worst = 0.;
  for (std::size_t k = 0; k < q.size(); k += 3)
    {
      worst = std::max({worst,
                        std::abs(q[k] - q_exact),
                        std::abs(double(q[k + 1])),
                        std::abs(double(q[k + 2]))});
    }
  std::printf("heat flux %.6f W/m^2, largest error at the output points "
              "%.1e W/m^2\n",
              q_exact,
              worst);
  EXPECT_LT(worst, 1e-6 * q_exact);
  // The temperature is there too: T_L at x = 0.
  const auto t = vtu["temperature"].values<float>();
  for (std::size_t k = 0; k < t.size(); ++k)
    if (xyz[3 * k] == 0.)
      {
        EXPECT_NEAR(t[k], tl, 1e-6 * tl);
      }
}
