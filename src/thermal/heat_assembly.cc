/**
 * @file
 * The assembly of the heat equation for both linear-algebra types (see
 * heat_assembly.h): cell matrices, fixed integrals, loads, Dirichlet data
 * with the explicit instantiations for dealii::Vector<double> (serial) and
 * the Trilinos MPI vector (distributed). The joint contact conductance is
 * in heat_joints.cc.
 */
#include "heat_assembly.h"

#include <rockdda/io/error.h>
#include <rockdda/io/output.h>

#include <deal.II/base/quadrature_lib.h>
#include <deal.II/dofs/dof_tools.h>
#include <deal.II/lac/trilinos_vector.h>
#include <deal.II/lac/vector.h>

#include "heat_internal.h"
#include <algorithm>
#include <cmath>
#include <map>
#include <set>
#include <stdexcept>

namespace rockdda::thermal::internal
{
  using namespace dealii;

  namespace
  {
    /// Size @p v for the @p owned dofs: all dofs of a serial vector.
    void
    reinit_vector(Vector<double> &v, const IndexSet &owned, const MPI_Comm)
    {
      v.reinit(owned.size());
    }

    void
    reinit_vector(TrilinosWrappers::MPI::Vector &v,
                  const IndexSet                &owned,
                  const MPI_Comm                 comm)
    {
      v.reinit(owned, comm);
    }
  } // namespace



  std::vector<unsigned int>
  uniform_loads(const HeatParameters &prm, bool &nonuniform)
  {
    std::vector<unsigned int> uniform;
    nonuniform = static_cast<bool>(prm.source);
    for (unsigned int k = 0; k < prm.boundary_conditions.size(); ++k)
      {
        const auto &bc = prm.boundary_conditions[k];
        if (!bc.value && bc.type != BoundaryCondition::Type::flux)
          throw InputError("heat: boundary condition for tag '" + bc.tag
                           + "' has no value");
        if (bc.type == BoundaryCondition::Type::convective
            && !(bc.heat_transfer_coefficient >= 0.))
          throw InputError("heat: the heat transfer coefficient of tag '"
                           + bc.tag + "' must be >= 0 W/(m^2 K)");
        if (bc.type == BoundaryCondition::Type::temperature || !bc.value)
          continue;
        if (bc.uniform)
          uniform.push_back(k);
        else
          nonuniform = true;
      }
    return uniform;
  }



  bool
  add_cell_load(const HeatParameters                      &prm,
                const DoFHandler<2>::active_cell_iterator &cell,
                const double                               t,
                FEValues<2>                               &fe_values,
                FEFaceValues<2>                           &fe_face,
                Vector<double>                            &cell_vec,
                double                                    &boundary_rate,
                double                                    &source_rate)
  {
    const unsigned int dpc = cell_vec.size();
    bool               any = false;
    if (prm.source)
      {
        any = true;
        fe_values.reinit(cell);
        for (const unsigned int q : fe_values.quadrature_point_indices())
          {
            const auto  &x = fe_values.quadrature_point(q);
            const double s = prm.source(x[0], x[1], t) * fe_values.JxW(q);
            source_rate += s;
            for (unsigned int i = 0; i < dpc; ++i)
              cell_vec(i) += s * fe_values.shape_value(i, q);
          }
      }
    for (const auto fi : cell->face_indices())
      if (cell->face(fi)->at_boundary()
          && cell->face(fi)->boundary_id() < prm.boundary_conditions.size())
        {
          const auto &bc
            = prm.boundary_conditions[cell->face(fi)->boundary_id()];
          if (bc.uniform || !bc.value
              || bc.type == BoundaryCondition::Type::temperature)
            continue;
          any = true;
          fe_face.reinit(cell, fi);
          const double w = bc.type == BoundaryCondition::Type::convective
                             ? bc.heat_transfer_coefficient
                             : 1.;
          for (const unsigned int q : fe_face.quadrature_point_indices())
            {
              const auto  &x = fe_face.quadrature_point(q);
              const double g = w * bc.value(x[0], x[1], t) * fe_face.JxW(q);
              boundary_rate += g;
              for (unsigned int i = 0; i < dpc; ++i)
                cell_vec(i) += g * fe_face.shape_value(i, q);
            }
        }
    return any;
  }



  void
  cell_matrices(const HeatParameters                      &prm,
                const DoFHandler<2>::active_cell_iterator &cell,
                const FEValues<2>                         &fe_values,
                FEFaceValues<2>                           &fe_face,
                FullMatrix<double>                        &cell_mass,
                FullMatrix<double>                        &cell_stiff)
  {
    const unsigned int dpc = fe_values.get_fe().n_dofs_per_cell();
    const Material    &mat
      = prm.materials[prm.blocks[cell->material_id()].material];
    const double rho_c = mat.density * mat.heat_capacity;
    cell_mass          = 0.;
    cell_stiff         = 0.;
    for (const unsigned int q : fe_values.quadrature_point_indices())
      {
        const double jxw = fe_values.JxW(q);
        for (unsigned int i = 0; i < dpc; ++i)
          for (unsigned int j = 0; j < dpc; ++j)
            {
              cell_mass(i, j) += rho_c * fe_values.shape_value(i, q)
                                 * fe_values.shape_value(j, q) * jxw;
              cell_stiff(i, j)
                += mat.conductivity
                   * (fe_values.shape_grad(i, q) * fe_values.shape_grad(j, q))
                   * jxw;
            }
      }
    for (const auto f : cell->face_indices())
      if (cell->face(f)->at_boundary()
          && cell->face(f)->boundary_id() < prm.boundary_conditions.size())
        {
          const auto &bc
            = prm.boundary_conditions[cell->face(f)->boundary_id()];
          if (bc.type != BoundaryCondition::Type::convective || !bc.value)
            continue;
          fe_face.reinit(cell, f);
          const double h = bc.heat_transfer_coefficient;
          for (const unsigned int q : fe_face.quadrature_point_indices())
            for (unsigned int i = 0; i < dpc; ++i)
              for (unsigned int j = 0; j < dpc; ++j)
                cell_stiff(i, j) += h * fe_face.shape_value(i, q)
                                    * fe_face.shape_value(j, q)
                                    * fe_face.JxW(q);
        }
  }



  template <typename VectorType>
  void
  assemble_fixed_integrals(const AssemblyScope        &scope,
                           const IndexSet             &owned,
                           FixedIntegrals<VectorType> &fixed,
                           const CellMatrixSink       &matrices)
  {
    const auto &[prm, mapping, dof_handler, hanging, comm] = scope;
    const FiniteElement<2> &fe = dof_handler.get_fe();
    CellIntegrators         integrators(mapping,
                                fe,
                                update_values | update_quadrature_points
                                  | update_JxW_values
                                  | (matrices ? update_gradients
                                                      : update_default),
                                update_values | update_JxW_values);
    FEValues<2>            &fe_values = integrators.values;
    FEFaceValues<2>        &fe_face   = integrators.face;
    const unsigned int      dpc       = fe.n_dofs_per_cell();
    FullMatrix<double>      cell_mass(dpc, dpc), cell_stiff(dpc, dpc);
    Vector<double> v_cap(dpc), v_phi(dpc), v_x(dpc), v_y(dpc), v_load(dpc),
      v_robin(dpc);
    std::vector<types::global_dof_index> dofs(dpc);

    fixed.uniform_bc = uniform_loads(prm, fixed.nonuniform);
    fixed.uniform_vectors.resize(fixed.uniform_bc.size());
    fixed.uniform_rates.assign(fixed.uniform_bc.size(), 0.);
    std::vector<int> uniform_slot(prm.boundary_conditions.size(), -1);
    for (unsigned int s = 0; s < fixed.uniform_bc.size(); ++s)
      {
        uniform_slot[fixed.uniform_bc[s]] = s;
        reinit_vector(fixed.uniform_vectors[s], owned, comm);
      }
    reinit_vector(fixed.capacity, owned, comm);
    reinit_vector(fixed.robin_weights, owned, comm);
    // (reinit, not assignment: Trilinos vector assignment may keep the old
    // parallel layout after the mesh has changed.)
    const unsigned int n_blocks = prm.blocks.size();
    for (auto *vectors :
         {&fixed.block_phi, &fixed.block_xphi, &fixed.block_yphi})
      {
        vectors->resize(n_blocks);
        for (auto &v : *vectors)
          reinit_vector(v, owned, comm);
      }
    fixed.block_geometry.assign(
      n_blocks, std::array<double, 6>{{0., 0., 0., 0., 0., 0.}});

    for (const auto &cell : dof_handler.active_cell_iterators())
      if (cell->is_locally_owned())
        {
          fe_values.reinit(cell);
          cell->get_dof_indices(dofs);
          const unsigned int block = cell->material_id();
          const Material    &mat   = prm.materials[prm.blocks[block].material];
          const double       rho_c = mat.density * mat.heat_capacity;
          auto              &geo   = fixed.block_geometry[block];
          v_cap                    = 0.;
          v_phi                    = 0.;
          v_x                      = 0.;
          v_y                      = 0.;
          for (const unsigned int q : fe_values.quadrature_point_indices())
            {
              const double jxw = fe_values.JxW(q);
              const auto  &x   = fe_values.quadrature_point(q);
              add_geometry(geo, x, jxw);
              for (unsigned int i = 0; i < dpc; ++i)
                {
                  const double phi = fe_values.shape_value(i, q) * jxw;
                  v_cap(i) += rho_c * phi;
                  v_phi(i) += phi;
                  v_x(i) += x[0] * phi;
                  v_y(i) += x[1] * phi;
                }
            }
          hanging.distribute_local_to_global(v_cap, dofs, fixed.capacity);
          hanging.distribute_local_to_global(v_phi,
                                             dofs,
                                             fixed.block_phi[block]);
          hanging.distribute_local_to_global(v_x,
                                             dofs,
                                             fixed.block_xphi[block]);
          hanging.distribute_local_to_global(v_y,
                                             dofs,
                                             fixed.block_yphi[block]);

          for (const auto f : cell->face_indices())
            if (cell->face(f)->at_boundary()
                && cell->face(f)->boundary_id()
                     < prm.boundary_conditions.size())
              {
                const unsigned int k  = cell->face(f)->boundary_id();
                const auto        &bc = prm.boundary_conditions[k];
                if (bc.type == BoundaryCondition::Type::temperature
                    || !bc.value)
                  continue;
                fe_face.reinit(cell, f);
                const bool convective
                  = bc.type == BoundaryCondition::Type::convective;
                const double h = convective ? bc.heat_transfer_coefficient : 0.;
                const double w = convective ? h : 1.;
                double       ds = 0.;
                v_load          = 0.;
                v_robin         = 0.;
                for (const unsigned int q : fe_face.quadrature_point_indices())
                  {
                    const double jxw = fe_face.JxW(q);
                    ds += jxw;
                    for (unsigned int i = 0; i < dpc; ++i)
                      {
                        v_load(i) += w * fe_face.shape_value(i, q) * jxw;
                        v_robin(i) += h * fe_face.shape_value(i, q) * jxw;
                      }
                  }
                hanging.distribute_local_to_global(v_robin,
                                                   dofs,
                                                   fixed.robin_weights);
                if (uniform_slot[k] >= 0)
                  {
                    hanging.distribute_local_to_global(
                      v_load, dofs, fixed.uniform_vectors[uniform_slot[k]]);
                    fixed.uniform_rates[uniform_slot[k]] += w * ds;
                  }
              }

          if (matrices)
            {
              cell_matrices(
                prm, cell, fe_values, fe_face, cell_mass, cell_stiff);
              matrices(cell, dofs, cell_mass, cell_stiff);
            }
        }
    fixed.capacity.compress(VectorOperation::add);
    fixed.robin_weights.compress(VectorOperation::add);
    for (auto &v : fixed.uniform_vectors)
      v.compress(VectorOperation::add);
    for (unsigned int b = 0; b < n_blocks; ++b)
      {
        fixed.block_phi[b].compress(VectorOperation::add);
        fixed.block_xphi[b].compress(VectorOperation::add);
        fixed.block_yphi[b].compress(VectorOperation::add);
        for (auto &g : fixed.block_geometry[b])
          g = Utilities::MPI::sum(g, comm);
      }
    for (auto &r : fixed.uniform_rates)
      r = Utilities::MPI::sum(r, comm);
  }



  template <typename VectorType>
  LoadRates
  FixedIntegrals<VectorType>::loads(const AssemblyScope &scope,
                                    const double         t,
                                    VectorType          &f) const
  {
    const auto &[prm, mapping, dof_handler, hanging, comm] = scope;

    LoadRates rates;
    f = 0.;
    add_uniform_loads(
      prm, uniform_bc, uniform_vectors, uniform_rates, t, f, rates.boundary);
    if (!nonuniform)
      return rates;

    CellIntegrators    integrators(mapping, dof_handler.get_fe());
    const unsigned int dpc = dof_handler.get_fe().n_dofs_per_cell();
    Vector<double>     cell_vec(dpc);
    std::vector<types::global_dof_index> dofs(dpc);
    double                               local_boundary = 0., local_source = 0.;
    for (const auto &cell : dof_handler.active_cell_iterators())
      if (cell->is_locally_owned())
        {
          cell_vec = 0.;
          if (add_cell_load(prm,
                            cell,
                            t,
                            integrators.values,
                            integrators.face,
                            cell_vec,
                            local_boundary,
                            local_source))
            {
              cell->get_dof_indices(dofs);
              hanging.distribute_local_to_global(cell_vec, dofs, f);
            }
        }
    f.compress(VectorOperation::add);
    rates.boundary += Utilities::MPI::sum(local_boundary, comm);
    rates.source += Utilities::MPI::sum(local_source, comm);
    return rates;
  }



  void
  DirichletDofs::find(const HeatParameters      &prm,
                      const Mapping<2>          &mapping,
                      const DoFHandler<2>       &dof_handler,
                      const AffineConstraints<> &hanging)
  {
    dofs.clear();
    points.clear();
    bc.clear();
    const IndexSet &owned = dof_handler.locally_owned_dofs();
    std::map<types::global_dof_index, Point<2>> support;
    DoFTools::map_dofs_to_support_points(mapping, dof_handler, support);
    std::set<types::global_dof_index> taken;
    for (unsigned int k = 0; k < prm.boundary_conditions.size(); ++k)
      if (prm.boundary_conditions[k].type
          == BoundaryCondition::Type::temperature)
        {
          const IndexSet set
            = DoFTools::extract_boundary_dofs(dof_handler,
                                              ComponentMask(),
                                              {types::boundary_id(k)});
          for (const auto i : set)
            if (owned.is_element(i) && !hanging.is_constrained(i)
                && taken.insert(i).second)
              {
                dofs.push_back(i);
                points.push_back(support.at(i));
                bc.push_back(k);
              }
        }
  }



  template <typename VectorType>
  void
  DirichletDofs::set_values(const HeatParameters &prm,
                            const double          t,
                            VectorType           &v) const
  {
    for (std::size_t d = 0; d < dofs.size(); ++d)
      {
        const auto  &p         = points[d];
        const auto  &condition = prm.boundary_conditions[bc[d]];
        const double g         = condition.value(p[0], p[1], t);
        if (!std::isfinite(g))
          throw std::runtime_error("heat: temperature of tag '" + condition.tag
                                   + "' is not finite at t = "
                                   + io::format_number(t, 8) + " s");
        v[dofs[d]] = g;
      }
  }



#define ROCKDDA_HEAT_ASSEMBLY_INSTANTIATE(VectorType)                         \
  template void assemble_fixed_integrals<VectorType>(                         \
    const AssemblyScope &,                                                    \
    const IndexSet &,                                                         \
    FixedIntegrals<VectorType> &,                                             \
    const CellMatrixSink &);                                                  \
  template LoadRates FixedIntegrals<VectorType>::loads(const AssemblyScope &, \
                                                       const double,          \
                                                       VectorType &) const;   \
  template void DirichletDofs::set_values<VectorType>(const HeatParameters &, \
                                                      const double,           \
                                                      VectorType &) const;

  ROCKDDA_HEAT_ASSEMBLY_INSTANTIATE(Vector<double>)
  ROCKDDA_HEAT_ASSEMBLY_INSTANTIATE(TrilinosWrappers::MPI::Vector)
#undef ROCKDDA_HEAT_ASSEMBLY_INSTANTIATE
} // namespace rockdda::thermal::internal
