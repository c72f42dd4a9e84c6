/**
 * @file
 * Internal to the thermal subsystem: the state of the distributed heat
 * solver (DistributedHeat::Impl: p4est triangulation, Trilinos matrices
 * and vectors) and the matrices and solver of one theta step. Its member
 * functions live in the files named after what they do:
 * heat_solver_mpi.cc (setup, probes, interface), heat_time_stepping.cc
 * (theta scheme), heat_arkode.cc (ARKODE), heat_adaptivity.cc (Kelly
 * refinement) and heat_checkpoint.cc (saving and restoring the state).
 */
#ifndef ROCKDDA_THERMAL_HEAT_SOLVER_DISTRIBUTED_H
#define ROCKDDA_THERMAL_HEAT_SOLVER_DISTRIBUTED_H

#include <deal.II/base/index_set.h>
#include <deal.II/base/mpi.h>
#include <deal.II/base/point.h>
#include <deal.II/base/timer.h>
#include <deal.II/distributed/tria.h>
#include <deal.II/dofs/dof_handler.h>
#include <deal.II/fe/fe_q.h>
#include <deal.II/fe/mapping_q1.h>
#include <deal.II/lac/affine_constraints.h>
#include <deal.II/lac/dynamic_sparsity_pattern.h>
#include <deal.II/lac/solver_control.h>
#include <deal.II/lac/trilinos_precondition.h>
#include <deal.II/lac/trilinos_solver.h>
#include <deal.II/lac/trilinos_sparse_matrix.h>
#include <deal.II/lac/trilinos_vector.h>

#include "heat_assembly.h"
#include "heat_internal.h"
#include "heat_probes.h"
#include "heat_solver_mpi.h"
#include <memory>
#include <sstream>
#include <vector>

namespace rockdda::thermal::internal
{
  /// The vector type of the distributed solver.
  using DistributedVector = dealii::TrilinosWrappers::MPI::Vector;

  /// Matrices and solver of one theta-scheme step size.
  struct DistributedOperator
  {
    double dt    = 0.;
    double theta = 0.;
    /// M + theta dt K with hanging nodes and Dirichlet rows and columns
    /// condensed (homogeneous): the system for T - g.
    dealii::TrilinosWrappers::SparseMatrix a_hom;
    /// M + theta dt K (hanging nodes only): lifts the Dirichlet values.
    dealii::TrilinosWrappers::SparseMatrix a_full;
    /// M - (1 - theta) dt K (hanging nodes only).
    dealii::TrilinosWrappers::SparseMatrix                  b;
    dealii::TrilinosWrappers::PreconditionAMG               amg;
    dealii::SolverControl                                   direct_control;
    std::unique_ptr<dealii::TrilinosWrappers::SolverDirect> direct;
  };



  class DistributedHeat::Impl : public StepState
  {
  public:
    explicit Impl(const HeatParameters &parameters);

    void
    advance_to(const double end_time);
    Probe
    locate(const dealii::Point<2> &p) const;
    void
    update_ghosts() const;

    HeatParameters                                    prm;
    MPI_Comm                                          comm;
    unsigned int                                      rank = 0, n_ranks = 1;
    dealii::parallel::distributed::Triangulation<2>   tria;
    dealii::FE_Q<2>                                   fe;
    dealii::DoFHandler<2>                             dof_handler;
    dealii::MappingQ1<2>                              mapping;
    MeshInfo                                          mesh;
    dealii::IndexSet                                  owned, relevant;
    dealii::AffineConstraints<double>                 hanging, constraints_hom;
    dealii::DynamicSparsityPattern                    dsp;
    std::vector<std::unique_ptr<DistributedOperator>> operators;

    DistributedVector solution, new_solution, rhs_old, rhs_new, tmp, g_ext,
      increment_old;
    mutable DistributedVector ghosted;
    mutable bool              ghosted_valid = false;

    /// The joint contact conductance ('Joint contact = conductance').
    DistributedJoints joints;
    /// Mass and stiffness matrices (hanging nodes condensed), assembled
    /// for ARKODE only.
    dealii::TrilinosWrappers::SparseMatrix mass, stiffness;

    DirichletDofs                     dirichlet;
    bool                              any_dirichlet = false;
    FixedIntegrals<DistributedVector> fixed;

    std::vector<Probe>            probes;
    std::vector<dealii::Point<2>> probe_points;

    unsigned long linear_iterations = 0;
    /// Checkpoints written (selects the file set of the next one).
    unsigned long checkpoints_written = 0;

    std::ostringstream  timer_stream;
    dealii::TimerOutput timer;

    void
    setup_system();
    void
    assemble_fixed();
    void
    assemble_rhs(const double       t,
                 DistributedVector &f,
                 double            &boundary_rate,
                 double            &source_rate) const;
    DistributedOperator &
    get_operator(const double dt, const double theta);
    void
    theta_step(const double dt, const double theta);
    void
    adapt_mesh();
  };
} // namespace rockdda::thermal::internal

#endif
