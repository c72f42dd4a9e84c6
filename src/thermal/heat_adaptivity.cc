/**
 * @file
 * Adaptive refinement of the heat solver's mesh during the run: the Kelly
 * error estimator, fixed-fraction refinement and coarsening within the
 * limits of internal::limit_adaptation_flags() (minimum cell size, cell
 * budget, coarse size, a priori band), and the transfer of the field and
 * of the previous increment to the new mesh, with the heat the (not
 * conservative) transfer adds booked in the statistics; written once for
 * HeatSystem, with the serial or the p4est refinement and field transfer
 * as its linear-algebra traits select.
 */
#include <deal.II/base/quadrature_lib.h>
#include <deal.II/distributed/grid_refinement.h>
#include <deal.II/distributed/solution_transfer.h>
#include <deal.II/grid/grid_refinement.h>
#include <deal.II/numerics/error_estimator.h>
#include <deal.II/numerics/solution_transfer.h>

#include "heat_internal.h"
#include "heat_system.h"
#include <limits>

namespace rockdda::thermal
{
  using namespace dealii;

  namespace internal
  {
    template <typename LA>
    void
    HeatSystem<LA>::adapt_mesh()
    {
      TimerOutput::Scope scope(timer, "adapt mesh");
      // Kelly et al. (1983): jumps of the normal gradient across faces.
      Vector<float> indicator(tria.n_active_cells());
      KellyErrorEstimator<2>::estimate(mapping,
                                       dof_handler,
                                       QGauss<1>(fe.degree + 1),
                                       {},
                                       field(),
                                       indicator,
                                       ComponentMask(),
                                       nullptr,
                                       numbers::invalid_unsigned_int,
                                       tria.locally_owned_subdomain());
      if (!(Utilities::MPI::sum(double(indicator.l1_norm()), comm) > 0.))
        return;
      bool capped = false;
      if constexpr (LA::distributed)
        {
          parallel::distributed::GridRefinement::
            refine_and_coarsen_fixed_fraction(tria,
                                              indicator,
                                              prm.refine_fraction,
                                              prm.coarsen_fraction);
          capped = prm.adaptive_max_cells > 0
                   && tria.n_global_active_cells() >= prm.adaptive_max_cells;
        }
      else
        GridRefinement::refine_and_coarsen_fixed_fraction(
          tria,
          indicator,
          prm.refine_fraction,
          prm.coarsen_fraction,
          prm.adaptive_max_cells > 0
            ? prm.adaptive_max_cells
            : std::numeric_limits<unsigned int>::max());
      // Limits: no cell finer than the minimum size; no cell coarser than
      // the coarse size, nor than the band size inside the a priori band.
      bool any = false;
      for (const auto &cell : tria.active_cell_iterators())
        if (cell->is_locally_owned())
          any = limit_adaptation_flags(cell, prm, mesh.band_segments, capped)
                || any;
      if (!Utilities::MPI::logical_or(any, comm))
        return;

      const double heat_before = fixed.capacity * solution;
      tria.prepare_coarsening_and_refinement();
      if constexpr (LA::distributed)
        {
          VectorType old_increment(owned, relevant, comm);
          old_increment = increment_old;
          parallel::distributed::SolutionTransfer<2, VectorType> transfer(
            dof_handler);
          const std::vector<const VectorType *> in{&field(), &old_increment};
          transfer.prepare_for_coarsening_and_refinement(in);
          tria.execute_coarsening_and_refinement();
          setup_system();
          assemble_fixed();
          std::vector<VectorType *> out{&solution, &increment_old};
          transfer.interpolate(out);
        }
      else
        {
          SolutionTransfer<2, VectorType> transfer(dof_handler);
          const std::vector<VectorType>   in{solution, increment_old};
          transfer.prepare_for_coarsening_and_refinement(in);
          tria.execute_coarsening_and_refinement();
          setup_system();
          assemble_fixed();
          std::vector<VectorType> out(in.size(),
                                      VectorType(dof_handler.n_dofs()));
          transfer.interpolate(in, out);
          solution.swap(out[0]);
          increment_old.swap(out[1]);
        }
      ghosted_valid = false;

      // The hanging values, the step operators and loads to be rebuilt,
      // the probes located anew, and the heat the transfer changed booked.
      hanging.distribute(solution);
      hanging.distribute(increment_old);
      operators.clear();
      rhs_old_valid = false;
      for (unsigned int k = 0; k < probes.size(); ++k)
        probes[k] = locate(probe_points[k]);
      stats.mesh_transfer_heat += fixed.capacity * solution - heat_before;
      ++stats.n_adaptations;
    }

    template void
    HeatSystem<LinearAlgebra::Serial>::adapt_mesh();
    template void
    HeatSystem<LinearAlgebra::Trilinos>::adapt_mesh();
  } // namespace internal
} // namespace rockdda::thermal
