/**
 * @file
 * The thermal load of a coupled run: the heat solver's periodic block
 * temperatures at the times the DDA asks for, turned into eigenstrains.
 * The heat solver and DDA never call each other; this is where they meet.
 */
#ifndef ROCKDDA_COUPLING_THERMAL_LOAD_H
#define ROCKDDA_COUPLING_THERMAL_LOAD_H

#include <rockdda/dda/block_system.h>
#include <rockdda/thermal/heat_solver.h>

#include <Eigen/Core>

#include <complex>
#include <vector>

namespace rockdda::coupling
{
  /// Air temperature at the exposed faces: a mean and sinusoids (SI).
  struct SeasonalForcing
  {
    /// Mean air temperature (deg C) = the stress-free reference.
    double mean = 20.;
    /// Annual amplitude (K) and period (s).
    double annual_amplitude = 9.;
    double period           = 31557600.;
    /// Daily amplitude (K); its period is period / daily_cycles.
    double       daily_amplitude = 0.;
    unsigned int daily_cycles    = 365;
    /// Heat transfer coefficient of the exposed faces (W/(m^2 K)).
    double heat_transfer_coefficient = 10.;
    /// Air temperature at @p time (s).
    double
    air(const double time) const;
  };

  /// Controls of the heat solution (SI).
  struct HeatControls
  {
    thermal::Material material;
    unsigned int      degree    = 2;
    double            cell_size = 1.;
    /// Heat time step (s); the samples must be a multiple of it.
    double       time_step         = 86400.;
    unsigned int spin_up_cycles    = 4;
    unsigned int samples_per_cycle = 24;
    /// The periodic field from the heat solver's harmonic solves (exact
    /// in time: no spin-up, time step or samples; serial runs), or by time
    /// stepping (spin-up periods, then a table of samples).
    bool harmonic = true;
  };

  /**
   * One period of per-block mean temperatures, computed once. Harmonic
   * (HeatControls::harmonic, the default): the air temperature is a mean
   * and sinusoids, the boundaries convective or adiabatic, so the periodic
   * field is the mean plus one complex response per frequency
   * (thermal::HeatSolver::harmonic_block_means), exact at any time.
   * Otherwise the heat solver runs @p spin_up_cycles periods from the mean
   * temperature (the field is then periodic: after n periods the transient of
   * the start has decayed by exp(-n pi^2 kappa T / L^2) in the slowest mode;
   * with the skin depth well below the blocks' size a few periods suffice) and
   * records @p samples_per_cycle samples of the next period. After that,
   * temperatures at any time come from the table (linear in time, periodic):
   * heat that is known is not solved again.
   */
  class PeriodicBlockTemperature
  {
  public:
    /// Run the heat solver on @p blocks (tags "exposed" and "crack": air;
    /// "adiabatic": no flux; "interior": shared faces).
    PeriodicBlockTemperature(const std::vector<thermal::Block> &blocks,
                             const SeasonalForcing             &forcing,
                             const HeatControls                &controls);
    /// Mean temperature of heat block @p b at @p time (s), deg C.
    double
    mean(const unsigned int b, const double time) const;
    /// Number of samples per period and the sample times' temperatures.
    unsigned int
    n_samples() const
    {
      return samples;
    }
    /// Area of heat block @p b (m^2).
    double
    area(const unsigned int b) const
    {
      return areas[b];
    }
    /// Whether the field came from harmonic solves (else time stepping).
    bool
    harmonic() const
    {
      return !annual.empty();
    }
    /// Heat solver cells and time steps of the solution (cost).
    unsigned int  n_cells = 0;
    unsigned long n_steps = 0;

  private:
    SeasonalForcing forcing;
    unsigned int    samples = 0;
    /// Harmonic: per block the complex mean response to the annual and
    /// the daily sinusoid of 1 K (empty when time-stepped).
    std::vector<std::complex<double>> annual, daily;
    /// table[k][b]: block b at phase k / samples of the period.
    std::vector<std::vector<double>> table;
    std::vector<double>              areas;
  };

  /**
   * Where each DDA block takes its temperature from: index[b] >= 0 one heat
   * block; -1 the air; -2 none (fixed blocks); -3 the area-weighted mean of
   * the heat blocks pieces[b] (a DDA block meshed in several conforming
   * pieces for the heat solver).
   */
  struct BlockHeatMap
  {
    std::vector<int>              index;
    std::vector<std::vector<int>> pieces;
    /// Mean temperature of DDA block @p b at @p time (deg C).
    double
    temperature(const unsigned int              b,
                const PeriodicBlockTemperature &heat,
                const SeasonalForcing          &forcing,
                const double                    time) const;
  };

  /**
   * The eigenstrains of a DDA scene at @p time: alpha (T - T_ref) of each
   * block's material (plane strain or stress, dda::thermal_eigenstrain),
   * with T from @p map (none for fixed blocks).
   */
  std::vector<Eigen::Vector3d>
  thermal_eigenstrains(const dda::BlockSystem         &scene,
                       const BlockHeatMap             &map,
                       const PeriodicBlockTemperature &temperature,
                       const SeasonalForcing          &forcing,
                       const double                    alpha,
                       const double                    time);
} // namespace rockdda::coupling

#endif
