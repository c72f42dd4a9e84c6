/**
 * @file
 * Time stepping of the heat solver with the theta scheme (Crank-Nicolson
 * with Rannacher start-up steps, or backward Euler): the step sequence,
 * the choice of theta, the time loop and the cache of step operators of
 * HeatSystem, written once, and what differs with the linear-algebra
 * traits: building a step operator and the linear solve (serial: Eigen's
 * sparse Cholesky or CG + SSOR; distributed: Amesos KLU or CG + AMG). The
 * step itself, with its heat bookkeeping and oscillation indicator, is
 * internal::theta_step() (heat_internal.h); ARKODE is in heat_arkode.cc.
 */
#include <deal.II/base/timer.h>
#include <deal.II/lac/solver_cg.h>
#include <deal.II/lac/solver_control.h>

#include "heat_internal.h"
#include "heat_system.h"
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



  namespace internal
  {
    namespace
    {
      /// Copy a deal.II sparse matrix (optionally only some columns,
      /// renumbered by @p column_map, -1 = skip) into Eigen.
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
                const int col = column_map ? (*column_map)[it->column()]
                                           : int(it->column());
                if (col >= 0)
                  triplets.emplace_back(row, col, it->value());
              }
        out.resize(m.m(), column_map ? n_columns : m.n());
        out.setFromTriplets(triplets.begin(), triplets.end());
      }
    } // namespace



    // Serial: A = M + theta dt K and B = M - (1 - theta) dt K from the
    // assembled mass and stiffness; the Dirichlet rows and columns of A are
    // removed (symmetric), then factorised by Eigen or preconditioned by
    // SSOR.
    template <>
    void
    HeatSystem<LinearAlgebra::Serial>::build_operator(StepOperator &op)
    {
      const double dt = op.dt, theta = op.theta;
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
            throw std::runtime_error("heat: the factorisation of the system "
                                     "matrix failed (not positive definite?)");
        }
      else
        op.ssor.initialize(op.a_mod, 1.2);
    }



    template <>
    void
    HeatSystem<LinearAlgebra::Serial>::solve_step(StepOperator &op)
    {
      const double dt = op.dt, theta = op.theta;
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
    }



    // Distributed: A (with and without the homogeneous Dirichlet
    // constraints) and B assembled cell by cell, with the joint
    // conductance; Amesos KLU or AMG.
    template <>
    void
    HeatSystem<LinearAlgebra::Trilinos>::build_operator(StepOperator &op)
    {
      const double dt = op.dt, theta = op.theta;
      LinearAlgebra::Trilinos::reinit(op.a_hom, dsp, sparsity, owned, comm);
      LinearAlgebra::Trilinos::reinit(op.a_full, dsp, sparsity, owned, comm);
      LinearAlgebra::Trilinos::reinit(op.b, dsp, sparsity, owned, comm);

      CellIntegrators    integrators(mapping,
                                  fe,
                                  update_values | update_gradients
                                    | update_JxW_values,
                                  update_values | update_JxW_values);
      FEValues<2>       &fe_values = integrators.values;
      FEFaceValues<2>   &fe_face   = integrators.face;
      const unsigned int dpc       = fe.n_dofs_per_cell();
      FullMatrix<double> cell_mass(dpc, dpc), cell_stiff(dpc, dpc),
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
            constraints_hom.distribute_local_to_global(cell_a, dofs, op.a_hom);
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
    }



    template <>
    void
    HeatSystem<LinearAlgebra::Trilinos>::solve_step(StepOperator &op)
    {
      const double dt = op.dt, theta = op.theta;
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
    }



    /**
     * The step operator of (@p dt, @p theta) among the last four built (a
     * run uses one or two: Rannacher start-up, whole and final step), or a
     * new one, built and factorised.
     */
    template <typename LA>
    typename HeatSystem<LA>::StepOperator &
    HeatSystem<LA>::get_operator(const double dt, const double theta)
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
      build_operator(*op);
      ++stats.n_factorizations;
      operators.push_back(std::move(op));
      return *operators.back();
    }



    template <typename LA>
    void
    HeatSystem<LA>::theta_step(const double dt, const double theta)
    {
      StepOperator &op = get_operator(dt, theta);
      internal::theta_step(*this, dt, theta, [&]() { solve_step(op); });
      ghosted_valid = false;
    }



    /**
     * To @p end_time by ARKODE or by theta steps, adapting the mesh every
     * adaptive_interval steps.
     */
    template <typename LA>
    void
    HeatSystem<LA>::advance_to(const double end_time)
    {
      if (!(end_time >= time - 1e-9 * prm.time_step))
        throw std::invalid_argument("heat: advance_to() into the past");
      if (prm.stepper == TimeStepper::arkode)
        {
          TimerOutput::Scope scope(timer, "time stepping (ARKODE)");
          arkode_advance(*this, end_time, owned, comm);
        }
      else
        {
          TimerOutput::Scope scope(timer, "time stepping");
          take_steps(time, end_time, prm.time_step, [&](const double h) {
            theta_step(h, step_theta(prm, stats, steps_taken));
            if (prm.adaptive_refinement
                && steps_taken % prm.adaptive_interval == 0)
              adapt_mesh();
          });
          time = end_time;
        }
      ghosted_valid = false;
    }



    template LinearAlgebra::Serial::StepOperator &
    HeatSystem<LinearAlgebra::Serial>::get_operator(const double, const double);
    template void
    HeatSystem<LinearAlgebra::Serial>::theta_step(const double, const double);
    template void
    HeatSystem<LinearAlgebra::Serial>::advance_to(const double);
    template LinearAlgebra::Trilinos::StepOperator &
    HeatSystem<LinearAlgebra::Trilinos>::get_operator(const double,
                                                      const double);
    template void
    HeatSystem<LinearAlgebra::Trilinos>::theta_step(const double, const double);
    template void
    HeatSystem<LinearAlgebra::Trilinos>::advance_to(const double);
  } // namespace internal
} // namespace rockdda::thermal
