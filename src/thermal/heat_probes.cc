/**
 * @file
 * Evaluating the temperature field of either heat solver (see
 * heat_probes.h): probe weights and the L2 error, instantiated for the
 * serial and the Trilinos vector.
 */
#include "heat_probes.h"

#include <deal.II/base/quadrature_lib.h>
#include <deal.II/fe/fe_values.h>
#include <deal.II/lac/trilinos_vector.h>
#include <deal.II/lac/vector.h>

#include "heat_internal.h"
#include <cmath>

namespace rockdda::thermal::internal
{
  using namespace dealii;

  void
  fill_probe(const Mapping<2>                          &mapping,
             const DoFHandler<2>::active_cell_iterator &cell,
             const Point<2>                            &unit,
             Probe                                     &probe)
  {
    const Quadrature<2> q(GeometryInfo<2>::project_to_unit_cell(unit));
    FEValues<2>         fe_values(mapping, cell->get_fe(), q, update_values);
    fe_values.reinit(cell);
    probe.dofs.resize(cell->get_fe().n_dofs_per_cell());
    cell->get_dof_indices(probe.dofs);
    probe.weights.clear();
    for (unsigned int i = 0; i < probe.dofs.size(); ++i)
      probe.weights.push_back(fe_values.shape_value(i, 0));
  }



  BlockMoments
  block_moments_from(const std::array<double, 6> &g,
                     const double                 t0,
                     const double                 tx,
                     const double                 ty)
  {
    BlockMoments m;
    m.area           = g[0];
    m.centroid_x     = g[1] / g[0];
    m.centroid_y     = g[2] / g[0];
    m.mean           = t0 / g[0];
    m.moment_x       = tx - m.centroid_x * t0;
    m.moment_y       = ty - m.centroid_y * t0;
    const double ixx = g[3] - g[1] * g[1] / g[0];
    const double ixy = g[4] - g[1] * g[2] / g[0];
    const double iyy = g[5] - g[2] * g[2] / g[0];
    const double det = ixx * iyy - ixy * ixy;
    m.gradient_x     = (iyy * m.moment_x - ixy * m.moment_y) / det;
    m.gradient_y     = (ixx * m.moment_y - ixy * m.moment_x) / det;
    return m;
  }



  template <typename VectorType>
  double
  l2_error_of(const Mapping<2>        &mapping,
              const DoFHandler<2>     &dof_handler,
              const VectorType        &field,
              const SpaceTimeFunction &exact,
              const double             t,
              const MPI_Comm           comm)
  {
    const QGauss<2>     quadrature(dof_handler.get_fe().degree + 2);
    FEValues<2>         fe_values(mapping,
                          dof_handler.get_fe(),
                          quadrature,
                          update_values | update_quadrature_points
                            | update_JxW_values);
    std::vector<double> v(quadrature.size());
    double              sum = 0.;
    for (const auto &cell : dof_handler.active_cell_iterators())
      if (cell->is_locally_owned())
        {
          fe_values.reinit(cell);
          fe_values.get_function_values(field, v);
          for (const unsigned int q : fe_values.quadrature_point_indices())
            {
              const auto  &x = fe_values.quadrature_point(q);
              const double e = v[q] - exact(x[0], x[1], t);
              sum += e * e * fe_values.JxW(q);
            }
        }
    return std::sqrt(Utilities::MPI::sum(sum, comm));
  }

  template double
  l2_error_of(const Mapping<2> &,
              const DoFHandler<2> &,
              const Vector<double> &,
              const SpaceTimeFunction &,
              const double,
              const MPI_Comm);
  template double
  l2_error_of(const Mapping<2> &,
              const DoFHandler<2> &,
              const TrilinosWrappers::MPI::Vector &,
              const SpaceTimeFunction &,
              const double,
              const MPI_Comm);
} // namespace rockdda::thermal::internal
