#include <rockdda/analytical/analyses.h>
#include <rockdda/io/parameters.h>

#include <cmath>

namespace rockdda::analytical
{
  std::vector<std::unique_ptr<io::Analysis>>
  make_analyses()
  {
    std::vector<std::unique_ptr<io::Analysis>> list;
    list.push_back(internal::make_newmark_analysis());
    list.push_back(internal::make_sliding3d_analysis());
    list.push_back(internal::make_yield_analysis());
    list.push_back(internal::make_rate_state_analysis());
    list.push_back(internal::make_back_analysis());
    list.push_back(internal::make_ratchet_analytical_analysis());
    return list;
  }



  void
  declare_friction_parameters(dealii::ParameterHandler &prm)
  {
    using dealii::Patterns::Double;
    if (prm.subsection_path_exists({"Friction"}))
      return;
    prm.enter_subsection("Friction");
    io::declare(prm,
                "Law",
                "coulomb",
                dealii::Patterns::Selection("coulomb|steady-state"),
                "-",
                "'coulomb': mu = tan(phi); 'steady-state': mu(V) = tan(phi) + "
                "(A - B) ln(V / V0) (thesis Eq. 2.3), held at mu(Vc) below "
                "the cutoff velocity Vc and clipped at 0.");
    io::declare(prm,
                "A minus B",
                "0",
                Double(-1., 1.),
                "-",
                "Steady-state rate dependence A - B; negative is velocity "
                "weakening.");
    io::declare(prm,
                "Reference velocity",
                "1e-6",
                io::DoubleInterval::positive(),
                "m/s",
                "Reference slip rate V0 of the rate-dependent law. Must be > "
                "0.");
    io::declare(prm,
                "Cutoff velocity",
                "1e-6",
                io::DoubleInterval::positive(),
                "m/s",
                "Below this slip rate (and at rest) the rate-dependent law is "
                "evaluated at the cutoff. Must be > 0.");
    prm.leave_subsection();
  }



  FrictionLaw
  parse_friction(dealii::ParameterHandler &prm,
                 const std::string        &prm_file,
                 const double              phi_deg,
                 const std::string        &phi_key)
  {
    io::require(phi_deg >= 0. && phi_deg < 90.,
                prm_file,
                phi_key,
                phi_deg,
                "0 <= friction angle < 90 deg");
    FrictionLaw law = FrictionLaw::coulomb_deg(phi_deg);
    prm.enter_subsection("Friction");
    if (prm.get("Law") == "steady-state")
      {
        law.type      = FrictionLaw::Type::steady_state;
        law.a_minus_b = prm.get_double("A minus B");
        law.v0        = prm.get_double("Reference velocity");
        law.v_cutoff  = prm.get_double("Cutoff velocity");
        io::require(law.v0 > 0.,
                    prm_file,
                    "Friction/Reference velocity",
                    law.v0,
                    "V0 > 0 m/s");
        io::require(law.v_cutoff > 0.,
                    prm_file,
                    "Friction/Cutoff velocity",
                    law.v_cutoff,
                    "Vc > 0 m/s");
      }
    prm.leave_subsection();
    return law;
  }
} // namespace rockdda::analytical
