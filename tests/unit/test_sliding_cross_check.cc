/**
 * @file
 * Thesis Fig. 4-2A: the 3D single-face solution and the 1D Newmark solution
 * are the same physics for a plane loaded along its dip direction, so they
 * must agree up to the time-step error.
 */
#include <rockdda/analytical/newmark.h>
#include <rockdda/analytical/sliding3d.h>

#include <gtest/gtest.h>

#include <cmath>

using namespace rockdda;

TEST(CrossCheck, Fig42aThreeDimensionalEqualsNewmark)
{
  // Plane 20/090, phi = 30 deg, r = [0.5 sin(10 t), 0, -1] g, t in [0, 2 pi].
  const double alpha = 20., phi = 30., T = 2. * M_PI;

  analytical::Sliding3dOptions o3;
  o3.plane1.dip_deg           = alpha;
  o3.plane1.dip_direction_deg = 90.;
  o3.plane1.friction          = analytical::FrictionLaw::coulomb_deg(phi);
  o3.time_step                = 1e-3; // the thesis's step
  o3.duration                 = T;
  o3.output_interval          = T;
  const auto r3               = analytical::slide_3d(
    [](const double t) {
      return Eigen::Vector3d(0.5 * std::sin(10. * t), 0., -1.);
    },
    o3);
  // Project on the down-dip unit vector (cos a sin b, cos a cos b, -sin a).
  const double          a = alpha * M_PI / 180.;
  const Eigen::Vector3d down_dip(std::cos(a), 0., -std::sin(a));
  const double          d3 = r3.final_displacement.dot(down_dip);

  // 1D Newmark, plane model: the horizontal inertial acceleration 0.5 sin(10 t)
  // g acts toward the dip direction (+x), so it is the downslope input.
  seismic::Record rec;
  rec.dt = 1e-3;
  for (std::size_t i = 0;
       i <= static_cast<std::size_t>(std::llround(T / rec.dt));
       ++i)
    rec.acceleration.push_back(0.5 * std::sin(10. * i * rec.dt));
  analytical::NewmarkOptions o1;
  o1.yield_model     = analytical::NewmarkOptions::YieldModel::plane;
  o1.dip_deg         = alpha;
  o1.friction        = analytical::FrictionLaw::coulomb_deg(phi);
  o1.output_interval = T;
  const double d1    = analytical::newmark_sliding(rec, o1).final_displacement;

  // Both are second-order in dt (benchmarks/sliding-block); at dt = 1 ms
  // each is within ~3e-5 of the closed form 1.2377 m, so the 0.5 %
  // (the thesis reports 3 % for its own code) holds with a wide margin.
  ASSERT_GT(d1, 1.);
  EXPECT_LT(std::abs(d3 - d1) / d1, 0.005) << "3D " << d3 << " m, 1D " << d1;
  // and no motion off the dip line
  EXPECT_LT(std::abs(r3.final_displacement.dot(Eigen::Vector3d(0., 1., 0.))),
            1e-12);
}
