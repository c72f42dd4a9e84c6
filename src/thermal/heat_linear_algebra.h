/**
 * @file
 * Internal to the thermal subsystem: the linear-algebra types the heat
 * solver (internal::HeatSystem, heat_system.h) is written over, as a
 * traits class per kind of run, in the way of deal.II's step-40 and
 * ASPECT: LinearAlgebra::Serial (deal.II Triangulation, Vector and
 * SparseMatrix; Eigen's sparse Cholesky or CG + SSOR) and
 * LinearAlgebra::Trilinos (p4est triangulation, Trilinos MPI vectors and
 * matrices; Amesos KLU or CG + AMG). Each names its triangulation, vector,
 * matrix, sparsity pattern, joint-conductance data and step operator (the
 * matrices and the solver of one theta step), and the few calls that
 * differ between the types (creating the triangulation, sizing vectors and
 * matrices, finishing the sparsity pattern).
 */
#ifndef ROCKDDA_THERMAL_HEAT_LINEAR_ALGEBRA_H
#define ROCKDDA_THERMAL_HEAT_LINEAR_ALGEBRA_H

#include <deal.II/base/index_set.h>
#include <deal.II/base/mpi.h>
#include <deal.II/distributed/tria.h>
#include <deal.II/grid/tria.h>
#include <deal.II/lac/dynamic_sparsity_pattern.h>
#include <deal.II/lac/precondition.h>
#include <deal.II/lac/solver_control.h>
#include <deal.II/lac/sparse_matrix.h>
#include <deal.II/lac/sparsity_pattern.h>
#include <deal.II/lac/sparsity_tools.h>
#include <deal.II/lac/trilinos_precondition.h>
#include <deal.II/lac/trilinos_solver.h>
#include <deal.II/lac/trilinos_sparse_matrix.h>
#include <deal.II/lac/trilinos_vector.h>
#include <deal.II/lac/vector.h>

#include <Eigen/SparseCholesky>
#include <Eigen/SparseCore>

#include "heat_assembly.h"
#include <memory>
#include <vector>

namespace rockdda::thermal::internal::LinearAlgebra
{
  /**
   * Serial runs: deal.II's serial types on all cells of one process (the
   * 2:1 balance at vertices that p4est enforces, so that both kinds of run
   * build the same meshes), direct solves by Eigen's sparse LDL^T.
   */
  struct Serial
  {
    static constexpr bool distributed = false;

    using Triangulation   = dealii::Triangulation<2>;
    using Vector          = dealii::Vector<double>;
    using Matrix          = dealii::SparseMatrix<double>;
    using SparsityPattern = dealii::SparsityPattern;
    /// The faces facing each other across the joints.
    using Joints = std::vector<JointPair>;

    /// Matrices and factorisation of one theta-scheme step size.
    struct StepOperator
    {
      double dt    = 0.;
      double theta = 0.;
      Matrix a;     ///< M + theta dt K (hanging-condensed)
      Matrix a_mod; ///< a with Dirichlet rows/cols removed
      Matrix b;     ///< M - (1 - theta) dt K
      dealii::PreconditionSSOR<Matrix> ssor;
      // The per-step work of the direct path in Eigen (serial, no task
      // overhead for the small systems of long runs): b, the Dirichlet
      // columns of a, and the sparse Cholesky (LDL^T) factors of a_mod.
      Eigen::SparseMatrix<double, Eigen::RowMajor> eigen_b, eigen_a_dirichlet;
      Eigen::SimplicialLDLT<Eigen::SparseMatrix<double>> ldlt;
    };

    static MPI_Comm
    communicator()
    {
      return MPI_COMM_SELF;
    }

    static Triangulation
    create_triangulation()
    {
      return Triangulation(Triangulation::limit_level_difference_at_vertices);
    }

    static void
    reinit(Vector &v, const dealii::IndexSet &owned, const MPI_Comm)
    {
      v.reinit(owned.size());
    }

    /// The pattern of the matrices from @p dsp (which is then released).
    static void
    finish_sparsity(dealii::DynamicSparsityPattern &dsp,
                    SparsityPattern                &pattern,
                    const dealii::IndexSet &,
                    const dealii::IndexSet &,
                    const MPI_Comm)
    {
      pattern.copy_from(dsp);
      dsp.reinit(0, 0);
    }

    static void
    reinit(Matrix &m,
           const dealii::DynamicSparsityPattern &,
           const SparsityPattern &pattern,
           const dealii::IndexSet &,
           const MPI_Comm)
    {
      m.reinit(pattern);
    }
  };



  /// Distributed runs on all ranks of MPI_COMM_WORLD: p4est and Trilinos.
  struct Trilinos
  {
    static constexpr bool distributed = true;

    using Triangulation = dealii::parallel::distributed::Triangulation<2>;
    using Vector        = dealii::TrilinosWrappers::MPI::Vector;
    using Matrix        = dealii::TrilinosWrappers::SparseMatrix;
    /// The matrices are built from the distributed dynamic pattern itself.
    struct SparsityPattern
    {};
    /// The joint faces of all ranks (heat_joints.cc).
    using Joints = DistributedJoints;

    /// Matrices and solver of one theta-scheme step size.
    struct StepOperator
    {
      double dt    = 0.;
      double theta = 0.;
      /// M + theta dt K with hanging nodes and Dirichlet rows and columns
      /// condensed (homogeneous): the system for T - g.
      Matrix a_hom;
      /// M + theta dt K (hanging nodes only): lifts the Dirichlet values.
      Matrix a_full;
      /// M - (1 - theta) dt K (hanging nodes only).
      Matrix                                                  b;
      dealii::TrilinosWrappers::PreconditionAMG               amg;
      dealii::SolverControl                                   direct_control;
      std::unique_ptr<dealii::TrilinosWrappers::SolverDirect> direct;
    };

    static MPI_Comm
    communicator()
    {
      return MPI_COMM_WORLD;
    }

    static Triangulation
    create_triangulation()
    {
      return Triangulation(MPI_COMM_WORLD);
    }

    static void
    reinit(Vector &v, const dealii::IndexSet &owned, const MPI_Comm comm)
    {
      v.reinit(owned, comm);
    }

    /// Distribute @p dsp, which the matrices are then built from.
    static void
    finish_sparsity(dealii::DynamicSparsityPattern &dsp,
                    SparsityPattern &,
                    const dealii::IndexSet &owned,
                    const dealii::IndexSet &relevant,
                    const MPI_Comm          comm)
    {
      dealii::SparsityTools::distribute_sparsity_pattern(dsp,
                                                         owned,
                                                         comm,
                                                         relevant);
    }

    static void
    reinit(Matrix                               &m,
           const dealii::DynamicSparsityPattern &dsp,
           const SparsityPattern &,
           const dealii::IndexSet &owned,
           const MPI_Comm          comm)
    {
      m.reinit(owned, owned, dsp, comm);
    }
  };
} // namespace rockdda::thermal::internal::LinearAlgebra

#endif
