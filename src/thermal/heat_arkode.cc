/**
 * @file
 * Time stepping of the serial heat solver with SUNDIALS ARKODE: the
 * implicit DIRK method with adaptive error control on M y' = -K y + F(t),
 * the Dirichlet rows replaced by y_D' = g'(t); the heat that entered is
 * booked with the trapezoidal rule between the output times.
 */
#include <deal.II/lac/solver_control.h>
#include <deal.II/lac/solver_gmres.h>
#include <deal.II/lac/sparse_direct.h>
#include <deal.II/sundials/arkode.h>

#include "heat_solver_serial.h"
#include <algorithm>
#include <arkode/arkode_arkstep.h>
#include <cmath>

namespace rockdda::thermal
{
  using namespace dealii;

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
} // namespace rockdda::thermal
