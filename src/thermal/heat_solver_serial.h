/**
 * @file
 * Internal to the thermal subsystem: the state of the serial heat solver
 * (HeatSolver::Impl: deal.II Triangulation, SparseMatrix and Vector, Eigen
 * sparse Cholesky) and the matrices of one theta step. Its member
 * functions live in the files named after what they do:
 * heat_solver_serial.cc (setup and assembly), heat_time_stepping.cc (theta
 * scheme), heat_arkode.cc (ARKODE, written once for both solvers),
 * heat_adaptivity.cc (Kelly refinement) and heat_checkpoint.cc (saving and
 * restoring the state).
 */
#ifndef ROCKDDA_THERMAL_HEAT_SOLVER_SERIAL_H
#define ROCKDDA_THERMAL_HEAT_SOLVER_SERIAL_H

#include <rockdda/thermal/heat_solver.h>

#include <deal.II/base/point.h>
#include <deal.II/base/timer.h>
#include <deal.II/dofs/dof_handler.h>
#include <deal.II/fe/fe_q.h>
#include <deal.II/fe/mapping_q1.h>
#include <deal.II/grid/tria.h>
#include <deal.II/lac/affine_constraints.h>
#include <deal.II/lac/precondition.h>
#include <deal.II/lac/sparse_matrix.h>
#include <deal.II/lac/sparsity_pattern.h>
#include <deal.II/lac/vector.h>

#include <Eigen/SparseCholesky>
#include <Eigen/SparseCore>

#include "heat_assembly.h"
#include "heat_internal.h"
#include "heat_probes.h"
#include <array>
#include <memory>
#include <sstream>
#include <string>
#include <vector>

namespace rockdda::thermal
{
  namespace internal
  {
    /// Matrices and factorisation of one theta-scheme step size.
    struct StepOperator
    {
      double                       dt    = 0.;
      double                       theta = 0.;
      dealii::SparseMatrix<double> a; ///< M + theta dt K (hanging-condensed)
      dealii::SparseMatrix<double>
        a_mod;                        ///< a with Dirichlet rows/cols removed
      dealii::SparseMatrix<double> b; ///< M - (1 - theta) dt K
      dealii::PreconditionSSOR<dealii::SparseMatrix<double>> ssor;
      // The per-step work of the direct path in Eigen (serial, no task
      // overhead for the small systems of long runs): b, the Dirichlet
      // columns of a, and the sparse Cholesky (LDL^T) factors of a_mod.
      Eigen::SparseMatrix<double, Eigen::RowMajor> eigen_b, eigen_a_dirichlet;
      Eigen::SimplicialLDLT<Eigen::SparseMatrix<double>> ldlt;
    };
  } // namespace internal



  class HeatSolver::Impl : public internal::StepState
  {
  public:
    explicit Impl(const HeatParameters &parameters);

    void
    advance_to(const double end_time);

    HeatParameters                                       prm;
    dealii::Triangulation<2>                             tria;
    dealii::FE_Q<2>                                      fe;
    dealii::DoFHandler<2>                                dof_handler;
    dealii::MappingQ1<2>                                 mapping;
    dealii::AffineConstraints<double>                    hanging;
    dealii::SparsityPattern                              sparsity;
    dealii::SparseMatrix<double>                         mass, stiffness;
    std::vector<std::unique_ptr<internal::StepOperator>> operators;

    dealii::Vector<double> solution, new_solution, rhs_old, rhs_new, tmp, g_ext,
      increment_old;

    // Tags, boundary ids (= index into prm.boundary_conditions).
    std::vector<std::string>                         tags;
    internal::DirichletDofs                          dirichlet;
    std::vector<bool>                                is_dirichlet;
    internal::FixedIntegrals<dealii::Vector<double>> fixed;

    std::vector<internal::Probe>  probes;
    std::vector<dealii::Point<2>> probe_points;
    /// Polygon edges carrying a refine_near_tags tag.
    std::vector<std::array<Point2, 2>> band_segments;

    /// Boundary id of joint faces (contact conductance).
    dealii::types::boundary_id       joint_id = 0;
    std::vector<internal::JointPair> joint_pairs;


    std::ostringstream  timer_stream;
    dealii::TimerOutput timer;

    /// Probe at @p p (throws InputError if outside the rock).
    internal::Probe
    locate_probe(const dealii::Point<2> &p) const;
    /// One theta step of size @p dt (heat_time_stepping.cc).
    void
    theta_step(const double dt, const double theta);
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
    assemble_rhs(const double            t,
                 dealii::Vector<double> &f,
                 double                 &boundary_rate,
                 double                 &source_rate) const;

  private:
    void
    setup_system();
    void
    assemble_fixed();
    internal::StepOperator &
    get_operator(const double dt, const double theta);
  };
} // namespace rockdda::thermal

#endif
