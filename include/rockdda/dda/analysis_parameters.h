/**
 * @file
 * The run controls that the 2D and the 3D DDA analyses ("dda", "dda3d")
 * share: declared, read and checked once over the dimension.
 */
#ifndef ROCKDDA_DDA_ANALYSIS_PARAMETERS_H
#define ROCKDDA_DDA_ANALYSIS_PARAMETERS_H

#include <rockdda/dda/contact_mechanics.h>
#include <rockdda/dda/linear_solver.h>

#include <deal.II/base/parameter_handler.h>

#include <string>
#include <vector>

namespace rockdda::dda
{
  /**
   * The keys of the DDA analyses that mean the same in 2D and in 3D, in the
   * section of the analysis of dimension @p dim ("DDA" for 2, "DDA 3d" for
   * 3): the block file, the end time, the time step, the dynamic control,
   * the iteration and displacement limits of a step, the shear and fixed
   * point penalties, the strain and contact damping, the settling steps,
   * gravity and the output spacings. Each analysis declares and reads its own
   * keys (contact penalty, minimum time step, seismic input, solver, ...) in
   * the same section, between declare_parameters() / parse_parameters() calls
   * of this class. Where the engines differ (the size a displacement ratio
   * refers to, the direction of gravity, the snapshot files), the help text
   * says so for each dimension.
   */
  template <int dim>
  struct AnalysisParameters
  {
    static_assert(dim == 2 || dim == 3, "DDA is 2D or 3D");

    /// The scene's block file, resolved against the parameter file.
    std::string block_file;
    /// Simulated duration (s), > 0.
    double end_time = 1.;
    /// Largest (and initial) time step (s), > 0.
    double time_step = 1e-3;
    /// Dynamic control parameter (-), in [0, 1].
    double dynamic = 1.;
    /// Kelvin-Voigt viscous time of the blocks' strain (s), >= 0
    /// (dda::StrainDamping).
    double strain_damping = 0.;
    /// Dashpots of the closed contacts (dda::ContactDamping): ratio of
    /// critical (-) and numerical step damping (-), both >= 0.
    double contact_damping = 0., contact_step_damping = 0.;
    /// State-changing open-close iterations before a cut, in [1, 100].
    unsigned int max_open_close = 12;
    /// Largest vertex displacement per step / size (-), in (0, 1].
    double max_displacement_ratio = 0.01;
    /// Shear penalty / normal penalty (-), > 0.
    double shear_ratio = 0.4;
    /// Shear penalty (N/m), >= 0; 0: shear_ratio x the normal penalty
    /// (dda::ContactLaw::fixed_shear_penalty).
    double shear_penalty = 0.;
    /// Force tolerance of the contact conditions, fraction of the lighter
    /// block's weight (dda::ContactLaw::force_tolerance).
    double force_tolerance = 1e-4;
    /// CG tolerance while the contact states settle / the solver
    /// tolerance (-), in [1, 1e6] (inexact Newton; 1: off).
    double inexact_factor = 1.;
    /// Deepest numerical penetration of a closed contact (N / penalty) an
    /// accepted step may have, as a fraction of the smaller block's size
    /// (-), in (0, 0.1] (dda::PlausibilityLimits::penetration_ratio).
    double penetration_ratio = 0.01;
    /// Spring of fixed points (N/m), >= 0; 0: 10 x the contact penalty.
    double fixed_penalty = 0.;
    /// Static steps under gravity before t = 0, in [0, 100000].
    unsigned int settling_steps = 0;
    /// Gravitational acceleration (m/s^2), >= 0.
    double gravity = 9.80665;
    /// Spacing of snapshots (s), >= 0; 0: none.
    double output_interval = 0.1;
    /// Spacing of rows of statistics.csv (s), >= 0; 0: every step.
    double statistics_interval = 0.;
    /// 'Snapshot format' = hdf5: HDF5 + XDMF snapshots (2D; 3D keeps VTU)
    /// and statistics.h5 beside statistics.csv (both).
    bool hdf5_output = false;
    /// Velocity-dependent friction of every joint (JointMaterial::a_minus_b
    /// (-), reference_velocity and min_velocity (m/s)): A - B in [-1, 1],
    /// V0 > 0, 0 < V_min <= V0.
    double a_minus_b = 0., reference_velocity = 1e-6, min_velocity = 1e-6;

    /// Give every joint of @p joints the velocity-dependent friction law
    /// of these parameters (the block file's friction angle is its mu0 =
    /// tan(phi) at V0).
    void
    apply_friction_law(std::vector<JointMaterial> &joints) const;

    /// The analysis's section: "DDA" (2D) or "DDA 3d" (3D).
    static std::string
    section();

    /**
     * Declare the shared keys in the subsection the caller has entered
     * (section()).
     */
    static void
    declare_parameters(dealii::ParameterHandler &prm);

    /**
     * Read the shared keys from the subsection the caller has entered
     * (section()) of parameter file @p prm_file, and check them: the end
     * time and the time step > 0 and at most io::max_planned_steps steps,
     * the displacement ratio in (0, 1], the shear ratio > 0, a block file
     * given (resolved against @p prm_file). Throws InputError naming the
     * file and the key otherwise.
     */
    void
    parse_parameters(dealii::ParameterHandler &prm,
                     const std::string        &prm_file);
  };

  /**
   * The linear solver keys of the DDA analysis of dimension @p dim, in its
   * section (AnalysisParameters<dim>::section()): 'Linear solver',
   * 'Preconditioner', 'Solver tolerance', 'Threads' and, in 2D only (the
   * distributed solver is written for 6 unknowns per block), 'Distributed
   * preconditioner'. Both engines solve with LinearSolverOf<6 or 12>.
   */
  template <int dim>
  struct SolverParameters
  {
    /// Declare the keys in the subsection the caller has entered.
    static void
    declare_parameters(dealii::ParameterHandler &prm);

    /**
     * Read the keys from the subsection the caller has entered, of
     * parameter file @p prm_file; throws InputError naming the file and
     * the key for 'distributed' without MPI.
     */
    static SolverOptions
    parse_parameters(dealii::ParameterHandler &prm,
                     const std::string        &prm_file);
  };
} // namespace rockdda::dda

#endif
