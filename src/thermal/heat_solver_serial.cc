/**
 * @file
 * The serial heat solver's setup (see heat_solver_serial.h): the mesh,
 * dofs, hanging-node constraints and Dirichlet dofs, the mass and
 * stiffness matrices with the joint contact conductance, the fixed
 * integrals and loads (written once in heat_assembly.cc for both
 * solvers), the initial condition and the location of probes.
 */
#include "heat_solver_serial.h"

#include <rockdda/io/error.h>
#include <rockdda/io/output.h>

#include <deal.II/dofs/dof_tools.h>
#include <deal.II/grid/grid_tools.h>
#include <deal.II/lac/dynamic_sparsity_pattern.h>

#include "heat_internal.h"

namespace rockdda::thermal
{
  using namespace dealii;

  HeatSolver::Impl::Impl(const HeatParameters &parameters)
      : prm(parameters)
      // The 2:1 balance at vertices that p4est enforces in the distributed
      // solver, so that both solvers build the same meshes.
      , tria(Triangulation<2>::limit_level_difference_at_vertices)
      , fe(std::max(1u, parameters.degree))
      , timer(timer_stream, TimerOutput::never, TimerOutput::wall_times)
  {
    internal::validate_parameters(prm);
    for (const auto &m : prm.materials)
      kappa_max = std::max(kappa_max, m.diffusivity());

    TimerOutput::Scope scope(timer, "setup");
    internal::MeshInfo mesh_info;
    internal::build_mesh(tria, prm, mesh_info);
    tags          = mesh_info.tags;
    joint_id      = mesh_info.joint_id;
    band_segments = mesh_info.band_segments;
    dof_handler.reinit(tria);
    setup_system();
    assemble_fixed();

    // Initial condition.
    solution.reinit(dof_handler.n_dofs());
    std::vector<Point<2>> support(dof_handler.n_dofs());
    DoFTools::map_dofs_to_support_points(mapping, dof_handler, support);
    for (unsigned int i = 0; i < solution.size(); ++i)
      solution[i] = prm.initial_field
                      ? prm.initial_field(support[i][0], support[i][1])
                      : prm.initial_temperature;
    hanging.distribute(solution);
    time = prm.start_time;
  }



  internal::Probe
  HeatSolver::Impl::locate_probe(const Point<2> &point) const
  {
    std::pair<DoFHandler<2>::active_cell_iterator, Point<2>> found;
    try
      {
        found = GridTools::find_active_cell_around_point(mapping,
                                                         dof_handler,
                                                         point);
      }
    catch (...)
      {
        found.first = dof_handler.end();
      }
    if (found.first == dof_handler.end()
        || found.first.state() != IteratorState::valid)
      throw InputError("heat: probe point (" + io::format_number(point[0], 6)
                       + ", " + io::format_number(point[1], 6)
                       + ") m is outside the rock");
    internal::Probe probe;
    internal::fill_probe(mapping, found.first, found.second, probe);
    return probe;
  }



  void
  HeatSolver::Impl::setup_system()
  {
    dof_handler.distribute_dofs(fe);
    hanging.clear();
    DoFTools::make_hanging_node_constraints(dof_handler, hanging);
    hanging.close();

    DynamicSparsityPattern dsp(dof_handler.n_dofs());
    DoFTools::make_sparsity_pattern(dof_handler, dsp, hanging, true);
    joint_pairs.clear();
    if (prm.joint_contact == HeatParameters::JointContact::conductance)
      joint_pairs = internal::find_joint_pairs(dof_handler, joint_id);
    for (const auto &pair : joint_pairs)
      hanging.add_entries_local_to_global(internal::joint_pair_dofs(pair),
                                          dsp,
                                          true);
    sparsity.copy_from(dsp);
    mass.reinit(sparsity);
    stiffness.reinit(sparsity);

    const unsigned int n = dof_handler.n_dofs();
    new_solution.reinit(n);
    rhs_old.reinit(n);
    rhs_new.reinit(n);
    tmp.reinit(n);
    g_ext.reinit(n);
    increment_old.reinit(n);

    dirichlet.find(prm, mapping, dof_handler, hanging);
    is_dirichlet.assign(n, false);
    for (const auto i : dirichlet.dofs)
      is_dirichlet[i] = true;
    internal::update_mesh_statistics(tria, n, prm.degree, stats, h_min);
  }



  void
  HeatSolver::Impl::assemble_fixed()
  {
    internal::assemble_fixed_integrals(prm,
                                       mapping,
                                       dof_handler,
                                       hanging,
                                       dof_handler.locally_owned_dofs(),
                                       tria.get_communicator(),
                                       fixed,
                                       internal::add_to_matrices(hanging,
                                                                 mass,
                                                                 stiffness));
    internal::assemble_joint_conductance(
      prm, mapping, fe, hanging, joint_pairs, stiffness);
  }



  void
  HeatSolver::Impl::assemble_rhs(const double    t,
                                 Vector<double> &f,
                                 double         &boundary_rate,
                                 double         &source_rate) const
  {
    internal::assemble_loads(prm,
                             mapping,
                             dof_handler,
                             hanging,
                             fixed,
                             tria.get_communicator(),
                             t,
                             f,
                             boundary_rate,
                             source_rate);
  }
} // namespace rockdda::thermal
