/**
 * @file
 * Internal to the thermal subsystem: what either heat solver writes about
 * itself: the VTU piece of the field (temperature, heat flux, block, and
 * the rank in distributed runs) and the description of the time stepper.
 */
#ifndef ROCKDDA_THERMAL_HEAT_OUTPUT_H
#define ROCKDDA_THERMAL_HEAT_OUTPUT_H

#include <rockdda/thermal/heat_solver.h>

#include <deal.II/base/mpi.h>
#include <deal.II/dofs/dof_handler.h>
#include <deal.II/lac/trilinos_vector.h>

#include <string>
#include <utility>
#include <vector>

namespace rockdda::thermal::internal
{
  /**
   * The VTU text of the locally owned cells of @p field (with ghosts) at
   * time @p t: temperature, heat flux and block; with @p rank >= 0, also
   * the rank of each cell.
   */
  template <typename VectorType>
  std::string
  vtu_piece(const HeatParameters        &prm,
            const dealii::DoFHandler<2> &dof_handler,
            const VectorType            &field,
            const double                 t,
            const int                    rank = -1);

  /**
   * The VTU files of the distributed @p field (with ghosts) at time @p t,
   * named after @p name: NAME.pvtu and one piece NAME.RANK.vtu per rank,
   * all returned on rank 0 (nothing on the others). Collective.
   */
  std::vector<std::pair<std::string, std::string>>
  pvtu_files(const HeatParameters                        &prm,
             const dealii::DoFHandler<2>                 &dof_handler,
             const dealii::TrilinosWrappers::MPI::Vector &field,
             const double                                 t,
             const std::string                           &name,
             const MPI_Comm                               comm);

  /// The time stepper and its step or tolerances, and the FE degree.
  std::string
  stepper_description(const HeatParameters &prm);
} // namespace rockdda::thermal::internal

#endif
