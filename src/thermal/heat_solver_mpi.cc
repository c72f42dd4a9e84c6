/**
 * @file
 * The distributed heat solver (DistributedHeat, heat_solver_distributed.h):
 * its setup on the parallel::distributed::Triangulation (p4est) with
 * Trilinos vectors, the location of probes on the rank that owns them, and
 * the interface HeatSolver forwards to. Its assembly and output (written
 * once for both solvers) are in heat_assembly.cc and heat_output.cc, its
 * time stepping, adaptivity and checkpoints next to the serial solver's in
 * heat_time_stepping.cc, heat_adaptivity.cc and heat_checkpoint.cc (see
 * doc/theory/heat.md).
 */
#include <rockdda/io/binary_stream.h>
#include <rockdda/io/error.h>
#include <rockdda/io/output.h>
#include <rockdda/thermal/polygon_mesh.h>

#include <deal.II/base/index_set.h>
#include <deal.II/base/mpi.h>
#include <deal.II/base/quadrature_lib.h>
#include <deal.II/base/timer.h>
#include <deal.II/distributed/grid_refinement.h>
#include <deal.II/distributed/solution_transfer.h>
#include <deal.II/distributed/tria.h>
#include <deal.II/dofs/dof_handler.h>
#include <deal.II/dofs/dof_tools.h>
#include <deal.II/fe/fe_q.h>
#include <deal.II/fe/fe_values.h>
#include <deal.II/fe/mapping_q1.h>
#include <deal.II/grid/grid_tools.h>
#include <deal.II/lac/affine_constraints.h>
#include <deal.II/lac/dynamic_sparsity_pattern.h>
#include <deal.II/lac/solver_cg.h>
#include <deal.II/lac/solver_control.h>
#include <deal.II/lac/sparsity_tools.h>
#include <deal.II/lac/trilinos_precondition.h>
#include <deal.II/lac/trilinos_solver.h>
#include <deal.II/lac/trilinos_sparse_matrix.h>
#include <deal.II/lac/trilinos_vector.h>
#include <deal.II/numerics/data_out.h>
#include <deal.II/numerics/error_estimator.h>
#include <deal.II/numerics/vector_tools.h>

#include "heat_assembly.h"
#include "heat_flux.h"
#include "heat_internal.h"
#include "heat_output.h"
#include "heat_probes.h"
#include "heat_solver_distributed.h"
#include <cmath>
#include <fstream>
#include <limits>
#include <map>
#include <set>
#include <sstream>

namespace rockdda::thermal::internal
{
  using namespace dealii;
  using VectorType = TrilinosWrappers::MPI::Vector;



  bool
  use_distributed_solver(const HeatParameters &parameters)
  {
    if (!Utilities::MPI::job_supports_mpi())
      {
        if (parameters.distributed)
          throw InputError(
            "heat: the distributed solver ('Linear solver = amg') needs "
            "MPI: run the driver with mpirun -np N (N >= 1)");
        return false;
      }
    return parameters.distributed
           || Utilities::MPI::n_mpi_processes(MPI_COMM_WORLD) > 1;
  }



  DistributedHeat::Impl::Impl(const HeatParameters &parameters)
      : prm(parameters)
      , comm(MPI_COMM_WORLD)
      , rank(Utilities::MPI::this_mpi_process(MPI_COMM_WORLD))
      , n_ranks(Utilities::MPI::n_mpi_processes(MPI_COMM_WORLD))
      , tria(MPI_COMM_WORLD)
      , fe(std::max(1u, parameters.degree))
      , timer(timer_stream, TimerOutput::never, TimerOutput::wall_times)
  {
    validate_parameters(prm);
    for (const auto &m : prm.materials)
      kappa_max = std::max(kappa_max, m.diffusivity());

    TimerOutput::Scope scope(timer, "setup");
    build_mesh(tria, prm, mesh);
    dof_handler.reinit(tria);
    setup_system();
    assemble_fixed();

    std::map<types::global_dof_index, Point<2>> support;
    DoFTools::map_dofs_to_support_points(mapping, dof_handler, support);
    for (const auto i : owned)
      {
        const Point<2> &x = support.at(i);
        solution[i]       = prm.initial_field ? prm.initial_field(x[0], x[1])
                                              : prm.initial_temperature;
      }
    solution.compress(VectorOperation::insert);
    hanging.distribute(solution);
    time = prm.start_time;
  }



  void
  DistributedHeat::Impl::setup_system()
  {
    dof_handler.distribute_dofs(fe);
    owned    = dof_handler.locally_owned_dofs();
    relevant = DoFTools::extract_locally_relevant_dofs(dof_handler);

    hanging.clear();
    hanging.reinit(relevant);
    DoFTools::make_hanging_node_constraints(dof_handler, hanging);
    hanging.close();

    // Homogeneous Dirichlet constraints on top (the first temperature tag
    // wins at shared corners: constrained dofs are not overwritten).
    constraints_hom.clear();
    constraints_hom.reinit(relevant);
    DoFTools::make_hanging_node_constraints(dof_handler, constraints_hom);
    for (unsigned int k = 0; k < prm.boundary_conditions.size(); ++k)
      if (prm.boundary_conditions[k].type
          == BoundaryCondition::Type::temperature)
        VectorTools::interpolate_boundary_values(mapping,
                                                 dof_handler,
                                                 types::boundary_id(k),
                                                 Functions::ZeroFunction<2>(),
                                                 constraints_hom);
    constraints_hom.close();

    dsp.reinit(relevant.size(), relevant.size(), relevant);
    DoFTools::make_sparsity_pattern(dof_handler, dsp, hanging, true);
    if (prm.joint_contact == HeatParameters::JointContact::conductance)
      {
        joints.setup(
          prm, dof_handler, hanging, constraints_hom, mesh.joint_id, comm);
        joints.add_sparsity(dsp);
      }
    SparsityTools::distribute_sparsity_pattern(dsp, owned, comm, relevant);

    for (VectorType *v : {&solution,
                          &new_solution,
                          &rhs_old,
                          &rhs_new,
                          &tmp,
                          &g_ext,
                          &increment_old})
      v->reinit(owned, comm);
    ghosted.reinit(owned, relevant, comm);
    ghosted_valid = false;

    dirichlet.find(prm, mapping, dof_handler, hanging);
    any_dirichlet = Utilities::MPI::logical_or(!dirichlet.dofs.empty(), comm);
    update_mesh_statistics(
      tria, dof_handler.n_dofs(), prm.degree, stats, h_min);
  }



  void
  DistributedHeat::Impl::assemble_fixed()
  {
    if (prm.stepper != TimeStepper::arkode)
      return assemble_fixed_integrals(
        prm, mapping, dof_handler, hanging, owned, comm, fixed);
    // ARKODE works on the mass and stiffness matrices themselves.
    mass.reinit(owned, owned, dsp, comm);
    stiffness.reinit(owned, owned, dsp, comm);
    assemble_fixed_integrals(prm,
                             mapping,
                             dof_handler,
                             hanging,
                             owned,
                             comm,
                             fixed,
                             add_to_matrices(hanging, mass, stiffness));
    joints.add_to(stiffness, 1., false);
    mass.compress(VectorOperation::add);
    stiffness.compress(VectorOperation::add);
  }



  void
  DistributedHeat::Impl::assemble_rhs(const double t,
                                      VectorType  &f,
                                      double      &boundary_rate,
                                      double      &source_rate) const
  {
    assemble_loads(prm,
                   mapping,
                   dof_handler,
                   hanging,
                   fixed,
                   comm,
                   t,
                   f,
                   boundary_rate,
                   source_rate);
  }



  void
  DistributedHeat::Impl::update_ghosts() const
  {
    if (!ghosted_valid)
      {
        ghosted       = solution;
        ghosted_valid = true;
      }
  }



  Probe
  DistributedHeat::Impl::locate(const Point<2> &point) const
  {
    Probe                                                    probe;
    std::pair<DoFHandler<2>::active_cell_iterator, Point<2>> found;
    bool                                                     mine = false;
    try
      {
        // A point on a vertex or face shared by cells of several ranks:
        // take a locally owned one of the cells around it (the field is
        // continuous, so any of them gives the same value).
        for (const auto &candidate :
             GridTools::find_all_active_cells_around_point(
               mapping, dof_handler, point, 1e-10))
          if (candidate.first->is_locally_owned())
            {
              found = candidate;
              mine  = true;
              break;
            }
      }
    catch (...)
      {
        mine = false;
      }
    probe.owner = Utilities::MPI::min(mine ? rank : n_ranks, comm);
    if (probe.owner == n_ranks)
      throw InputError("heat: point (" + io::format_number(point[0], 6) + ", "
                       + io::format_number(point[1], 6)
                       + ") m is outside the rock");
    if (probe.owner == rank)
      {
        fill_probe(mapping, found.first, found.second, probe);
      }
    return probe;
  }



  // -------------------------------------------------------------------------
  DistributedHeat::DistributedHeat(const HeatParameters &parameters)
      : impl(std::make_unique<Impl>(parameters))
  {}

  DistributedHeat::~DistributedHeat() = default;

  double
  DistributedHeat::time() const
  {
    return impl->time;
  }

  void
  DistributedHeat::advance_to(const double end_time)
  {
    impl->advance_to(end_time);
  }

  double
  DistributedHeat::value(const double x, const double y) const
  {
    const Probe p = impl->locate(Point<2>(x, y));
    impl->update_ghosts();
    return Utilities::MPI::sum(probe_sum(p, impl->ghosted), impl->comm);
  }

  unsigned int
  DistributedHeat::add_probe(const double x, const double y)
  {
    impl->probes.push_back(impl->locate(Point<2>(x, y)));
    impl->probe_points.emplace_back(x, y);
    return impl->probes.size() - 1;
  }

  double
  DistributedHeat::probe_value(const unsigned int index) const
  {
    const Probe &p = impl->probes.at(index);
    impl->update_ghosts();
    return Utilities::MPI::sum(probe_sum(p, impl->ghosted), impl->comm);
  }

  std::vector<BlockMoments>
  DistributedHeat::block_moments() const
  {
    return internal::block_moments_of(impl->fixed, impl->solution);
  }

  double
  DistributedHeat::stored_heat() const
  {
    return impl->fixed.capacity * impl->solution;
  }

  double
  DistributedHeat::boundary_heat_in() const
  {
    return impl->boundary_heat;
  }

  double
  DistributedHeat::source_heat_in() const
  {
    return impl->source_heat;
  }

  double
  DistributedHeat::l2_error(const SpaceTimeFunction &exact) const
  {
    impl->update_ghosts();
    return l2_error_of(impl->mapping,
                       impl->dof_handler,
                       impl->ghosted,
                       exact,
                       impl->time,
                       impl->comm);
  }

  std::vector<std::pair<std::string, std::string>>
  DistributedHeat::vtu_files(const std::string &name) const
  {
    impl->update_ghosts();
    return pvtu_files(impl->prm,
                      impl->dof_handler,
                      impl->ghosted,
                      impl->time,
                      name,
                      impl->comm);
  }

  HeatStatistics
  DistributedHeat::statistics() const
  {
    return impl->statistics(impl->prm.time_step);
  }

  std::string
  DistributedHeat::method_description() const
  {
    const auto &p = impl->prm;
    std::string s = stepper_description(p);
    s += "; distributed on " + std::to_string(impl->n_ranks)
         + " MPI rank(s) (p4est, Trilinos); ";
    if (p.stepper == TimeStepper::arkode)
      return s + "Newton systems GMRES + Amesos KLU (direct)";
    s += "linear solver "
         + (p.direct_solver && !p.distributed
              ? "Amesos KLU (direct)"
              : "CG + AMG (ML), relative tolerance "
                  + io::format_number(p.cg_tolerance, 3));
    return s;
  }

  std::string
  DistributedHeat::timing_summary() const
  {
    impl->timer_stream.str("");
    impl->timer.print_summary();
    return impl->timer_stream.str()
           + "CG iterations: " + std::to_string(impl->linear_iterations) + "\n";
  }
} // namespace rockdda::thermal::internal
