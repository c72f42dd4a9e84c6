/**
 * @file
 * The deal.II heat solver (the only translation unit of the thermal
 * subsystem that includes deal.II's finite-element headers).
 */
#include <rockdda/io/binary_stream.h>
#include <rockdda/io/error.h>
#include <rockdda/io/output.h>
#include <rockdda/thermal/heat_solver.h>
#include <rockdda/thermal/polygon_mesh.h>

#include <deal.II/base/quadrature_lib.h>
#include <deal.II/base/timer.h>
#include <deal.II/dofs/dof_handler.h>
#include <deal.II/dofs/dof_tools.h>
#include <deal.II/fe/fe_q.h>
#include <deal.II/fe/fe_values.h>
#include <deal.II/fe/mapping_q1.h>
#include <deal.II/grid/grid_refinement.h>
#include <deal.II/grid/grid_tools.h>
#include <deal.II/grid/tria.h>
#include <deal.II/lac/affine_constraints.h>
#include <deal.II/lac/dynamic_sparsity_pattern.h>
#include <deal.II/lac/precondition.h>
#include <deal.II/lac/solver_cg.h>
#include <deal.II/lac/solver_control.h>
#include <deal.II/lac/solver_gmres.h>
#include <deal.II/lac/sparse_direct.h>
#include <deal.II/lac/sparse_matrix.h>
#include <deal.II/lac/sparsity_pattern.h>
#include <deal.II/lac/vector.h>
#include <deal.II/numerics/data_out.h>
#include <deal.II/numerics/error_estimator.h>
#include <deal.II/numerics/solution_transfer.h>
#include <deal.II/sundials/arkode.h>

#include <Eigen/SparseCholesky>
#include <Eigen/SparseCore>

#include "heat_flux.h"
#include "heat_internal.h"
#include "heat_solver_mpi.h"
#include <arkode/arkode_arkstep.h>
#include <boost/archive/binary_iarchive.hpp>
#include <boost/archive/binary_oarchive.hpp>
#include <cmath>
#include <limits>
#include <map>
#include <set>
#include <sstream>

namespace rockdda::thermal
{
  using namespace dealii;

  namespace
  {
    /// Matrices and factorisation of one theta-scheme step size.
    struct StepOperator
    {
      double               dt    = 0.;
      double               theta = 0.;
      SparseMatrix<double> a;     ///< M + theta dt K (hanging-condensed)
      SparseMatrix<double> a_mod; ///< a with Dirichlet rows/cols removed
      SparseMatrix<double> b;     ///< M - (1 - theta) dt K
      PreconditionSSOR<SparseMatrix<double>> ssor;
      // The per-step work of the direct path in Eigen (serial, no task
      // overhead for the small systems of long runs): b, the Dirichlet
      // columns of a, and the sparse Cholesky (LDL^T) factors of a_mod.
      Eigen::SparseMatrix<double, Eigen::RowMajor> eigen_b, eigen_a_dirichlet;
      Eigen::SimplicialLDLT<Eigen::SparseMatrix<double>> ldlt;
    };

    /// Copy a deal.II sparse matrix (optionally only some columns, renumbered
    /// by @p column_map, -1 = skip) into Eigen.
    template <typename EigenMatrix>
    void
    to_eigen(const SparseMatrix<double> &m,
             EigenMatrix                &out,
             const std::vector<int>     *column_map = nullptr,
             const unsigned int          n_columns  = 0)
    {
      std::vector<Eigen::Triplet<double>> triplets;
      triplets.reserve(m.n_nonzero_elements());
      for (unsigned int row = 0; row < m.m(); ++row)
        for (auto it = m.begin(row); it != m.end(row); ++it)
          if (it->value() != 0.)
            {
              const int col
                = column_map ? (*column_map)[it->column()] : int(it->column());
              if (col >= 0)
                triplets.emplace_back(row, col, it->value());
            }
      out.resize(m.m(), column_map ? n_columns : m.n());
      out.setFromTriplets(triplets.begin(), triplets.end());
    }

    /// Two cells facing each other across a joint (contact conductance):
    /// quadrature points (real coordinates) and weights on the overlap of
    /// their faces.
    struct JointPair
    {
      DoFHandler<2>::active_cell_iterator a, b;
      std::vector<Point<2>>               points;
      std::vector<double>                 weights;
    };

    /// A probe: dof indices and shape values at a fixed point.
    struct Probe
    {
      std::vector<types::global_dof_index> dofs;
      std::vector<double>                  weights;
    };
  } // namespace



  namespace internal
  {
    void
    validate_parameters(const HeatParameters &prm)
    {
      if (prm.degree < 1 || prm.degree > 3)
        throw InputError("heat: FE degree " + std::to_string(prm.degree)
                         + " is not supported (1, 2 or 3)");
      if (prm.materials.empty())
        throw InputError("heat: no material");
      for (const auto &m : prm.materials)
        validate(m, "heat");
      for (const auto &b : prm.blocks)
        if (b.material >= prm.materials.size())
          throw InputError("heat: block '" + b.name
                           + "' refers to a material that does not exist");
      if (!(prm.time_step > 0.) || !std::isfinite(prm.time_step))
        throw InputError("heat: the time step must be > 0 s");
      if (prm.joint_contact == HeatParameters::JointContact::conductance
          && (!(prm.joint_conductance > 0.)
              || !std::isfinite(prm.joint_conductance)))
        throw InputError("heat: the joint conductance "
                         + io::format_number(prm.joint_conductance, 6)
                         + " W/(m^2 K) must be > 0 and finite");
      if (prm.adaptive_refinement)
        {
          if (prm.stepper == TimeStepper::arkode)
            throw InputError("heat: adaptive refinement needs a theta scheme "
                             "(crank-nicolson or backward-euler), not arkode");
          if (prm.adaptive_interval < 1)
            throw InputError("heat: the adaptive interval must be >= 1 step");
          if (!(prm.refine_fraction >= 0. && prm.refine_fraction <= 1.
                && prm.coarsen_fraction >= 0. && prm.coarsen_fraction <= 1.
                && prm.refine_fraction + prm.coarsen_fraction <= 1.))
            throw InputError("heat: the refine fraction ("
                             + io::format_number(prm.refine_fraction, 6)
                             + ") and coarsen fraction ("
                             + io::format_number(prm.coarsen_fraction, 6)
                             + ") must lie in [0, 1] with a sum <= 1");
          if (!(prm.adaptive_min_cell_size >= 0.))
            throw InputError("heat: the minimum cell size must be >= 0 m");
        }
    }



    double
    distance_to_segments(const Point<2>                           &c,
                         const std::vector<std::array<Point2, 2>> &segments)
    {
      const Point2 p{{c[0], c[1]}};
      double       d = std::numeric_limits<double>::max();
      for (const auto &s : segments)
        d = std::min(d, distance_to_segment(p, s[0], s[1]));
      return d;
    }



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



    double
    step_theta(const HeatParameters &prm,
               const HeatStatistics &stats,
               const unsigned long   steps_taken)
    {
      const double chosen
        = prm.stepper == TimeStepper::crank_nicolson ? 0.5 : 1.;
      const double theta     = std::isnan(stats.fallback_time) ? chosen : 1.;
      const bool   rannacher = theta < 1. && steps_taken < prm.rannacher_steps;
      return rannacher ? 1. : theta;
    }



    void
    take_steps(const double                      &time,
               const double                       end_time,
               const double                       dt,
               const std::function<void(double)> &step)
    {
      const double remaining = end_time - time;
      const long   n_whole   = std::lround(remaining / dt);
      if (n_whole >= 1 && std::abs(remaining - n_whole * dt) <= 1e-6 * dt)
        for (long i = 0; i < n_whole; ++i)
          step(dt);
      else
        {
          const long n = static_cast<long>(std::floor(remaining / dt));
          for (long i = 0; i < n; ++i)
            step(dt);
          if (end_time - time > 1e-6 * dt)
            step(end_time - time);
        }
    }



    void
    build_mesh(Triangulation<2>     &tria,
               const HeatParameters &prm,
               MeshInfo             &info,
               const bool            coarse_only)
    {
      const bool merge
        = prm.joint_contact == HeatParameters::JointContact::perfect;
      const CoarseMesh coarse
        = mesh_blocks(prm.blocks, prm.coarse_cell_size, merge);

      std::vector<Point<2>> vertices;
      for (const auto &v : coarse.vertices)
        vertices.emplace_back(v[0], v[1]);
      std::vector<CellData<2>> cells(coarse.quads.size());
      for (unsigned int c = 0; c < coarse.quads.size(); ++c)
        {
          const auto &q = coarse.quads[c];
          // deal.II numbers quadrilateral vertices lexicographically.
          cells[c].vertices    = {q[0], q[1], q[3], q[2]};
          cells[c].material_id = coarse.quad_block[c];
        }
      GridTools::consistently_order_cells(cells);
      tria.create_triangulation(vertices, cells, SubCellData());

      // Boundary ids from the polygon edges: the tag of the closest edge of
      // the cell's block.
      for (const auto &b : prm.blocks)
        for (const auto &t : b.edge_tags)
          if (std::find(info.tags.begin(), info.tags.end(), t)
              == info.tags.end())
            info.tags.push_back(t);
      std::map<std::string, unsigned int> bc_of_tag;
      for (unsigned int k = 0; k < prm.boundary_conditions.size(); ++k)
        {
          const auto &tag = prm.boundary_conditions[k].tag;
          if (std::find(info.tags.begin(), info.tags.end(), tag)
              == info.tags.end())
            {
              std::string known;
              for (const auto &t : info.tags)
                known += (known.empty() ? "" : ", ") + t;
              throw InputError("heat: boundary condition for unknown boundary "
                               "tag '"
                               + tag + "' (the geometry's tags are: " + known
                               + ")");
            }
          if (bc_of_tag.count(tag))
            throw InputError("heat: two boundary conditions for tag '" + tag
                             + "'");
          bc_of_tag[tag] = k;
        }
      const unsigned int adiabatic_id = prm.boundary_conditions.size();
      info.joint_id                   = adiabatic_id + 1;
      const bool conductance
        = prm.joint_contact == HeatParameters::JointContact::conductance;

      // Edges shared by two blocks (joints), to detect non-conforming meshes.
      const auto on_other_block_edge =
        [&](const Point2 &p, const unsigned int block, const double tol) {
          for (unsigned int b = 0; b < prm.blocks.size(); ++b)
            if (b != block)
              {
                const auto &v = prm.blocks[b].vertices;
                for (std::size_t i = 0; i < v.size(); ++i)
                  if (distance_to_segment(p, v[i], v[(i + 1) % v.size()]) < tol)
                    return b;
              }
          return numbers::invalid_unsigned_int;
        };

      for (const auto &cell : tria.active_cell_iterators())
        for (const auto f : cell->face_indices())
          if (cell->face(f)->at_boundary())
            {
              const unsigned int block = cell->material_id();
              const auto        &v     = prm.blocks[block].vertices;
              const auto         c     = cell->face(f)->center();
              const Point2       p{{c[0], c[1]}};
              double             best = std::numeric_limits<double>::max();
              unsigned int       edge = 0;
              for (std::size_t i = 0; i < v.size(); ++i)
                {
                  const double d
                    = distance_to_segment(p, v[i], v[(i + 1) % v.size()]);
                  if (d < best)
                    best = d, edge = i;
                }
              const double       tol   = 1e-6 * cell->face(f)->diameter();
              const unsigned int other = (merge || conductance)
                                           ? on_other_block_edge(p, block, tol)
                                           : numbers::invalid_unsigned_int;
              if (conductance && other != numbers::invalid_unsigned_int)
                {
                  // A joint face: coupled to the other side, its tag unused.
                  cell->face(f)->set_boundary_id(info.joint_id);
                  continue;
                }
              if (merge)
                {
                  if (other != numbers::invalid_unsigned_int)
                    throw InputError(
                      "heat: blocks '" + prm.blocks[block].name + "' and '"
                      + prm.blocks[other].name
                      + "' touch along an edge that is not shared vertex to "
                        "vertex; with perfect joint contact, neighbouring "
                        "blocks must have the same joint end points (split the "
                        "longer edge), or use insulated joints");
                }
              const std::string &tag = prm.blocks[block].edge_tags[edge];
              const auto         it  = bc_of_tag.find(tag);
              if (it != bc_of_tag.end())
                cell->face(f)->set_boundary_id(it->second);
              else if (tag == "adiabatic")
                cell->face(f)->set_boundary_id(adiabatic_id);
              else
                throw InputError("heat: boundary tag '" + tag + "' of block '"
                                 + prm.blocks[block].name
                                 + "' has no boundary condition (give one, or "
                                   "name the tag 'adiabatic')");
            }

      if (coarse_only)
        return;

      // Refine to the target coarse cell size.
      for (unsigned int cycle = 0; cycle < 30; ++cycle)
        {
          bool any = false;
          for (const auto &cell : tria.active_cell_iterators())
            if (cell->is_locally_owned()
                && cell->diameter() > 1.5 * prm.coarse_cell_size)
              cell->set_refine_flag(), any = true;
          if (!Utilities::MPI::logical_or(any, tria.get_communicator()))
            break;
          tria.execute_coarsening_and_refinement();
        }
      if (prm.global_refinements > 0)
        tria.refine_global(prm.global_refinements);

      // A priori band within band_width of the listed (exposed) tags.
      info.band_segments.clear();
      if (prm.band_width > 0. && prm.band_cell_size > 0.)
        {
          for (const auto &b : prm.blocks)
            for (std::size_t i = 0; i < b.vertices.size(); ++i)
              if (std::find(prm.refine_near_tags.begin(),
                            prm.refine_near_tags.end(),
                            b.edge_tags[i])
                  != prm.refine_near_tags.end())
                info.band_segments.push_back(std::array<Point2, 2>{
                  {b.vertices[i], b.vertices[(i + 1) % b.vertices.size()]}});
          for (unsigned int cycle = 0;
               cycle < 30 && !info.band_segments.empty();
               ++cycle)
            {
              bool any = false;
              for (const auto &cell : tria.active_cell_iterators())
                if (cell->is_locally_owned()
                    && cell->diameter() > 1.5 * prm.band_cell_size)
                  {
                    const double d = distance_to_segments(cell->center(),
                                                          info.band_segments);
                    if (d < prm.band_width + 0.5 * cell->diameter())
                      cell->set_refine_flag(), any = true;
                  }
              if (!Utilities::MPI::logical_or(any, tria.get_communicator()))
                break;
              tria.execute_coarsening_and_refinement();
            }
        }
    }
  } // namespace internal



  class HeatSolver::Impl
  {
  public:
    explicit Impl(const HeatParameters &parameters);

    void
    advance_to(const double end_time);

    HeatParameters                             prm;
    Triangulation<2>                           tria;
    FE_Q<2>                                    fe;
    DoFHandler<2>                              dof_handler;
    MappingQ1<2>                               mapping;
    AffineConstraints<double>                  hanging;
    SparsityPattern                            sparsity;
    SparseMatrix<double>                       mass, stiffness;
    std::vector<std::unique_ptr<StepOperator>> operators;

    Vector<double> solution, new_solution, rhs_old, rhs_new, tmp, g_ext,
      increment_old;

    // Tags, boundary ids (= index into prm.boundary_conditions).
    std::vector<std::string>             tags;
    std::vector<types::global_dof_index> dirichlet_dofs;
    std::vector<Point<2>>                dirichlet_points;
    std::vector<unsigned int>            dirichlet_bc;
    std::vector<bool>                    is_dirichlet;

    // Uniform boundary data: F(t) += g_k(t) v_k; heat rate += g_k(t) s_k.
    std::vector<unsigned int>   uniform_bc;
    std::vector<Vector<double>> uniform_vectors;
    std::vector<double>         uniform_rates;
    bool                        nonuniform = false;
    Vector<double>              robin_weights; ///< int h phi_j ds
    Vector<double>              capacity;      ///< int rho c phi_j dA

    // Per block: int phi, int x phi, int y phi; geometry moments.
    std::vector<Vector<double>> block_phi, block_xphi, block_yphi;
    std::vector<std::array<double, 6>>
      block_geometry; // A, Sx, Sy, Sxx, Sxy, Syy

    std::vector<Probe>    probes;
    std::vector<Point<2>> probe_points;
    /// Polygon edges carrying a refine_near_tags tag.
    std::vector<std::array<Point2, 2>> band_segments;

    /// Boundary id of joint faces (contact conductance).
    types::boundary_id     joint_id = 0;
    std::vector<JointPair> joint_pairs;

    double         time              = 0.;
    double         boundary_heat     = 0.;
    double         source_heat       = 0.;
    double         rate_old          = 0.; ///< boundary heat rate at time
    double         source_rate_old   = 0.;
    bool           rhs_old_valid     = false;
    bool           last_step_flipped = false;
    unsigned long  steps_taken       = 0;
    double         kappa_max         = 0.;
    double         h_min             = 0.;
    HeatStatistics stats;

    std::ostringstream timer_stream;
    TimerOutput        timer;

    /// Probe at @p p (throws InputError if outside the rock).
    Probe
    locate_probe(const Point<2> &p) const;
    /// Kelly estimate, refine and coarsen, transfer the field, rebuild.
    void
    adapt_mesh();
    /// The mesh as bytes (boost binary archive of the triangulation).
    std::string
    saved_mesh() const;
    /// Replace the mesh by saved_mesh() @p bytes and rebuild the system
    /// (dofs, matrices, probes) on it; the field must be set afterwards.
    void
    load_mesh(const std::string &bytes);

    /// Condensed right-hand side at @p t into @p f; returns the boundary
    /// data part of the heat rate (without -w.T) and the source rate.
    void
    assemble_rhs(const double    t,
                 Vector<double> &f,
                 double         &boundary_rate,
                 double         &source_rate) const;

  private:
    /// Pair the faces on both sides of every joint (contact conductance).
    void
    find_joint_pairs();
    void
    setup_system();
    void
    assemble_fixed();
    StepOperator &
    get_operator(const double dt, const double theta);
    void
    theta_step(const double dt, const double theta);
    void
    arkode_advance(const double end_time);
    void
    apply_dirichlet_values(const double t, Vector<double> &v) const;
  };



  HeatSolver::Impl::Impl(const HeatParameters &parameters)
      : prm(parameters)
      // The 2:1 balance at vertices that p4est enforces in the distributed
      // solver, so that both solvers build the same meshes.
      , tria(Triangulation<2>::limit_level_difference_at_vertices)
      , fe(std::max(1u, parameters.degree))
      , timer(timer_stream, TimerOutput::never, TimerOutput::wall_times)
  {
    internal::validate_parameters(prm);
    for (const auto &m : prm.materials)
      kappa_max = std::max(kappa_max, m.diffusivity());

    TimerOutput::Scope scope(timer, "setup");
    internal::MeshInfo mesh_info;
    internal::build_mesh(tria, prm, mesh_info);
    tags          = mesh_info.tags;
    joint_id      = mesh_info.joint_id;
    band_segments = mesh_info.band_segments;
    dof_handler.reinit(tria);
    setup_system();
    assemble_fixed();

    // Initial condition.
    solution.reinit(dof_handler.n_dofs());
    std::vector<Point<2>> support(dof_handler.n_dofs());
    DoFTools::map_dofs_to_support_points(mapping, dof_handler, support);
    for (unsigned int i = 0; i < solution.size(); ++i)
      solution[i] = prm.initial_field
                      ? prm.initial_field(support[i][0], support[i][1])
                      : prm.initial_temperature;
    hanging.distribute(solution);
    time = prm.start_time;
  }



  Probe
  HeatSolver::Impl::locate_probe(const Point<2> &point) const
  {
    std::pair<DoFHandler<2>::active_cell_iterator, Point<2>> found;
    try
      {
        found = GridTools::find_active_cell_around_point(mapping,
                                                         dof_handler,
                                                         point);
      }
    catch (...)
      {
        found.first = dof_handler.end();
      }
    if (found.first == dof_handler.end()
        || found.first.state() != IteratorState::valid)
      throw InputError("heat: probe point (" + io::format_number(point[0], 6)
                       + ", " + io::format_number(point[1], 6)
                       + ") m is outside the rock");
    const Quadrature<2> q(GeometryInfo<2>::project_to_unit_cell(found.second));
    FEValues<2>         fe_values(mapping, fe, q, update_values);
    fe_values.reinit(found.first);
    Probe probe;
    probe.dofs.resize(fe.n_dofs_per_cell());
    found.first->get_dof_indices(probe.dofs);
    for (unsigned int i = 0; i < probe.dofs.size(); ++i)
      probe.weights.push_back(fe_values.shape_value(i, 0));
    return probe;
  }



  void
  HeatSolver::Impl::adapt_mesh()
  {
    TimerOutput::Scope scope(timer, "adapt mesh");
    // Kelly et al. (1983): jumps of the normal gradient across faces.
    Vector<float> indicator(tria.n_active_cells());
    KellyErrorEstimator<2>::estimate(
      mapping, dof_handler, QGauss<1>(fe.degree + 1), {}, solution, indicator);
    if (!(indicator.l1_norm() > 0.))
      return;
    GridRefinement::refine_and_coarsen_fixed_fraction(
      tria,
      indicator,
      prm.refine_fraction,
      prm.coarsen_fraction,
      prm.adaptive_max_cells > 0 ? prm.adaptive_max_cells
                                 : std::numeric_limits<unsigned int>::max());
    // Limits: no cell finer than the minimum size; no cell coarser than the
    // coarse size, nor than the band size inside the a priori band.
    bool any = false;
    for (const auto &cell : tria.active_cell_iterators())
      any = internal::limit_adaptation_flags(cell, prm, band_segments, false)
            || any;
    if (!any)
      return;

    const double                        heat_before = capacity * solution;
    SolutionTransfer<2, Vector<double>> transfer(dof_handler);
    tria.prepare_coarsening_and_refinement();
    const std::vector<Vector<double>> in{solution, increment_old};
    transfer.prepare_for_coarsening_and_refinement(in);
    tria.execute_coarsening_and_refinement();
    setup_system();
    assemble_fixed();
    std::vector<Vector<double>> out(in.size(),
                                    Vector<double>(dof_handler.n_dofs()));
    transfer.interpolate(in, out);
    solution.swap(out[0]);
    increment_old.swap(out[1]);
    hanging.distribute(solution);
    hanging.distribute(increment_old);
    operators.clear();
    rhs_old_valid = false;
    for (unsigned int k = 0; k < probes.size(); ++k)
      probes[k] = locate_probe(probe_points[k]);
    stats.mesh_transfer_heat += capacity * solution - heat_before;
    ++stats.n_adaptations;
  }



  std::string
  HeatSolver::Impl::saved_mesh() const
  {
    std::ostringstream              out;
    boost::archive::binary_oarchive archive(out);
    archive << tria;
    return out.str();
  }



  void
  HeatSolver::Impl::load_mesh(const std::string &bytes)
  {
    std::istringstream              in(bytes);
    boost::archive::binary_iarchive archive(in);
    archive >> tria;
    setup_system();
    assemble_fixed();
    operators.clear();
    rhs_old_valid = false;
    for (unsigned int k = 0; k < probes.size(); ++k)
      probes[k] = locate_probe(probe_points[k]);
  }



  void
  HeatSolver::Impl::find_joint_pairs()
  {
    joint_pairs.clear();
    if (prm.joint_contact != HeatParameters::JointContact::conductance)
      return;
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
    // Sort by the x of the face centre so that only nearby faces are
    // compared (the overlap test is exact for any pair).
    std::sort(faces.begin(), faces.end(), [](const auto &u, const auto &v) {
      return std::min(u.p0[0], u.p1[0]) < std::min(v.p0[0], v.p1[0]);
    });
    const QGauss<1> gauss(fe.degree + 1);
    for (std::size_t i = 0; i < faces.size(); ++i)
      {
        const auto        &fa   = faces[i];
        const double       len  = fa.p0.distance(fa.p1);
        const double       tol  = 1e-6 * len;
        const Tensor<1, 2> t    = (fa.p1 - fa.p0) / len;
        const double       xmax = std::max(fa.p0[0], fa.p1[0]) + tol;
        for (std::size_t j = i + 1; j < faces.size(); ++j)
          {
            const auto &fb = faces[j];
            if (std::min(fb.p0[0], fb.p1[0]) > xmax)
              break;
            if (fb.cell->material_id() == fa.cell->material_id())
              continue;
            // Collinear (both end points of b on the line of a)?
            const auto offset = [&](const Point<2> &q) {
              const Tensor<1, 2> d = q - fa.p0;
              return std::abs(d[0] * t[1] - d[1] * t[0]);
            };
            if (offset(fb.p0) > tol || offset(fb.p1) > tol)
              continue;
            const double s0 = (fb.p0 - fa.p0) * t, s1 = (fb.p1 - fa.p0) * t;
            const double lo = std::max(0., std::min(s0, s1));
            const double hi = std::min(len, std::max(s0, s1));
            if (hi - lo <= tol)
              continue;
            JointPair pair;
            pair.a = fa.cell;
            pair.b = fb.cell;
            for (unsigned int q = 0; q < gauss.size(); ++q)
              {
                const double s = lo + gauss.point(q)[0] * (hi - lo);
                pair.points.push_back(fa.p0 + s * t);
                pair.weights.push_back(gauss.weight(q) * (hi - lo));
              }
            joint_pairs.push_back(std::move(pair));
          }
      }
  }



  void
  HeatSolver::Impl::setup_system()
  {
    dof_handler.distribute_dofs(fe);
    hanging.clear();
    DoFTools::make_hanging_node_constraints(dof_handler, hanging);
    hanging.close();

    DynamicSparsityPattern dsp(dof_handler.n_dofs());
    DoFTools::make_sparsity_pattern(dof_handler, dsp, hanging, true);
    find_joint_pairs();
    {
      const unsigned int                   dpc = fe.n_dofs_per_cell();
      std::vector<types::global_dof_index> dofs(2 * dpc), dofs_a(dpc),
        dofs_b(dpc);
      for (const auto &pair : joint_pairs)
        {
          pair.a->get_dof_indices(dofs_a);
          pair.b->get_dof_indices(dofs_b);
          std::copy(dofs_a.begin(), dofs_a.end(), dofs.begin());
          std::copy(dofs_b.begin(), dofs_b.end(), dofs.begin() + dpc);
          hanging.add_entries_local_to_global(dofs, dsp, true);
        }
    }
    sparsity.copy_from(dsp);
    mass.reinit(sparsity);
    stiffness.reinit(sparsity);

    const unsigned int n = dof_handler.n_dofs();
    new_solution.reinit(n);
    rhs_old.reinit(n);
    rhs_new.reinit(n);
    tmp.reinit(n);
    g_ext.reinit(n);
    increment_old.reinit(n);
    robin_weights.reinit(n);
    capacity.reinit(n);

    // Dirichlet dofs (the first temperature tag wins at shared corners).
    is_dirichlet.assign(n, false);
    dirichlet_dofs.clear();
    dirichlet_points.clear();
    dirichlet_bc.clear();
    std::vector<Point<2>> support(n);
    DoFTools::map_dofs_to_support_points(mapping, dof_handler, support);
    for (unsigned int k = 0; k < prm.boundary_conditions.size(); ++k)
      if (prm.boundary_conditions[k].type
          == BoundaryCondition::Type::temperature)
        {
          const IndexSet set
            = DoFTools::extract_boundary_dofs(dof_handler,
                                              ComponentMask(),
                                              {types::boundary_id(k)});
          for (const auto i : set)
            if (!is_dirichlet[i] && !hanging.is_constrained(i))
              {
                is_dirichlet[i] = true;
                dirichlet_dofs.push_back(i);
                dirichlet_points.push_back(support[i]);
                dirichlet_bc.push_back(k);
              }
        }

    stats.n_cells       = tria.n_active_cells();
    stats.max_n_cells   = std::max(stats.max_n_cells, stats.n_cells);
    stats.n_dofs        = n;
    stats.min_cell_size = std::numeric_limits<double>::max();
    stats.max_cell_size = 0.;
    for (const auto &cell : tria.active_cell_iterators())
      {
        stats.min_cell_size = std::min(stats.min_cell_size, cell->diameter());
        stats.max_cell_size = std::max(stats.max_cell_size, cell->diameter());
      }
    // Smallest node spacing: cell diameter / sqrt(2) / degree.
    h_min = stats.min_cell_size / std::sqrt(2.) / prm.degree;
  }



  void
  HeatSolver::Impl::assemble_fixed()
  {
    internal::CellIntegrators integrators(mapping,
                                          fe,
                                          update_values | update_gradients
                                            | update_quadrature_points
                                            | update_JxW_values,
                                          update_values | update_JxW_values);
    FEValues<2>              &fe_values = integrators.values;
    FEFaceValues<2>          &fe_face   = integrators.face;
    const unsigned int        dpc       = fe.n_dofs_per_cell();
    FullMatrix<double>        cell_mass(dpc, dpc), cell_stiff(dpc, dpc);
    Vector<double>            cell_vec(dpc), cell_vec2(dpc);
    std::vector<types::global_dof_index> dofs(dpc);

    uniform_bc = internal::uniform_loads(prm, nonuniform);
    uniform_vectors.clear();
    uniform_rates.assign(uniform_bc.size(), 0.);
    std::vector<int> uniform_slot(prm.boundary_conditions.size(), -1);
    for (unsigned int s = 0; s < uniform_bc.size(); ++s)
      {
        uniform_slot[uniform_bc[s]] = s;
        uniform_vectors.emplace_back(dof_handler.n_dofs());
      }

    const unsigned int n_blocks = prm.blocks.size();
    block_phi.assign(n_blocks, Vector<double>(dof_handler.n_dofs()));
    block_xphi = block_phi;
    block_yphi = block_phi;
    block_geometry.assign(n_blocks,
                          std::array<double, 6>{{0., 0., 0., 0., 0., 0.}});

    for (const auto &cell : dof_handler.active_cell_iterators())
      {
        fe_values.reinit(cell);
        cell->get_dof_indices(dofs);
        const unsigned int block = cell->material_id();
        const Material    &mat   = prm.materials[prm.blocks[block].material];
        const double       rho_c = mat.density * mat.heat_capacity;
        cell_mass                = 0.;
        cell_stiff               = 0.;
        auto &geo                = block_geometry[block];
        for (const unsigned int q : fe_values.quadrature_point_indices())
          {
            const double jxw = fe_values.JxW(q);
            const auto  &x   = fe_values.quadrature_point(q);
            internal::add_geometry(geo, x, jxw);
            for (unsigned int i = 0; i < dpc; ++i)
              {
                const double phi_i = fe_values.shape_value(i, q);
                capacity[dofs[i]] += rho_c * phi_i * jxw;
                block_phi[block][dofs[i]] += phi_i * jxw;
                block_xphi[block][dofs[i]] += x[0] * phi_i * jxw;
                block_yphi[block][dofs[i]] += x[1] * phi_i * jxw;
                for (unsigned int j = 0; j < dpc; ++j)
                  {
                    cell_mass(i, j)
                      += rho_c * phi_i * fe_values.shape_value(j, q) * jxw;
                    cell_stiff(i, j) += mat.conductivity
                                        * (fe_values.shape_grad(i, q)
                                           * fe_values.shape_grad(j, q))
                                        * jxw;
                  }
              }
          }
        for (const auto f : cell->face_indices())
          if (cell->face(f)->at_boundary()
              && cell->face(f)->boundary_id() < prm.boundary_conditions.size())
            {
              const unsigned int k  = cell->face(f)->boundary_id();
              const auto        &bc = prm.boundary_conditions[k];
              if (bc.type == BoundaryCondition::Type::temperature || !bc.value)
                continue;
              fe_face.reinit(cell, f);
              const double h = bc.type == BoundaryCondition::Type::convective
                                 ? bc.heat_transfer_coefficient
                                 : 0.;
              cell_vec       = 0.;
              double ds      = 0.;
              for (const unsigned int q : fe_face.quadrature_point_indices())
                {
                  const double jxw = fe_face.JxW(q);
                  ds += jxw;
                  for (unsigned int i = 0; i < dpc; ++i)
                    {
                      const double phi_i = fe_face.shape_value(i, q);
                      // Uniform data: v_k = int w phi, w = h or 1.
                      cell_vec(i)
                        += (h > 0.
                              ? h
                              : (bc.type == BoundaryCondition::Type::flux ? 1.
                                                                          : 0.))
                           * phi_i * jxw;
                      robin_weights[dofs[i]] += h * phi_i * jxw;
                      for (unsigned int j = 0; j < dpc; ++j)
                        cell_stiff(i, j)
                          += h * phi_i * fe_face.shape_value(j, q) * jxw;
                    }
                }
              if (uniform_slot[k] >= 0)
                {
                  hanging.distribute_local_to_global(
                    cell_vec, dofs, uniform_vectors[uniform_slot[k]]);
                  uniform_rates[uniform_slot[k]]
                    += (bc.type == BoundaryCondition::Type::convective ? h : 1.)
                       * ds;
                }
            }
        hanging.distribute_local_to_global(cell_mass, dofs, mass);
        hanging.distribute_local_to_global(cell_stiff, dofs, stiffness);
      }

    // Contact conductance: h_j int_joint (T_a - T_b)(v_a - v_b) ds, with
    // the points of each pair mapped into both cells.
    const double                         hj = prm.joint_conductance;
    FullMatrix<double>                   pair_matrix(2 * dpc, 2 * dpc);
    std::vector<types::global_dof_index> pair_dofs(2 * dpc), dofs_b(dpc);
    std::vector<double>                  jump(2 * dpc);
    for (const auto &pair : joint_pairs)
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
        pair.a->get_dof_indices(dofs);
        pair.b->get_dof_indices(dofs_b);
        std::copy(dofs.begin(), dofs.end(), pair_dofs.begin());
        std::copy(dofs_b.begin(), dofs_b.end(), pair_dofs.begin() + dpc);
        hanging.distribute_local_to_global(pair_matrix, pair_dofs, stiffness);
      }
  }



  void
  HeatSolver::Impl::assemble_rhs(const double    t,
                                 Vector<double> &f,
                                 double         &boundary_rate,
                                 double         &source_rate) const
  {
    f             = 0.;
    boundary_rate = 0.;
    source_rate   = 0.;
    internal::add_uniform_loads(
      prm, uniform_bc, uniform_vectors, uniform_rates, t, f, boundary_rate);
    if (!nonuniform)
      return;

    internal::CellIntegrators            integrators(mapping, fe);
    FEValues<2>                         &fe_values = integrators.values;
    FEFaceValues<2>                     &fe_face   = integrators.face;
    const unsigned int                   dpc       = fe.n_dofs_per_cell();
    Vector<double>                       cell_vec(dpc);
    std::vector<types::global_dof_index> dofs(dpc);
    for (const auto &cell : dof_handler.active_cell_iterators())
      {
        cell_vec       = 0.;
        const bool any = internal::add_cell_load(prm,
                                                 cell,
                                                 t,
                                                 fe_values,
                                                 fe_face,
                                                 cell_vec,
                                                 boundary_rate,
                                                 source_rate);
        if (any)
          {
            cell->get_dof_indices(dofs);
            hanging.distribute_local_to_global(cell_vec, dofs, f);
          }
      }
  }



  StepOperator &
  HeatSolver::Impl::get_operator(const double dt, const double theta)
  {
    for (auto &op : operators)
      if (op->dt == dt && op->theta == theta)
        return *op;
    if (operators.size() >= 4)
      operators.erase(operators.begin());
    TimerOutput::Scope scope(timer, "factorize");
    auto               op = std::make_unique<StepOperator>();
    op->dt                = dt;
    op->theta             = theta;
    op->a.reinit(sparsity);
    op->a.copy_from(mass);
    op->a.add(theta * dt, stiffness);
    op->b.reinit(sparsity);
    op->b.copy_from(mass);
    op->b.add(-(1. - theta) * dt, stiffness);
    op->a_mod.reinit(sparsity);
    op->a_mod.copy_from(op->a);
    // Remove Dirichlet rows and columns (keeps the matrix symmetric).
    if (!dirichlet_dofs.empty())
      for (unsigned int row = 0; row < op->a_mod.m(); ++row)
        for (auto it = op->a_mod.begin(row); it != op->a_mod.end(row); ++it)
          if ((is_dirichlet[row] || is_dirichlet[it->column()])
              && it->column() != row)
            it->value() = 0.;
    if (prm.direct_solver)
      {
        to_eigen(op->b, op->eigen_b);
        std::vector<int> column_map(dof_handler.n_dofs(), -1);
        for (std::size_t d = 0; d < dirichlet_dofs.size(); ++d)
          column_map[dirichlet_dofs[d]] = d;
        to_eigen(op->a,
                 op->eigen_a_dirichlet,
                 &column_map,
                 dirichlet_dofs.size());
        Eigen::SparseMatrix<double> a_mod;
        to_eigen(op->a_mod, a_mod);
        op->ldlt.compute(a_mod);
        if (op->ldlt.info() != Eigen::Success)
          throw std::runtime_error("heat: the factorisation of the system "
                                   "matrix failed (not positive definite?)");
      }
    else
      op->ssor.initialize(op->a_mod, 1.2);
    ++stats.n_factorizations;
    operators.push_back(std::move(op));
    return *operators.back();
  }



  void
  HeatSolver::Impl::apply_dirichlet_values(const double    t,
                                           Vector<double> &v) const
  {
    for (std::size_t d = 0; d < dirichlet_dofs.size(); ++d)
      {
        const auto  &p = dirichlet_points[d];
        const double g
          = prm.boundary_conditions[dirichlet_bc[d]].value(p[0], p[1], t);
        if (!std::isfinite(g))
          throw std::runtime_error(
            "heat: temperature of tag '"
            + prm.boundary_conditions[dirichlet_bc[d]].tag
            + "' is not finite at t = " + io::format_number(t, 8) + " s");
        v[dirichlet_dofs[d]] = g;
      }
  }



  void
  HeatSolver::Impl::theta_step(const double dt, const double theta)
  {
    StepOperator &op = get_operator(dt, theta);
    internal::theta_step(*this, dt, theta, [&]() {
      // b = B T + dt (theta F_new + (1 - theta) F_old) - A g
      const unsigned int n = solution.size();
      using Map            = Eigen::Map<Eigen::VectorXd>;
      using ConstMap       = Eigen::Map<const Eigen::VectorXd>;
      if (prm.direct_solver)
        Map(tmp.begin(), n).noalias()
          = op.eigen_b * ConstMap(solution.begin(), n);
      else
        op.b.vmult(tmp, solution);
      tmp.add(dt * theta, rhs_new, dt * (1. - theta), rhs_old);
      if (!dirichlet_dofs.empty())
        {
          g_ext = 0.;
          apply_dirichlet_values(time + dt, g_ext);
          if (prm.direct_solver)
            {
              Eigen::VectorXd g(dirichlet_dofs.size());
              for (std::size_t d = 0; d < dirichlet_dofs.size(); ++d)
                g[d] = g_ext[dirichlet_dofs[d]];
              Map(tmp.begin(), n) -= op.eigen_a_dirichlet * g;
            }
          else
            {
              op.a.vmult(new_solution, g_ext);
              tmp -= new_solution;
            }
          for (const auto i : dirichlet_dofs)
            tmp[i] = op.a.diag_element(i) * g_ext[i];
        }
      hanging.set_zero(tmp);

      if (prm.direct_solver)
        Map(new_solution.begin(), n) = op.ldlt.solve(ConstMap(tmp.begin(), n));
      else
        {
          SolverControl            control(10000,
                                prm.cg_tolerance
                                  * std::max(tmp.l2_norm(), 1e-300));
          SolverCG<Vector<double>> cg(control);
          new_solution = solution;
          cg.solve(op.a_mod, new_solution, tmp, op.ssor);
        }
      hanging.distribute(new_solution);
    });
  }



  void
  HeatSolver::Impl::advance_to(const double end_time)
  {
    if (!(end_time >= time - 1e-9 * prm.time_step))
      throw std::invalid_argument("heat: advance_to() into the past");
    if (prm.stepper == TimeStepper::arkode)
      {
        TimerOutput::Scope scope(timer, "time stepping (ARKODE)");
        arkode_advance(end_time);
        return;
      }
    TimerOutput::Scope scope(timer, "time stepping");
    const double       dt   = prm.time_step;
    const auto         step = [&](const double h) {
      theta_step(h, internal::step_theta(prm, stats, steps_taken));
      if (prm.adaptive_refinement && steps_taken % prm.adaptive_interval == 0)
        adapt_mesh();
    };
    internal::take_steps(time, end_time, dt, step);
    time = end_time;
  }



  void
  HeatSolver::Impl::arkode_advance(const double end_time)
  {
    // M y' = -K y + F(t) with Dirichlet rows replaced by y_D' = g'(t)
    // (finite difference of g); implicit DIRK with adaptive error control.
    using VectorType = Vector<double>;
    if (end_time - time <= 0.)
      return;
    SUNDIALS::ARKode<VectorType>::AdditionalData data(
      time,
      end_time,
      std::min(prm.time_step, end_time - time),
      end_time - time,
      1e-12 * (end_time - time),
      5,
      10,
      true,
      false,
      true,
      3,
      prm.arkode_absolute_tolerance,
      prm.arkode_relative_tolerance);
    SUNDIALS::ARKode<VectorType> ode(data);

    // Central difference for g'(t): step ~ cube root of round-off times the
    // time scale (the larger of |t| and dt).
    const double g_eps
      = 1e-5 * std::max({std::abs(time), std::abs(end_time), prm.time_step});
    Vector<double> g0(dof_handler.n_dofs()), g1(dof_handler.n_dofs());
    double         dummy_rate, dummy_source;
    Vector<double> f(dof_handler.n_dofs());
    // Free-row mask: zero at Dirichlet and hanging rows.
    ode.implicit_function
      = [&](const double t, const VectorType &y, VectorType &ydot) {
          // ydot here is the right-hand side f_I(t, y) = -K y + F(t) (mass
          // matrix handled by ARKODE's mass solver).
          assemble_rhs(t, f, dummy_rate, dummy_source);
          stiffness.vmult(ydot, y);
          ydot.sadd(-1., 1., f);
          if (!dirichlet_dofs.empty())
            {
              g0 = 0.;
              g1 = 0.;
              apply_dirichlet_values(t - g_eps, g0);
              apply_dirichlet_values(t + g_eps, g1);
              for (const auto i : dirichlet_dofs)
                ydot[i] = mass.diag_element(i) * (g1[i] - g0[i]) / (2. * g_eps);
            }
          for (unsigned int i = 0; i < ydot.size(); ++i)
            if (hanging.is_constrained(i))
              ydot[i] = 0.;
          return 0;
        };

    // Mass matrix with Dirichlet rows/cols reduced to the diagonal.
    // (Free rows keep their Dirichlet columns: M_iD g'(t) is part of the
    // equation; the matrix is then non-symmetric, which UMFPACK handles.)
    SparseMatrix<double> m_mod(sparsity);
    m_mod.copy_from(mass);
    for (unsigned int row = 0; row < m_mod.m(); ++row)
      if (is_dirichlet[row])
        for (auto it = m_mod.begin(row); it != m_mod.end(row); ++it)
          if (it->column() != row)
            it->value() = 0.;
    SparseMatrix<double> jacobian(sparsity);
    SparseDirectUMFPACK  jac_solver, mass_solver;
    mass_solver.initialize(m_mod);
    double gamma_current = -1.;

    ode.mass_times_vector
      = [&](const double, const VectorType &v, VectorType &mv) {
          m_mod.vmult(mv, v);
          return 0;
        };
    ode.solve_mass = [&](SUNDIALS::SundialsOperator<VectorType> &,
                         SUNDIALS::SundialsPreconditioner<VectorType> &,
                         VectorType       &x,
                         const VectorType &b,
                         double) {
      mass_solver.vmult(x, b);
      return 0;
    };
    ode.jacobian_times_setup
      = [&](double, const VectorType &, const VectorType &) { return 0; };
    ode.jacobian_times_vector = [&](const VectorType &v,
                                    VectorType       &jv,
                                    double,
                                    const VectorType &,
                                    const VectorType &) {
      stiffness.vmult(jv, v);
      jv *= -1.;
      for (const auto i : dirichlet_dofs)
        jv[i] = 0.;
      for (unsigned int i = 0; i < jv.size(); ++i)
        if (hanging.is_constrained(i))
          jv[i] = 0.;
      return 0;
    };
    ode.jacobian_preconditioner_setup = [&](double,
                                            const VectorType &,
                                            const VectorType &,
                                            int,
                                            int   &j_current,
                                            double gamma) {
      // Newton matrix M - gamma J = M + gamma K (Dirichlet rows: M_ii).
      if (gamma != gamma_current)
        {
          jacobian.copy_from(mass);
          jacobian.add(gamma, stiffness);
          for (unsigned int row = 0; row < jacobian.m(); ++row)
            for (auto it = jacobian.begin(row); it != jacobian.end(row); ++it)
              if (is_dirichlet[row] || hanging.is_constrained(row))
                it->value()
                  = (it->column() == row) ? mass.diag_element(row) : 0.;
          jac_solver.initialize(jacobian);
          gamma_current = gamma;
          ++stats.n_factorizations;
        }
      j_current = 1;
      return 0;
    };
    ode.jacobian_preconditioner_solve = [&](double,
                                            const VectorType &,
                                            const VectorType &,
                                            const VectorType &r,
                                            VectorType       &z,
                                            double,
                                            double,
                                            int) {
      jac_solver.vmult(z, r);
      return 0;
    };
    ode.solve_linearized_system
      = [&](SUNDIALS::SundialsOperator<VectorType>       &op,
            SUNDIALS::SundialsPreconditioner<VectorType> &prec,
            VectorType                                   &x,
            const VectorType                             &b,
            double                                        tol) -> int {
      ReductionControl        control(200, 1e-14, std::max(tol, 1e-12));
      SolverGMRES<VectorType> gmres(control);
      gmres.solve(op, x, b, prec);
      return 0;
    };


    // Heat bookkeeping is only approximate with ARKODE (trapezoidal in the
    // output points); the theta scheme is exact.
    double rate0 = 0., src0 = 0.;
    assemble_rhs(time, f, rate0, src0);
    rate0 -= robin_weights * solution;

    VectorType y = solution;
    apply_dirichlet_values(time, y);
    hanging.distribute(y);
    ode.solve_ode(y);
    long int n_fails = 0, n_steps = 0;
    ARKStepGetNumErrTestFails(ode.get_arkode_memory(), &n_fails);
    ARKStepGetNumSteps(ode.get_arkode_memory(), &n_steps);
    stats.n_rejected_steps += n_fails;
    apply_dirichlet_values(end_time, y);
    hanging.distribute(y);
    solution     = y;
    double rate1 = 0., src1 = 0.;
    assemble_rhs(end_time, f, rate1, src1);
    rate1 -= robin_weights * solution;
    boundary_heat += 0.5 * (end_time - time) * (rate0 + rate1);
    source_heat += 0.5 * (end_time - time) * (src0 + src1);
    stats.n_steps += n_steps;
    time          = end_time;
    rhs_old_valid = false;
  }



  // -------------------------------------------------------------------------
  HeatSolver::HeatSolver(const HeatParameters &parameters)
  {
    if (internal::use_distributed_solver(parameters))
      distributed = std::make_unique<internal::DistributedHeat>(parameters);
    else
      impl = std::make_unique<Impl>(parameters);
  }

  HeatSolver::~HeatSolver() = default;

  double
  HeatSolver::time() const
  {
    if (distributed)
      return distributed->time();
    return impl->time;
  }

  void
  HeatSolver::advance_to(const double end_time)
  {
    if (distributed)
      return distributed->advance_to(end_time);
    impl->advance_to(end_time);
  }

  double
  HeatSolver::value(const double x, const double y) const
  {
    if (distributed)
      return distributed->value(x, y);
    const auto found
      = GridTools::find_active_cell_around_point(impl->mapping,
                                                 impl->dof_handler,
                                                 Point<2>(x, y));
    if (found.first.state() != IteratorState::valid)
      throw InputError("heat: point (" + io::format_number(x, 6) + ", "
                       + io::format_number(y, 6) + ") m is outside the rock");
    const Quadrature<2> q(GeometryInfo<2>::project_to_unit_cell(found.second));
    FEValues<2>         fe_values(impl->mapping, impl->fe, q, update_values);
    fe_values.reinit(found.first);
    std::vector<double> v(1);
    fe_values.get_function_values(impl->solution, v);
    return v[0];
  }

  unsigned int
  HeatSolver::add_probe(const double x, const double y)
  {
    if (distributed)
      return distributed->add_probe(x, y);
    impl->probes.push_back(impl->locate_probe(Point<2>(x, y)));
    impl->probe_points.emplace_back(x, y);
    return impl->probes.size() - 1;
  }

  double
  HeatSolver::probe_value(const unsigned int index) const
  {
    if (distributed)
      return distributed->probe_value(index);
    const Probe &p = impl->probes.at(index);
    double       v = 0.;
    for (unsigned int i = 0; i < p.dofs.size(); ++i)
      v += p.weights[i] * impl->solution[p.dofs[i]];
    return v;
  }

  std::vector<BlockMoments>
  HeatSolver::block_moments() const
  {
    if (distributed)
      return distributed->block_moments();
    return internal::block_moments_of(impl->block_geometry,
                                      impl->block_phi,
                                      impl->block_xphi,
                                      impl->block_yphi,
                                      impl->solution);
  }

  double
  HeatSolver::stored_heat() const
  {
    if (distributed)
      return distributed->stored_heat();
    return impl->capacity * impl->solution;
  }

  double
  HeatSolver::boundary_heat_in() const
  {
    if (distributed)
      return distributed->boundary_heat_in();
    return impl->boundary_heat;
  }

  double
  HeatSolver::source_heat_in() const
  {
    if (distributed)
      return distributed->source_heat_in();
    return impl->source_heat;
  }

  double
  HeatSolver::l2_error(const SpaceTimeFunction &exact) const
  {
    if (distributed)
      return distributed->l2_error(exact);
    const QGauss<2>     quadrature(impl->fe.degree + 2);
    FEValues<2>         fe_values(impl->mapping,
                          impl->fe,
                          quadrature,
                          update_values | update_quadrature_points
                            | update_JxW_values);
    std::vector<double> v(quadrature.size());
    double              sum = 0.;
    for (const auto &cell : impl->dof_handler.active_cell_iterators())
      {
        fe_values.reinit(cell);
        fe_values.get_function_values(impl->solution, v);
        for (const unsigned int q : fe_values.quadrature_point_indices())
          {
            const auto  &x = fe_values.quadrature_point(q);
            const double e = v[q] - exact(x[0], x[1], impl->time);
            sum += e * e * fe_values.JxW(q);
          }
      }
    return std::sqrt(sum);
  }

  std::vector<std::pair<std::string, std::string>>
  HeatSolver::vtu_files(const std::string &name) const
  {
    if (distributed)
      return distributed->vtu_files(name);
    return {{name + ".vtu", vtu()}};
  }

  bool
  HeatSolver::is_output_rank() const
  {
    return !Utilities::MPI::job_supports_mpi()
           || Utilities::MPI::this_mpi_process(MPI_COMM_WORLD) == 0;
  }

  namespace
  {
    constexpr char heat_magic[] = "rockdda heat solver checkpoint 1";
  }

  std::string
  HeatSolver::checkpoint(const std::string &mesh_files) const
  {
    if (distributed)
      return distributed->checkpoint(mesh_files);
    io::BinaryWriter w;
    w.put_string(heat_magic);
    // An adaptive mesh changes during the run: it is stored too.
    w.put_string(impl->prm.adaptive_refinement ? impl->saved_mesh()
                                               : std::string());
    w.put<std::uint64_t>(impl->tria.n_active_cells());
    w.put_doubles(impl->solution);
    w.put_doubles(impl->increment_old);
    w.put(impl->time);
    w.put(impl->boundary_heat);
    w.put(impl->source_heat);
    w.put<std::uint8_t>(impl->last_step_flipped ? 1 : 0);
    w.put<std::uint64_t>(impl->steps_taken);
    w.put(impl->stats);
    return w.bytes;
  }



  void
  HeatSolver::restore(const std::string &bytes, const std::string &source)
  {
    if (distributed)
      {
        distributed->restore(bytes, source);
        return;
      }
    io::BinaryReader r(bytes, source);
    if (r.get_string() != heat_magic)
      throw InputError(source + ": not a rockdda heat checkpoint");
    const std::string mesh = r.get_string();
    if (mesh.empty() == impl->prm.adaptive_refinement)
      throw InputError(source + ": the checkpoint was written "
                       + (mesh.empty()
                            ? "without adaptive refinement, this run uses it"
                            : "with adaptive refinement, this run does not"));
    if (!mesh.empty())
      try
        {
          impl->load_mesh(mesh);
        }
      catch (const InputError &)
        {
          throw;
        }
      catch (const std::exception &e)
        {
          throw InputError(source + ": the stored mesh cannot be read ("
                           + e.what() + ")");
        }
    const auto          cells     = r.get<std::uint64_t>();
    std::vector<double> solution  = r.get_doubles();
    std::vector<double> increment = r.get_doubles();
    const std::size_t   n         = impl->dof_handler.n_dofs();
    if (cells != impl->tria.n_active_cells() || solution.size() != n
        || increment.size() != n)
      throw InputError(source + ": the checkpoint has " + std::to_string(cells)
                       + " cells and " + std::to_string(solution.size())
                       + " unknowns, the mesh of this run "
                       + std::to_string(impl->tria.n_active_cells()) + " and "
                       + std::to_string(n) + ": it belongs to another mesh");
    const double time          = r.get<double>();
    const double boundary_heat = r.get<double>();
    const double source_heat   = r.get<double>();
    const bool   flipped       = r.get<std::uint8_t>() != 0;
    const auto   steps         = r.get<std::uint64_t>();
    const auto   stats         = r.get<HeatStatistics>();
    if (!r.at_end())
      throw InputError(source + ": the checkpoint has trailing data");
    for (const double v : solution)
      if (!std::isfinite(v))
        throw InputError(source
                         + ": the checkpoint holds non-finite "
                           "temperatures");
    impl->solution.reinit(n);
    impl->increment_old.reinit(n);
    std::copy(solution.begin(), solution.end(), impl->solution.begin());
    std::copy(increment.begin(), increment.end(), impl->increment_old.begin());
    impl->time              = time;
    impl->boundary_heat     = boundary_heat;
    impl->source_heat       = source_heat;
    impl->last_step_flipped = flipped;
    impl->steps_taken       = steps;
    impl->stats             = stats;
    impl->rhs_old_valid     = false; // reassembled at the restored time
  }



  std::string
  HeatSolver::vtu() const
  {
    if (distributed)
      throw std::logic_error("heat: vtu() of the distributed solver; use "
                             "vtu_files()");
    const internal::HeatFluxPostprocessor heat_flux(impl->prm);
    DataOut<2>                            data_out;
    data_out.attach_dof_handler(impl->dof_handler);
    data_out.add_data_vector(impl->solution, "temperature");
    data_out.add_data_vector(impl->solution, heat_flux);
    Vector<float> block(impl->tria.n_active_cells());
    for (const auto &cell : impl->tria.active_cell_iterators())
      block[cell->active_cell_index()] = cell->material_id();
    data_out.add_data_vector(block, "block");
    data_out.build_patches(impl->fe.degree);
    // Binary, zlib-compressed when deal.II has zlib (write_vtu).
    DataOutBase::VtkFlags flags;
    flags.time              = impl->time;
    flags.compression_level = DataOutBase::VtkFlags::best_speed;
    flags.physical_units    = {{"heat_flux", "W/m^2"}};
    data_out.set_flags(flags);
    std::ostringstream out;
    data_out.write_vtu(out);
    return out.str();
  }

  HeatStatistics
  HeatSolver::statistics() const
  {
    if (distributed)
      return distributed->statistics();
    HeatStatistics s = impl->stats;
    s.stiffness_ratio
      = impl->prm.time_step * impl->kappa_max / (impl->h_min * impl->h_min);
    return s;
  }

  std::string
  HeatSolver::method_description() const
  {
    if (distributed)
      return distributed->method_description();
    const auto &p = impl->prm;
    std::string s;
    switch (p.stepper)
      {
        case TimeStepper::crank_nicolson:
          s = "Crank-Nicolson (theta = 1/2), dt = "
              + io::format_number(p.time_step, 6) + " s, "
              + std::to_string(p.rannacher_steps)
              + " backward-Euler start-up steps";
          break;
        case TimeStepper::backward_euler:
          s = "backward Euler (theta = 1), dt = "
              + io::format_number(p.time_step, 6) + " s";
          break;
        case TimeStepper::arkode:
          s = "SUNDIALS ARKODE (implicit DIRK, adaptive), rtol = "
              + io::format_number(p.arkode_relative_tolerance, 3) + ", atol = "
              + io::format_number(p.arkode_absolute_tolerance, 3) + " K";
          break;
      }
    s += "; FE_Q(" + std::to_string(p.degree) + "); linear solver "
         + (p.direct_solver ? "sparse Cholesky (Eigen LDLT, direct)"
                            : "CG + SSOR");
    return s;
  }

  std::string
  HeatSolver::timing_summary() const
  {
    if (distributed)
      return distributed->timing_summary();
    impl->timer_stream.str("");
    impl->timer.print_summary();
    return impl->timer_stream.str();
  }
} // namespace rockdda::thermal
