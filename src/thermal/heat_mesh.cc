/**
 * @file
 * The mesh and geometry of the heat solver, shared by the serial and the
 * distributed solver: the parameter checks, the coarse quadrilateral mesh
 * of the blocks with the boundary ids of their tags (joint faces
 * recognised), the refinement to the coarse cell size and the a priori
 * band near exposed faces, and the mesh statistics.
 */
#include <rockdda/io/error.h>
#include <rockdda/io/output.h>
#include <rockdda/thermal/polygon_mesh.h>

#include <deal.II/base/mpi.h>
#include <deal.II/grid/grid_tools.h>
#include <deal.II/grid/tria.h>

#include "heat_internal.h"
#include <algorithm>
#include <cmath>
#include <limits>
#include <map>

namespace rockdda::thermal::internal
{
  using namespace dealii;

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
        if (std::find(info.tags.begin(), info.tags.end(), t) == info.tags.end())
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
    const auto on_other_block_edge
      = [&](const Point2 &p, const unsigned int block, const double tol) {
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
        for (unsigned int cycle = 0; cycle < 30 && !info.band_segments.empty();
             ++cycle)
          {
            bool any = false;
            for (const auto &cell : tria.active_cell_iterators())
              if (cell->is_locally_owned()
                  && cell->diameter() > 1.5 * prm.band_cell_size)
                {
                  const double d
                    = distance_to_segments(cell->center(), info.band_segments);
                  if (d < prm.band_width + 0.5 * cell->diameter())
                    cell->set_refine_flag(), any = true;
                }
            if (!Utilities::MPI::logical_or(any, tria.get_communicator()))
              break;
            tria.execute_coarsening_and_refinement();
          }
      }
  }



  void
  update_mesh_statistics(const Triangulation<2> &tria,
                         const unsigned int      n_dofs,
                         const unsigned int      degree,
                         HeatStatistics         &stats,
                         double                 &h_min)
  {
    stats.n_cells     = tria.n_global_active_cells();
    stats.n_dofs      = n_dofs;
    stats.max_n_cells = std::max(stats.max_n_cells, stats.n_cells);
    double hmin = std::numeric_limits<double>::max(), hmax = 0.;
    for (const auto &cell : tria.active_cell_iterators())
      if (cell->is_locally_owned())
        {
          hmin = std::min(hmin, cell->diameter());
          hmax = std::max(hmax, cell->diameter());
        }
    stats.min_cell_size = Utilities::MPI::min(hmin, tria.get_communicator());
    stats.max_cell_size = Utilities::MPI::max(hmax, tria.get_communicator());
    // Smallest node spacing: cell diameter / sqrt(2) / degree.
    h_min = stats.min_cell_size / std::sqrt(2.) / degree;
  }
} // namespace rockdda::thermal::internal
