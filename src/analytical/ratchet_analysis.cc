/**
 * @file
 * Analysis type "ratchet-analytical": the thermal ratchet (wedging) model of
 * Pasten (2012), thesis Eqs. 5.1-5.6 and 5.9, for one case, its thresholds,
 * sweeps over wedge length, beta, alpha, temperature amplitude, friction and
 * slope, and the reproduction of thesis Fig. 5-13. Driven by the section
 * "Ratchet analytical" (subsections "Field cycle", "Sweeps",
 * "Figure 5-13").
 */
#include <rockdda/analytical/analyses.h>
#include <rockdda/analytical/ratchet.h>
#include <rockdda/io/error.h>
#include <rockdda/io/parameters.h>
#include <rockdda/io/plot.h>

#include <array>
#include <cmath>
#include <limits>
#include <memory>
#include <string>
#include <vector>

namespace rockdda::analytical
{
  namespace
  {
    using dealii::Patterns::Double;

    /// One swept parameter: its keys, output file, column and how a swept
    /// value maps onto RatchetInput.
    struct SweepSpec
    {
      /// Key stem in "Sweeps" ("<stem> min", "<stem> max").
      std::string key;
      /// Output file sweep_<file>.csv and the name of its first column.
      std::string file;
      /// SI unit of the swept value.
      std::string unit;
      /// The member of RatchetInput it sets.
      double RatchetInput::*member;
      /// Member value = factor * swept value (2 for amplitude -> peak to
      /// peak).
      double factor;
      /// Default ends of the sweep.
      std::string min, max;
      /// Help text of the range, e.g. "; >= 0.", "; 0 <= phi < 90.".
      std::string range;
    };

    /// The six sweeps, in output order.
    const std::vector<SweepSpec> &
    sweep_specs()
    {
      static const std::vector<SweepSpec> specs = {
        {"Wedge length",
         "wedge_length",
         "m",
         &RatchetInput::wedge_length,
         1.,
         "0",
         "0.2",
         "; >= 0."},
        {"Beta",
         "beta",
         "-",
         &RatchetInput::beta,
         1.,
         "0.1",
         "1",
         "; 0 < beta <= 1."},
        {"Thermal expansion coefficient",
         "thermal_expansion",
         "1/K",
         &RatchetInput::thermal_expansion,
         1.,
         "4e-6",
         "1.2e-5",
         "; >= 0."},
        {"Temperature amplitude",
         "temperature_amplitude",
         "K",
         &RatchetInput::temperature_change,
         2.,
         "0",
         "15",
         "; >= 0. The model uses Delta T_p = 2 x amplitude."},
        {"Friction angle",
         "friction_angle",
         "deg",
         &RatchetInput::friction_angle_deg,
         1.,
         "35",
         "45",
         "; 0 <= phi < 90, and above the slope."},
        {"Slope",
         "slope",
         "deg",
         &RatchetInput::slope_deg,
         1.,
         "10",
         "25",
         "; 0 <= eta < 90, and below the friction angle."},
      };
      return specs;
    }

    /// The pattern of a sweep end of @p spec.
    std::unique_ptr<dealii::Patterns::PatternBase>
    sweep_pattern(const SweepSpec &spec)
    {
      if (spec.key == "Beta")
        return io::DoubleInterval(0., true, 1., false).clone();
      if (spec.key == "Friction angle" || spec.key == "Slope")
        return io::DoubleInterval::right_open(0., 90.).clone();
      return Double(0.).clone();
    }

    /// @p n values evenly spaced from @p a to @p b.
    std::vector<double>
    linspace(const double a, const double b, const unsigned int n)
    {
      std::vector<double> v(n);
      for (unsigned int i = 0; i < n; ++i)
        v[i] = n == 1 ? a : a + (b - a) * i / (n - 1.);
      return v;
    }

    /// The "ratchet-analytical" analysis.
    class RatchetAnalyticalAnalysis : public io::Analysis
    {
    public:
      std::string
      name() const override
      {
        return "ratchet-analytical";
      }

      std::string
      description() const override
      {
        return "analytical thermal ratchet (wedging) model of Pasten (2012), "
               "thesis Eqs. 5.1-5.9: permanent displacement per seasonal "
               "cycle, thresholds, sweeps and the Fig. 5-13 reproduction";
      }

      void
      declare_parameters(dealii::ParameterHandler &prm) const override
      {
        using io::DoubleInterval;
        prm.enter_subsection("Ratchet analytical");
        io::declare(prm,
                    "Block length",
                    block1_default(&analytical::Block1Section::length),
                    DoubleInterval::positive(),
                    "m",
                    "Length L_B of the sliding block (thesis Fig. 5-9, Eqs. "
                    "5.3-5.5); also the slab length of the homogenisation "
                    "time t* = 2 L_B^2 / D_T. Must be > 0.");
        io::declare(prm,
                    "Block height",
                    block1_default(&analytical::Block1Section::height),
                    DoubleInterval::positive(),
                    "m",
                    "Height H of the block's front (downslope) face (Eqs. "
                    "5.3, 5.4); the back face at the tension crack is H - L_B "
                    "tan(slope) high and the cross-section L_B (H - L_B "
                    "tan(slope) / 2) (doc/theory/block1.md). Must be > 0 and "
                    "exceed L_B tan(slope) / 2.");
        io::declare(prm,
                    "Wedge length",
                    "0.2",
                    Double(0.),
                    "m",
                    "Length L_W of the rock fragments (wedge) in the tension "
                    "crack (Eqs. 5.2, 5.4). Must be >= 0.");
        io::declare(prm,
                    "Slope",
                    block1_default(&analytical::Block1Section::slope_deg),
                    DoubleInterval::right_open(0., 90.),
                    "deg",
                    "Dip eta of the sliding plane, 0 <= eta < 90; must be "
                    "below the friction angle (else the block is not stable "
                    "without the crack).");
        io::declare(prm,
                    "Friction angle",
                    "41",
                    DoubleInterval::right_open(0., 90.),
                    "deg",
                    "Friction angle phi of the sliding plane, 0 <= phi < 90.");
        io::declare(prm,
                    "Density",
                    "2600",
                    DoubleInterval::positive(),
                    "kg/m^3",
                    "Mass density rho of the rock. Must be > 0.");
        io::declare(prm,
                    "Gravity",
                    "9.80665",
                    DoubleInterval::positive(),
                    "m/s^2",
                    "Gravitational acceleration g; unit weight gamma = rho g. "
                    "Must be > 0.");
        io::declare(prm,
                    "Young's modulus",
                    "40e9",
                    DoubleInterval::positive(),
                    "Pa",
                    "Young's modulus E of the intact rock (Eq. 5.4). Must be "
                    "> 0.");
        io::declare(prm,
                    "Joint shear stiffness",
                    "1e9",
                    DoubleInterval::positive(),
                    "Pa/m",
                    "Shear stiffness k_j of the sliding joint (Eq. 5.5; "
                    "Masada bedding plane 1 GPa/m). Must be > 0.");
        io::declare(prm,
                    "Thermal expansion coefficient",
                    "8e-6",
                    Double(0.),
                    "1/K",
                    "Linear thermal expansion coefficient alpha of the rock "
                    "(Eq. 5.2). Must be >= 0.");
        io::declare(prm,
                    "Temperature amplitude",
                    "9",
                    Double(0.),
                    "K",
                    "Annual temperature amplitude (Table 5-2: 9 K). Eq. 5.2 "
                    "uses the peak-to-peak change Delta T_p = 2 x amplitude. "
                    "Must be >= 0.");
        io::declare(prm,
                    "Beta",
                    "0.45",
                    DoubleInterval(0., true, 1., false),
                    "-",
                    "Coefficient of the non-uniform temperature distribution "
                    "in the block (Eq. 5.2), 0 < beta <= 1.");
        io::declare(prm,
                    "Thermal conductivity",
                    "1.7",
                    DoubleInterval::positive(),
                    "W/(m K)",
                    "Thermal conductivity lambda of the rock. Must be > 0.");
        io::declare(prm,
                    "Specific heat capacity",
                    "810",
                    DoubleInterval::positive(),
                    "J/(kg K)",
                    "Specific heat capacity c_p of the rock. Must be > 0.");
        io::declare(prm,
                    "Exposure time",
                    "15552000",
                    DoubleInterval::positive(),
                    "s",
                    "Exposure time t_exp of one heating season in Eq. 5.1 "
                    "(180 days = 15552000 s). Must be > 0.");
        io::declare(prm,
                    "Plots",
                    "true",
                    dealii::Patterns::Bool(),
                    "-",
                    "Draw sweeps.png, figure_5_13.png and field_cycle.png "
                    "with scripts/plot_ratchet.py (/usr/bin/python3 and "
                    "matplotlib); skipped with a note if unavailable.");

        prm.enter_subsection("Field cycle");
        io::declare(prm,
                    "Joint displacement",
                    "1.4e-4",
                    Double(0.),
                    "m",
                    "Annual joint displacement dL of a block without ratchet "
                    "(Eq. 5.9; WJM 2 at the West station: 0.14 mm). Must be "
                    ">= 0.");
        io::declare(prm,
                    "Temperature change",
                    "9",
                    DoubleInterval::positive(),
                    "K",
                    "Temperature change dT of Eq. 5.9 (the thesis uses the 9 "
                    "K amplitude). Must be > 0.");
        io::declare(prm,
                    "Block length",
                    "1.6",
                    DoubleInterval::positive(),
                    "m",
                    "Length L_B of the monitored block (Eq. 5.9; West "
                    "station: 1.6 m). Must be > 0.");
        io::declare(prm,
                    "Skin depth",
                    "0",
                    Double(0.),
                    "m",
                    "Skin depth S_d of Eq. 5.9; 0 takes Eq. 5.1 for the rock "
                    "mass behind the joint (no homogenisation limit: 2.5 m "
                    "at Masada). Must be >= 0.");
        prm.leave_subsection();

        prm.enter_subsection("Sweeps");
        io::declare(prm,
                    "Points",
                    "41",
                    dealii::Patterns::Integer(2, 100000),
                    "-",
                    "Number of values in each sweep, ends included, 2 to "
                    "100000.");
        for (const SweepSpec &s : sweep_specs())
          {
            io::declare(prm,
                        s.key + " min",
                        s.min,
                        *sweep_pattern(s),
                        s.unit,
                        "Lower end of the sweep written to sweep_" + s.file
                          + ".csv" + s.range);
            io::declare(prm,
                        s.key + " max",
                        s.max,
                        *sweep_pattern(s),
                        s.unit,
                        "Upper end of the sweep written to sweep_" + s.file
                          + ".csv" + s.range
                          + (s.key == "Wedge length"
                               ? " Also the wedge-length range of the Fig. "
                                 "5-13 reproduction."
                               : ""));
          }
        prm.leave_subsection();

        prm.enter_subsection("Figure 5-13");
        for (const std::string i : {"1", "2"})
          {
            io::declare(prm,
                        "Beta " + i,
                        i == "1" ? "0.45" : "0.7",
                        DoubleInterval(0., true, 1., false),
                        "-",
                        "beta of curve " + i
                          + " of the Fig. 5-13 reproduction (statistics.csv), "
                            "0 < beta <= 1.");
            io::declare(prm,
                        "Thermal expansion coefficient " + i,
                        i == "1" ? "8e-6" : "6e-6",
                        Double(0.),
                        "1/K",
                        "alpha of curve " + i
                          + " of the Fig. 5-13 reproduction. Must be >= 0.");
          }
        prm.leave_subsection();
        prm.leave_subsection();
      }

      void
      parse_parameters(dealii::ParameterHandler &prm,
                       const std::string        &prm_file) override
      {
        prm.enter_subsection("Ratchet analytical");
        input.block_length          = prm.get_double("Block length");
        input.block_height          = prm.get_double("Block height");
        input.wedge_length          = prm.get_double("Wedge length");
        input.slope_deg             = prm.get_double("Slope");
        input.friction_angle_deg    = prm.get_double("Friction angle");
        input.density               = prm.get_double("Density");
        input.gravity               = prm.get_double("Gravity");
        input.youngs_modulus        = prm.get_double("Young's modulus");
        input.joint_shear_stiffness = prm.get_double("Joint shear stiffness");
        input.thermal_expansion
          = prm.get_double("Thermal expansion coefficient");
        input.temperature_change = 2. * prm.get_double("Temperature amplitude");
        input.beta               = prm.get_double("Beta");
        input.conductivity       = prm.get_double("Thermal conductivity");
        input.heat_capacity      = prm.get_double("Specific heat capacity");
        input.exposure_time      = prm.get_double("Exposure time");
        plots                    = prm.get_bool("Plots");

        prm.enter_subsection("Field cycle");
        field_displacement = prm.get_double("Joint displacement");
        field_temperature  = prm.get_double("Temperature change");
        field_length       = prm.get_double("Block length");
        field_skin_depth   = prm.get_double("Skin depth");
        prm.leave_subsection();

        prm.enter_subsection("Sweeps");
        points = prm.get_integer("Points");
        sweep_ends.clear();
        for (const SweepSpec &s : sweep_specs())
          sweep_ends.emplace_back(prm.get_double(s.key + " min"),
                                  prm.get_double(s.key + " max"));
        prm.leave_subsection();

        prm.enter_subsection("Figure 5-13");
        for (unsigned int i = 0; i < 2; ++i)
          {
            const std::string n = std::to_string(i + 1);
            figure_beta[i]      = prm.get_double("Beta " + n);
            figure_alpha[i]
              = prm.get_double("Thermal expansion coefficient " + n);
          }
        prm.leave_subsection();
        prm.leave_subsection();

        io::with_parameter_file(prm_file, [&]() { validate(input); });
        if (field_skin_depth == 0.)
          field_skin_depth
            = skin_depth(thermal_diffusivity(input.conductivity,
                                             input.density,
                                             input.heat_capacity),
                         input.exposure_time,
                         std::numeric_limits<double>::infinity());

        // Every sweep end must give a valid case (the model is monotonic in
        // each parameter, so the ends suffice).
        for (std::size_t k = 0; k < sweep_specs().size(); ++k)
          {
            const SweepSpec  &s   = sweep_specs()[k];
            const std::string key = "Ratchet analytical/Sweeps/" + s.key;
            io::require(sweep_ends[k].first <= sweep_ends[k].second,
                        prm_file,
                        key + " min",
                        sweep_ends[k].first,
                        "min <= '" + s.key + " max' = "
                          + io::format_number(sweep_ends[k].second, 6));
            for (const auto &[end, value] :
                 {std::make_pair(std::string(" min"), sweep_ends[k].first),
                  std::make_pair(std::string(" max"), sweep_ends[k].second)})
              {
                RatchetInput trial = input;
                trial.*s.member    = s.factor * value;
                try
                  {
                    validate(trial);
                  }
                catch (const InputError &e)
                  {
                    throw InputError(prm_file + ": key '" + key + end
                                     + "' = " + io::format_number(value, 6)
                                     + " gives an invalid case: " + e.what());
                  }
              }
          }
        for (unsigned int i = 0; i < 2; ++i)
          {
            RatchetInput trial      = input;
            trial.beta              = figure_beta[i];
            trial.thermal_expansion = figure_alpha[i];
            io::with_parameter_file(prm_file, [&]() { validate(trial); });
          }
      }

      void
      run(io::RunContext &context) override
      {
        auto &log = context.log;
        auto &sum = context.summary;

        // The single case.
        const RatchetResult r             = ratchet(input);
        const double        threshold_dt  = threshold_temperature_change(input);
        const double        threshold_phi = threshold_friction_angle(input);
        sum.add("diffusivity", r.diffusivity, "m^2/s");
        sum.add("homogenisation_time", r.homogenisation_time, "s");
        sum.add("homogenised", r.homogenised ? 1. : 0., "-");
        sum.add("skin_depth", r.skin_depth, "m");
        sum.add("temperature_change", input.temperature_change, "K");
        sum.add("thermal_displacement", r.thermal_displacement, "m");
        sum.add("max_force", r.max_force, "N/m");
        sum.add("elastic_displacement", r.elastic_displacement, "m");
        sum.add("joint_displacement", r.joint_displacement, "m");
        sum.add("excess_displacement", r.excess, "m");
        sum.add("plastic_displacement", r.plastic_displacement, "m");
        sum.add("ratchet_rate", 1e3 * r.plastic_displacement, "mm/yr");
        sum.add("threshold_temperature_change", threshold_dt, "K");
        sum.add("threshold_temperature_amplitude", 0.5 * threshold_dt, "K");
        sum.add("threshold_friction_angle", threshold_phi, "deg");
        log.line(
          "skin depth " + io::format_number(r.skin_depth, 4) + " m"
          + (r.homogenised ? " (homogenised: t_exp > t*, S_d = L_B/2)" : "")
          + ", F_max " + io::format_number(r.max_force, 4) + " N/m");
        log.line("per cycle: delta_T " + mm(r.thermal_displacement)
                 + ", delta_sigma " + mm(r.elastic_displacement) + ", delta_j "
                 + mm(r.joint_displacement) + ", delta_p "
                 + mm(r.plastic_displacement));
        log.line("no ratchet below a peak-to-peak temperature change of "
                 + io::format_number(threshold_dt, 4) + " K (amplitude "
                 + io::format_number(0.5 * threshold_dt, 4)
                 + " K) or above a friction angle of "
                 + io::format_number(threshold_phi, 4) + " deg");

        // Eq. 5.9: alpha from the field cycle, for the case's beta and
        // against beta (Fig. 5-11B).
        const double alpha_field
          = thermal_expansion_from_field_cycle(field_displacement,
                                               field_temperature,
                                               field_length,
                                               input.beta,
                                               field_skin_depth);
        sum.add("field_skin_depth", field_skin_depth, "m");
        sum.add("alpha_field_cycle", alpha_field, "1/K");
        log.line("Eq. 5.9: alpha = " + io::format_number(alpha_field, 4)
                 + " 1/K for beta = " + io::format_number(input.beta, 4)
                 + " (S_d = " + io::format_number(field_skin_depth, 4) + " m)");
        {
          io::Table table;
          table.add_column("beta", "-");
          table.add_column("alpha", "1/K");
          for (const double beta : linspace(0.05, 1., 96))
            table.add_row(
              {beta,
               thermal_expansion_from_field_cycle(field_displacement,
                                                  field_temperature,
                                                  field_length,
                                                  beta,
                                                  field_skin_depth)});
          context.output.write("field_cycle.csv", table.csv());
        }

        // The sweeps.
        for (std::size_t k = 0; k < sweep_specs().size(); ++k)
          {
            const SweepSpec          &s = sweep_specs()[k];
            const std::vector<double> values
              = linspace(sweep_ends[k].first, sweep_ends[k].second, points);
            std::vector<double> member_values;
            for (const double v : values)
              member_values.push_back(s.factor * v);
            const auto results = ratchet_sweep(input, s.member, member_values);
            io::Table  table;
            table.add_column(s.file, s.unit);
            add_result_columns(table);
            for (std::size_t i = 0; i < values.size(); ++i)
              table.add_row(result_row(values[i], results[i]));
            context.output.write("sweep_" + s.file + ".csv", table.csv());
          }
        log.line("sweeps: " + std::to_string(sweep_specs().size()) + " x "
                 + std::to_string(points) + " cases");

        // Fig. 5-13: delta_p against wedge length for two (beta, alpha).
        {
          const std::vector<double> wedge
            = linspace(sweep_ends[0].first, sweep_ends[0].second, points);
          std::array<std::vector<RatchetResult>, 2> curves;
          for (unsigned int c = 0; c < 2; ++c)
            {
              RatchetInput base      = input;
              base.beta              = figure_beta[c];
              base.thermal_expansion = figure_alpha[c];
              curves[c]
                = ratchet_sweep(base, &RatchetInput::wedge_length, wedge);
            }
          io::Table table;
          table.add_column("wedge_length", "m");
          for (const std::string c : {"1", "2"})
            table.add_column("plastic_displacement_" + c, "m");
          for (const std::string c : {"1", "2"})
            table.add_column("ratchet_rate_" + c, "mm/yr");
          for (std::size_t i = 0; i < wedge.size(); ++i)
            table.add_row({wedge[i],
                           curves[0][i].plastic_displacement,
                           curves[1][i].plastic_displacement,
                           1e3 * curves[0][i].plastic_displacement,
                           1e3 * curves[1][i].plastic_displacement});
          context.output.write("statistics.csv", table.csv());
          for (unsigned int c = 0; c < 2; ++c)
            {
              const std::string n = std::to_string(c + 1);
              sum.add("figure_5_13_beta_" + n, figure_beta[c], "-");
              sum.add("figure_5_13_alpha_" + n, figure_alpha[c], "1/K");
              sum.add("figure_5_13_rate_" + n + "_min_wedge",
                      1e3 * curves[c].front().plastic_displacement,
                      "mm/yr");
              sum.add("figure_5_13_rate_" + n + "_max_wedge",
                      1e3 * curves[c].back().plastic_displacement,
                      "mm/yr");
              log.line(
                "Fig. 5-13 curve " + n + " (beta "
                + io::format_number(figure_beta[c], 3) + ", alpha "
                + io::format_number(figure_alpha[c], 3) + "): "
                + io::format_number(1e3
                                      * curves[c].front().plastic_displacement,
                                    4)
                + " to "
                + io::format_number(1e3 * curves[c].back().plastic_displacement,
                                    4)
                + " mm/yr for L_W " + io::format_number(1e3 * wedge.front(), 4)
                + " to " + io::format_number(1e3 * wedge.back(), 4) + " mm");
            }
        }

        if (plots)
          draw_plots(context, r);
      }

    private:
      RatchetInput                           input;
      bool                                   plots              = true;
      double                                 field_displacement = 1.4e-4;
      double                                 field_temperature  = 9.;
      double                                 field_length       = 1.6;
      double                                 field_skin_depth   = 0.;
      unsigned int                           points             = 41;
      std::vector<std::pair<double, double>> sweep_ends;
      std::array<double, 2>                  figure_beta{{0.45, 0.7}};
      std::array<double, 2>                  figure_alpha{{8e-6, 6e-6}};

      /// A length in mm as text.
      static std::string
      mm(const double metres)
      {
        return io::format_number(1e3 * metres, 4) + " mm";
      }

      /// The result columns of a sweep table (after the swept value).
      static void
      add_result_columns(io::Table &table)
      {
        table.add_column("skin_depth", "m");
        table.add_column("max_force", "N/m");
        table.add_column("thermal_displacement", "m");
        table.add_column("elastic_displacement", "m");
        table.add_column("joint_displacement", "m");
        table.add_column("plastic_displacement", "m");
      }

      /// One row of a sweep table.
      static std::vector<double>
      result_row(const double value, const RatchetResult &r)
      {
        return {value,
                r.skin_depth,
                r.max_force,
                r.thermal_displacement,
                r.elastic_displacement,
                r.joint_displacement,
                r.plastic_displacement};
      }

      /// Run scripts/plot_ratchet.py on the output folder, handing it the
      /// scalars it labels the plots with (summary.csv is written later).
      void
      draw_plots(io::RunContext &context, const RatchetResult &r) const
      {
        std::string arguments;
        const auto  arg = [&](const std::string &name, const double value) {
          arguments += " " + name + "=" + io::format_number(value, 17);
        };
        for (unsigned int c = 0; c < 2; ++c)
          {
            arg("figure_5_13_beta_" + std::to_string(c + 1), figure_beta[c]);
            arg("figure_5_13_alpha_" + std::to_string(c + 1), figure_alpha[c]);
          }
        arg("field_skin_depth", field_skin_depth);
        arg("plastic_displacement", r.plastic_displacement);
        io::run_plot_script(context.output,
                            context.log,
                            "plot_ratchet.py",
                            {"sweeps.png",
                             "figure_5_13.png",
                             "field_cycle.png"},
                            arguments);
      }
    };
  } // namespace



  std::unique_ptr<io::Analysis>
  internal::make_ratchet_analytical_analysis()
  {
    return std::make_unique<RatchetAnalyticalAnalysis>();
  }
} // namespace rockdda::analytical
