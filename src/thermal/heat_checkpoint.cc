/**
 * @file
 * Checkpoints of the heat solver (HeatSystem): the state needed to
 * continue a run bit for bit (field, previous increment, time, heat
 * balance, counters) and the restore with its checks. The format is the
 * one thing that differs with the linear-algebra traits, so each has its
 * own: serially all is bytes, with the mesh (a boost archive of the
 * triangulation) when it is adaptive; the distributed solver writes its
 * mesh and field with p4est into alternating file sets and the rest as
 * bytes.
 */
#include <rockdda/io/binary_stream.h>
#include <rockdda/io/error.h>

#include <deal.II/distributed/solution_transfer.h>

#include "heat_system.h"
#include <boost/archive/binary_iarchive.hpp>
#include <boost/archive/binary_oarchive.hpp>
#include <cmath>
#include <cstdint>
#include <fstream>
#include <sstream>
#include <tuple>

namespace rockdda::thermal::internal
{
  using namespace dealii;

  namespace
  {
    constexpr char heat_magic[] = "rockdda heat solver checkpoint 1";
    constexpr char distributed_magic[]
      = "rockdda distributed heat checkpoint 1";

    /// Write the time, heat balance and step count of @p s.
    void
    put_balance(io::BinaryWriter &w, const StepState &s)
    {
      w.put(s.time);
      w.put(s.boundary_heat);
      w.put(s.source_heat);
      w.put<std::uint8_t>(s.last_step_flipped ? 1 : 0);
      w.put<std::uint64_t>(s.steps_taken);
    }

    /// Read what put_balance() wrote into @p s.
    void
    get_balance(io::BinaryReader &r, StepState &s)
    {
      s.time              = r.get<double>();
      s.boundary_heat     = r.get<double>();
      s.source_heat       = r.get<double>();
      s.last_step_flipped = r.get<std::uint8_t>() != 0;
      s.steps_taken       = r.get<std::uint64_t>();
    }

    /// Continue @p s from the balance and statistics of @p saved; the
    /// load at the restored time is assembled anew.
    void
    take_balance(StepState &s, const StepState &saved)
    {
      std::tie(s.time,
               s.boundary_heat,
               s.source_heat,
               s.last_step_flipped,
               s.steps_taken,
               s.stats)
        = std::tie(saved.time,
                   saved.boundary_heat,
                   saved.source_heat,
                   saved.last_step_flipped,
                   saved.steps_taken,
                   saved.stats);
      s.rhs_old_valid = false;
    }

    /// A reader of the checkpoint @p bytes of the file @p source, past its
    /// magic string; InputError if that is not @p magic (the file is not
    /// @p what).
    io::BinaryReader
    open_checkpoint(const std::string &bytes,
                    const std::string &source,
                    const std::string &magic,
                    const std::string &what)
    {
      io::BinaryReader r(bytes, source);
      if (r.get_string() != magic)
        throw InputError(source + ": not " + what);
      return r;
    }

    /// The serial mesh as bytes (boost binary archive).
    std::string
    saved_mesh(const Triangulation<2> &tria)
    {
      std::ostringstream              out;
      boost::archive::binary_oarchive archive(out);
      archive << tria;
      return out.str();
    }
  } // namespace

  template <>
  void
  HeatSystem<LinearAlgebra::Serial>::restore(const std::string &bytes,
                                             const std::string &source)
  {
    io::BinaryReader r
      = open_checkpoint(bytes, source, heat_magic, "a rockdda heat checkpoint");
    const std::string mesh = r.get_string();
    if (mesh.empty() == prm.adaptive_refinement)
      throw InputError(source + ": the checkpoint was written "
                       + (mesh.empty()
                            ? "without adaptive refinement, this run uses it"
                            : "with adaptive refinement, this run does not"));
    if (!mesh.empty())
      try
        {
          // Replace the mesh and rebuild the system on it.
          std::istringstream              in(mesh);
          boost::archive::binary_iarchive archive(in);
          archive >> tria;
          setup_system();
          assemble_fixed();
          operators.clear();
          rhs_old_valid = false;
          for (unsigned int k = 0; k < probes.size(); ++k)
            probes[k] = locate(probe_points[k]);
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
    std::vector<double> values    = r.get_doubles();
    std::vector<double> increment = r.get_doubles();
    const std::size_t   n         = dof_handler.n_dofs();
    if (cells != tria.n_active_cells() || values.size() != n
        || increment.size() != n)
      throw InputError(source + ": the checkpoint has " + std::to_string(cells)
                       + " cells and " + std::to_string(values.size())
                       + " unknowns, the mesh of this run "
                       + std::to_string(tria.n_active_cells()) + " and "
                       + std::to_string(n) + ": it belongs to another mesh");
    StepState saved;
    get_balance(r, saved);
    saved.stats = r.get<HeatStatistics>();
    if (!r.at_end())
      throw InputError(source + ": the checkpoint has trailing data");
    for (const double v : values)
      if (!std::isfinite(v))
        throw InputError(source
                         + ": the checkpoint holds non-finite "
                           "temperatures");
    solution.reinit(n);
    increment_old.reinit(n);
    std::copy(values.begin(), values.end(), solution.begin());
    std::copy(increment.begin(), increment.end(), increment_old.begin());
    take_balance(*this, saved);
  }



  template <>
  std::string
  HeatSystem<LinearAlgebra::Serial>::checkpoint(const std::string &) const
  {
    io::BinaryWriter w;
    w.put_string(heat_magic);
    // An adaptive mesh changes during the run: it is stored too.
    w.put_string(prm.adaptive_refinement ? saved_mesh(tria) : std::string());
    w.put<std::uint64_t>(tria.n_active_cells());
    w.put_doubles(solution);
    w.put_doubles(increment_old);
    put_balance(w, *this);
    w.put(stats);
    return w.bytes;
  }



  template <>
  std::string
  HeatSystem<LinearAlgebra::Trilinos>::checkpoint(
    const std::string &mesh_files) const
  {
    if (mesh_files.empty())
      throw std::invalid_argument(
        "heat: the distributed solver needs a file prefix for checkpoints");
    // Alternate between two file sets: a save interrupted half-way leaves
    // the set named by the previous checkpoint.bin intact.
    const std::string name
      = mesh_files + "-" + std::to_string(checkpoints_written++ % 2);
    VectorType increment(owned, relevant, comm);
    increment = increment_old;
    parallel::distributed::SolutionTransfer<2, VectorType> transfer(
      dof_handler);
    transfer.prepare_for_serialization(
      std::vector<const VectorType *>{&field(), &increment});
    tria.save(name);
    io::BinaryWriter w;
    w.put_string(distributed_magic);
    w.put_string(name);
    w.put<std::uint64_t>(tria.n_global_active_cells());
    put_balance(w, *this);
    w.put<std::uint64_t>(linear_iterations);
    w.put(stats);
    return w.bytes;
  }



  template <>
  void
  HeatSystem<LinearAlgebra::Trilinos>::restore(const std::string &bytes,
                                               const std::string &source)
  {
    io::BinaryReader r = open_checkpoint(
      bytes,
      source,
      distributed_magic,
      "a checkpoint of the distributed heat solver (written by a serial run?)");
    const std::string name  = r.get_string();
    const auto        cells = r.get<std::uint64_t>();
    StepState         saved;
    get_balance(r, saved);
    const auto linear = r.get<std::uint64_t>();
    saved.stats       = r.get<HeatStatistics>();
    if (!r.at_end())
      throw InputError(source + ": the checkpoint has trailing data");
    if (!std::ifstream(name + ".info"))
      throw InputError(source + ": the mesh files " + name
                       + ".* of the checkpoint are missing");
    // p4est loads into a triangulation holding only the coarse mesh.
    tria.clear();
    MeshInfo coarse;
    build_mesh(tria, prm, coarse, true);
    tria.load(name);
    if (tria.n_global_active_cells() != cells)
      throw InputError(source + ": the mesh files " + name + ".* hold "
                       + std::to_string(tria.n_global_active_cells())
                       + " cells, the checkpoint " + std::to_string(cells));
    setup_system();
    assemble_fixed();
    parallel::distributed::SolutionTransfer<2, VectorType> transfer(
      dof_handler);
    std::vector<VectorType *> targets{&solution, &increment_old};
    transfer.deserialize(targets);
    hanging.distribute(solution);
    hanging.distribute(increment_old);
    take_balance(*this, saved);
    linear_iterations = linear;
    operators.clear();
    ghosted_valid = false;
    for (unsigned int k = 0; k < probes.size(); ++k)
      probes[k] = locate(probe_points[k]);
  }
} // namespace rockdda::thermal::internal
