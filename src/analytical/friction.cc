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
    return steady_state_friction(mu0, a_minus_b, v0, v_cutoff, v);
  }
} // namespace rockdda::analytical
