/**
 * @file
 * Internal to the thermal subsystem: the heat flux q = -lambda grad T
 * (W/m^2) as a vector field of the VTU output, shared by the serial and the
 * distributed heat solvers.
 */
#ifndef ROCKDDA_THERMAL_HEAT_FLUX_H
#define ROCKDDA_THERMAL_HEAT_FLUX_H

#include <rockdda/thermal/heat_solver.h>

#include <deal.II/numerics/data_postprocessor.h>

#include <vector>

namespace rockdda::thermal::internal
{
  /**
   * DataOut postprocessor of the heat flux q = -lambda grad T (W/m^2) of a
   * temperature field: the conductivity lambda (W/(m K)) is that of the
   * block a cell belongs to (the cell's material id is the block index).
   * The flux is evaluated from the finite-element gradient, element by
   * element, so it is discontinuous across cell faces (and joints).
   */
  class HeatFluxPostprocessor : public dealii::DataPostprocessorVector<2>
  {
  public:
    /// The conductivity of each block of @p prm.
    explicit HeatFluxPostprocessor(const HeatParameters &prm)
        : dealii::DataPostprocessorVector<2>("heat_flux",
                                             dealii::update_gradients)
    {
      for (const auto &b : prm.blocks)
        conductivity.push_back(prm.materials[b.material].conductivity);
    }

    void
    evaluate_scalar_field(
      const dealii::DataPostprocessorInputs::Scalar<2> &inputs,
      std::vector<dealii::Vector<double>> &computed_quantities) const override
    {
      const auto   cell   = inputs.template get_cell<2>();
      const double lambda = conductivity.at(cell->material_id());
      for (unsigned int q = 0; q < computed_quantities.size(); ++q)
        for (unsigned int d = 0; d < 2; ++d)
          computed_quantities[q][d] = -lambda * inputs.solution_gradients[q][d];
    }

  private:
    /// lambda of each block (W/(m K)).
    std::vector<double> conductivity;
  };
} // namespace rockdda::thermal::internal

#endif
