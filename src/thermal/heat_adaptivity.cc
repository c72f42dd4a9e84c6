/**
 * @file
 * Adaptive refinement of the heat solver's mesh during the run: the Kelly
 * error estimator, fixed-fraction refinement and coarsening within the
 * limits of internal::limit_adaptation_flags() (minimum cell size, cell
 * budget, coarse size, a priori band), and the transfer of the field and
 * of the previous increment to the new mesh, with the heat the (not
 * conservative) transfer adds booked in the statistics.
 */
#include <deal.II/base/quadrature_lib.h>
#include <deal.II/grid/grid_refinement.h>
#include <deal.II/numerics/error_estimator.h>
#include <deal.II/numerics/solution_transfer.h>

#include "heat_internal.h"
#include "heat_solver_serial.h"
#include <limits>

namespace rockdda::thermal
{
  using namespace dealii;

  void
  HeatSolver::Impl::adapt_mesh()
  {
    TimerOutput::Scope scope(timer, "adapt mesh");
    // Kelly et al. (1983): jumps of the normal gradient across faces.
    Vector<float> indicator(tria.n_active_cells());
    KellyErrorEstimator<2>::estimate(
      mapping, dof_handler, QGauss<1>(fe.degree + 1), {}, solution, indicator);
    if (!(indicator.l1_norm() > 0.))
      return;
    GridRefinement::refine_and_coarsen_fixed_fraction(
      tria,
      indicator,
      prm.refine_fraction,
      prm.coarsen_fraction,
      prm.adaptive_max_cells > 0 ? prm.adaptive_max_cells
                                 : std::numeric_limits<unsigned int>::max());
    // Limits: no cell finer than the minimum size; no cell coarser than the
    // coarse size, nor than the band size inside the a priori band.
    bool any = false;
    for (const auto &cell : tria.active_cell_iterators())
      any = internal::limit_adaptation_flags(cell, prm, band_segments, false)
            || any;
    if (!any)
      return;

    const double                        heat_before = fixed.capacity * solution;
    SolutionTransfer<2, Vector<double>> transfer(dof_handler);
    tria.prepare_coarsening_and_refinement();
    const std::vector<Vector<double>> in{solution, increment_old};
    transfer.prepare_for_coarsening_and_refinement(in);
    tria.execute_coarsening_and_refinement();
    setup_system();
    assemble_fixed();
    std::vector<Vector<double>> out(in.size(),
                                    Vector<double>(dof_handler.n_dofs()));
    transfer.interpolate(in, out);
    solution.swap(out[0]);
    increment_old.swap(out[1]);
    hanging.distribute(solution);
    hanging.distribute(increment_old);
    operators.clear();
    rhs_old_valid = false;
    for (unsigned int k = 0; k < probes.size(); ++k)
      probes[k] = locate_probe(probe_points[k]);
    stats.mesh_transfer_heat += fixed.capacity * solution - heat_before;
    ++stats.n_adaptations;
  }
} // namespace rockdda::thermal
