/**
 * @file
 * The heat solver HeatSystem (heat_system.h), written once over the
 * linear-algebra traits: its setup on the mesh (dofs, hanging-node and
 * Dirichlet constraints, the sparsity pattern with the joint pairs, the
 * vectors), the fixed integrals and loads (heat_assembly.cc), the initial
 * condition, the location of probes on the rank that owns them, and the
 * interface HeatSolver forwards to. Instantiated for
 * LinearAlgebra::Serial and LinearAlgebra::Trilinos.
 */
#include "heat_system.h"

#include <rockdda/io/error.h>
#include <rockdda/io/output.h>

#include <deal.II/base/utilities.h>
#include <deal.II/dofs/dof_tools.h>
#include <deal.II/grid/grid_tools.h>
#include <deal.II/numerics/vector_tools.h>

#include <Eigen/SparseCore>
#include <Eigen/SparseLU>

#include "heat_output.h"
#include <algorithm>
#include <map>
#include <stdexcept>

namespace rockdda::thermal::internal
{
  using namespace dealii;

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



  template <typename LA>
  HeatSystem<LA>::HeatSystem(const HeatParameters &parameters)
      : prm(parameters)
      , comm(LA::communicator())
      // A serial run may have no MPI at all.
      , rank(LA::distributed ? Utilities::MPI::this_mpi_process(comm) : 0)
      , n_ranks(LA::distributed ? Utilities::MPI::n_mpi_processes(comm) : 1)
      , tria(LA::create_triangulation())
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

    // Initial condition.
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



  template <typename LA>
  void
  HeatSystem<LA>::setup_system()
  {
    dof_handler.distribute_dofs(fe);
    owned    = dof_handler.locally_owned_dofs();
    relevant = DoFTools::extract_locally_relevant_dofs(dof_handler);

    hanging.clear();
    if constexpr (LA::distributed)
      hanging.reinit(relevant);
    DoFTools::make_hanging_node_constraints(dof_handler, hanging);
    hanging.close();

    if constexpr (LA::distributed)
      {
        // Homogeneous Dirichlet constraints on top (the first temperature
        // tag wins at shared corners: constrained dofs are not overwritten).
        constraints_hom.clear();
        constraints_hom.reinit(relevant);
        DoFTools::make_hanging_node_constraints(dof_handler, constraints_hom);
        for (unsigned int k = 0; k < prm.boundary_conditions.size(); ++k)
          if (prm.boundary_conditions[k].type
              == BoundaryCondition::Type::temperature)
            VectorTools::interpolate_boundary_values(
              mapping,
              dof_handler,
              types::boundary_id(k),
              Functions::ZeroFunction<2>(),
              constraints_hom);
        constraints_hom.close();
      }

    dsp.reinit(relevant.size(), relevant.size(), relevant);
    DoFTools::make_sparsity_pattern(dof_handler, dsp, hanging, true);
    if (prm.joint_contact == HeatParameters::JointContact::conductance)
      {
        if constexpr (LA::distributed)
          {
            joints.setup(
              prm, dof_handler, hanging, constraints_hom, mesh.joint_id, comm);
            joints.add_sparsity(dsp);
          }
        else
          {
            joints = find_joint_pairs(dof_handler, mesh.joint_id);
            for (const auto &pair : joints)
              hanging.add_entries_local_to_global(joint_pair_dofs(pair),
                                                  dsp,
                                                  true);
          }
      }
    LA::finish_sparsity(dsp, sparsity, owned, relevant, comm);

    for (VectorType *v : {&solution,
                          &new_solution,
                          &rhs_old,
                          &rhs_new,
                          &tmp,
                          &g_ext,
                          &increment_old})
      LA::reinit(*v, owned, comm);
    if constexpr (LA::distributed)
      ghosted.reinit(owned, relevant, comm);
    ghosted_valid = false;

    dirichlet.find(prm, mapping, dof_handler, hanging);
    is_dirichlet.assign(dof_handler.n_dofs(), false);
    for (const auto i : dirichlet.dofs)
      is_dirichlet[i] = true;
    any_dirichlet = Utilities::MPI::logical_or(!dirichlet.dofs.empty(), comm);
    update_mesh_statistics(
      tria, dof_handler.n_dofs(), prm.degree, stats, h_min);
  }



  template <typename LA>
  void
  HeatSystem<LA>::assemble_fixed()
  {
    // The serial theta scheme and ARKODE work on the mass and stiffness
    // matrices themselves; the distributed theta scheme assembles its step
    // matrices directly.
    const AssemblyScope scope{prm, mapping, dof_handler, hanging, comm};
    if (LA::distributed && prm.stepper != TimeStepper::arkode)
      return assemble_fixed_integrals(scope, owned, fixed);
    LA::reinit(mass, dsp, sparsity, owned, comm);
    LA::reinit(stiffness, dsp, sparsity, owned, comm);
    assemble_fixed_integrals(scope,
                             owned,
                             fixed,
                             add_to_matrices(hanging, mass, stiffness));
    if constexpr (LA::distributed)
      joints.add_to(stiffness, 1., false);
    else
      assemble_joint_conductance(prm, mapping, fe, hanging, joints, stiffness);
    mass.compress(VectorOperation::add);
    stiffness.compress(VectorOperation::add);
  }



  template <typename LA>
  void
  HeatSystem<LA>::assemble_rhs(const double t,
                               VectorType  &f,
                               double      &boundary_rate,
                               double      &source_rate) const
  {
    const LoadRates rates
      = fixed.loads(AssemblyScope{prm, mapping, dof_handler, hanging, comm},
                    t,
                    f);
    boundary_rate = rates.boundary;
    source_rate   = rates.source;
  }



  template <typename LA>
  const typename HeatSystem<LA>::VectorType &
  HeatSystem<LA>::field() const
  {
    if constexpr (!LA::distributed)
      return solution;
    if (!ghosted_valid)
      {
        ghosted       = solution;
        ghosted_valid = true;
      }
    return ghosted;
  }



  template <typename LA>
  Probe
  HeatSystem<LA>::locate(const Point<2> &point) const
  {
    Probe                                                    probe;
    std::pair<DoFHandler<2>::active_cell_iterator, Point<2>> found;
    bool                                                     mine = false;
    try
      {
        if constexpr (LA::distributed)
          {
            // A point on a vertex or face shared by cells of several
            // ranks: take a locally owned one of the cells around it (the
            // field is continuous, so any of them gives the same value).
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
        else
          {
            found = GridTools::find_active_cell_around_point(mapping,
                                                             dof_handler,
                                                             point);
            mine  = found.first != dof_handler.end()
                   && found.first.state() == IteratorState::valid;
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
      fill_probe(mapping, found.first, found.second, probe);
    return probe;
  }



  template <typename LA>
  double
  HeatSystem<LA>::value(const double x, const double y) const
  {
    return Utilities::MPI::sum(probe_sum(locate(Point<2>(x, y)), field()),
                               comm);
  }

  template <typename LA>
  unsigned int
  HeatSystem<LA>::add_probe(const double x, const double y)
  {
    probes.push_back(locate(Point<2>(x, y)));
    probe_points.emplace_back(x, y);
    return probes.size() - 1;
  }

  template <typename LA>
  double
  HeatSystem<LA>::probe_value(const unsigned int index) const
  {
    return Utilities::MPI::sum(probe_sum(probes.at(index), field()), comm);
  }

  template <typename LA>
  std::vector<BlockMoments>
  HeatSystem<LA>::block_moments() const
  {
    return block_moments_of(fixed, solution);
  }

  template <typename LA>
  double
  HeatSystem<LA>::stored_heat() const
  {
    return fixed.capacity * solution;
  }

  template <typename LA>
  double
  HeatSystem<LA>::l2_error(const SpaceTimeFunction &exact) const
  {
    return l2_error_of(mapping, dof_handler, field(), exact, time, comm);
  }

  template <typename LA>
  std::vector<std::pair<std::string, std::string>>
  HeatSystem<LA>::vtu_files(const std::string &name) const
  {
    if constexpr (LA::distributed)
      return pvtu_files(prm, dof_handler, field(), time, name, comm);
    else
      return {{name + ".vtu", vtu()}};
  }

  template <typename LA>
  std::string
  HeatSystem<LA>::vtu() const
  {
    if constexpr (LA::distributed)
      throw std::logic_error("heat: vtu() of the distributed solver; use "
                             "vtu_files()");
    else
      return vtu_piece(prm, dof_handler, solution, time);
  }

  template <typename LA>
  HeatStatistics
  HeatSystem<LA>::statistics() const
  {
    return StepState::statistics(prm.time_step);
  }

  template <typename LA>
  std::string
  HeatSystem<LA>::method_description() const
  {
    std::string s = stepper_description(prm);
    if constexpr (LA::distributed)
      {
        s += "; distributed on " + std::to_string(n_ranks)
             + " MPI rank(s) (p4est, Trilinos); ";
        if (prm.stepper == TimeStepper::arkode)
          return s + "Newton systems GMRES + Amesos KLU (direct)";
        return s + "linear solver "
               + (prm.direct_solver && !prm.distributed
                    ? "Amesos KLU (direct)"
                    : "CG + AMG (ML), relative tolerance "
                        + io::format_number(prm.cg_tolerance, 3));
      }
    if (prm.stepper == TimeStepper::arkode)
      return s + "; Newton systems GMRES + UMFPACK (direct)";
    return s + "; linear solver "
           + (prm.direct_solver ? "sparse Cholesky (Eigen LDLT, direct)"
                                : "CG + SSOR");
  }

  template <typename LA>
  bool
  HeatSystem<LA>::harmonic_available() const
  {
    return !LA::distributed && !any_dirichlet && !fixed.nonuniform;
  }

  template <typename LA>
  std::vector<std::complex<double>>
  HeatSystem<LA>::harmonic_block_means(const double omega) const
  {
    if (!harmonic_available())
      throw std::logic_error("HeatSolver::harmonic_block_means: serial runs "
                             "without Dirichlet conditions or spatially "
                             "varying data only");
    if constexpr (!LA::distributed)
      {
        using Complex = std::complex<double>;
        // F_conv: the convective conditions' load vectors at 1 K.
        Eigen::VectorXcd f = Eigen::VectorXcd::Zero(dof_handler.n_dofs());
        for (std::size_t k = 0; k < fixed.uniform_bc.size(); ++k)
          if (prm.boundary_conditions[fixed.uniform_bc[k]].type
              == BoundaryCondition::Type::convective)
            for (unsigned int i = 0; i < f.size(); ++i)
              f[i] += fixed.uniform_vectors[k][i];
        // K + i omega M on the common pattern (hanging rows keep their
        // diagonal entries, so they solve to 0 and are distributed below).
        std::vector<Eigen::Triplet<Complex>> entries;
        entries.reserve(stiffness.n_nonzero_elements());
        // Both matrices live on the one sparsity pattern: walk them
        // together.
        for (auto it = stiffness.begin(), m = mass.begin();
             it != stiffness.end();
             ++it, ++m)
          entries.emplace_back(it->row(),
                               it->column(),
                               Complex(it->value(), omega * m->value()));
        Eigen::SparseMatrix<Complex> a(f.size(), f.size());
        a.setFromTriplets(entries.begin(), entries.end());
        Eigen::SparseLU<Eigen::SparseMatrix<Complex>> lu;
        lu.compute(a);
        if (lu.info() != Eigen::Success)
          throw std::runtime_error("HeatSolver::harmonic_block_means: the "
                                   "complex system is singular");
        const Eigen::VectorXcd theta = lu.solve(f);
        VectorType             re(solution), im(solution);
        for (unsigned int i = 0; i < f.size(); ++i)
          {
            re[i] = theta[i].real();
            im[i] = theta[i].imag();
          }
        hanging.distribute(re);
        hanging.distribute(im);
        const auto           mr = block_moments_of(fixed, re);
        const auto           mi = block_moments_of(fixed, im);
        std::vector<Complex> means(mr.size());
        for (std::size_t b = 0; b < mr.size(); ++b)
          means[b] = Complex(mr[b].mean, mi[b].mean);
        return means;
      }
    return {};
  }

  template <typename LA>
  std::string
  HeatSystem<LA>::timing_summary() const
  {
    timer_stream.str("");
    timer.print_summary();
    if (LA::distributed)
      return timer_stream.str()
             + "CG iterations: " + std::to_string(linear_iterations) + "\n";
    return timer_stream.str();
  }

  template class HeatSystem<LinearAlgebra::Serial>;
  template class HeatSystem<LinearAlgebra::Trilinos>;
} // namespace rockdda::thermal::internal
