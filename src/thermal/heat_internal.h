/**
 * @file
 * Internal to the thermal subsystem (deal.II types): the mesh of the
 * blocks and the parameter checks shared by the serial and the
 * distributed (MPI) heat solvers.
 */
#ifndef ROCKDDA_THERMAL_HEAT_INTERNAL_H
#define ROCKDDA_THERMAL_HEAT_INTERNAL_H

#include <rockdda/thermal/heat_solver.h>

#include <deal.II/base/point.h>
#include <deal.II/grid/tria.h>

#include <array>
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
   * priori band (only locally owned cells are flagged).
   */
  void
  build_mesh(dealii::Triangulation<2> &tria,
             const HeatParameters     &prm,
             MeshInfo                 &info);

  /// Distance from @p p to the nearest of @p segments, m.
  double
  distance_to_segments(const dealii::Point<2>                   &p,
                       const std::vector<std::array<Point2, 2>> &segments);
} // namespace rockdda::thermal::internal

#endif
