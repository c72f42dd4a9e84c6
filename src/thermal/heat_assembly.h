/**
 * @file
 * Internal to the thermal subsystem: the assembly of the heat equation,
 * written once for the serial (deal.II Vector, SparseMatrix) and the
 * distributed (Trilinos) solver: the cell mass and stiffness matrices with
 * the convective (Robin) term, the fixed integrals (heat capacity, Robin
 * weights, uniform boundary loads, block moments), the time-dependent load
 * vector, the Dirichlet data and the joint contact conductance
 * (heat_joints.cc). The
 * templates are defined in heat_assembly.cc and instantiated there for the
 * two linear-algebra types (VectorType = dealii::Vector<double> or
 * dealii::TrilinosWrappers::MPI::Vector); loops run over the locally owned
 * cells, which are all cells of a serial mesh.
 */
#ifndef ROCKDDA_THERMAL_HEAT_ASSEMBLY_H
#define ROCKDDA_THERMAL_HEAT_ASSEMBLY_H

#include <rockdda/thermal/heat_solver.h>

#include <deal.II/base/index_set.h>
#include <deal.II/base/mpi.h>
#include <deal.II/base/point.h>
#include <deal.II/dofs/dof_handler.h>
#include <deal.II/fe/fe_values.h>
#include <deal.II/fe/mapping.h>
#include <deal.II/lac/affine_constraints.h>
#include <deal.II/lac/dynamic_sparsity_pattern.h>
#include <deal.II/lac/full_matrix.h>
#include <deal.II/lac/sparse_matrix.h>
#include <deal.II/lac/trilinos_sparse_matrix.h>

#include <array>
#include <functional>
#include <vector>

namespace rockdda::thermal::internal
{
  /// What the assembly loops run over: the parameters, the mapping and
  /// dofs of the mesh, its hanging-node constraints and the communicator
  /// of the vectors.
  struct AssemblyScope
  {
    const HeatParameters              &prm;
    const dealii::Mapping<2>          &mapping;
    const dealii::DoFHandler<2>       &dof_handler;
    const dealii::AffineConstraints<> &hanging;
    const MPI_Comm                     comm;
  };

  /// The heat rates of a load, W/m: of the boundary data (without -w.T)
  /// and of the source.
  struct LoadRates
  {
    double boundary = 0.;
    double source   = 0.;
  };

  /// The integrals that do not change between time steps (only with the
  /// mesh), in the solver's vector type.
  template <typename VectorType>
  struct FixedIntegrals
  {
    /// Indices of the spatially uniform flux and convective conditions.
    std::vector<unsigned int> uniform_bc;
    /// Their load vectors: F(t) += g_k(t) v_k.
    std::vector<VectorType> uniform_vectors;
    /// Their heat rates: rate += g_k(t) s_k, W/m per unit value.
    std::vector<double> uniform_rates;
    /// Any load (source or condition) that varies in space.
    bool       nonuniform = false;
    VectorType robin_weights; ///< int h phi_j ds
    VectorType capacity;      ///< int rho c phi_j dA
    /// Per block: int phi, int x phi, int y phi dA.
    std::vector<VectorType> block_phi, block_xphi, block_yphi;
    /// Per block: int 1, x, y, x^2, xy, y^2 dA.
    std::vector<std::array<double, 6>> block_geometry;

    /// The condensed load vector at time @p t into @p f (compressed), and
    /// its heat rates summed over the ranks of the communicator of
    /// @p scope.
    LoadRates
    loads(const AssemblyScope &scope, const double t, VectorType &f) const;
  };

  /// Called with the cell, its dof indices, cell mass and stiffness.
  using CellMatrixSink
    = std::function<void(const dealii::DoFHandler<2>::active_cell_iterator &,
                         const std::vector<dealii::types::global_dof_index> &,
                         const dealii::FullMatrix<double> &,
                         const dealii::FullMatrix<double> &)>;

  /// A CellMatrixSink that adds the cell matrices into @p mass and
  /// @p stiffness (serial or Trilinos), condensing the @p hanging nodes.
  template <typename MatrixType>
  CellMatrixSink
  add_to_matrices(const dealii::AffineConstraints<> &hanging,
                  MatrixType                        &mass,
                  MatrixType                        &stiffness)
  {
    return
      [h = &hanging,
       m = &mass,
       k = &stiffness](const dealii::DoFHandler<2>::active_cell_iterator &,
                       const std::vector<dealii::types::global_dof_index> &dofs,
                       const dealii::FullMatrix<double> &cell_mass,
                       const dealii::FullMatrix<double> &cell_stiff) {
        h->distribute_local_to_global(cell_mass, dofs, *m);
        h->distribute_local_to_global(cell_stiff, dofs, *k);
      };
  }

  /**
   * Cell mass rho c_p phi_i phi_j and stiffness lambda grad phi_i grad phi_j
   * plus the convective term h phi_i phi_j on the faces of @p cell.
   * @p fe_values must be reinit()ed on @p cell and have values, gradients
   * and JxW; @p fe_face needs values and JxW.
   */
  void
  cell_matrices(const HeatParameters                              &prm,
                const dealii::DoFHandler<2>::active_cell_iterator &cell,
                const dealii::FEValues<2>                         &fe_values,
                dealii::FEFaceValues<2>                           &fe_face,
                dealii::FullMatrix<double>                        &cell_mass,
                dealii::FullMatrix<double>                        &cell_stiff);

  /**
   * Assemble @p fixed over the locally owned cells of @p scope (@p owned
   * dofs), condensing the hanging nodes; with @p matrices, also call it
   * with each cell's mass and stiffness matrices.
   */
  template <typename VectorType>
  void
  assemble_fixed_integrals(const AssemblyScope        &scope,
                           const dealii::IndexSet     &owned,
                           FixedIntegrals<VectorType> &fixed,
                           const CellMatrixSink &matrices = CellMatrixSink());

  /// The locally owned Dirichlet dofs (not hanging), their support points
  /// and conditions; the first temperature tag wins at shared corners.
  struct DirichletDofs
  {
    std::vector<dealii::types::global_dof_index> dofs;
    std::vector<dealii::Point<2>>                points;
    std::vector<unsigned int>                    bc;

    /// Find them on the current mesh.
    void
    find(const HeatParameters              &prm,
         const dealii::Mapping<2>          &mapping,
         const dealii::DoFHandler<2>       &dof_handler,
         const dealii::AffineConstraints<> &hanging);

    /// Set the entries of @p v at the Dirichlet dofs to the values at time
    /// @p t (not compressed); throws if a value is not finite.
    template <typename VectorType>
    void
    set_values(const HeatParameters &prm, const double t, VectorType &v) const;
  };

  /// Two cells facing each other across a joint (contact conductance):
  /// quadrature points (real coordinates) and weights on the overlap of
  /// their faces.
  struct JointPair
  {
    dealii::DoFHandler<2>::active_cell_iterator a, b;
    std::vector<dealii::Point<2>>               points;
    std::vector<double>                         weights;
  };

  /// Pair the faces with boundary id @p joint_id of different blocks that
  /// overlap (contact conductance), with Gauss points on each overlap.
  std::vector<JointPair>
  find_joint_pairs(const dealii::DoFHandler<2>     &dof_handler,
                   const dealii::types::boundary_id joint_id);

  /// The dofs of both cells of @p pair (cell a first).
  std::vector<dealii::types::global_dof_index>
  joint_pair_dofs(const JointPair &pair);

  /**
   * Add the contact conductance h_j int_joint (T_a - T_b)(v_a - v_b) ds of
   * the @p pairs to @p stiffness, the points of each pair mapped into both
   * cells.
   */
  void
  assemble_joint_conductance(const HeatParameters              &prm,
                             const dealii::Mapping<2>          &mapping,
                             const dealii::FiniteElement<2>    &fe,
                             const dealii::AffineConstraints<> &hanging,
                             const std::vector<JointPair>      &pairs,
                             dealii::SparseMatrix<double>      &stiffness);

  /**
   * The joint contact conductance of the distributed solver, whose two
   * faces of a joint may lie on different ranks (their cells are not
   * neighbours, so neither is a ghost of the other). setup() publishes
   * each rank's joint faces (end points, cell vertices, dofs and their
   * constraint lines) to all ranks and pairs the rank's own faces with
   * the faces of other blocks; each rank assembles the rows of its own
   * faces, so that every pair enters the matrix once. The shape values at
   * the other face come from its cell's vertices (MappingQ1, straight
   * cells). heat_joints.cc.
   */
  class DistributedJoints
  {
  public:
    /// Find the pairs on the current mesh (collective).
    void
    setup(const HeatParameters              &prm,
          const dealii::DoFHandler<2>       &dof_handler,
          const dealii::AffineConstraints<> &hanging,
          const dealii::AffineConstraints<> &constraints_hom,
          const dealii::types::boundary_id   joint_id,
          const MPI_Comm                     comm);

    /// Add the entries of the pairs to @p dsp (before it is distributed).
    void
    add_sparsity(dealii::DynamicSparsityPattern &dsp) const;

    /// Add @p factor times the conductance matrix to @p matrix, with the
    /// hanging-node constraints or, if @p homogeneous, with the hanging
    /// and homogeneous Dirichlet ones (not compressed).
    void
    add_to(dealii::TrilinosWrappers::SparseMatrix &matrix,
           const double                            factor,
           const bool                              homogeneous) const;

  private:
    /// One pair: h_j int jump_i jump_j over the rows of the own face's
    /// dofs and the columns of both faces' dofs.
    struct Pair
    {
      std::vector<dealii::types::global_dof_index> rows, columns;
      dealii::FullMatrix<double>                   matrix;
    };
    std::vector<Pair> pairs;
    /// The constraints of every dof of the pairs.
    dealii::AffineConstraints<> joint_hanging, joint_hom;
  };
} // namespace rockdda::thermal::internal

#endif
