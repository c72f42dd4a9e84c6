/**
 * @file
 * The heat solver's public interface (HeatSolver): it runs the one solver
 * internal::HeatSystem (heat_system.h) over the serial linear-algebra types
 * or, with more than one MPI rank or when asked for, over the Trilinos ones
 * (heat_linear_algebra.h), and forwards every call to it. The pieces of the
 * solver are in the files named after what they do: heat_system.cc,
 * heat_mesh.cc, heat_assembly.cc, heat_joints.cc, heat_time_stepping.cc,
 * heat_arkode.cc, heat_adaptivity.cc, heat_probes.cc, heat_checkpoint.cc
 * and heat_output.cc.
 */
#include <deal.II/base/mpi.h>

#include "heat_system.h"

namespace rockdda::thermal
{
  using namespace dealii;

  HeatSolver::HeatSolver(const HeatParameters &parameters)
  {
    using namespace internal;
    if (use_distributed_solver(parameters))
      impl = std::make_unique<HeatSystem<LinearAlgebra::Trilinos>>(parameters);
    else
      impl = std::make_unique<HeatSystem<LinearAlgebra::Serial>>(parameters);
  }

  HeatSolver::~HeatSolver() = default;

  double
  HeatSolver::time() const
  {
    return impl->time;
  }

  void
  HeatSolver::advance_to(const double end_time)
  {
    impl->advance_to(end_time);
  }

  double
  HeatSolver::value(const double x, const double y) const
  {
    return impl->value(x, y);
  }

  unsigned int
  HeatSolver::add_probe(const double x, const double y)
  {
    return impl->add_probe(x, y);
  }

  double
  HeatSolver::probe_value(const unsigned int index) const
  {
    return impl->probe_value(index);
  }

  std::vector<BlockMoments>
  HeatSolver::block_moments() const
  {
    return impl->block_moments();
  }

  std::vector<std::complex<double>>
  HeatSolver::harmonic_block_means(const double omega) const
  {
    return impl->harmonic_block_means(omega);
  }

  bool
  HeatSolver::harmonic_available() const
  {
    return impl->harmonic_available();
  }

  double
  HeatSolver::stored_heat() const
  {
    return impl->stored_heat();
  }

  double
  HeatSolver::boundary_heat_in() const
  {
    return impl->boundary_heat;
  }

  double
  HeatSolver::source_heat_in() const
  {
    return impl->source_heat;
  }

  double
  HeatSolver::l2_error(const SpaceTimeFunction &exact) const
  {
    return impl->l2_error(exact);
  }

  std::vector<std::pair<std::string, std::string>>
  HeatSolver::vtu_files(const std::string &name) const
  {
    return impl->vtu_files(name);
  }

  bool
  HeatSolver::is_output_rank() const
  {
    return !Utilities::MPI::job_supports_mpi()
           || Utilities::MPI::this_mpi_process(MPI_COMM_WORLD) == 0;
  }

  std::string
  HeatSolver::vtu() const
  {
    return impl->vtu();
  }

  HeatStatistics
  HeatSolver::statistics() const
  {
    return impl->statistics();
  }

  std::string
  HeatSolver::method_description() const
  {
    return impl->method_description();
  }

  std::string
  HeatSolver::timing_summary() const
  {
    return impl->timing_summary();
  }

  std::string
  HeatSolver::checkpoint(const std::string &mesh_files) const
  {
    return impl->checkpoint(mesh_files);
  }

  void
  HeatSolver::restore(const std::string &bytes, const std::string &source)
  {
    impl->restore(bytes, source);
  }
} // namespace rockdda::thermal
