#include <rockdda/thermal/verification.h>

#include <cmath>

namespace rockdda::thermal
{
  Material
  masada_dolomite()
  {
    Material m;
    m.name          = "Masada dolomite";
    m.conductivity  = 1.7;
    m.density       = 2600.;
    m.heat_capacity = 810.;
    return m;
  }



  HeatParameters
  manufactured_problem(const unsigned int degree,
                       const double       h,
                       const double       dt,
                       const TimeStepper  stepper,
                       const ScalarField &exact,
                       const ScalarField &dtdx,
                       const ScalarField &dtdy,
                       const ScalarField &source)
  {
    HeatParameters p;
    Material       unit;
    unit.name         = "unit";
    unit.conductivity = unit.density = unit.heat_capacity = 1.;
    p.materials                                           = {unit};
    Block b;
    b.name             = "unit square";
    b.vertices         = {{{0., 0.}}, {{1., 0.}}, {{1., 1.}}, {{0., 1.}}};
    b.edge_tags        = {"dirichlet", "robin", "flux", "dirichlet"};
    p.blocks           = {b};
    p.degree           = degree;
    p.coarse_cell_size = h;
    p.time_step        = dt;
    p.stepper          = stepper;
    BoundaryCondition d, r, f;
    d.tag                       = "dirichlet";
    d.type                      = BoundaryCondition::Type::temperature;
    d.value                     = exact;
    d.uniform                   = false;
    r.tag                       = "robin";
    r.type                      = BoundaryCondition::Type::convective;
    r.heat_transfer_coefficient = 2.;
    r.value                     = [=](double x, double y, double t) {
      return exact(x, y, t) + dtdx(x, y, t) / 2.;
    };
    r.uniform             = false;
    f.tag                 = "flux";
    f.type                = BoundaryCondition::Type::flux;
    f.value               = dtdy;
    f.uniform             = false;
    p.boundary_conditions = {d, r, f};
    p.initial_field       = [=](double x, double y) { return exact(x, y, 0.); };
    p.source              = source;
    return p;
  }



  HeatParameters
  half_space_column(const double       width,
                    const unsigned int degree,
                    const double       cell_size,
                    const double       amplitude,
                    const double       mean)
  {
    const double   year = 365.25 * 86400.;
    HeatParameters p;
    p.materials = {masada_dolomite()};
    Block b;
    b.name      = "column";
    b.vertices  = {{{0., -30.}}, {{width, -30.}}, {{width, 0.}}, {{0., 0.}}};
    b.edge_tags = {"adiabatic", "adiabatic", "exposed", "adiabatic"};
    p.blocks    = {b};
    p.degree    = degree;
    p.coarse_cell_size = cell_size;
    BoundaryCondition surface;
    surface.tag   = "exposed";
    surface.type  = BoundaryCondition::Type::temperature;
    surface.value = [=](double, double, double t) {
      return mean + amplitude * std::sin(2. * M_PI * t / year);
    };
    p.boundary_conditions = {surface};
    p.stepper             = TimeStepper::crank_nicolson;
    p.time_step           = year / 365.;
    p.initial_temperature = mean;
    return p;
  }
} // namespace rockdda::thermal
