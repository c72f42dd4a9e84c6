/**
 * @file
 * The heat solver's public interface (HeatSolver): it runs the serial
 * solver (HeatSolver::Impl, heat_solver_serial.h) or, with more than one
 * MPI rank or when asked for, the distributed one
 * (internal::DistributedHeat, heat_solver_mpi.h), and forwards every call
 * to it. The pieces of the solvers are in the files named after what
 * they do: heat_mesh.cc, heat_assembly.cc, heat_time_stepping.cc,
 * heat_arkode.cc, heat_adaptivity.cc, heat_probes.cc, heat_checkpoint.cc
 * and heat_output.cc.
 */
#include <rockdda/io/error.h>
#include <rockdda/io/output.h>

#include <deal.II/base/mpi.h>
#include <deal.II/fe/fe_values.h>
#include <deal.II/grid/grid_tools.h>

#include "heat_internal.h"
#include "heat_output.h"
#include "heat_probes.h"
#include "heat_solver_mpi.h"
#include "heat_solver_serial.h"
#include <cmath>

namespace rockdda::thermal
{
  using namespace dealii;

  // -------------------------------------------------------------------------
  HeatSolver::HeatSolver(const HeatParameters &parameters)
  {
    if (internal::use_distributed_solver(parameters))
      distributed = std::make_unique<internal::DistributedHeat>(parameters);
    else
      impl = std::make_unique<Impl>(parameters);
  }

  HeatSolver::~HeatSolver() = default;

  double
  HeatSolver::time() const
  {
    if (distributed)
      return distributed->time();
    return impl->time;
  }

  void
  HeatSolver::advance_to(const double end_time)
  {
    if (distributed)
      return distributed->advance_to(end_time);
    impl->advance_to(end_time);
  }

  double
  HeatSolver::value(const double x, const double y) const
  {
    if (distributed)
      return distributed->value(x, y);
    const auto found
      = GridTools::find_active_cell_around_point(impl->mapping,
                                                 impl->dof_handler,
                                                 Point<2>(x, y));
    if (found.first.state() != IteratorState::valid)
      throw InputError("heat: point (" + io::format_number(x, 6) + ", "
                       + io::format_number(y, 6) + ") m is outside the rock");
    const Quadrature<2> q(GeometryInfo<2>::project_to_unit_cell(found.second));
    FEValues<2>         fe_values(impl->mapping, impl->fe, q, update_values);
    fe_values.reinit(found.first);
    std::vector<double> v(1);
    fe_values.get_function_values(impl->solution, v);
    return v[0];
  }

  unsigned int
  HeatSolver::add_probe(const double x, const double y)
  {
    if (distributed)
      return distributed->add_probe(x, y);
    impl->probes.push_back(impl->locate_probe(Point<2>(x, y)));
    impl->probe_points.emplace_back(x, y);
    return impl->probes.size() - 1;
  }

  double
  HeatSolver::probe_value(const unsigned int index) const
  {
    if (distributed)
      return distributed->probe_value(index);
    return internal::probe_sum(impl->probes.at(index), impl->solution);
  }

  std::vector<BlockMoments>
  HeatSolver::block_moments() const
  {
    if (distributed)
      return distributed->block_moments();
    return internal::block_moments_of(impl->fixed, impl->solution);
  }

  double
  HeatSolver::stored_heat() const
  {
    if (distributed)
      return distributed->stored_heat();
    return impl->fixed.capacity * impl->solution;
  }

  double
  HeatSolver::boundary_heat_in() const
  {
    if (distributed)
      return distributed->boundary_heat_in();
    return impl->boundary_heat;
  }

  double
  HeatSolver::source_heat_in() const
  {
    if (distributed)
      return distributed->source_heat_in();
    return impl->source_heat;
  }

  double
  HeatSolver::l2_error(const SpaceTimeFunction &exact) const
  {
    if (distributed)
      return distributed->l2_error(exact);
    return internal::l2_error_of(impl->mapping,
                                 impl->dof_handler,
                                 impl->solution,
                                 exact,
                                 impl->time,
                                 impl->tria.get_communicator());
  }

  std::vector<std::pair<std::string, std::string>>
  HeatSolver::vtu_files(const std::string &name) const
  {
    if (distributed)
      return distributed->vtu_files(name);
    return {{name + ".vtu", vtu()}};
  }

  bool
  HeatSolver::is_output_rank() const
  {
    return !Utilities::MPI::job_supports_mpi()
           || Utilities::MPI::this_mpi_process(MPI_COMM_WORLD) == 0;
  }

  std::string
  HeatSolver::vtu() const
  {
    if (distributed)
      throw std::logic_error("heat: vtu() of the distributed solver; use "
                             "vtu_files()");
    return internal::vtu_piece(impl->prm,
                               impl->dof_handler,
                               impl->solution,
                               impl->time);
  }

  HeatStatistics
  HeatSolver::statistics() const
  {
    if (distributed)
      return distributed->statistics();
    return impl->statistics(impl->prm.time_step);
  }

  std::string
  HeatSolver::method_description() const
  {
    if (distributed)
      return distributed->method_description();
    if (impl->prm.stepper == TimeStepper::arkode)
      return internal::stepper_description(impl->prm)
             + "; Newton systems GMRES + UMFPACK (direct)";
    return internal::stepper_description(impl->prm) + "; linear solver "
           + (impl->prm.direct_solver ? "sparse Cholesky (Eigen LDLT, direct)"
                                      : "CG + SSOR");
  }

  std::string
  HeatSolver::timing_summary() const
  {
    if (distributed)
      return distributed->timing_summary();
    impl->timer_stream.str("");
    impl->timer.print_summary();
    return impl->timer_stream.str();
  }
} // namespace rockdda::thermal
