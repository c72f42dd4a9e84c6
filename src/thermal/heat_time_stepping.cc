/**
 * @file
 * Time stepping of the heat solver with the theta scheme (Crank-Nicolson
 * with Rannacher start-up steps, or backward Euler): the step sequence,
 * the choice of theta and the time loop shared by both solvers, and each
 * solver's step operators and linear solve (serial: Eigen's sparse
 * Cholesky or CG + SSOR; distributed: Amesos KLU or CG + AMG). The step itself,
 * with its heat bookkeeping and oscillation indicator, is
 * internal::theta_step() (heat_internal.h); ARKODE is in heat_arkode.cc.
 */
#include <deal.II/base/timer.h>
#include <deal.II/lac/solver_cg.h>
#include <deal.II/lac/solver_control.h>

#include "heat_internal.h"
#include "heat_solver_distributed.h"
#include "heat_solver_serial.h"
#include <cmath>
#include <stdexcept>

namespace rockdda::thermal
{
  using namespace dealii;

  namespace internal
  {
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



  namespace
  {
    using internal::StepOperator;

    /**
     * The step operator of (@p dt, @p theta) among the last four built
     * (a run uses one or two: Rannacher start-up, whole and final step),
     * or a new one that @p build assembles and factorises.
     */
    template <typename Operator, typename Build>
    Operator &
    cached_operator(std::vector<std::unique_ptr<Operator>> &operators,
                    const double                            dt,
                    const double                            theta,
                    TimerOutput                            &timer,
                    HeatStatistics                         &stats,
                    Build                                 &&build)
    {
      for (auto &op : operators)
        if (op->dt == dt && op->theta == theta)
          return *op;
      if (operators.size() >= 4)
        operators.erase(operators.begin());
      TimerOutput::Scope scope(timer, "factorize");
      auto               op = std::make_unique<Operator>();
      op->dt                = dt;
      op->theta             = theta;
      build(*op);
      ++stats.n_factorizations;
      operators.push_back(std::move(op));
      return *operators.back();
    }

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



  StepOperator &
  HeatSolver::Impl::get_operator(const double dt, const double theta)
  {
    return cached_operator(
      operators, dt, theta, timer, stats, [&](StepOperator &op) {
        op.a.reinit(sparsity);
        op.a.copy_from(mass);
        op.a.add(theta * dt, stiffness);
        op.b.reinit(sparsity);
        op.b.copy_from(mass);
        op.b.add(-(1. - theta) * dt, stiffness);
        op.a_mod.reinit(sparsity);
        op.a_mod.copy_from(op.a);
        // Remove Dirichlet rows and columns (keeps the matrix symmetric).
        if (!dirichlet.dofs.empty())
          for (unsigned int row = 0; row < op.a_mod.m(); ++row)
            for (auto it = op.a_mod.begin(row); it != op.a_mod.end(row); ++it)
              if ((is_dirichlet[row] || is_dirichlet[it->column()])
                  && it->column() != row)
                it->value() = 0.;
        if (prm.direct_solver)
          {
            to_eigen(op.b, op.eigen_b);
            std::vector<int> column_map(dof_handler.n_dofs(), -1);
            for (std::size_t d = 0; d < dirichlet.dofs.size(); ++d)
              column_map[dirichlet.dofs[d]] = d;
            to_eigen(op.a,
                     op.eigen_a_dirichlet,
                     &column_map,
                     dirichlet.dofs.size());
            Eigen::SparseMatrix<double> a_mod;
            to_eigen(op.a_mod, a_mod);
            op.ldlt.compute(a_mod);
            if (op.ldlt.info() != Eigen::Success)
              throw std::runtime_error(
                "heat: the factorisation of the system "
                "matrix failed (not positive definite?)");
          }
        else
          op.ssor.initialize(op.a_mod, 1.2);
      });
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



  namespace
  {
    /// Throw if @p end_time lies before the current time @p time.
    void
    check_end_time(const HeatParameters &prm,
                   const double          time,
                   const double          end_time)
    {
      if (!(end_time >= time - 1e-9 * prm.time_step))
        throw std::invalid_argument("heat: advance_to() into the past");
    }

    /**
     * Theta steps of @p s (either solver: members prm, stats, time,
     * steps_taken, timer, theta_step() and adapt_mesh()) to @p end_time,
     * adapting the mesh every adaptive_interval steps.
     */
    template <typename Solver>
    void
    advance_theta_scheme(Solver &s, const double end_time)
    {
      check_end_time(s.prm, s.time, end_time);
      TimerOutput::Scope scope(s.timer, "time stepping");
      const auto         step = [&](const double h) {
        s.theta_step(h, internal::step_theta(s.prm, s.stats, s.steps_taken));
        if (s.prm.adaptive_refinement
            && s.steps_taken % s.prm.adaptive_interval == 0)
          s.adapt_mesh();
      };
      internal::take_steps(s.time, end_time, s.prm.time_step, step);
      s.time = end_time;
    }

    /// Either solver @p s to @p end_time by ARKODE or the theta scheme;
    /// @p owned: its locally owned dofs.
    template <typename Solver>
    void
    advance(Solver &s, const double end_time, const IndexSet &owned)
    {
      if (s.prm.stepper != TimeStepper::arkode)
        return advance_theta_scheme(s, end_time);
      check_end_time(s.prm, s.time, end_time);
      TimerOutput::Scope scope(s.timer, "time stepping (ARKODE)");
      internal::arkode_advance(s, end_time, owned, s.tria.get_communicator());
    }
  } // namespace



  void
  HeatSolver::Impl::advance_to(const double end_time)
  {
    advance(*this, end_time, dof_handler.locally_owned_dofs());
  }



  namespace internal
  {
    using VectorType = DistributedVector;

    DistributedOperator &
    DistributedHeat::Impl::get_operator(const double dt, const double theta)
    {
      return cached_operator(
        operators, dt, theta, timer, stats, [&](DistributedOperator &op) {
          op.a_hom.reinit(owned, owned, dsp, comm);
          op.a_full.reinit(owned, owned, dsp, comm);
          op.b.reinit(owned, owned, dsp, comm);

          internal::CellIntegrators integrators(mapping,
                                                fe,
                                                update_values | update_gradients
                                                  | update_JxW_values,
                                                update_values
                                                  | update_JxW_values);
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
                cell_matrices(
                  prm, cell, fe_values, fe_face, cell_mass, cell_stiff);
                cell_a = cell_mass;
                cell_a.add(theta * dt, cell_stiff);
                cell_b = cell_mass;
                cell_b.add(-(1. - theta) * dt, cell_stiff);
                cell->get_dof_indices(dofs);
                constraints_hom.distribute_local_to_global(cell_a,
                                                           dofs,
                                                           op.a_hom);
                hanging.distribute_local_to_global(cell_a, dofs, op.a_full);
                hanging.distribute_local_to_global(cell_b, dofs, op.b);
              }
          joints.add_to(op.a_hom, theta * dt, true);
          joints.add_to(op.a_full, theta * dt, false);
          joints.add_to(op.b, -(1. - theta) * dt, false);
          op.a_hom.compress(VectorOperation::add);
          op.a_full.compress(VectorOperation::add);
          op.b.compress(VectorOperation::add);

          if (prm.direct_solver && !prm.distributed)
            {
              op.direct = std::make_unique<TrilinosWrappers::SolverDirect>(
                op.direct_control,
                TrilinosWrappers::SolverDirect::AdditionalData(false,
                                                               "Amesos_Klu"));
              op.direct->initialize(op.a_hom);
            }
          else
            {
              TrilinosWrappers::PreconditionAMG::AdditionalData data;
              data.elliptic              = true;
              data.higher_order_elements = fe.degree > 1;
              data.smoother_sweeps       = 2;
              data.aggregation_threshold = 0.02;
              op.amg.initialize(op.a_hom, data);
            }
        });
    }



    void
    DistributedHeat::Impl::theta_step(const double dt, const double theta)
    {
      DistributedOperator &op = get_operator(dt, theta);
      internal::theta_step(*this, dt, theta, [&]() {
        // (M + theta dt K)(T_new) = B T + dt (theta F_new + (1 - theta) F_old),
        // solved for u = T_new - g with g the Dirichlet values (zero
        // elsewhere).
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
    DistributedHeat::Impl::advance_to(const double end_time)
    {
      advance(*this, end_time, owned);
      ghosted_valid = false;
    }
  } // namespace internal
} // namespace rockdda::thermal
