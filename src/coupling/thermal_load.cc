#include <rockdda/coupling/thermal_load.h>
#include <rockdda/dda/block_matrices.h>
#include <rockdda/io/error.h>
#include <rockdda/thermal/heat_cycles.h>

#include <cmath>

namespace rockdda::coupling
{
  namespace
  {
    constexpr double two_pi = 6.28318530717958647692;
  }



  double
  SeasonalForcing::air(const double time) const
  {
    return mean + annual_amplitude * std::sin(two_pi * time / period)
           + daily_amplitude * std::sin(two_pi * time * daily_cycles / period);
  }



  PeriodicBlockTemperature::PeriodicBlockTemperature(
    const std::vector<thermal::Block> &blocks,
    const SeasonalForcing             &forcing_,
    const HeatControls                &controls)
      : forcing(forcing_)
      , samples(controls.samples_per_cycle)
  {
    require_in_range(samples >= 4,
                     "Thermal forcing/Samples per cycle",
                     samples,
                     ">= 4");
    const double dt_sample = forcing.period / samples;
    const double steps_per_sample
      = std::max(1., std::round(dt_sample / controls.time_step));
    thermal::HeatParameters p;
    p.materials           = {controls.material};
    p.blocks              = blocks;
    p.joint_contact       = thermal::HeatParameters::JointContact::perfect;
    p.degree              = controls.degree;
    p.coarse_cell_size    = controls.cell_size;
    p.stepper             = thermal::TimeStepper::crank_nicolson;
    p.time_step           = dt_sample / steps_per_sample;
    p.initial_temperature = forcing.mean;
    thermal::BoundaryCondition air;
    air.type = thermal::BoundaryCondition::Type::convective;
    air.heat_transfer_coefficient = forcing.heat_transfer_coefficient;
    const SeasonalForcing f       = forcing;
    air.value
      = [f](const double, const double, const double t) { return f.air(t); };
    air.uniform = true;
    for (const std::string tag : {"exposed", "crack"})
      {
        air.tag = tag;
        p.boundary_conditions.push_back(air);
      }
    thermal::BoundaryCondition none;
    none.type  = thermal::BoundaryCondition::Type::flux;
    none.tag   = "adiabatic";
    none.value = [](const double, const double, const double) { return 0.; };
    p.boundary_conditions.push_back(none);

    thermal::HeatSolver heat(p);
    n_cells = heat.statistics().n_cells;
    // Harmonic where the heat solver can (a serial run; under MPI with
    // several ranks it is distributed and steps in time instead).
    if (controls.harmonic && heat.harmonic_available())
      {
        const double omega = two_pi / forcing.period;
        annual             = heat.harmonic_block_means(omega);
        daily              = forcing.daily_amplitude != 0.
                               ? heat.harmonic_block_means(omega * forcing.daily_cycles)
                               : std::vector<std::complex<double>>(annual.size(), 0.);
        const auto moments = heat.block_moments();
        areas.resize(blocks.size());
        for (std::size_t b = 0; b < blocks.size(); ++b)
          {
            areas[b] = moments[b].area;
            if (!std::isfinite(std::abs(annual[b]))
                || !std::isfinite(std::abs(daily[b])))
              throw InputError(
                "the harmonic heat solution of block " + std::to_string(b + 1)
                + " is not finite: check its polygon and the heat controls "
                  "(Thermal forcing/Cell size)");
          }
        return;
      }
    const auto moments = thermal::sample_block_moments(
      heat,
      p,
      controls.spin_up_cycles * forcing.period,
      dt_sample,
      samples,
      "check its polygon and the heat controls (Thermal forcing/Cell size, "
      "Time step)");
    table.assign(samples, std::vector<double>(blocks.size()));
    areas.resize(blocks.size());
    for (unsigned int k = 0; k < samples; ++k)
      for (std::size_t b = 0; b < blocks.size(); ++b)
        {
          table[k][b] = moments[k][b].mean;
          areas[b]    = moments[k][b].area;
        }
    n_steps = heat.statistics().n_steps;
  }



  double
  PeriodicBlockTemperature::mean(const unsigned int b, const double time) const
  {
    if (!annual.empty())
      {
        // The air's sinusoids a sin(w t) = Re(-i a e^{i w t}).
        const double               w = two_pi * time / forcing.period;
        const std::complex<double> minus_i(0., -1.);
        return forcing.mean
               + forcing.annual_amplitude
                   * std::real(minus_i * annual[b] * std::polar(1., w))
               + forcing.daily_amplitude
                   * std::real(minus_i * daily[b]
                               * std::polar(1., w * forcing.daily_cycles));
      }
    double phase = std::fmod(time / forcing.period, 1.);
    if (phase < 0.)
      phase += 1.;
    const double       x = phase * samples;
    const unsigned int k = std::min(static_cast<unsigned int>(x), samples - 1);
    const double       w = x - k;
    return (1. - w) * table[k][b] + w * table[(k + 1) % samples][b];
  }



  double
  BlockHeatMap::temperature(const unsigned int              b,
                            const PeriodicBlockTemperature &heat,
                            const SeasonalForcing          &forcing,
                            const double                    time) const
  {
    if (index[b] >= 0)
      return heat.mean(index[b], time);
    if (index[b] == -1)
      return forcing.air(time);
    if (index[b] == -3)
      {
        double sum = 0., area = 0.;
        for (const int p : pieces[b])
          {
            sum += heat.area(p) * heat.mean(p, time);
            area += heat.area(p);
          }
        return sum / area;
      }
    return forcing.mean;
  }



  std::vector<Eigen::Vector3d>
  thermal_eigenstrains(const dda::BlockSystem         &scene,
                       const BlockHeatMap             &map,
                       const PeriodicBlockTemperature &temperature,
                       const SeasonalForcing          &forcing,
                       const double                    alpha,
                       const double                    time)
  {
    std::vector<Eigen::Vector3d> e(scene.blocks.size(),
                                   Eigen::Vector3d::Zero());
    for (std::size_t b = 0; b < scene.blocks.size(); ++b)
      {
        if (map.index[b] == -2)
          continue;
        const double T = map.temperature(b, temperature, forcing, time);
        e[b]
          = dda::thermal_eigenstrain(scene.materials[scene.blocks[b].material],
                                     alpha * (T - forcing.mean));
      }
    return e;
  }
} // namespace rockdda::coupling
