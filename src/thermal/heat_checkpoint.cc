/**
 * @file
 * Checkpoints of the serial heat solver: the state needed to continue a
 * run bit for bit (field, previous increment, time, heat balance,
 * counters) as bytes, with the mesh (a boost archive of the
 * triangulation) when it is adaptive, and the restore with its checks
 * (same mesh, finite values). The distributed solver writes its mesh and
 * field with p4est into alternating file sets and the rest as bytes.
 */
#include <rockdda/io/binary_stream.h>
#include <rockdda/io/error.h>

#include <deal.II/distributed/solution_transfer.h>

#include "heat_solver_distributed.h"
#include "heat_solver_mpi.h"
#include "heat_solver_serial.h"
#include <boost/archive/binary_iarchive.hpp>
#include <boost/archive/binary_oarchive.hpp>
#include <cmath>
#include <cstdint>
#include <fstream>
#include <sstream>

namespace rockdda::thermal
{
  using namespace dealii;

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



  namespace internal
  {
    using VectorType = DistributedVector;

    namespace
    {
      constexpr char distributed_magic[]
        = "rockdda distributed heat checkpoint 1";
    }

    std::string
    DistributedHeat::checkpoint(const std::string &mesh_files) const
    {
      Impl &d = *impl;
      if (mesh_files.empty())
        throw std::invalid_argument(
          "heat: the distributed solver needs a file prefix for checkpoints");
      // Alternate between two file sets: a save interrupted half-way leaves
      // the set named by the previous checkpoint.bin intact.
      const std::string name
        = mesh_files + "-" + std::to_string(d.checkpoints_written++ % 2);
      d.update_ghosts();
      VectorType increment(d.owned, d.relevant, d.comm);
      increment = d.increment_old;
      parallel::distributed::SolutionTransfer<2, VectorType> transfer(
        d.dof_handler);
      transfer.prepare_for_serialization(
        std::vector<const VectorType *>{&d.ghosted, &increment});
      d.tria.save(name);
      io::BinaryWriter w;
      w.put_string(distributed_magic);
      w.put_string(name);
      w.put<std::uint64_t>(d.tria.n_global_active_cells());
      w.put(d.time);
      w.put(d.boundary_heat);
      w.put(d.source_heat);
      w.put<std::uint8_t>(d.last_step_flipped ? 1 : 0);
      w.put<std::uint64_t>(d.steps_taken);
      w.put<std::uint64_t>(d.linear_iterations);
      w.put(d.stats);
      return w.bytes;
    }



    void
    DistributedHeat::restore(const std::string &bytes,
                             const std::string &source)
    {
      Impl            &d = *impl;
      io::BinaryReader r(bytes, source);
      if (r.get_string() != distributed_magic)
        throw InputError(source
                         + ": not a checkpoint of the distributed heat solver "
                           "(written by a serial run?)");
      const std::string name   = r.get_string();
      const auto        cells  = r.get<std::uint64_t>();
      const double      time   = r.get<double>();
      const double      q_in   = r.get<double>();
      const double      s_in   = r.get<double>();
      const bool        flip   = r.get<std::uint8_t>() != 0;
      const auto        steps  = r.get<std::uint64_t>();
      const auto        linear = r.get<std::uint64_t>();
      const auto        stats  = r.get<HeatStatistics>();
      if (!r.at_end())
        throw InputError(source + ": the checkpoint has trailing data");
      if (!std::ifstream(name + ".info"))
        throw InputError(source + ": the mesh files " + name
                         + ".* of the checkpoint are missing");
      // p4est loads into a triangulation holding only the coarse mesh.
      d.tria.clear();
      MeshInfo coarse;
      build_mesh(d.tria, d.prm, coarse, true);
      d.tria.load(name);
      if (d.tria.n_global_active_cells() != cells)
        throw InputError(source + ": the mesh files " + name + ".* hold "
                         + std::to_string(d.tria.n_global_active_cells())
                         + " cells, the checkpoint " + std::to_string(cells));
      d.setup_system();
      d.assemble_fixed();
      parallel::distributed::SolutionTransfer<2, VectorType> transfer(
        d.dof_handler);
      std::vector<VectorType *> targets{&d.solution, &d.increment_old};
      transfer.deserialize(targets);
      d.hanging.distribute(d.solution);
      d.hanging.distribute(d.increment_old);
      d.time              = time;
      d.boundary_heat     = q_in;
      d.source_heat       = s_in;
      d.last_step_flipped = flip;
      d.steps_taken       = steps;
      d.linear_iterations = linear;
      d.stats             = stats;
      d.operators.clear();
      d.rhs_old_valid = false;
      d.ghosted_valid = false;
      for (unsigned int k = 0; k < d.probes.size(); ++k)
        d.probes[k] = d.locate(d.probe_points[k]);
    }
  } // namespace internal
} // namespace rockdda::thermal
