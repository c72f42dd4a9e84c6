#include <rockdda/analytical/friction.h>

#include <algorithm>
#include <cmath>

namespace rockdda::analytical
{
  FrictionLaw
  FrictionLaw::coulomb_deg(const double phi_deg)
  {
    FrictionLaw law;
    law.type = Type::coulomb;
    law.mu0  = std::tan(phi_deg * M_PI / 180.);
    return law;
  }



  double
  FrictionLaw::coefficient(const double v) const
  {
    if (type == Type::coulomb)
      return mu0;
    const double speed = std::max(std::abs(v), v_cutoff);
    return std::max(0., mu0 + a_minus_b * std::log(speed / v0));
  }
} // namespace rockdda::analytical
