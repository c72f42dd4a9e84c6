/**
 * @file
 * Transient heat conduction rho c_p dT/dt = div(lambda grad T) + s in the 2D
 * rock (deal.II, FE_Q), with boundary conditions per boundary tag, per-block
 * materials, probes and per-block moments of the temperature.
 *
 * The header is deal.II-free (the solver is a pimpl), so that users of the
 * solver compile fast.
 */
#ifndef ROCKDDA_THERMAL_HEAT_SOLVER_H
#define ROCKDDA_THERMAL_HEAT_SOLVER_H

#include <array>
#include <complex>
#include <functional>
#include <limits>
#include <memory>
#include <string>
#include <utility>
#include <vector>

namespace rockdda::thermal
{
  namespace internal
  {
    class HeatSystemBase;
  }

  /// A 2D point or vector (m).
  using Point2 = std::array<double, 2>;

  /// A scalar field of position (m) and time (s).
  using SpaceTimeFunction
    = std::function<double(const double x, const double y, const double t)>;

  /// Thermal properties of one rock material (SI units).
  struct Material
  {
    std::string name          = "rock";
    double      conductivity  = 1.7;   ///< lambda, W/(m K)
    double      density       = 2600.; ///< rho, kg/m^3
    double      heat_capacity = 810.;  ///< c_p, J/(kg K)

    /// Diffusivity kappa = lambda / (rho c_p), m^2/s.
    double
    diffusivity() const
    {
      return conductivity / (density * heat_capacity);
    }
  };

  /**
   * One block (region) of the rock: a simple polygon, counter-clockwise or
   * clockwise, with one boundary tag per edge (edge i runs from vertex i to
   * vertex i+1). Edges shared by two blocks are joints; their tag is used
   * only when the blocks are insulated from each other.
   */
  struct Block
  {
    std::string              name;
    std::vector<Point2>      vertices;
    std::vector<std::string> edge_tags;
    unsigned int material = 0; ///< index into HeatParameters::materials
  };

  /// A boundary condition on all faces carrying one tag.
  struct BoundaryCondition
  {
    enum class Type
    {
      temperature, ///< T = value(x, y, t)
      convective,  ///< lambda dT/dn = h (value(x, y, t) - T), value = air T
      flux         ///< lambda dT/dn = value(x, y, t), W/m^2 into the rock
    };
    std::string       tag;
    Type              type = Type::flux;
    SpaceTimeFunction value; ///< K (temperature, air) or W/m^2 (flux)
    double heat_transfer_coefficient = 0.; ///< h, W/(m^2 K), convective
    /// True if value does not depend on position (cheaper right-hand side).
    bool uniform = true;
  };

  /// Time stepping methods.
  enum class TimeStepper
  {
    crank_nicolson, ///< theta = 1/2, second order
    backward_euler, ///< theta = 1, first order, L-stable
    arkode          ///< SUNDIALS ARKODE (DIRK, adaptive error control)
  };

  /// Everything the solver needs (plain data; SI units).
  struct HeatParameters
  {
    std::vector<Material>          materials{Material()};
    std::vector<Block>             blocks;
    std::vector<BoundaryCondition> boundary_conditions;
    /// Heat conduction across joints (edges shared by two blocks).
    enum class JointContact
    {
      perfect,     ///< the blocks form one conforming domain
      conductance, ///< each block is its own mesh; the joint passes
                   ///< q = h_j (T1 - T2) (joint_conductance)
      insulated    ///< each block is its own domain; joint faces use their tag
    } joint_contact
      = JointContact::perfect;
    /// Contact conductance h_j of the joints (JointContact::conductance),
    /// W/(m^2 K); > 0.
    double joint_conductance = 1000.;

    unsigned int degree             = 2;  ///< FE_Q degree, 1..3
    double       coarse_cell_size   = 1.; ///< target coarse cell size, m
    unsigned int global_refinements = 0;
    /// Tags of exposed faces near which the mesh is refined (a priori band).
    std::vector<std::string> refine_near_tags;
    double                   band_width     = 0.; ///< m; 0 = no band
    double                   band_cell_size = 0.; ///< m, cell size in the band

    /// Kelly-estimator refinement and coarsening during the run (theta
    /// scheme), every adaptive_interval steps; the solution is transferred.
    bool         adaptive_refinement = false;
    unsigned int adaptive_interval   = 10; ///< steps between adaptations
    /// Cells holding this fraction of the estimated error are refined.
    double refine_fraction = 0.3;
    /// Cells holding this fraction of the estimated error are coarsened.
    double coarsen_fraction = 0.03;
    /// No refinement of cells of about this size (diameter <= 1.5 times
    /// it), m; 0: limited only by adaptive_max_cells.
    double adaptive_min_cell_size = 0.;
    /// Upper limit of the number of cells; 0: no limit.
    unsigned int adaptive_max_cells = 0;

    TimeStepper stepper    = TimeStepper::crank_nicolson;
    double      time_step  = 86400.; ///< s (theta scheme; ARKODE initial)
    double      start_time = 0.;     ///< s
    /// Crank-Nicolson only: number of backward-Euler start-up steps after
    /// the initial condition (Rannacher smoothing); see doc/theory/heat.md.
    unsigned int rannacher_steps = 2;
    /// Crank-Nicolson only: when the oscillation indicator fires, continue
    /// with backward Euler (reported in HeatStatistics).
    bool   oscillation_fallback      = true;
    double arkode_relative_tolerance = 1e-6;
    double arkode_absolute_tolerance = 1e-6; ///< K
    /// Linear solver of the theta scheme: direct (serial: sparse Cholesky;
    /// MPI: Trilinos Amesos KLU) or CG (serial: SSOR; MPI: AMG).
    bool direct_solver = true;
    /// Use the distributed (p4est + Trilinos, CG + AMG) solver even on one
    /// MPI rank; it is used anyway when the run has more than one rank.
    bool   distributed  = false;
    double cg_tolerance = 1e-12; ///< relative residual

    double initial_temperature = 0.; ///< K (or deg C), uniform
    /// Optional initial field (overrides the uniform value).
    std::function<double(const double x, const double y)> initial_field;
    /// Optional volumetric heat source, W/m^3.
    SpaceTimeFunction source;
  };

  /// Mean temperature of a block and its linear trend (first moments).
  struct BlockMoments
  {
    double area       = 0.; ///< m^2
    double centroid_x = 0.; ///< m
    double centroid_y = 0.; ///< m
    double mean       = 0.; ///< area-averaged T, K
    double moment_x   = 0.; ///< int (T - mean)(x - xc) dA, K m^3
    double moment_y   = 0.; ///< int (T - mean)(y - yc) dA, K m^3
    double gradient_x = 0.; ///< least-squares linear trend dT/dx, K/m
    double gradient_y = 0.; ///< least-squares linear trend dT/dy, K/m
  };

  /// Mesh and cost counters.
  struct HeatStatistics
  {
    unsigned int  n_cells          = 0;
    unsigned int  n_dofs           = 0;
    double        min_cell_size    = 0.; ///< m (diameter)
    double        max_cell_size    = 0.; ///< m
    unsigned long n_steps          = 0;
    unsigned long n_factorizations = 0;
    unsigned long n_rejected_steps = 0; ///< ARKODE error-test failures
    /// dt kappa_max / h_min^2 of the fixed step (> 1: CN may oscillate).
    double stiffness_ratio = 0.;
    /// Number of steps at which a sign-alternating (CN) oscillation of the
    /// temperature increment was detected; see doc/theory/heat.md.
    unsigned long oscillation_steps = 0;
    /// Time at which Crank-Nicolson fell back to backward Euler (s), or
    /// NaN if it did not.
    double        fallback_time = std::numeric_limits<double>::quiet_NaN();
    unsigned long n_adaptations = 0; ///< mesh changes by the Kelly estimator
    unsigned int  max_n_cells   = 0; ///< largest mesh during the run
    /// Heat added by interpolating the field onto adapted meshes (the
    /// transfer is not conservative), J/m; part of the energy balance.
    double mesh_transfer_heat = 0.;
  };

  /**
   * The heat solver. Construct with the parameters (builds the mesh and the
   * matrices and sets the initial condition), then advance_to() later times
   * and query the field in between.
   */
  class HeatSolver
  {
  public:
    /// Throws InputError for invalid parameters or geometry.
    explicit HeatSolver(const HeatParameters &parameters);
    ~HeatSolver();
    HeatSolver(const HeatSolver &) = delete;
    HeatSolver &
    operator=(const HeatSolver &)
      = delete;

    /// Current time, s.
    double
    time() const;

    /// Step (fixed dt, or adaptively with ARKODE) until @p end_time.
    void
    advance_to(const double end_time);

    /// Temperature at a point (throws InputError if outside the rock).
    double
    value(const double x, const double y) const;

    /**
     * A probe: precomputes the cell and shape values of a point once, so
     * that probe_value() is cheap. Returns the probe's index.
     */
    unsigned int
    add_probe(const double x, const double y);

    /// Temperature at probe @p index, K.
    double
    probe_value(const unsigned int index) const;

    /// Mean and first moments of T per block (index as in the parameters).
    std::vector<BlockMoments>
    block_moments() const;

    /// Stored heat int rho c_p T dA (per unit thickness), J/m.
    double
    stored_heat() const;

    /**
     * The periodic response to an ambient temperature Re(e^{i omega t})
     * (K) on every convective boundary, with the sources and the flux data
     * off: T(x, t) = Re(Theta(x) e^{i omega t}) solves the complex system
     * (K + i omega M) Theta = F_conv in one direct solve (M the heat
     * capacity, K the conduction with the joints and the convective term,
     * F_conv the convective load per kelvin of ambient temperature).
     * Returns each block's mean of Theta (index as in the parameters). By
     * linearity, an ambient temperature T_0 + sum_k a_k sin(omega_k t) on
     * convective and adiabatic boundaries has the periodic block means
     * T_0 + sum_k a_k Re(-i m_k e^{i omega_k t}): no spin-up and no time
     * step. Only where harmonic_available() (throws std::logic_error
     * otherwise).
     */
    std::vector<std::complex<double>>
    harmonic_block_means(const double omega) const;

    /// Whether harmonic_block_means() can run: a serial run without
    /// Dirichlet conditions or spatially varying data.
    bool
    harmonic_available() const;

    /**
     * Heat that entered through convective and flux boundaries since the
     * start, integrated in time consistently with the time stepper, J/m.
     */
    double
    boundary_heat_in() const;

    /// Heat added by the volume source since the start, J/m.
    double
    source_heat_in() const;

    /// L2 norm of T - @p exact at the current time, K m.
    double
    l2_error(const SpaceTimeFunction &exact) const;

    /// The field as VTU text (temperature, block index); serial solver.
    std::string
    vtu() const;

    /**
     * The field as VTU files (file name, content) named after @p name: one
     * file NAME.vtu from the serial solver; NAME.pvtu and one piece
     * NAME.RANK.vtu per rank from the distributed solver (all returned on
     * rank 0, nothing on the others). The first entry is the file to
     * reference (.vtu or .pvtu). Collective.
     */
    std::vector<std::pair<std::string, std::string>>
    vtu_files(const std::string &name) const;

    /// True on the rank that writes the results (rank 0, or no MPI).
    bool
    is_output_rank() const;

    /**
     * The state needed to continue the run bit for bit (field, previous
     * increment, time, heat balance, counters), as the bytes of a
     * checkpoint file, with the mesh when it is adaptive. The distributed
     * solver writes its mesh and field into the files @p mesh_files-0.* or
     * -1.* (alternately, so that an interrupted save keeps the previous
     * set) and names them in the bytes; collective.
     */
    std::string
    checkpoint(const std::string &mesh_files = std::string()) const;

    /**
     * Continue from the checkpoint() @p bytes of a solver built from the
     * same parameters; throws InputError naming @p source if they belong
     * to another mesh or are damaged. The time-step operators are rebuilt
     * (one more factorisation than the uninterrupted run counts).
     * Collective.
     */
    void
    restore(const std::string &bytes, const std::string &source);

    /// Mesh and cost counters.
    HeatStatistics
    statistics() const;

    /// Name of the time stepper and linear solver in use.
    std::string
    method_description() const;

    /// Wall-time breakdown (deal.II TimerOutput summary).
    std::string
    timing_summary() const;

  private:
    /// The solver over the serial or the Trilinos linear-algebra types.
    std::unique_ptr<internal::HeatSystemBase> impl;
  };

  /// Amplitude, phase and mean of a sinusoid fitted to samples.
  struct SinusoidFit
  {
    double mean      = 0.;
    double amplitude = 0.;
    double phase = 0.; ///< rad, in (-pi, pi]: fit = mean + A sin(w t + phase)
  };

  /**
   * Least-squares fit of mean + a sin(omega t) + b cos(omega t) to samples
   * (t_i, T_i), typically one whole period.
   */
  SinusoidFit
  fit_sinusoid(const std::vector<double> &t,
               const std::vector<double> &values,
               const double               omega);

  /// Skin depth sqrt(2 kappa / omega) of a periodic half-space, m.
  double
  periodic_skin_depth(const double diffusivity, const double period);

  /// The thesis's seasonal skin depth, Eq. 5.1: sqrt(kappa t_exp / 2), m.
  double
  thesis_skin_depth(const double diffusivity, const double exposure_time);

  /**
   * Check a material: lambda, rho, c_p > 0 and finite. Throws InputError
   * naming @p where.
   */
  void
  validate(const Material &material, const std::string &where);
} // namespace rockdda::thermal

#endif
