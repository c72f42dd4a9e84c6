/**
 * @file
 * The joint contact conductance h_j int_joint (T_a - T_b)(v_a - v_b) ds
 * between the faces of different blocks that touch (heat_assembly.h):
 * pairing the faces, the pair matrices and their assembly, for the serial
 * solver (all cells at hand) and for the distributed one, where the two
 * faces of a joint may lie on different ranks (DistributedJoints: every
 * rank publishes its joint faces, and each rank assembles the rows of the
 * faces it owns).
 */
#include <deal.II/base/mpi.h>
#include <deal.II/base/quadrature_lib.h>
#include <deal.II/base/utilities.h>
#include <deal.II/fe/fe_values.h>
#include <deal.II/lac/trilinos_sparse_matrix.h>

#include "heat_assembly.h"
#include <algorithm>
#include <array>
#include <boost/serialization/utility.hpp>
#include <boost/serialization/vector.hpp>
#include <cmath>

namespace rockdda::thermal::internal
{
  using namespace dealii;

  namespace
  {
    /**
     * If the faces @p a0 - @p a1 and @p b0 - @p b1 are collinear and
     * overlap (beyond 1e-6 of the length of a), the Gauss points of
     * @p gauss on the overlap (real coordinates) and their weights.
     */
    bool
    overlap_quadrature(const Point<2>        &a0,
                       const Point<2>        &a1,
                       const Point<2>        &b0,
                       const Point<2>        &b1,
                       const QGauss<1>       &gauss,
                       std::vector<Point<2>> &points,
                       std::vector<double>   &weights)
    {
      const double       len = a0.distance(a1);
      const double       tol = 1e-6 * len;
      const Tensor<1, 2> t   = (a1 - a0) / len;
      // Collinear (both end points of b on the line of a)?
      const auto offset = [&](const Point<2> &q) {
        const Tensor<1, 2> d = q - a0;
        return std::abs(d[0] * t[1] - d[1] * t[0]);
      };
      if (offset(b0) > tol || offset(b1) > tol)
        return false;
      const double s0 = (b0 - a0) * t, s1 = (b1 - a0) * t;
      const double lo = std::max(0., std::min(s0, s1));
      const double hi = std::min(len, std::max(s0, s1));
      if (hi - lo <= tol)
        return false;
      for (unsigned int q = 0; q < gauss.size(); ++q)
        {
          const double s = lo + gauss.point(q)[0] * (hi - lo);
          points.push_back(a0 + s * t);
          weights.push_back(gauss.weight(q) * (hi - lo));
        }
      return true;
    }



    /// The smallest x of a face, for sorting faces along x.
    template <typename Face>
    double
    left_end(const Face &f)
    {
      return std::min(f.p0[0], f.p1[0]);
    }
  } // namespace



  std::vector<JointPair>
  find_joint_pairs(const DoFHandler<2>     &dof_handler,
                   const types::boundary_id joint_id)
  {
    std::vector<JointPair> pairs;
    // Joint faces with their end points.
    struct JointFace
    {
      DoFHandler<2>::active_cell_iterator cell;
      Point<2>                            p0, p1;
    };
    std::vector<JointFace> faces;
    for (const auto &cell : dof_handler.active_cell_iterators())
      for (const auto f : cell->face_indices())
        if (cell->face(f)->at_boundary()
            && cell->face(f)->boundary_id() == joint_id)
          faces.push_back(
            {cell, cell->face(f)->vertex(0), cell->face(f)->vertex(1)});
    // Sort by the x of the face's left end so that only nearby faces are
    // compared (the overlap test is exact for any pair).
    std::sort(faces.begin(), faces.end(), [](const auto &u, const auto &v) {
      return left_end(u) < left_end(v);
    });
    const QGauss<1> gauss(dof_handler.get_fe().degree + 1);
    for (std::size_t i = 0; i < faces.size(); ++i)
      {
        const auto  &fa = faces[i];
        const double xmax
          = std::max(fa.p0[0], fa.p1[0]) + 1e-6 * fa.p0.distance(fa.p1);
        for (std::size_t j = i + 1; j < faces.size(); ++j)
          {
            const auto &fb = faces[j];
            if (left_end(fb) > xmax)
              break;
            if (fb.cell->material_id() == fa.cell->material_id())
              continue;
            JointPair pair;
            if (!overlap_quadrature(
                  fa.p0, fa.p1, fb.p0, fb.p1, gauss, pair.points, pair.weights))
              continue;
            pair.a = fa.cell;
            pair.b = fb.cell;
            pairs.push_back(std::move(pair));
          }
      }
    return pairs;
  }



  std::vector<types::global_dof_index>
  joint_pair_dofs(const JointPair &pair)
  {
    const unsigned int dpc = pair.a->get_fe().n_dofs_per_cell();
    std::vector<types::global_dof_index> dofs(2 * dpc), dofs_b(dpc);
    std::vector<types::global_dof_index> dofs_a(dpc);
    pair.a->get_dof_indices(dofs_a);
    pair.b->get_dof_indices(dofs_b);
    std::copy(dofs_a.begin(), dofs_a.end(), dofs.begin());
    std::copy(dofs_b.begin(), dofs_b.end(), dofs.begin() + dpc);
    return dofs;
  }



  void
  assemble_joint_conductance(const HeatParameters         &prm,
                             const Mapping<2>             &mapping,
                             const FiniteElement<2>       &fe,
                             const AffineConstraints<>    &hanging,
                             const std::vector<JointPair> &pairs,
                             SparseMatrix<double>         &stiffness)
  {
    const unsigned int  dpc = fe.n_dofs_per_cell();
    const double        hj  = prm.joint_conductance;
    FullMatrix<double>  pair_matrix(2 * dpc, 2 * dpc);
    std::vector<double> jump(2 * dpc);
    for (const auto &pair : pairs)
      {
        std::vector<Point<2>> unit_a, unit_b;
        for (const auto &x : pair.points)
          {
            unit_a.push_back(GeometryInfo<2>::project_to_unit_cell(
              mapping.transform_real_to_unit_cell(pair.a, x)));
            unit_b.push_back(GeometryInfo<2>::project_to_unit_cell(
              mapping.transform_real_to_unit_cell(pair.b, x)));
          }
        FEValues<2> va(mapping, fe, Quadrature<2>(unit_a), update_values);
        FEValues<2> vb(mapping, fe, Quadrature<2>(unit_b), update_values);
        va.reinit(pair.a);
        vb.reinit(pair.b);
        pair_matrix = 0.;
        for (unsigned int q = 0; q < pair.points.size(); ++q)
          {
            for (unsigned int i = 0; i < dpc; ++i)
              {
                jump[i]       = va.shape_value(i, q);
                jump[dpc + i] = -vb.shape_value(i, q);
              }
            const double w = hj * pair.weights[q];
            for (unsigned int i = 0; i < 2 * dpc; ++i)
              for (unsigned int j = 0; j < 2 * dpc; ++j)
                pair_matrix(i, j) += w * jump[i] * jump[j];
          }
        hanging.distribute_local_to_global(pair_matrix,
                                           joint_pair_dofs(pair),
                                           stiffness);
      }
  }



  namespace
  {
    /// A dof's closed constraint line: its masters and their weights.
    using Line = std::vector<std::pair<types::global_dof_index, double>>;

    /// A joint face of a locally owned cell, as published to all ranks.
    struct PublishedFace
    {
      Point<2>                             p0, p1;
      types::material_id                   material = 0;
      std::array<Point<2>, 4>              vertices;
      std::vector<types::global_dof_index> dofs;
      /// Per dof: constrained by 'hanging' / by 'constraints_hom', and the
      /// lines there (empty for a Dirichlet dof of constraints_hom).
      std::vector<char> in_hanging, in_hom;
      std::vector<Line> hanging_lines, hom_lines;

      template <class Archive>
      void
      serialize(Archive &ar, const unsigned int)
      {
        ar &p0 &p1 &material &vertices &dofs &in_hanging &in_hom &hanging_lines
          &hom_lines;
      }
    };

    /// The unit-cell point of the bilinear quadrilateral @p v (deal.II's
    /// vertex order) at @p x (Newton's method; MappingQ1 on straight
    /// cells), projected into the unit cell.
    Point<2>
    unit_point(const std::array<Point<2>, 4> &v, const Point<2> &x)
    {
      Point<2> xi(0.5, 0.5);
      for (unsigned int it = 0; it < 50; ++it)
        {
          const double   s = xi[0], t = xi[1];
          const Point<2> f
            = Point<2>() + (1 - s) * (1 - t) * (v[0] - Point<2>())
              + s * (1 - t) * (v[1] - Point<2>())
              + (1 - s) * t * (v[2] - Point<2>()) + s * t * (v[3] - Point<2>());
          const Tensor<1, 2> ds  = (1 - t) * (v[1] - v[0]) + t * (v[3] - v[2]);
          const Tensor<1, 2> dt  = (1 - s) * (v[2] - v[0]) + s * (v[3] - v[1]);
          const Tensor<1, 2> r   = x - f;
          const double       det = ds[0] * dt[1] - ds[1] * dt[0];
          const double       d0  = (r[0] * dt[1] - r[1] * dt[0]) / det;
          const double       d1  = (ds[0] * r[1] - ds[1] * r[0]) / det;
          xi[0] += d0;
          xi[1] += d1;
          if (std::abs(d0) + std::abs(d1) < 1e-14)
            break;
        }
      return GeometryInfo<2>::project_to_unit_cell(xi);
    }
  } // namespace



  void
  DistributedJoints::setup(const HeatParameters      &prm,
                           const DoFHandler<2>       &dof_handler,
                           const AffineConstraints<> &hanging,
                           const AffineConstraints<> &constraints_hom,
                           const types::boundary_id   joint_id,
                           const MPI_Comm             comm)
  {
    pairs.clear();
    joint_hanging.clear();
    joint_hom.clear();
    const FiniteElement<2> &fe  = dof_handler.get_fe();
    const unsigned int      dpc = fe.n_dofs_per_cell();

    // This rank's joint faces, with what the other ranks need to assemble
    // against them.
    const auto line_of
      = [](const AffineConstraints<> &c, const types::global_dof_index i) {
          const auto *entries = c.get_constraint_entries(i);
          return entries ? Line(entries->begin(), entries->end()) : Line();
        };
    std::vector<PublishedFace> mine;
    for (const auto &cell : dof_handler.active_cell_iterators())
      if (cell->is_locally_owned())
        for (const auto f : cell->face_indices())
          if (cell->face(f)->at_boundary()
              && cell->face(f)->boundary_id() == joint_id)
            {
              PublishedFace face;
              face.p0       = cell->face(f)->vertex(0);
              face.p1       = cell->face(f)->vertex(1);
              face.material = cell->material_id();
              for (unsigned int v = 0; v < 4; ++v)
                face.vertices[v] = cell->vertex(v);
              face.dofs.resize(dpc);
              cell->get_dof_indices(face.dofs);
              for (const auto i : face.dofs)
                {
                  face.in_hanging.push_back(hanging.is_constrained(i));
                  face.in_hom.push_back(constraints_hom.is_constrained(i));
                  face.hanging_lines.push_back(line_of(hanging, i));
                  face.hom_lines.push_back(line_of(constraints_hom, i));
                }
              mine.push_back(std::move(face));
            }
    std::vector<PublishedFace> all;
    for (auto &faces : Utilities::MPI::all_gather(comm, mine))
      for (auto &face : faces)
        all.push_back(std::move(face));

    // The constraints of every dof the pairs touch (the closed lines of
    // the rank that owns the face).
    const auto add_lines = [&](const PublishedFace &face) {
      for (unsigned int k = 0; k < dpc; ++k)
        {
          const auto i = face.dofs[k];
          if (face.in_hanging[k] && !joint_hanging.is_constrained(i))
            {
              joint_hanging.add_line(i);
              joint_hanging.add_entries(i, face.hanging_lines[k]);
            }
          if (face.in_hom[k] && !joint_hom.is_constrained(i))
            {
              joint_hom.add_line(i);
              joint_hom.add_entries(i, face.hom_lines[k]);
            }
        }
    };

    // Pair each own face (rows) with the faces of other blocks (columns);
    // the other rank assembles the rows of its face, so that each pair
    // enters the matrix once, as in the serial solver.
    const QGauss<1>     gauss(fe.degree + 1);
    const double        hj = prm.joint_conductance;
    std::vector<double> jump(2 * dpc);
    for (const auto &a : mine)
      for (const auto &b : all)
        {
          if (b.material == a.material)
            continue;
          std::vector<Point<2>> points;
          std::vector<double>   weights;
          if (!overlap_quadrature(
                a.p0, a.p1, b.p0, b.p1, gauss, points, weights))
            continue;
          Pair pair;
          pair.rows    = a.dofs;
          pair.columns = a.dofs;
          pair.columns.insert(pair.columns.end(), b.dofs.begin(), b.dofs.end());
          pair.matrix.reinit(dpc, 2 * dpc);
          for (unsigned int q = 0; q < points.size(); ++q)
            {
              const Point<2> ua = unit_point(a.vertices, points[q]);
              const Point<2> ub = unit_point(b.vertices, points[q]);
              for (unsigned int i = 0; i < dpc; ++i)
                {
                  jump[i]       = fe.shape_value(i, ua);
                  jump[dpc + i] = -fe.shape_value(i, ub);
                }
              const double w = hj * weights[q];
              for (unsigned int i = 0; i < dpc; ++i)
                for (unsigned int j = 0; j < 2 * dpc; ++j)
                  pair.matrix(i, j) += w * jump[i] * jump[j];
            }
          add_lines(a);
          add_lines(b);
          pairs.push_back(std::move(pair));
        }
    joint_hanging.close();
    joint_hom.close();
  }



  void
  DistributedJoints::add_sparsity(DynamicSparsityPattern &dsp) const
  {
    for (const auto &pair : pairs)
      joint_hanging.add_entries_local_to_global(pair.rows,
                                                pair.columns,
                                                dsp,
                                                true);
  }



  void
  DistributedJoints::add_to(TrilinosWrappers::SparseMatrix &matrix,
                            const double                    factor,
                            const bool                      homogeneous) const
  {
    FullMatrix<double> scaled;
    for (const auto &pair : pairs)
      {
        scaled = pair.matrix;
        scaled *= factor;
        (homogeneous ? joint_hom : joint_hanging)
          .distribute_local_to_global(scaled, pair.rows, pair.columns, matrix);
      }
  }
} // namespace rockdda::thermal::internal
