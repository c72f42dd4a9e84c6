#include <rockdda/io/output.h>
#include <rockdda/seismic/attenuation.h>

#include <cmath>
#include <stdexcept>

namespace rockdda::seismic
{
  double
  bjf97_pga(const Bjf97Scenario &s)
  {
    if (!std::isfinite(s.magnitude) || !std::isfinite(s.distance_km)
        || !std::isfinite(s.vs30) || !std::isfinite(s.n_sigma)
        || s.distance_km < 0. || !(s.vs30 > 0.))
      throw std::invalid_argument("bjf97_pga: needs finite values, Rjb >= 0 "
                                  "km and Vs30 > 0 m/s");
    // Boore, Joyner & Fumal (1997), Table 8, PGA (randomly oriented
    // horizontal component).
    const double b1 = s.mechanism == FaultMechanism::strike_slip ? -0.313
                      : s.mechanism == FaultMechanism::reverse   ? -0.117
                                                                 : -0.242;
    const double b2 = 0.527, b3 = 0., b5 = -0.778, bv = -0.371;
    const double va = 1396., h = 5.57;
    const double r    = std::sqrt(s.distance_km * s.distance_km + h * h);
    const double dm   = s.magnitude - 6.;
    const double ln_y = b1 + b2 * dm + b3 * dm * dm + b5 * std::log(r)
                        + bv * std::log(s.vs30 / va)
                        + s.n_sigma * bjf97_sigma_ln_pga;
    return std::exp(ln_y);
  }



  std::vector<std::string>
  bjf97_warnings(const Bjf97Scenario &s)
  {
    std::vector<std::string> w;
    if (s.magnitude < 4. || s.magnitude > 8.)
      w.push_back("BJF97: magnitude M = " + io::format_number(s.magnitude, 6)
                  + " is outside the range the relation was fitted to "
                    "(4 <= M <= 8); the PGA is an extrapolation");
    if (s.distance_km > 80.)
      w.push_back("BJF97: Joyner-Boore distance Rjb = "
                  + io::format_number(s.distance_km, 6)
                  + " km is beyond the range the relation was fitted to "
                    "(Rjb <= 80 km); the PGA is an extrapolation");
    return w;
  }
} // namespace rockdda::seismic
