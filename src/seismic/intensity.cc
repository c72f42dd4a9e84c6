#include <rockdda/seismic/intensity.h>

#include <algorithm>
#include <cmath>

namespace rockdda::seismic
{
  namespace
  {
    constexpr double standard_gravity = 9.80665;
  }



  IntegratedMotion
  integrate(const Record &record)
  {
    const auto      &a = record.acceleration;
    const double     h = record.dt, g = standard_gravity;
    IntegratedMotion m;
    m.velocity.assign(a.size(), 0.);
    m.displacement.assign(a.size(), 0.);
    for (std::size_t i = 1; i < a.size(); ++i)
      {
        m.velocity[i]     = m.velocity[i - 1] + 0.5 * h * g * (a[i - 1] + a[i]);
        m.displacement[i] = m.displacement[i - 1]
                            + 0.5 * h * (m.velocity[i - 1] + m.velocity[i]);
      }
    return m;
  }



  IntensityMeasures
  intensity_measures(const Record &record)
  {
    IntensityMeasures im;
    const auto       &a = record.acceleration;
    if (a.empty())
      return im;
    const auto m = integrate(record);
    im.pga       = record.peak();
    for (std::size_t i = 0; i < a.size(); ++i)
      {
        im.pgv = std::max(im.pgv, std::abs(m.velocity[i]));
        im.pgd = std::max(im.pgd, std::abs(m.displacement[i]));
      }
    im.final_velocity     = m.velocity.back();
    im.final_displacement = m.displacement.back();

    // Husid function: cumulative int a^2 dt (trapezoidal).
    const double        g = standard_gravity, h = record.dt;
    std::vector<double> husid(a.size(), 0.);
    for (std::size_t i = 1; i < a.size(); ++i)
      husid[i]
        = husid[i - 1] + 0.5 * h * g * g * (a[i - 1] * a[i - 1] + a[i] * a[i]);
    im.arias = M_PI / (2. * g) * husid.back();
    if (!(husid.back() > 0.))
      return im;
    const auto time_of = [&](const double fraction) {
      const double target = fraction * husid.back();
      const auto   it = std::lower_bound(husid.begin(), husid.end(), target);
      const std::size_t i = it - husid.begin();
      if (i == 0)
        return 0.;
      const double w = (target - husid[i - 1]) / (husid[i] - husid[i - 1]);
      return h * (i - 1 + w);
    };
    im.t5    = time_of(0.05);
    im.t95   = time_of(0.95);
    im.d5_95 = im.t95 - im.t5;
    return im;
  }
} // namespace rockdda::seismic
