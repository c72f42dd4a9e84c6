/**
 * @file
 * The deal.II heat solver (the only translation unit of the thermal
 * subsystem that includes deal.II's finite-element headers).
 */
#include <rockdda/io/binary_stream.h>
#include <rockdda/io/error.h>
#include <rockdda/io/output.h>
#include <rockdda/thermal/heat_solver.h>
#include <rockdda/thermal/polygon_mesh.h>

#include <deal.II/base/quadrature_lib.h>
#include <deal.II/base/timer.h>
#include <deal.II/dofs/dof_handler.h>
#include <deal.II/dofs/dof_tools.h>
#include <deal.II/fe/fe_q.h>
#include <deal.II/fe/fe_values.h>
#include <deal.II/fe/mapping_q1.h>
#include <deal.II/grid/grid_refinement.h>
#include <deal.II/grid/grid_tools.h>
#include <deal.II/grid/tria.h>
#include <deal.II/lac/affine_constraints.h>
#include <deal.II/lac/dynamic_sparsity_pattern.h>
#include <deal.II/lac/precondition.h>
#include <deal.II/lac/solver_cg.h>
#include <deal.II/lac/solver_control.h>
#include <deal.II/lac/solver_gmres.h>
#include <deal.II/lac/sparse_direct.h>
#include <deal.II/lac/sparse_matrix.h>
#include <deal.II/lac/sparsity_pattern.h>
#include <deal.II/lac/vector.h>
#include <deal.II/numerics/data_out.h>
#include <deal.II/numerics/error_estimator.h>
#include <deal.II/numerics/solution_transfer.h>
#include <deal.II/sundials/arkode.h>

#include <Eigen/SparseCholesky>
#include <Eigen/SparseCore>

#include "heat_assembly.h"
#include "heat_internal.h"
#include "heat_output.h"
#include "heat_probes.h"
#include "heat_solver_mpi.h"
#include <arkode/arkode_arkstep.h>
#include <boost/archive/binary_iarchive.hpp>
#include <boost/archive/binary_oarchive.hpp>
#include <cmath>
#include <limits>
#include <map>
#include <set>
#include <sstream>

namespace rockdda::thermal
{
  using namespace dealii;

  namespace
  {
    /// Matrices and factorisation of one theta-scheme step size.
    struct StepOperator
    {
      double               dt    = 0.;
      double               theta = 0.;
      SparseMatrix<double> a;     ///< M + theta dt K (hanging-condensed)
      SparseMatrix<double> a_mod; ///< a with Dirichlet rows/cols removed
      SparseMatrix<double> b;     ///< M - (1 - theta) dt K
      PreconditionSSOR<SparseMatrix<double>> ssor;
      // The per-step work of the direct path in Eigen (serial, no task
      // overhead for the small systems of long runs): b, the Dirichlet
      // columns of a, and the sparse Cholesky (LDL^T) factors of a_mod.
      Eigen::SparseMatrix<double, Eigen::RowMajor> eigen_b, eigen_a_dirichlet;
      Eigen::SimplicialLDLT<Eigen::SparseMatrix<double>> ldlt;
    };

    /// Copy a deal.II sparse matrix (optionally only some columns, renumbered
    /// by @p column_map, -1 = skip) into Eigen.
    template <typename EigenMatrix>
    void
    to_eigen(const SparseMatrix<double> &m,
             EigenMatrix                &out,
             const std::vector<int>     *column_map = nullptr,
             const unsigned int          n_columns  = 0)
    {
      std::vector<Eigen::Triplet<double>> triplets;
      triplets.reserve(m.n_nonzero_elements());
      for (unsigned int row = 0; row < m.m(); ++row)
        for (auto it = m.begin(row); it != m.end(row); ++it)
          if (it->value() != 0.)
            {
              const int col
                = column_map ? (*column_map)[it->column()] : int(it->column());
              if (col >= 0)
                triplets.emplace_back(row, col, it->value());
            }
      out.resize(m.m(), column_map ? n_columns : m.n());
      out.setFromTriplets(triplets.begin(), triplets.end());
    }

  } // namespace



  namespace internal
  {

    BlockMoments
    block_moments_from(const std::array<double, 6> &g,
                       const double                 t0,
                       const double                 tx,
                       const double                 ty)
    {
      BlockMoments m;
      m.area           = g[0];
      m.centroid_x     = g[1] / g[0];
      m.centroid_y     = g[2] / g[0];
      m.mean           = t0 / g[0];
      m.moment_x       = tx - m.centroid_x * t0;
      m.moment_y       = ty - m.centroid_y * t0;
      const double ixx = g[3] - g[1] * g[1] / g[0];
      const double ixy = g[4] - g[1] * g[2] / g[0];
      const double iyy = g[5] - g[2] * g[2] / g[0];
      const double det = ixx * iyy - ixy * ixy;
      m.gradient_x     = (iyy * m.moment_x - ixy * m.moment_y) / det;
      m.gradient_y     = (ixx * m.moment_y - ixy * m.moment_x) / det;
      return m;
    }



    double
    step_theta(const HeatParameters &prm,
               const HeatStatistics &stats,
               const unsigned long   steps_taken)
    {
      const double chosen
        = prm.stepper == TimeStepper::crank_nicolson ? 0.5 : 1.;
      const double theta     = std::isnan(stats.fallback_time) ? chosen : 1.;
      const bool   rannacher = theta < 1. && steps_taken < prm.rannacher_steps;
      return rannacher ? 1. : theta;
    }



    void
    take_steps(const double                      &time,
               const double                       end_time,
               const double                       dt,
               const std::function<void(double)> &step)
    {
      const double remaining = end_time - time;
      const long   n_whole   = std::lround(remaining / dt);
      if (n_whole >= 1 && std::abs(remaining - n_whole * dt) <= 1e-6 * dt)
        for (long i = 0; i < n_whole; ++i)
          step(dt);
      else
        {
          const long n = static_cast<long>(std::floor(remaining / dt));
          for (long i = 0; i < n; ++i)
            step(dt);
          if (end_time - time > 1e-6 * dt)
            step(end_time - time);
        }
    }



  } // namespace internal



  class HeatSolver::Impl
  {
  public:
    explicit Impl(const HeatParameters &parameters);

    void
    advance_to(const double end_time);

    HeatParameters                             prm;
    Triangulation<2>                           tria;
    FE_Q<2>                                    fe;
    DoFHandler<2>                              dof_handler;
    MappingQ1<2>                               mapping;
    AffineConstraints<double>                  hanging;
    SparsityPattern                            sparsity;
    SparseMatrix<double>                       mass, stiffness;
    std::vector<std::unique_ptr<StepOperator>> operators;

    Vector<double> solution, new_solution, rhs_old, rhs_new, tmp, g_ext,
      increment_old;

    // Tags, boundary ids (= index into prm.boundary_conditions).
    std::vector<std::string>                 tags;
    internal::DirichletDofs                  dirichlet;
    std::vector<bool>                        is_dirichlet;
    internal::FixedIntegrals<Vector<double>> fixed;

    std::vector<internal::Probe> probes;
    std::vector<Point<2>>        probe_points;
    /// Polygon edges carrying a refine_near_tags tag.
    std::vector<std::array<Point2, 2>> band_segments;

    /// Boundary id of joint faces (contact conductance).
    types::boundary_id               joint_id = 0;
    std::vector<internal::JointPair> joint_pairs;

    double         time              = 0.;
    double         boundary_heat     = 0.;
    double         source_heat       = 0.;
    double         rate_old          = 0.; ///< boundary heat rate at time
    double         source_rate_old   = 0.;
    bool           rhs_old_valid     = false;
    bool           last_step_flipped = false;
    unsigned long  steps_taken       = 0;
    double         kappa_max         = 0.;
    double         h_min             = 0.;
    HeatStatistics stats;

    std::ostringstream timer_stream;
    TimerOutput        timer;

    /// Probe at @p p (throws InputError if outside the rock).
    internal::Probe
    locate_probe(const Point<2> &p) const;
    /// Kelly estimate, refine and coarsen, transfer the field, rebuild.
    void
    adapt_mesh();
    /// The mesh as bytes (boost binary archive of the triangulation).
    std::string
    saved_mesh() const;
    /// Replace the mesh by saved_mesh() @p bytes and rebuild the system
    /// (dofs, matrices, probes) on it; the field must be set afterwards.
    void
    load_mesh(const std::string &bytes);

    /// Condensed right-hand side at @p t into @p f; returns the boundary
    /// data part of the heat rate (without -w.T) and the source rate.
    void
    assemble_rhs(const double    t,
                 Vector<double> &f,
                 double         &boundary_rate,
                 double         &source_rate) const;

  private:
    void
    setup_system();
    void
    assemble_fixed();
    StepOperator &
    get_operator(const double dt, const double theta);
    void
    theta_step(const double dt, const double theta);
    void
    arkode_advance(const double end_time);
  };



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



  std::string
  HeatSolver::Impl::saved_mesh() const
  {
    std::ostringstream              out;
    boost::archive::binary_oarchive archive(out);
    archive << tria;
    return out.str();
  }



  void
  HeatSolver::Impl::load_mesh(const std::string &bytes)
  {
    std::istringstream              in(bytes);
    boost::archive::binary_iarchive archive(in);
    archive >> tria;
    setup_system();
    assemble_fixed();
    operators.clear();
    rhs_old_valid = false;
    for (unsigned int k = 0; k < probes.size(); ++k)
      probes[k] = locate_probe(probe_points[k]);
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
    internal::assemble_fixed_integrals(
      prm,
      mapping,
      dof_handler,
      hanging,
      dof_handler.locally_owned_dofs(),
      tria.get_communicator(),
      fixed,
      [&](const DoFHandler<2>::active_cell_iterator &,
          const std::vector<types::global_dof_index> &dofs,
          const FullMatrix<double>                   &cell_mass,
          const FullMatrix<double>                   &cell_stiff) {
        hanging.distribute_local_to_global(cell_mass, dofs, mass);
        hanging.distribute_local_to_global(cell_stiff, dofs, stiffness);
      });
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



  StepOperator &
  HeatSolver::Impl::get_operator(const double dt, const double theta)
  {
    for (auto &op : operators)
      if (op->dt == dt && op->theta == theta)
        return *op;
    if (operators.size() >= 4)
      operators.erase(operators.begin());
    TimerOutput::Scope scope(timer, "factorize");
    auto               op = std::make_unique<StepOperator>();
    op->dt                = dt;
    op->theta             = theta;
    op->a.reinit(sparsity);
    op->a.copy_from(mass);
    op->a.add(theta * dt, stiffness);
    op->b.reinit(sparsity);
    op->b.copy_from(mass);
    op->b.add(-(1. - theta) * dt, stiffness);
    op->a_mod.reinit(sparsity);
    op->a_mod.copy_from(op->a);
    // Remove Dirichlet rows and columns (keeps the matrix symmetric).
    if (!dirichlet.dofs.empty())
      for (unsigned int row = 0; row < op->a_mod.m(); ++row)
        for (auto it = op->a_mod.begin(row); it != op->a_mod.end(row); ++it)
          if ((is_dirichlet[row] || is_dirichlet[it->column()])
              && it->column() != row)
            it->value() = 0.;
    if (prm.direct_solver)
      {
        to_eigen(op->b, op->eigen_b);
        std::vector<int> column_map(dof_handler.n_dofs(), -1);
        for (std::size_t d = 0; d < dirichlet.dofs.size(); ++d)
          column_map[dirichlet.dofs[d]] = d;
        to_eigen(op->a,
                 op->eigen_a_dirichlet,
                 &column_map,
                 dirichlet.dofs.size());
        Eigen::SparseMatrix<double> a_mod;
        to_eigen(op->a_mod, a_mod);
        op->ldlt.compute(a_mod);
        if (op->ldlt.info() != Eigen::Success)
          throw std::runtime_error("heat: the factorisation of the system "
                                   "matrix failed (not positive definite?)");
      }
    else
      op->ssor.initialize(op->a_mod, 1.2);
    ++stats.n_factorizations;
    operators.push_back(std::move(op));
    return *operators.back();
  }



  void
  HeatSolver::Impl::theta_step(const double dt, const double theta)
  {
    StepOperator &op = get_operator(dt, theta);
    internal::theta_step(*this, dt, theta, [&]() {
      // b = B T + dt (theta F_new + (1 - theta) F_old) - A g
      const unsigned int n = solution.size();
      using Map            = Eigen::Map<Eigen::VectorXd>;
      using ConstMap       = Eigen::Map<const Eigen::VectorXd>;
      if (prm.direct_solver)
        Map(tmp.begin(), n).noalias()
          = op.eigen_b * ConstMap(solution.begin(), n);
      else
        op.b.vmult(tmp, solution);
      tmp.add(dt * theta, rhs_new, dt * (1. - theta), rhs_old);
      if (!dirichlet.dofs.empty())
        {
          g_ext = 0.;
          dirichlet.set_values(prm, time + dt, g_ext);
          if (prm.direct_solver)
            {
              Eigen::VectorXd g(dirichlet.dofs.size());
              for (std::size_t d = 0; d < dirichlet.dofs.size(); ++d)
                g[d] = g_ext[dirichlet.dofs[d]];
              Map(tmp.begin(), n) -= op.eigen_a_dirichlet * g;
            }
          else
            {
              op.a.vmult(new_solution, g_ext);
              tmp -= new_solution;
            }
          for (const auto i : dirichlet.dofs)
            tmp[i] = op.a.diag_element(i) * g_ext[i];
        }
      hanging.set_zero(tmp);

      if (prm.direct_solver)
        Map(new_solution.begin(), n) = op.ldlt.solve(ConstMap(tmp.begin(), n));
      else
        {
          SolverControl            control(10000,
                                prm.cg_tolerance
                                  * std::max(tmp.l2_norm(), 1e-300));
          SolverCG<Vector<double>> cg(control);
          new_solution = solution;
          cg.solve(op.a_mod, new_solution, tmp, op.ssor);
        }
      hanging.distribute(new_solution);
    });
  }



  void
  HeatSolver::Impl::advance_to(const double end_time)
  {
    if (!(end_time >= time - 1e-9 * prm.time_step))
      throw std::invalid_argument("heat: advance_to() into the past");
    if (prm.stepper == TimeStepper::arkode)
      {
        TimerOutput::Scope scope(timer, "time stepping (ARKODE)");
        arkode_advance(end_time);
        return;
      }
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



  void
  HeatSolver::Impl::arkode_advance(const double end_time)
  {
    // M y' = -K y + F(t) with Dirichlet rows replaced by y_D' = g'(t)
    // (finite difference of g); implicit DIRK with adaptive error control.
    using VectorType = Vector<double>;
    if (end_time - time <= 0.)
      return;
    SUNDIALS::ARKode<VectorType>::AdditionalData data(
      time,
      end_time,
      std::min(prm.time_step, end_time - time),
      end_time - time,
      1e-12 * (end_time - time),
      5,
      10,
      true,
      false,
      true,
      3,
      prm.arkode_absolute_tolerance,
      prm.arkode_relative_tolerance);
    SUNDIALS::ARKode<VectorType> ode(data);

    // Central difference for g'(t): step ~ cube root of round-off times the
    // time scale (the larger of |t| and dt).
    const double g_eps
      = 1e-5 * std::max({std::abs(time), std::abs(end_time), prm.time_step});
    Vector<double> g0(dof_handler.n_dofs()), g1(dof_handler.n_dofs());
    double         dummy_rate, dummy_source;
    Vector<double> f(dof_handler.n_dofs());
    // Free-row mask: zero at Dirichlet and hanging rows.
    ode.implicit_function
      = [&](const double t, const VectorType &y, VectorType &ydot) {
          // ydot here is the right-hand side f_I(t, y) = -K y + F(t) (mass
          // matrix handled by ARKODE's mass solver).
          assemble_rhs(t, f, dummy_rate, dummy_source);
          stiffness.vmult(ydot, y);
          ydot.sadd(-1., 1., f);
          if (!dirichlet.dofs.empty())
            {
              g0 = 0.;
              g1 = 0.;
              dirichlet.set_values(prm, t - g_eps, g0);
              dirichlet.set_values(prm, t + g_eps, g1);
              for (const auto i : dirichlet.dofs)
                ydot[i] = mass.diag_element(i) * (g1[i] - g0[i]) / (2. * g_eps);
            }
          for (unsigned int i = 0; i < ydot.size(); ++i)
            if (hanging.is_constrained(i))
              ydot[i] = 0.;
          return 0;
        };

    // Mass matrix with Dirichlet rows/cols reduced to the diagonal.
    // (Free rows keep their Dirichlet columns: M_iD g'(t) is part of the
    // equation; the matrix is then non-symmetric, which UMFPACK handles.)
    SparseMatrix<double> m_mod(sparsity);
    m_mod.copy_from(mass);
    for (unsigned int row = 0; row < m_mod.m(); ++row)
      if (is_dirichlet[row])
        for (auto it = m_mod.begin(row); it != m_mod.end(row); ++it)
          if (it->column() != row)
            it->value() = 0.;
    SparseMatrix<double> jacobian(sparsity);
    SparseDirectUMFPACK  jac_solver, mass_solver;
    mass_solver.initialize(m_mod);
    double gamma_current = -1.;

    ode.mass_times_vector
      = [&](const double, const VectorType &v, VectorType &mv) {
          m_mod.vmult(mv, v);
          return 0;
        };
    ode.solve_mass = [&](SUNDIALS::SundialsOperator<VectorType> &,
                         SUNDIALS::SundialsPreconditioner<VectorType> &,
                         VectorType       &x,
                         const VectorType &b,
                         double) {
      mass_solver.vmult(x, b);
      return 0;
    };
    ode.jacobian_times_setup
      = [&](double, const VectorType &, const VectorType &) { return 0; };
    ode.jacobian_times_vector = [&](const VectorType &v,
                                    VectorType       &jv,
                                    double,
                                    const VectorType &,
                                    const VectorType &) {
      stiffness.vmult(jv, v);
      jv *= -1.;
      for (const auto i : dirichlet.dofs)
        jv[i] = 0.;
      for (unsigned int i = 0; i < jv.size(); ++i)
        if (hanging.is_constrained(i))
          jv[i] = 0.;
      return 0;
    };
    ode.jacobian_preconditioner_setup = [&](double,
                                            const VectorType &,
                                            const VectorType &,
                                            int,
                                            int   &j_current,
                                            double gamma) {
      // Newton matrix M - gamma J = M + gamma K (Dirichlet rows: M_ii).
      if (gamma != gamma_current)
        {
          jacobian.copy_from(mass);
          jacobian.add(gamma, stiffness);
          for (unsigned int row = 0; row < jacobian.m(); ++row)
            for (auto it = jacobian.begin(row); it != jacobian.end(row); ++it)
              if (is_dirichlet[row] || hanging.is_constrained(row))
                it->value()
                  = (it->column() == row) ? mass.diag_element(row) : 0.;
          jac_solver.initialize(jacobian);
          gamma_current = gamma;
          ++stats.n_factorizations;
        }
      j_current = 1;
      return 0;
    };
    ode.jacobian_preconditioner_solve = [&](double,
                                            const VectorType &,
                                            const VectorType &,
                                            const VectorType &r,
                                            VectorType       &z,
                                            double,
                                            double,
                                            int) {
      jac_solver.vmult(z, r);
      return 0;
    };
    ode.solve_linearized_system
      = [&](SUNDIALS::SundialsOperator<VectorType>       &op,
            SUNDIALS::SundialsPreconditioner<VectorType> &prec,
            VectorType                                   &x,
            const VectorType                             &b,
            double                                        tol) -> int {
      ReductionControl        control(200, 1e-14, std::max(tol, 1e-12));
      SolverGMRES<VectorType> gmres(control);
      gmres.solve(op, x, b, prec);
      return 0;
    };


    // Heat bookkeeping is only approximate with ARKODE (trapezoidal in the
    // output points); the theta scheme is exact.
    double rate0 = 0., src0 = 0.;
    assemble_rhs(time, f, rate0, src0);
    rate0 -= fixed.robin_weights * solution;

    VectorType y = solution;
    dirichlet.set_values(prm, time, y);
    hanging.distribute(y);
    ode.solve_ode(y);
    long int n_fails = 0, n_steps = 0;
    ARKStepGetNumErrTestFails(ode.get_arkode_memory(), &n_fails);
    ARKStepGetNumSteps(ode.get_arkode_memory(), &n_steps);
    stats.n_rejected_steps += n_fails;
    dirichlet.set_values(prm, end_time, y);
    hanging.distribute(y);
    solution     = y;
    double rate1 = 0., src1 = 0.;
    assemble_rhs(end_time, f, rate1, src1);
    rate1 -= fixed.robin_weights * solution;
    boundary_heat += 0.5 * (end_time - time) * (rate0 + rate1);
    source_heat += 0.5 * (end_time - time) * (src0 + src1);
    stats.n_steps += n_steps;
    time          = end_time;
    rhs_old_valid = false;
  }



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
    const auto &fixed = impl->fixed;
    return internal::block_moments_of(fixed.block_geometry,
                                      fixed.block_phi,
                                      fixed.block_xphi,
                                      fixed.block_yphi,
                                      impl->solution);
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

  namespace
  {
    constexpr char heat_magic[] = "rockdda heat solver checkpoint 1";
  }

  std::string
  HeatSolver::checkpoint(const std::string &mesh_files) const
  {
    if (distributed)
      return distributed->checkpoint(mesh_files);
    io::BinaryWriter w;
    w.put_string(heat_magic);
    // An adaptive mesh changes during the run: it is stored too.
    w.put_string(impl->prm.adaptive_refinement ? impl->saved_mesh()
                                               : std::string());
    w.put<std::uint64_t>(impl->tria.n_active_cells());
    w.put_doubles(impl->solution);
    w.put_doubles(impl->increment_old);
    w.put(impl->time);
    w.put(impl->boundary_heat);
    w.put(impl->source_heat);
    w.put<std::uint8_t>(impl->last_step_flipped ? 1 : 0);
    w.put<std::uint64_t>(impl->steps_taken);
    w.put(impl->stats);
    return w.bytes;
  }



  void
  HeatSolver::restore(const std::string &bytes, const std::string &source)
  {
    if (distributed)
      {
        distributed->restore(bytes, source);
        return;
      }
    io::BinaryReader r(bytes, source);
    if (r.get_string() != heat_magic)
      throw InputError(source + ": not a rockdda heat checkpoint");
    const std::string mesh = r.get_string();
    if (mesh.empty() == impl->prm.adaptive_refinement)
      throw InputError(source + ": the checkpoint was written "
                       + (mesh.empty()
                            ? "without adaptive refinement, this run uses it"
                            : "with adaptive refinement, this run does not"));
    if (!mesh.empty())
      try
        {
          impl->load_mesh(mesh);
        }
      catch (const InputError &)
        {
          throw;
        }
      catch (const std::exception &e)
        {
          throw InputError(source + ": the stored mesh cannot be read ("
                           + e.what() + ")");
        }
    const auto          cells     = r.get<std::uint64_t>();
    std::vector<double> solution  = r.get_doubles();
    std::vector<double> increment = r.get_doubles();
    const std::size_t   n         = impl->dof_handler.n_dofs();
    if (cells != impl->tria.n_active_cells() || solution.size() != n
        || increment.size() != n)
      throw InputError(source + ": the checkpoint has " + std::to_string(cells)
                       + " cells and " + std::to_string(solution.size())
                       + " unknowns, the mesh of this run "
                       + std::to_string(impl->tria.n_active_cells()) + " and "
                       + std::to_string(n) + ": it belongs to another mesh");
    const double time          = r.get<double>();
    const double boundary_heat = r.get<double>();
    const double source_heat   = r.get<double>();
    const bool   flipped       = r.get<std::uint8_t>() != 0;
    const auto   steps         = r.get<std::uint64_t>();
    const auto   stats         = r.get<HeatStatistics>();
    if (!r.at_end())
      throw InputError(source + ": the checkpoint has trailing data");
    for (const double v : solution)
      if (!std::isfinite(v))
        throw InputError(source
                         + ": the checkpoint holds non-finite "
                           "temperatures");
    impl->solution.reinit(n);
    impl->increment_old.reinit(n);
    std::copy(solution.begin(), solution.end(), impl->solution.begin());
    std::copy(increment.begin(), increment.end(), impl->increment_old.begin());
    impl->time              = time;
    impl->boundary_heat     = boundary_heat;
    impl->source_heat       = source_heat;
    impl->last_step_flipped = flipped;
    impl->steps_taken       = steps;
    impl->stats             = stats;
    impl->rhs_old_valid     = false; // reassembled at the restored time
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
    HeatStatistics s = impl->stats;
    s.stiffness_ratio
      = impl->prm.time_step * impl->kappa_max / (impl->h_min * impl->h_min);
    return s;
  }

  std::string
  HeatSolver::method_description() const
  {
    if (distributed)
      return distributed->method_description();
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
