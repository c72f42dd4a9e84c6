/**
 * @file
 * Time stepping of the heat solver with SUNDIALS ARKODE, written once for
 * the serial and the distributed solver: the implicit DIRK method with
 * adaptive error control on M y' = -K y + F(t), the Dirichlet rows
 * replaced by y_D' = g'(t) and the hanging rows by 0; the Newton systems
 * are solved by GMRES preconditioned with a direct factorisation (serial:
 * UMFPACK; distributed: Amesos KLU). The heat that entered is booked with
 * the trapezoidal rule between the output times.
 */
#include <deal.II/lac/solver_control.h>
#include <deal.II/lac/solver_gmres.h>
#include <deal.II/lac/sparse_direct.h>
#include <deal.II/lac/trilinos_solver.h>
#include <deal.II/sundials/arkode.h>

#include "heat_system.h"
#include <algorithm>
#include <arkode/arkode_arkstep.h>
#include <cmath>
#include <memory>

namespace rockdda::thermal
{
  using namespace dealii;

  namespace
  {
    /// A direct solver of the serial (UMFPACK) or the distributed (Amesos
    /// KLU) matrix type: initialize(matrix), then solve(x, b).
    template <typename MatrixType>
    struct DirectSolver;

    template <>
    struct DirectSolver<SparseMatrix<double>>
    {
      SparseDirectUMFPACK umfpack;

      void
      initialize(const SparseMatrix<double> &m)
      {
        umfpack.initialize(m);
      }

      void
      solve(Vector<double> &x, const Vector<double> &b)
      {
        umfpack.vmult(x, b);
      }
    };

    template <>
    struct DirectSolver<TrilinosWrappers::SparseMatrix>
    {
      SolverControl                                   control;
      std::unique_ptr<TrilinosWrappers::SolverDirect> klu;

      void
      initialize(const TrilinosWrappers::SparseMatrix &m)
      {
        klu = std::make_unique<TrilinosWrappers::SolverDirect>(
          control,
          TrilinosWrappers::SolverDirect::AdditionalData(false, "Amesos_Klu"));
        klu->initialize(m);
      }

      void
      solve(TrilinosWrappers::MPI::Vector       &x,
            const TrilinosWrappers::MPI::Vector &b)
      {
        klu->solve(x, b);
      }
    };

    /// @p m = @p source, with the sparsity pattern of @p source.
    void
    copy_matrix(SparseMatrix<double> &m, const SparseMatrix<double> &source)
    {
      m.reinit(source.get_sparsity_pattern());
      m.copy_from(source);
    }

    void
    copy_matrix(TrilinosWrappers::SparseMatrix       &m,
                const TrilinosWrappers::SparseMatrix &source)
    {
      m.copy_from(source);
    }

    /// Set row @p row of @p m to @p diagonal on the diagonal, 0 elsewhere.
    void
    keep_diagonal(SparseMatrix<double>         &m,
                  const types::global_dof_index row,
                  const double                  diagonal)
    {
      for (auto it = m.begin(row); it != m.end(row); ++it)
        it->value() = it->column() == row ? diagonal : 0.;
    }

    void
    keep_diagonal(TrilinosWrappers::SparseMatrix &m,
                  const types::global_dof_index   row,
                  const double                    diagonal)
    {
      m.clear_row(row, diagonal);
    }
  } // namespace



  namespace internal
  {
    template <typename Solver>
    void
    arkode_advance(Solver         &s,
                   const double    end_time,
                   const IndexSet &owned,
                   const MPI_Comm  comm)
    {
      using VectorType  = std::decay_t<decltype(s.solution)>;
      using MatrixType  = std::decay_t<decltype(s.mass)>;
      const double time = s.time;
      if (end_time - time <= 0.)
        return;
      const HeatParameters                                 &prm = s.prm;
      typename SUNDIALS::ARKode<VectorType>::AdditionalData data(
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
      SUNDIALS::ARKode<VectorType> ode(data, comm);

      // The locally owned rows that keep their diagonal only: Dirichlet
      // rows (y_D' = g'(t)) and hanging rows (0).
      std::vector<types::global_dof_index> hanging_rows;
      for (const auto i : owned)
        if (s.hanging.is_constrained(i))
          hanging_rows.push_back(i);
      const auto &dirichlet = s.dirichlet.dofs;

      // Central difference for g'(t): step ~ cube root of round-off times
      // the time scale (the larger of |t| and dt).
      const double g_eps
        = 1e-5 * std::max({std::abs(time), std::abs(end_time), prm.time_step});
      VectorType g0 = s.solution, g1 = s.solution, f = s.solution;
      double     dummy_rate, dummy_source;
      ode.implicit_function
        = [&](const double t, const VectorType &y, VectorType &ydot) {
            // The right-hand side f_I(t, y) = -K y + F(t) (the mass matrix
            // is ARKODE's mass solver's).
            s.assemble_rhs(t, f, dummy_rate, dummy_source);
            s.stiffness.vmult(ydot, y);
            ydot.sadd(-1., 1., f);
            // (On every rank, also one without Dirichlet dofs: compress()
            // is collective.)
            g0 = 0.;
            g1 = 0.;
            s.dirichlet.set_values(prm, t - g_eps, g0);
            s.dirichlet.set_values(prm, t + g_eps, g1);
            g0.compress(VectorOperation::insert);
            g1.compress(VectorOperation::insert);
            for (const auto i : dirichlet)
              ydot[i] = s.mass.diag_element(i) * (g1[i] - g0[i]) / (2. * g_eps);
            for (const auto i : hanging_rows)
              ydot[i] = 0.;
            ydot.compress(VectorOperation::insert);
            return 0;
          };

      // Mass matrix with the Dirichlet rows reduced to the diagonal. (Free
      // rows keep their Dirichlet columns: M_iD g'(t) is part of the
      // equation; the matrix is then non-symmetric, which the direct
      // solvers handle.)
      MatrixType m_mod, jacobian;
      copy_matrix(m_mod, s.mass);
      for (const auto i : dirichlet)
        keep_diagonal(m_mod, i, s.mass.diag_element(i));
      DirectSolver<MatrixType> jac_solver, mass_solver;
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
        mass_solver.solve(x, b);
        return 0;
      };
      ode.jacobian_times_setup
        = [&](double, const VectorType &, const VectorType &) { return 0; };
      ode.jacobian_times_vector = [&](const VectorType &v,
                                      VectorType       &jv,
                                      double,
                                      const VectorType &,
                                      const VectorType &) {
        s.stiffness.vmult(jv, v);
        jv *= -1.;
        for (const auto i : dirichlet)
          jv[i] = 0.;
        for (const auto i : hanging_rows)
          jv[i] = 0.;
        jv.compress(VectorOperation::insert);
        return 0;
      };
      ode.jacobian_preconditioner_setup = [&](double,
                                              const VectorType &,
                                              const VectorType &,
                                              int,
                                              int   &j_current,
                                              double gamma) {
        // Newton matrix M - gamma J = M + gamma K (kept rows: M_ii).
        if (gamma != gamma_current)
          {
            copy_matrix(jacobian, s.mass);
            jacobian.add(gamma, s.stiffness);
            for (const auto i : dirichlet)
              keep_diagonal(jacobian, i, s.mass.diag_element(i));
            for (const auto i : hanging_rows)
              keep_diagonal(jacobian, i, s.mass.diag_element(i));
            jac_solver.initialize(jacobian);
            gamma_current = gamma;
            ++s.stats.n_factorizations;
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
        jac_solver.solve(z, r);
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

      // Heat bookkeeping is only approximate with ARKODE (trapezoidal in
      // the output points); the theta scheme is exact.
      double rate0 = 0., src0 = 0.;
      s.assemble_rhs(time, f, rate0, src0);
      rate0 -= s.fixed.robin_weights * s.solution;

      VectorType y = s.solution;
      s.dirichlet.set_values(prm, time, y);
      y.compress(VectorOperation::insert);
      s.hanging.distribute(y);
      ode.solve_ode(y);
      long int n_fails = 0, n_steps = 0;
      ARKStepGetNumErrTestFails(ode.get_arkode_memory(), &n_fails);
      ARKStepGetNumSteps(ode.get_arkode_memory(), &n_steps);
      s.stats.n_rejected_steps += n_fails;
      s.dirichlet.set_values(prm, end_time, y);
      y.compress(VectorOperation::insert);
      s.hanging.distribute(y);
      s.solution   = y;
      double rate1 = 0., src1 = 0.;
      s.assemble_rhs(end_time, f, rate1, src1);
      rate1 -= s.fixed.robin_weights * s.solution;
      s.boundary_heat += 0.5 * (end_time - time) * (rate0 + rate1);
      s.source_heat += 0.5 * (end_time - time) * (src0 + src1);
      s.stats.n_steps += n_steps;
      s.time          = end_time;
      s.rhs_old_valid = false;
    }

    template void
    arkode_advance(HeatSystem<LinearAlgebra::Serial> &,
                   const double,
                   const IndexSet &,
                   const MPI_Comm);
    template void
    arkode_advance(HeatSystem<LinearAlgebra::Trilinos> &,
                   const double,
                   const IndexSet &,
                   const MPI_Comm);
  } // namespace internal
} // namespace rockdda::thermal
