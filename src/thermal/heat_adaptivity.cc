/**
 * @file
 * Adaptive refinement of the heat solver's mesh during the run: the Kelly
 * error estimator, fixed-fraction refinement and coarsening within the
 * limits of internal::limit_adaptation_flags() (minimum cell size, cell
 * budget, coarse size, a priori band), and the transfer of the field and
 * of the previous increment to the new mesh, with the heat the (not
 * conservative) transfer adds booked in the statistics; for the serial
 * and the distributed (p4est) mesh.
 */
#include <deal.II/base/quadrature_lib.h>
#include <deal.II/distributed/grid_refinement.h>
#include <deal.II/distributed/solution_transfer.h>
#include <deal.II/grid/grid_refinement.h>
#include <deal.II/numerics/error_estimator.h>
#include <deal.II/numerics/solution_transfer.h>

#include "heat_internal.h"
#include "heat_solver_distributed.h"
#include "heat_solver_serial.h"
#include <limits>

namespace rockdda::thermal
{
  using namespace dealii;

  namespace
  {
    /**
     * After the field and the previous increment of solver @p s (either)
     * went to the new mesh: their hanging values, the step operators and
     * loads to be rebuilt, the probes located anew by @p locate, and the
     * heat the transfer changed (against @p heat_before) booked.
     */
    template <typename Solver, typename Locate>
    void
    finish_adaptation(Solver &s, const double heat_before, Locate &&locate)
    {
      s.hanging.distribute(s.solution);
      s.hanging.distribute(s.increment_old);
      s.operators.clear();
      s.rhs_old_valid = false;
      for (unsigned int k = 0; k < s.probes.size(); ++k)
        s.probes[k] = locate(s.probe_points[k]);
      s.stats.mesh_transfer_heat += s.fixed.capacity * s.solution - heat_before;
      ++s.stats.n_adaptations;
    }
  } // namespace

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
    finish_adaptation(*this, heat_before, [&](const Point<2> &p) {
      return locate_probe(p);
    });
  }



  namespace internal
  {
    using VectorType = DistributedVector;

    void
    DistributedHeat::Impl::adapt_mesh()
    {
      TimerOutput::Scope scope(timer, "adapt mesh");
      update_ghosts();
      Vector<float> indicator(tria.n_active_cells());
      KellyErrorEstimator<2>::estimate(mapping,
                                       dof_handler,
                                       QGauss<1>(fe.degree + 1),
                                       {},
                                       ghosted,
                                       indicator,
                                       ComponentMask(),
                                       nullptr,
                                       numbers::invalid_unsigned_int,
                                       tria.locally_owned_subdomain());
      if (!(Utilities::MPI::sum(double(indicator.l1_norm()), comm) > 0.))
        return;
      parallel::distributed::GridRefinement::refine_and_coarsen_fixed_fraction(
        tria, indicator, prm.refine_fraction, prm.coarsen_fraction);
      const bool capped
        = prm.adaptive_max_cells > 0
          && tria.n_global_active_cells() >= prm.adaptive_max_cells;
      bool any = false;
      for (const auto &cell : tria.active_cell_iterators())
        if (cell->is_locally_owned())
          any = limit_adaptation_flags(cell, prm, mesh.band_segments, capped)
                || any;
      if (!Utilities::MPI::logical_or(any, comm))
        return;

      const double heat_before = fixed.capacity * solution;
      VectorType   old_increment(owned, relevant, comm);
      old_increment = increment_old;
      parallel::distributed::SolutionTransfer<2, VectorType> transfer(
        dof_handler);
      tria.prepare_coarsening_and_refinement();
      const std::vector<const VectorType *> in{&ghosted, &old_increment};
      transfer.prepare_for_coarsening_and_refinement(in);
      tria.execute_coarsening_and_refinement();
      setup_system();
      assemble_fixed();
      std::vector<VectorType *> out{&solution, &increment_old};
      transfer.interpolate(out);
      ghosted_valid = false;
      finish_adaptation(*this, heat_before, [&](const Point<2> &p) {
        return locate(p);
      });
    }
  } // namespace internal
} // namespace rockdda::thermal
