/**
 * @file
 * Internal to the thermal subsystem (deal.II types): what the serial and
 * the distributed (MPI) heat solvers share: the mesh of the blocks, the
 * parameter checks, the cell loads, the step sequence, the block moments
 * and the oscillation indicator.
 */
#ifndef ROCKDDA_THERMAL_HEAT_INTERNAL_H
#define ROCKDDA_THERMAL_HEAT_INTERNAL_H

#include <rockdda/io/output.h>
#include <rockdda/thermal/heat_solver.h>

#include <deal.II/base/index_set.h>
#include <deal.II/base/mpi.h>
#include <deal.II/base/point.h>
#include <deal.II/base/quadrature_lib.h>
#include <deal.II/dofs/dof_handler.h>
#include <deal.II/fe/fe_values.h>
#include <deal.II/fe/mapping.h>
#include <deal.II/grid/tria.h>
#include <deal.II/lac/vector.h>

#include <array>
#include <cmath>
#include <functional>
#include <limits>
#include <stdexcept>
#include <string>
#include <vector>

namespace rockdda::thermal::internal
{
  /// What build_mesh() found: tags, the joint boundary id, band segments.
  struct MeshInfo
  {
    std::vector<std::string>           tags;
    dealii::types::boundary_id         joint_id = 0;
    std::vector<std::array<Point2, 2>> band_segments;
  };

  /// Throw InputError for invalid parameters (degree, materials, steps,
  /// joint conductance, adaptivity settings).
  void
  validate_parameters(const HeatParameters &prm);

  /**
   * Mesh the blocks into @p tria (serial or parallel::distributed): coarse
   * quadrilaterals, boundary ids from the tags (index into
   * prm.boundary_conditions; adiabatic and joint faces after them), then
   * refinement to the coarse cell size, global refinements and the a
   * priori band (only locally owned cells are flagged); with
   * @p coarse_only, the coarse quadrilaterals and their ids only.
   */
  void
  build_mesh(dealii::Triangulation<2> &tria,
             const HeatParameters     &prm,
             MeshInfo                 &info,
             const bool                coarse_only = false);

  /**
   * Cell counts and sizes of @p tria (over all ranks) into @p stats, and
   * the smallest node spacing @p h_min (cell diameter / sqrt(2) / degree).
   */
  void
  update_mesh_statistics(const dealii::Triangulation<2> &tria,
                         const unsigned int              n_dofs,
                         const unsigned int              degree,
                         HeatStatistics                 &stats,
                         double                         &h_min);

  /// Distance from @p p to the nearest of @p segments, m.
  double
  distance_to_segments(const dealii::Point<2>                   &p,
                       const std::vector<std::array<Point2, 2>> &segments);
  /// FEValues and FEFaceValues on (degree + 1)-point Gauss rules, by
  /// default with values, quadrature points and JxW.
  struct CellIntegrators
  {
    CellIntegrators(const dealii::Mapping<2>       &mapping,
                    const dealii::FiniteElement<2> &fe,
                    const dealii::UpdateFlags       cell_flags
                    = dealii::update_values | dealii::update_quadrature_points
                      | dealii::update_JxW_values,
                    const dealii::UpdateFlags face_flags
                    = dealii::update_values | dealii::update_quadrature_points
                      | dealii::update_JxW_values)
        : quadrature(fe.degree + 1)
        , face_quadrature(fe.degree + 1)
        , values(mapping, fe, quadrature, cell_flags)
        , face(mapping, fe, face_quadrature, face_flags)
    {}

    const dealii::QGauss<2> quadrature;
    const dealii::QGauss<1> face_quadrature;
    dealii::FEValues<2>     values;
    dealii::FEFaceValues<2> face;
  };

  /**
   * Clear the adaptation flags of @p cell that would break the limits: no
   * refinement below 'Minimum cell size' (or at all when @p capped, the
   * cell budget being used up), no coarsening above the coarse cell size,
   * nor above the band cell size inside the a priori band of
   * @p band_segments. Returns true if a flag remains.
   */
  template <typename CellIterator>
  bool
  limit_adaptation_flags(
    const CellIterator                       &cell,
    const HeatParameters                     &prm,
    const std::vector<std::array<Point2, 2>> &band_segments,
    const bool                                capped)
  {
    if (cell->refine_flag_set()
        && (capped || cell->diameter() <= 1.5 * prm.adaptive_min_cell_size
            || cell->level() >= 24))
      cell->clear_refine_flag();
    if (cell->coarsen_flag_set())
      {
        const double parent = cell->level() > 0
                                ? cell->parent()->diameter()
                                : std::numeric_limits<double>::max();
        if (parent > 1.5 * prm.coarse_cell_size
            || (!band_segments.empty() && parent > 1.5 * prm.band_cell_size
                && distance_to_segments(cell->center(), band_segments)
                     < prm.band_width + 0.5 * parent))
          cell->clear_coarsen_flag();
      }
    return cell->refine_flag_set() || cell->coarsen_flag_set();
  }

  /**
   * The boundary conditions whose data enter the load vector (flux and
   * convective ones with a value): the indices of those with a spatially
   * uniform value (their load is value(t) times a fixed vector), in
   * order; @p nonuniform says whether any load varies in space (a
   * non-uniform condition or a heat source). Throws InputError for a
   * condition without a value or a negative heat transfer coefficient.
   */
  std::vector<unsigned int>
  uniform_loads(const HeatParameters &prm, bool &nonuniform);

  /// Add the area integrals of 1, x, y, x^2, xy, y^2 at quadrature point
  /// @p x with weight @p jxw to @p geometry.
  inline void
  add_geometry(std::array<double, 6>  &geometry,
               const dealii::Point<2> &x,
               const double            jxw)
  {
    geometry[0] += jxw;
    geometry[1] += x[0] * jxw;
    geometry[2] += x[1] * jxw;
    geometry[3] += x[0] * x[0] * jxw;
    geometry[4] += x[0] * x[1] * jxw;
    geometry[5] += x[1] * x[1] * jxw;
  }

  /**
   * The mean temperature of a block and its linear trend, from its
   * geometric integrals @p g (int 1, x, y, x^2, xy, y^2 dA) and the
   * temperature integrals int T, x T, y T dA (@p t0, @p tx, @p ty).
   */
  BlockMoments
  block_moments_from(const std::array<double, 6> &g,
                     const double                 t0,
                     const double                 tx,
                     const double                 ty);

  /**
   * Add the heat source and the non-uniform flux and convective loads of
   * @p cell at time @p t to @p cell_vector, and their integrals (W/m) to
   * @p boundary_rate and @p source_rate. Returns false (and adds nothing)
   * if the cell has none. @p fe_values and @p fe_face need values,
   * quadrature points and JxW.
   */
  bool
  add_cell_load(const HeatParameters                              &prm,
                const dealii::DoFHandler<2>::active_cell_iterator &cell,
                const double                                       t,
                dealii::FEValues<2>                               &fe_values,
                dealii::FEFaceValues<2>                           &fe_face,
                dealii::Vector<double>                            &cell_vector,
                double &boundary_rate,
                double &source_rate);

  /**
   * Call @p step(h) from @p time (advanced by @p step) to @p end_time:
   * whole steps of exactly @p dt (an interval within 1e-6 dt of a multiple
   * of dt counts as that multiple, so that one factorisation serves the
   * whole run), then one shorter step for a remainder.
   */
  void
  take_steps(const double                      &time,
             const double                       end_time,
             const double                       dt,
             const std::function<void(double)> &step);

  /**
   * The load of the spatially uniform conditions at time @p t: f =
   * sum_s value_s(t) vectors[s] and boundary_rate = sum_s value_s(t)
   * rates[s], over the conditions @p uniform (indices into
   * prm.boundary_conditions). Throws if a value is not finite.
   */
  template <typename VectorType>
  void
  add_uniform_loads(const HeatParameters            &prm,
                    const std::vector<unsigned int> &uniform,
                    const std::vector<VectorType>   &vectors,
                    const std::vector<double>       &rates,
                    const double                     t,
                    VectorType                      &f,
                    double                          &boundary_rate)
  {
    for (unsigned int s = 0; s < uniform.size(); ++s)
      {
        const auto  &bc = prm.boundary_conditions[uniform[s]];
        const double g  = bc.value(0., 0., t);
        if (!std::isfinite(g))
          throw std::runtime_error("heat: boundary value of tag '" + bc.tag
                                   + "' is not finite at t = "
                                   + io::format_number(t, 8) + " s");
        f.add(g, vectors[s]);
        boundary_rate += g * rates[s];
      }
  }


  /**
   * Advance solver @p s (the serial or the distributed one; members prm,
   * time, solution, mass, stiffness, hanging, dirichlet, fixed, stats,
   * boundary_heat, source_heat, rhs_old_valid and assemble_rhs()) from its
   * time to @p end_time with ARKODE (heat_arkode.cc); @p owned are its
   * locally owned dofs, @p comm its communicator.
   */
  template <typename Solver>
  void
  arkode_advance(Solver                 &s,
                 const double            end_time,
                 const dealii::IndexSet &owned,
                 const MPI_Comm          comm);

  /**
   * The theta of the next step: 1/2 (Crank-Nicolson) or 1 (backward
   * Euler) as chosen, but 1 for the first Rannacher start-up steps and
   * after an oscillation fall-back.
   */
  double
  step_theta(const HeatParameters &prm,
             const HeatStatistics &stats,
             const unsigned long   steps_taken);

  /**
   * Crank-Nicolson oscillation indicator, after a step from @p solution
   * with @p increment (new - old): consecutive increments nearly opposite
   * flip; two flips in a row (the stiff-mode oscillation; a smooth solution
   * turning at a peak flips once) count as an oscillating step, and set
   * the fall-back time @p step_end if the scheme (@p theta < 1) should
   * fall back to backward Euler. @p previous becomes @p increment.
   */
  template <typename VectorType>
  void
  check_oscillation(const VectorType &increment,
                    VectorType       &previous,
                    const VectorType &solution,
                    const bool        first_step,
                    const double      theta,
                    const bool        fallback,
                    const double      step_end,
                    bool             &last_step_flipped,
                    HeatStatistics   &stats)
  {
    const double n_new = increment.l2_norm(), n_old = previous.l2_norm();
    const bool   flip
      = !first_step
        && increment.linfty_norm() > 1e-6 * (1. + solution.linfty_norm())
        && (increment * previous) < -0.5 * n_new * n_old;
    const bool oscillating = flip && last_step_flipped;
    last_step_flipped      = flip;
    if (oscillating)
      {
        ++stats.oscillation_steps;
        if (theta < 1. && fallback && std::isnan(stats.fallback_time))
          stats.fallback_time = step_end;
      }
    previous = increment;
  }
  /**
   * The time, heat balance and counters of either solver (the members of
   * its state that theta_step() and the checkpoints use).
   */
  struct StepState
  {
    double         time            = 0.; ///< s
    double         boundary_heat   = 0.; ///< heat in through the boundary, J/m
    double         source_heat     = 0.; ///< heat added by the source, J/m
    double         rate_old        = 0.; ///< boundary heat rate at time, W/m
    double         source_rate_old = 0.; ///< source heat rate at time, W/m
    bool           rhs_old_valid   = false;   ///< the load at time is assembled
    bool           last_step_flipped = false; ///< see check_oscillation()
    unsigned long  steps_taken       = 0;
    double         kappa_max         = 0.; ///< largest diffusivity, m^2/s
    double         h_min             = 0.; ///< smallest node spacing, m
    HeatStatistics stats;

    /// The statistics with the stiffness ratio of the time step @p dt.
    HeatStatistics
    statistics(const double dt) const
    {
      HeatStatistics s  = stats;
      s.stiffness_ratio = dt * kappa_max / (h_min * h_min);
      return s;
    }
  };

  /**
   * One theta step of either solver. @p s is the solver's state (members
   * prm, stats, time, steps_taken, solution, new_solution, tmp, rhs_old,
   * rhs_new, rhs_old_valid, rate_old, source_rate_old, fixed (robin_weights),
   * boundary_heat, source_heat, increment_old, last_step_flipped and
   * assemble_rhs()). The loads at both ends of the step are assembled,
   * @p solve() computes new_solution from solution, rhs_old and rhs_new,
   * the heat that entered is booked with the scheme's own theta weights
   * (so the energy balance holds to round-off), the oscillation indicator
   * is updated and the state moves to time + dt.
   */
  template <typename State, typename Solve>
  void
  theta_step(State &s, const double dt, const double theta, Solve &&solve)
  {
    if (!s.rhs_old_valid)
      {
        s.assemble_rhs(s.time, s.rhs_old, s.rate_old, s.source_rate_old);
        s.rate_old -= s.fixed.robin_weights * s.solution;
        s.rhs_old_valid = true;
      }
    double rate_new = 0., source_rate_new = 0.;
    s.assemble_rhs(s.time + dt, s.rhs_new, rate_new, source_rate_new);
    solve();
    rate_new -= s.fixed.robin_weights * s.new_solution;
    s.boundary_heat += dt * (theta * rate_new + (1. - theta) * s.rate_old);
    s.source_heat
      += dt * (theta * source_rate_new + (1. - theta) * s.source_rate_old);
    s.rate_old        = rate_new;
    s.source_rate_old = source_rate_new;
    s.rhs_old.swap(s.rhs_new);

    s.tmp = s.new_solution;
    s.tmp -= s.solution;
    check_oscillation(s.tmp,
                      s.increment_old,
                      s.solution,
                      s.steps_taken == 0,
                      theta,
                      s.prm.oscillation_fallback,
                      s.time + dt,
                      s.last_step_flipped,
                      s.stats);
    s.solution.swap(s.new_solution);
    s.time += dt;
    ++s.steps_taken;
    ++s.stats.n_steps;
  }
} // namespace rockdda::thermal::internal

#endif
