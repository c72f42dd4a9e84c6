/**
 * @file
 * Internal to the thermal subsystem: the analysis type "heat" (class
 * HeatAnalysis), whose pieces live in the files named after what they do:
 * heat_analysis_parameters.cc (the "Heat" parameter sections),
 * heat_analysis_input.cc (reading them into HeatParameters) and
 * heat_analysis.cc (the run: spin-up, recording, checkpoints, summary and
 * the periodic half-space check).
 */
#ifndef ROCKDDA_THERMAL_HEAT_ANALYSIS_H
#define ROCKDDA_THERMAL_HEAT_ANALYSIS_H

#include <rockdda/io/analysis.h>
#include <rockdda/io/parameters.h>
#include <rockdda/thermal/heat_solver.h>

#include <deal.II/base/parameter_handler.h>

#include <string>
#include <vector>

namespace rockdda::thermal::internal
{
  /// Number of 'Heat/Boundary condition k' sections.
  constexpr unsigned int max_boundary_conditions = 6;

  /// The "heat" analysis.
  class HeatAnalysis : public io::Analysis
  {
  public:
    std::string
    name() const override
    {
      return "heat";
    }

    std::string
    description() const override
    {
      return "2D transient heat conduction in the rock blocks (deal.II)";
    }

    void
    declare_parameters(dealii::ParameterHandler &prm) const override;

    void
    parse_parameters(dealii::ParameterHandler &prm,
                     const std::string        &prm_file) override;

    void
    run(io::RunContext &context) override;

    bool
    resumes() const override
    {
      return resume;
    }

  private:
    HeatParameters           parameters;
    double                   end_time            = 0.;
    unsigned int             spin_up_cycles      = 0;
    double                   spin_up_period      = 0.;
    double                   output_interval     = 0.;
    double                   checkpoint_interval = 0.;
    bool                     resume              = false;
    std::vector<Point2>      probes;
    std::vector<double>      vtu_times;
    bool                     halfspace_check     = false;
    double                   surface_elevation   = 0.;
    double                   halfspace_amplitude = 0., halfspace_period = 0.;
    std::vector<std::string> bc_descriptions;
  };
} // namespace rockdda::thermal::internal

#endif
