/**
 * @file
 * Internal to the thermal subsystem: the heat solver, written once as the
 * class template HeatSystem over the linear-algebra traits of
 * heat_linear_algebra.h (LinearAlgebra::Serial for serial runs,
 * LinearAlgebra::Trilinos for distributed ones), and the interface
 * HeatSystemBase through which HeatSolver runs either. Its member
 * functions live in the files named after what they do: heat_system.cc
 * (setup, probes, the interface), heat_time_stepping.cc (theta scheme, step
 * operators and linear solves), heat_arkode.cc (ARKODE),
 * heat_adaptivity.cc (Kelly refinement) and heat_checkpoint.cc (saving and
 * restoring the state); each instantiates them for both traits.
 */
#ifndef ROCKDDA_THERMAL_HEAT_SYSTEM_H
#define ROCKDDA_THERMAL_HEAT_SYSTEM_H

#include <rockdda/thermal/heat_solver.h>

#include <deal.II/base/index_set.h>
#include <deal.II/base/mpi.h>
#include <deal.II/base/point.h>
#include <deal.II/base/timer.h>
#include <deal.II/dofs/dof_handler.h>
#include <deal.II/fe/fe_q.h>
#include <deal.II/fe/mapping_q1.h>
#include <deal.II/lac/affine_constraints.h>
#include <deal.II/lac/dynamic_sparsity_pattern.h>

#include "heat_assembly.h"
#include "heat_internal.h"
#include "heat_linear_algebra.h"
#include "heat_probes.h"
#include <memory>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

namespace rockdda::thermal::internal
{
  /// What HeatSolver asks of the solver, whichever its linear algebra
  /// (see the members of HeatSolver of the same names), and the time, heat
  /// balance and counters of its steps.
  class HeatSystemBase : public StepState
  {
  public:
    virtual ~HeatSystemBase() = default;
    virtual void
    advance_to(const double end_time)
      = 0;
    virtual double
    value(const double x, const double y) const = 0;
    virtual unsigned int
    add_probe(const double x, const double y)
      = 0;
    virtual double
    probe_value(const unsigned int index) const = 0;
    virtual std::vector<BlockMoments>
    block_moments() const = 0;
    virtual double
    stored_heat() const = 0;
    virtual std::vector<std::complex<double>>
    harmonic_block_means(const double omega) const = 0;
    virtual bool
    harmonic_available() const = 0;
    virtual double
    l2_error(const SpaceTimeFunction &exact) const = 0;
    virtual std::vector<std::pair<std::string, std::string>>
    vtu_files(const std::string &name) const = 0;
    virtual std::string
    vtu() const = 0;
    virtual HeatStatistics
    statistics() const = 0;
    virtual std::string
    method_description() const = 0;
    virtual std::string
    timing_summary() const = 0;
    virtual std::string
    checkpoint(const std::string &mesh_files) const = 0;
    virtual void
    restore(const std::string &bytes, const std::string &source)
      = 0;
  };

  /// The heat solver over the linear-algebra traits @p LA.
  template <typename LA>
  class HeatSystem : public HeatSystemBase
  {
  public:
    using VectorType   = typename LA::Vector;
    using MatrixType   = typename LA::Matrix;
    using StepOperator = typename LA::StepOperator;

    /// Throws InputError for invalid parameters.
    explicit HeatSystem(const HeatParameters &parameters);

    void
    advance_to(const double end_time) override;
    double
    value(const double x, const double y) const override;
    unsigned int
    add_probe(const double x, const double y) override;
    double
    probe_value(const unsigned int index) const override;
    std::vector<BlockMoments>
    block_moments() const override;
    double
    stored_heat() const override;
    std::vector<std::complex<double>>
    harmonic_block_means(const double omega) const override;
    bool
    harmonic_available() const override;
    double
    l2_error(const SpaceTimeFunction &exact) const override;
    std::vector<std::pair<std::string, std::string>>
    vtu_files(const std::string &name) const override;
    std::string
    vtu() const override;
    HeatStatistics
    statistics() const override;
    std::string
    method_description() const override;
    std::string
    timing_summary() const override;
    std::string
    checkpoint(const std::string &mesh_files) const override;
    void
    restore(const std::string &bytes, const std::string &source) override;

    /// Condensed right-hand side at @p t into @p f; returns the boundary
    /// data part of the heat rate (without -w.T) and the source rate.
    void
    assemble_rhs(const double t,
                 VectorType  &f,
                 double      &boundary_rate,
                 double      &source_rate) const;
    /// One theta step of size @p dt (heat_time_stepping.cc).
    void
    theta_step(const double dt, const double theta);
    /// Kelly estimate, refine and coarsen, transfer the field, rebuild.
    void
    adapt_mesh();

    HeatParameters              prm;
    const MPI_Comm              comm;
    const unsigned int          rank, n_ranks;
    typename LA::Triangulation  tria;
    dealii::FE_Q<2>             fe;
    dealii::DoFHandler<2>       dof_handler;
    dealii::MappingQ1<2>        mapping;
    MeshInfo                    mesh;
    dealii::IndexSet            owned, relevant;
    dealii::AffineConstraints<> hanging;
    /// Distributed runs: the hanging and homogeneous Dirichlet constraints.
    dealii::AffineConstraints<>    constraints_hom;
    dealii::DynamicSparsityPattern dsp;
    typename LA::SparsityPattern   sparsity;
    /// Mass and stiffness (hanging nodes condensed, with the joint
    /// conductance); distributed runs assemble them for ARKODE only.
    MatrixType                                 mass, stiffness;
    std::vector<std::unique_ptr<StepOperator>> operators;

    VectorType solution, new_solution, rhs_old, rhs_new, tmp, g_ext,
      increment_old;
    /// Distributed runs: the solution with ghost entries.
    mutable VectorType ghosted;
    mutable bool       ghosted_valid = false;

    /// The joint contact conductance ('Joint contact = conductance').
    typename LA::Joints        joints;
    DirichletDofs              dirichlet;
    std::vector<bool>          is_dirichlet;
    bool                       any_dirichlet = false;
    FixedIntegrals<VectorType> fixed;

    std::vector<Probe>            probes;
    std::vector<dealii::Point<2>> probe_points;

    /// CG iterations of the distributed solves.
    unsigned long linear_iterations = 0;
    /// Checkpoints written (selects the file set of the next one).
    mutable unsigned long checkpoints_written = 0;

    mutable std::ostringstream timer_stream;
    dealii::TimerOutput        timer;

    /// The solution with the ghost entries the rank reads (serial: itself).
    const VectorType &
    field() const;
    /// The probe at @p p (throws InputError if outside the rock).
    Probe
    locate(const dealii::Point<2> &p) const;
    /// Dofs, constraints, sparsity, vectors and Dirichlet dofs of the mesh.
    void
    setup_system();
    /// The fixed integrals (and mass and stiffness where needed).
    void
    assemble_fixed();
    /// The step operator of (@p dt, @p theta), built if not cached.
    StepOperator &
    get_operator(const double dt, const double theta);

  private:
    /// Assemble and factorise @p op (heat_time_stepping.cc, per traits).
    void
    build_operator(StepOperator &op);
    /// new_solution of the step of @p op from solution, rhs_old, rhs_new.
    void
    solve_step(StepOperator &op);
  };

  /// True if the heat solver should run distributed: MPI is initialised
  /// and there is more than one rank, or @p parameters ask for AMG.
  bool
  use_distributed_solver(const HeatParameters &parameters);
} // namespace rockdda::thermal::internal

#endif
