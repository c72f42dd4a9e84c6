/**
 * @file
 * The distributed heat solver: parallel::distributed::Triangulation (p4est),
 * Trilinos matrices and vectors, CG + AMG or Amesos KLU, theta scheme. Same
 * weak form, boundary data, energy bookkeeping and oscillation indicator as
 * the serial solver in heat_solver.cc (see doc/theory/heat.md).
 */
#include "heat_solver_mpi.h"

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

  namespace
  {
    /// Matrices and solver of one theta-scheme step size.
    struct DistributedOperator
    {
      double dt    = 0.;
      double theta = 0.;
      /// M + theta dt K with hanging nodes and Dirichlet rows and columns
      /// condensed (homogeneous): the system for T - g.
      TrilinosWrappers::SparseMatrix a_hom;
      /// M + theta dt K (hanging nodes only): lifts the Dirichlet values.
      TrilinosWrappers::SparseMatrix a_full;
      /// M - (1 - theta) dt K (hanging nodes only).
      TrilinosWrappers::SparseMatrix                  b;
      TrilinosWrappers::PreconditionAMG               amg;
      SolverControl                                   direct_control;
      std::unique_ptr<TrilinosWrappers::SolverDirect> direct;
    };

  } // namespace



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



  class DistributedHeat::Impl
  {
  public:
    explicit Impl(const HeatParameters &parameters);

    void
    advance_to(const double end_time);
    Probe
    locate(const Point<2> &p) const;
    void
    update_ghosts() const;

    HeatParameters                                    prm;
    MPI_Comm                                          comm;
    unsigned int                                      rank = 0, n_ranks = 1;
    parallel::distributed::Triangulation<2>           tria;
    FE_Q<2>                                           fe;
    DoFHandler<2>                                     dof_handler;
    MappingQ1<2>                                      mapping;
    MeshInfo                                          mesh;
    IndexSet                                          owned, relevant;
    AffineConstraints<double>                         hanging, constraints_hom;
    DynamicSparsityPattern                            dsp;
    std::vector<std::unique_ptr<DistributedOperator>> operators;

    VectorType solution, new_solution, rhs_old, rhs_new, tmp, g_ext,
      increment_old;
    mutable VectorType ghosted;
    mutable bool       ghosted_valid = false;

    DirichletDofs              dirichlet;
    bool                       any_dirichlet = false;
    FixedIntegrals<VectorType> fixed;

    std::vector<Probe>    probes;
    std::vector<Point<2>> probe_points;

    double        time              = 0.;
    double        boundary_heat     = 0.;
    double        source_heat       = 0.;
    double        rate_old          = 0.;
    double        source_rate_old   = 0.;
    bool          rhs_old_valid     = false;
    bool          last_step_flipped = false;
    unsigned long steps_taken       = 0;
    unsigned long linear_iterations = 0;
    /// Checkpoints written (selects the file set of the next one).
    unsigned long  checkpoints_written = 0;
    double         kappa_max           = 0.;
    double         h_min               = 0.;
    HeatStatistics stats;

    std::ostringstream timer_stream;
    TimerOutput        timer;

    void
    setup_system();
    void
    assemble_fixed();
    void
    assemble_rhs(const double t,
                 VectorType  &f,
                 double      &boundary_rate,
                 double      &source_rate) const;
    DistributedOperator &
    get_operator(const double dt, const double theta);
    void
    theta_step(const double dt, const double theta);
    void
    adapt_mesh();
  };



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
    if (prm.stepper == TimeStepper::arkode)
      throw InputError("heat: ARKODE is not available in the distributed "
                       "(MPI) solver; use crank-nicolson or backward-euler "
                       "with mpirun, or run on one rank without 'amg'");
    if (prm.joint_contact == HeatParameters::JointContact::conductance)
      throw InputError("heat: 'Joint contact = conductance' is not "
                       "available in the distributed (MPI) solver; run on "
                       "one rank without 'amg'");
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
    assemble_fixed_integrals(
      prm, mapping, dof_handler, hanging, owned, comm, fixed);
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



  DistributedOperator &
  DistributedHeat::Impl::get_operator(const double dt, const double theta)
  {
    for (auto &op : operators)
      if (op->dt == dt && op->theta == theta)
        return *op;
    if (operators.size() >= 4)
      operators.erase(operators.begin());
    TimerOutput::Scope scope(timer, "factorize");
    auto               op = std::make_unique<DistributedOperator>();
    op->dt                = dt;
    op->theta             = theta;
    op->a_hom.reinit(owned, owned, dsp, comm);
    op->a_full.reinit(owned, owned, dsp, comm);
    op->b.reinit(owned, owned, dsp, comm);

    internal::CellIntegrators integrators(mapping,
                                          fe,
                                          update_values | update_gradients
                                            | update_JxW_values,
                                          update_values | update_JxW_values);
    FEValues<2>              &fe_values = integrators.values;
    FEFaceValues<2>          &fe_face   = integrators.face;
    const unsigned int        dpc       = fe.n_dofs_per_cell();
    FullMatrix<double>        cell_mass(dpc, dpc), cell_stiff(dpc, dpc),
      cell_a(dpc, dpc), cell_b(dpc, dpc);
    std::vector<types::global_dof_index> dofs(dpc);
    for (const auto &cell : dof_handler.active_cell_iterators())
      if (cell->is_locally_owned())
        {
          fe_values.reinit(cell);
          cell_matrices(prm, cell, fe_values, fe_face, cell_mass, cell_stiff);
          cell_a = cell_mass;
          cell_a.add(theta * dt, cell_stiff);
          cell_b = cell_mass;
          cell_b.add(-(1. - theta) * dt, cell_stiff);
          cell->get_dof_indices(dofs);
          constraints_hom.distribute_local_to_global(cell_a, dofs, op->a_hom);
          hanging.distribute_local_to_global(cell_a, dofs, op->a_full);
          hanging.distribute_local_to_global(cell_b, dofs, op->b);
        }
    op->a_hom.compress(VectorOperation::add);
    op->a_full.compress(VectorOperation::add);
    op->b.compress(VectorOperation::add);

    if (prm.direct_solver && !prm.distributed)
      {
        op->direct = std::make_unique<TrilinosWrappers::SolverDirect>(
          op->direct_control,
          TrilinosWrappers::SolverDirect::AdditionalData(false, "Amesos_Klu"));
        op->direct->initialize(op->a_hom);
      }
    else
      {
        TrilinosWrappers::PreconditionAMG::AdditionalData data;
        data.elliptic              = true;
        data.higher_order_elements = fe.degree > 1;
        data.smoother_sweeps       = 2;
        data.aggregation_threshold = 0.02;
        op->amg.initialize(op->a_hom, data);
      }
    ++stats.n_factorizations;
    operators.push_back(std::move(op));
    return *operators.back();
  }



  void
  DistributedHeat::Impl::theta_step(const double dt, const double theta)
  {
    DistributedOperator &op = get_operator(dt, theta);
    internal::theta_step(*this, dt, theta, [&]() {
      // (M + theta dt K)(T_new) = B T + dt (theta F_new + (1 - theta) F_old),
      // solved for u = T_new - g with g the Dirichlet values (zero elsewhere).
      op.b.vmult(tmp, solution);
      tmp.add(dt * theta, rhs_new, dt * (1. - theta), rhs_old);
      g_ext = 0.;
      if (any_dirichlet)
        {
          dirichlet.set_values(prm, time + dt, g_ext);
          g_ext.compress(VectorOperation::insert);
          op.a_full.vmult(new_solution, g_ext);
          tmp -= new_solution;
        }
      constraints_hom.set_zero(tmp);

      {
        TimerOutput::Scope scope(timer, "linear solve");
        new_solution = solution;
        new_solution -= g_ext;
        constraints_hom.set_zero(new_solution);
        if (op.direct)
          op.direct->solve(new_solution, tmp);
        else
          {
            SolverControl        control(10000,
                                  prm.cg_tolerance
                                    * std::max(tmp.l2_norm(), 1e-300));
            SolverCG<VectorType> cg(control);
            cg.solve(op.a_hom, new_solution, tmp, op.amg);
            linear_iterations += control.last_step();
          }
      }
      constraints_hom.set_zero(new_solution);
      new_solution += g_ext;
      hanging.distribute(new_solution);
    });
    ghosted_valid = false;
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
    hanging.distribute(solution);
    hanging.distribute(increment_old);
    ghosted_valid = false;
    operators.clear();
    rhs_old_valid = false;
    for (unsigned int k = 0; k < probes.size(); ++k)
      probes[k] = locate(probe_points[k]);
    stats.mesh_transfer_heat += fixed.capacity * solution - heat_before;
    ++stats.n_adaptations;
  }



  void
  DistributedHeat::Impl::advance_to(const double end_time)
  {
    if (!(end_time >= time - 1e-9 * prm.time_step))
      throw std::invalid_argument("heat: advance_to() into the past");
    TimerOutput::Scope scope(timer, "time stepping");
    const double       dt   = prm.time_step;
    const auto         step = [&](const double h) {
      theta_step(h, internal::step_theta(prm, stats, steps_taken));
      if (prm.adaptive_refinement && steps_taken % prm.adaptive_interval == 0)
        adapt_mesh();
    };
    internal::take_steps(time, end_time, dt, step);
    time = end_time;
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
    const auto &fixed = impl->fixed;
    return internal::block_moments_of(fixed.block_geometry,
                                      fixed.block_phi,
                                      fixed.block_xphi,
                                      fixed.block_yphi,
                                      impl->solution);
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
    HeatStatistics s = impl->stats;
    s.stiffness_ratio
      = impl->prm.time_step * impl->kappa_max / (impl->h_min * impl->h_min);
    return s;
  }

  std::string
  DistributedHeat::method_description() const
  {
    const auto &p = impl->prm;
    std::string s = stepper_description(p);
    s += "; distributed on " + std::to_string(impl->n_ranks)
         + " MPI rank(s) (p4est, Trilinos); linear solver "
         + (p.direct_solver && !p.distributed
              ? "Amesos KLU (direct)"
              : "CG + AMG (ML), relative tolerance "
                  + io::format_number(p.cg_tolerance, 3));
    return s;
  }

  namespace
  {
    constexpr char distributed_magic[]
      = "rockdda distributed heat checkpoint 1";
  }

  std::string
  DistributedHeat::checkpoint(const std::string &mesh_files) const
  {
    Impl &d = *impl;
    if (mesh_files.empty())
      throw std::invalid_argument(
        "heat: the distributed solver needs a file prefix for checkpoints");
    // Alternate between two file sets: a save interrupted half-way leaves
    // the set named by the previous checkpoint.bin intact.
    const std::string name
      = mesh_files + "-" + std::to_string(d.checkpoints_written++ % 2);
    d.update_ghosts();
    VectorType increment(d.owned, d.relevant, d.comm);
    increment = d.increment_old;
    parallel::distributed::SolutionTransfer<2, VectorType> transfer(
      d.dof_handler);
    transfer.prepare_for_serialization(
      std::vector<const VectorType *>{&d.ghosted, &increment});
    d.tria.save(name);
    io::BinaryWriter w;
    w.put_string(distributed_magic);
    w.put_string(name);
    w.put<std::uint64_t>(d.tria.n_global_active_cells());
    w.put(d.time);
    w.put(d.boundary_heat);
    w.put(d.source_heat);
    w.put<std::uint8_t>(d.last_step_flipped ? 1 : 0);
    w.put<std::uint64_t>(d.steps_taken);
    w.put<std::uint64_t>(d.linear_iterations);
    w.put(d.stats);
    return w.bytes;
  }



  void
  DistributedHeat::restore(const std::string &bytes, const std::string &source)
  {
    Impl            &d = *impl;
    io::BinaryReader r(bytes, source);
    if (r.get_string() != distributed_magic)
      throw InputError(source
                       + ": not a checkpoint of the distributed heat solver "
                         "(written by a serial run?)");
    const std::string name   = r.get_string();
    const auto        cells  = r.get<std::uint64_t>();
    const double      time   = r.get<double>();
    const double      q_in   = r.get<double>();
    const double      s_in   = r.get<double>();
    const bool        flip   = r.get<std::uint8_t>() != 0;
    const auto        steps  = r.get<std::uint64_t>();
    const auto        linear = r.get<std::uint64_t>();
    const auto        stats  = r.get<HeatStatistics>();
    if (!r.at_end())
      throw InputError(source + ": the checkpoint has trailing data");
    if (!std::ifstream(name + ".info"))
      throw InputError(source + ": the mesh files " + name
                       + ".* of the checkpoint are missing");
    // p4est loads into a triangulation holding only the coarse mesh.
    d.tria.clear();
    MeshInfo coarse;
    build_mesh(d.tria, d.prm, coarse, true);
    d.tria.load(name);
    if (d.tria.n_global_active_cells() != cells)
      throw InputError(source + ": the mesh files " + name + ".* hold "
                       + std::to_string(d.tria.n_global_active_cells())
                       + " cells, the checkpoint " + std::to_string(cells));
    d.setup_system();
    d.assemble_fixed();
    parallel::distributed::SolutionTransfer<2, VectorType> transfer(
      d.dof_handler);
    std::vector<VectorType *> targets{&d.solution, &d.increment_old};
    transfer.deserialize(targets);
    d.hanging.distribute(d.solution);
    d.hanging.distribute(d.increment_old);
    d.time              = time;
    d.boundary_heat     = q_in;
    d.source_heat       = s_in;
    d.last_step_flipped = flip;
    d.steps_taken       = steps;
    d.linear_iterations = linear;
    d.stats             = stats;
    d.operators.clear();
    d.rhs_old_valid = false;
    d.ghosted_valid = false;
    for (unsigned int k = 0; k < d.probes.size(); ++k)
      d.probes[k] = d.locate(d.probe_points[k]);
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
