/**
 * @file
 * Verification problems of the heat solver, shared by the tests and the
 * benchmarks: the Masada rock properties and a manufactured problem.
 */
#ifndef ROCKDDA_THERMAL_VERIFICATION_H
#define ROCKDDA_THERMAL_VERIFICATION_H

#include <rockdda/thermal/heat_solver.h>

#include <functional>

namespace rockdda::thermal
{
  /// A scalar field f(x, y, t) (x, y in m, t in s).
  using ScalarField = std::function<double(double, double, double)>;

  /// Masada dolomite (thesis Table 5-2): lambda = 1.7 W/m/K,
  /// rho = 2600 kg/m^3, c_p = 810 J/kg/K.
  Material
  masada_dolomite();

  /**
   * A manufactured problem on the unit square (lambda = rho = c_p = 1): the
   * exact field @p exact with its derivatives @p dtdx, @p dtdy and the
   * matching @p source. Dirichlet on the left and bottom edges, a flux
   * (= dT/dy) on the top, convective exchange (h = 2) on the right, so every
   * boundary-condition type is exercised; FE_Q(@p degree), cells of size
   * @p h (m), step @p dt (s) with @p stepper.
   */
  HeatParameters
  manufactured_problem(const unsigned int degree,
                       const double       h,
                       const double       dt,
                       const TimeStepper  stepper,
                       const ScalarField &exact,
                       const ScalarField &dtdx,
                       const ScalarField &dtdy,
                       const ScalarField &source);

  /**
   * The periodic half-space as a column @p width m wide and 30 m deep
   * (Masada dolomite, adiabatic sides and base): the top is held at
   * @p mean + @p amplitude sin(2 pi t / 1 year) (K); FE_Q(@p degree),
   * coarse cells of @p cell_size m, Crank-Nicolson with daily steps,
   * starting from @p mean. Used by the adaptivity test and benchmark.
   */
  HeatParameters
  half_space_column(const double       width,
                    const unsigned int degree,
                    const double       cell_size,
                    const double       amplitude,
                    const double       mean);
} // namespace rockdda::thermal

#endif
