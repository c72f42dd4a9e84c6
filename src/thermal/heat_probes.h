/**
 * @file
 * Internal to the thermal subsystem: evaluating the temperature field of
 * either solver: probes (the dofs and shape values of a fixed point, on
 * the rank that owns it), the blocks' mean temperatures and linear trends,
 * and the L2 error against an exact field.
 */
#ifndef ROCKDDA_THERMAL_HEAT_PROBES_H
#define ROCKDDA_THERMAL_HEAT_PROBES_H

#include <rockdda/thermal/heat_solver.h>

#include <deal.II/base/mpi.h>
#include <deal.II/base/point.h>
#include <deal.II/dofs/dof_handler.h>
#include <deal.II/fe/mapping.h>

#include "heat_assembly.h"
#include "heat_internal.h"
#include <vector>

namespace rockdda::thermal::internal
{
  /// A probe: the rank that owns the point, its dofs and weights there
  /// (empty on the other ranks).
  struct Probe
  {
    unsigned int                                 owner = 0;
    std::vector<dealii::types::global_dof_index> dofs;
    std::vector<double>                          weights;
  };

  /// The dofs and shape values of @p cell at the point @p unit of the
  /// reference cell (projected into it).
  void
  fill_probe(const dealii::Mapping<2>                          &mapping,
             const dealii::DoFHandler<2>::active_cell_iterator &cell,
             const dealii::Point<2>                            &unit,
             Probe                                             &probe);

  /// This rank's part of the value of @p field at @p probe.
  template <typename VectorType>
  double
  probe_sum(const Probe &probe, const VectorType &field)
  {
    double v = 0.;
    for (unsigned int i = 0; i < probe.dofs.size(); ++i)
      v += probe.weights[i] * field[probe.dofs[i]];
    return v;
  }

  /// The blocks' mean temperatures and linear trends of the field
  /// @p solution, from the block integrals of @p fixed.
  template <typename VectorType>
  std::vector<BlockMoments>
  block_moments_of(const FixedIntegrals<VectorType> &fixed,
                   const VectorType                 &solution)
  {
    std::vector<BlockMoments> result(fixed.block_phi.size());
    for (unsigned int b = 0; b < result.size(); ++b)
      result[b] = block_moments_from(fixed.block_geometry[b],
                                     fixed.block_phi[b] * solution,
                                     fixed.block_xphi[b] * solution,
                                     fixed.block_yphi[b] * solution);
    return result;
  }

  /// L2 norm of @p field - @p exact at time @p t over the locally owned
  /// cells, summed over the ranks of @p comm (@p field with ghosts).
  template <typename VectorType>
  double
  l2_error_of(const dealii::Mapping<2>    &mapping,
              const dealii::DoFHandler<2> &dof_handler,
              const VectorType            &field,
              const SpaceTimeFunction     &exact,
              const double                 t,
              const MPI_Comm               comm);
} // namespace rockdda::thermal::internal

#endif
