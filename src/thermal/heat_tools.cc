/**
 * @file
 * Small deal.II-free helpers of the heat subsystem: sinusoid fit, skin
 * depths, material checks.
 */
#include <rockdda/io/error.h>
#include <rockdda/io/output.h>
#include <rockdda/thermal/heat_solver.h>

#include <cmath>
#include <stdexcept>

namespace rockdda::thermal
{
  SinusoidFit
  fit_sinusoid(const std::vector<double> &t,
               const std::vector<double> &values,
               const double               omega)
  {
    if (t.size() != values.size() || t.size() < 3)
      throw std::invalid_argument("fit_sinusoid: need >= 3 matching samples");
    // Normal equations of [1, sin, cos] (3x3, solved by Cramer's rule).
    double a[3][3] = {{0.}}, r[3] = {0.};
    for (std::size_t i = 0; i < t.size(); ++i)
      {
        const double f[3]
          = {1., std::sin(omega * t[i]), std::cos(omega * t[i])};
        for (int p = 0; p < 3; ++p)
          {
            r[p] += f[p] * values[i];
            for (int q = 0; q < 3; ++q)
              a[p][q] += f[p] * f[q];
          }
      }
    const auto det3 = [](const double m[3][3]) {
      return m[0][0] * (m[1][1] * m[2][2] - m[1][2] * m[2][1])
             - m[0][1] * (m[1][0] * m[2][2] - m[1][2] * m[2][0])
             + m[0][2] * (m[1][0] * m[2][1] - m[1][1] * m[2][0]);
    };
    const double det = det3(a);
    if (!(std::abs(det) > 0.))
      throw std::invalid_argument("fit_sinusoid: singular samples");
    double x[3];
    for (int c = 0; c < 3; ++c)
      {
        double m[3][3];
        for (int p = 0; p < 3; ++p)
          for (int q = 0; q < 3; ++q)
            m[p][q] = (q == c) ? r[p] : a[p][q];
        x[c] = det3(m) / det;
      }
    SinusoidFit fit;
    fit.mean      = x[0];
    fit.amplitude = std::hypot(x[1], x[2]);
    // a sin + b cos = A sin(w t + phase), A cos(phase) = a, A sin(phase) = b.
    fit.phase = std::atan2(x[2], x[1]);
    return fit;
  }



  double
  periodic_skin_depth(const double diffusivity, const double period)
  {
    const double omega = 2. * M_PI / period;
    return std::sqrt(2. * diffusivity / omega);
  }



  double
  thesis_skin_depth(const double diffusivity, const double exposure_time)
  {
    return std::sqrt(0.5 * diffusivity * exposure_time);
  }



  void
  validate(const Material &m, const std::string &where)
  {
    const auto check
      = [&](const double v, const std::string &what, const std::string &unit) {
          if (!(std::isfinite(v) && v > 0.))
            throw InputError(where + ": " + what + " of material '" + m.name
                             + "' is " + io::format_number(v, 6)
                             + " but must be > 0 " + unit);
        };
    check(m.conductivity, "thermal conductivity", "W/(m K)");
    check(m.density, "density", "kg/m^3");
    check(m.heat_capacity, "specific heat capacity", "J/(kg K)");
  }
} // namespace rockdda::thermal
