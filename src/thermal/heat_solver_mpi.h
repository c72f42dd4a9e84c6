/**
 * @file
 * Internal to the thermal subsystem: the distributed (MPI) heat solver on a
 * parallel::distributed::Triangulation (p4est) with Trilinos matrices and
 * vectors. HeatSolver uses it when the run has more than one MPI rank (or
 * when the linear solver 'amg' is asked for); it implements the same
 * equations and bookkeeping as the serial solver (theta scheme).
 */
#ifndef ROCKDDA_THERMAL_HEAT_SOLVER_MPI_H
#define ROCKDDA_THERMAL_HEAT_SOLVER_MPI_H

#include <rockdda/thermal/heat_solver.h>

#include <memory>
#include <string>
#include <utility>
#include <vector>

namespace rockdda::thermal::internal
{
  /// The heat solver on all ranks of MPI_COMM_WORLD (collective calls).
  class DistributedHeat
  {
  public:
    /// Throws InputError for invalid parameters.
    explicit DistributedHeat(const HeatParameters &parameters);
    ~DistributedHeat();

    double
    time() const;
    void
    advance_to(const double end_time);
    double
    value(const double x, const double y) const;
    unsigned int
    add_probe(const double x, const double y);
    double
    probe_value(const unsigned int index) const;
    std::vector<BlockMoments>
    block_moments() const;
    double
    stored_heat() const;
    double
    boundary_heat_in() const;
    double
    source_heat_in() const;
    double
    l2_error(const SpaceTimeFunction &exact) const;
    std::vector<std::pair<std::string, std::string>>
    vtu_files(const std::string &name) const;
    HeatStatistics
    statistics() const;
    std::string
    method_description() const;
    std::string
    timing_summary() const;
    /// See HeatSolver::checkpoint() (collective).
    std::string
    checkpoint(const std::string &mesh_files) const;
    /// See HeatSolver::restore() (collective).
    void
    restore(const std::string &bytes, const std::string &source);

  private:
    class Impl;
    std::unique_ptr<Impl> impl;
  };

  /// True if the heat solver should run distributed: MPI is initialised
  /// and there is more than one rank, or @p parameters ask for AMG.
  bool
  use_distributed_solver(const HeatParameters &parameters);
} // namespace rockdda::thermal::internal

#endif
