/**
 * @file
 * Reading the "Heat" parameter sections of the analysis type "heat" into
 * HeatParameters and the run's controls: the lists of numbers, points and
 * tags, the checks with messages that name the key, the planned number of
 * steps, and the boundary data (constant, seasonal or from a CSV file).
 */
#include <rockdda/io/error.h>
#include <rockdda/io/output.h>
#include <rockdda/io/progress.h>
#include <rockdda/io/text.h>
#include <rockdda/thermal/boundary_data.h>

#include <deal.II/base/mpi.h>

#include "heat_analysis.h"
#include <cmath>
#include <sstream>
#include <string>
#include <vector>

namespace rockdda::thermal::internal
{
  namespace
  {
    double
    number(const std::string &text,
           const std::string &prm_file,
           const std::string &key)
    {
      std::size_t used = 0;
      double      v    = 0.;
      try
        {
          v = std::stod(io::trim(text), &used);
        }
      catch (const std::exception &)
        {
          used = 0;
        }
      if (used == 0 || used != io::trim(text).size() || !std::isfinite(v))
        throw InputError(prm_file + ": key '" + key + "': '" + text
                         + "' is not a finite number");
      return v;
    }

    /// The non-empty fields of @p text between the @p separator, each
    /// converted by @p convert.
    template <typename T, typename Convert>
    std::vector<T>
    list(const std::string &text, const char separator, Convert &&convert)
    {
      std::vector<T> result;
      for (const auto &field : io::split_fields(text, separator))
        if (!field.empty())
          result.push_back(convert(field));
      return result;
    }

    /// "x, y; x, y; ..." -> points.
    std::vector<Point2>
    points(const std::string &text,
           const std::string &prm_file,
           const std::string &key)
    {
      return list<Point2>(text, ';', [&](const std::string &p) {
        const auto xy = io::split_fields(p, ',');
        if (xy.size() != 2)
          throw InputError(prm_file + ": key '" + key + "': '" + p
                           + "' is not a point 'x, y' (m)");
        return Point2{
          {number(xy[0], prm_file, key), number(xy[1], prm_file, key)}};
      });
    }

    /// "a, b, ..." -> numbers.
    std::vector<double>
    numbers(const std::string &text,
            const std::string &prm_file,
            const std::string &key)
    {
      return list<double>(text, ',', [&](const std::string &v) {
        return number(v, prm_file, key);
      });
    }
  } // namespace



  void
  HeatAnalysis::parse_parameters(dealii::ParameterHandler &prm,
                                 const std::string        &prm_file)
  {
    HeatParameters &p = parameters;
    p                 = HeatParameters();
    bc_descriptions.clear();
    prm.enter_subsection("Heat");

    // Materials.
    prm.enter_subsection("Materials");
    {
      const auto names = io::split_fields(prm.get("Names"), ',');
      const auto k     = numbers(prm.get("Thermal conductivity"),
                             prm_file,
                             "Heat/Materials/Thermal conductivity");
      const auto rho
        = numbers(prm.get("Density"), prm_file, "Heat/Materials/Density");
      const auto cp = numbers(prm.get("Specific heat capacity"),
                              prm_file,
                              "Heat/Materials/Specific heat capacity");
      if (k.size() != names.size() || rho.size() != names.size()
          || cp.size() != names.size())
        throw InputError(prm_file
                         + ": section Heat/Materials: 'Thermal "
                           "conductivity', 'Density' and 'Specific heat "
                           "capacity' need one value per name ("
                         + std::to_string(names.size()) + ")");
      p.materials.clear();
      for (std::size_t i = 0; i < names.size(); ++i)
        {
          Material m;
          m.name          = names[i];
          m.conductivity  = k[i];
          m.density       = rho[i];
          m.heat_capacity = cp[i];
          validate(m, prm_file + ": section Heat/Materials");
          p.materials.push_back(m);
        }
    }
    prm.leave_subsection();

    // Geometry.
    prm.enter_subsection("Geometry");
    {
      const auto polys = io::split_fields(prm.get("Blocks"), '|');
      const auto tags  = io::split_fields(prm.get("Boundary tags"), '|');
      const auto mats  = io::split_fields(prm.get("Block materials"), ',');
      if (tags.size() != polys.size())
        throw InputError(prm_file
                         + ": key 'Heat/Geometry/Boundary tags' "
                           "has "
                         + std::to_string(tags.size())
                         + " '|'-separated groups but there are "
                         + std::to_string(polys.size()) + " blocks");
      if (!mats.empty() && !(mats.size() == 1 && mats[0].empty())
          && mats.size() != polys.size())
        throw InputError(prm_file
                         + ": key 'Heat/Geometry/Block materials' needs one "
                           "name per block ("
                         + std::to_string(polys.size()) + ")");
      for (std::size_t b = 0; b < polys.size(); ++b)
        {
          Block block;
          block.name      = "block " + std::to_string(b + 1);
          block.vertices  = points(polys[b], prm_file, "Heat/Geometry/Blocks");
          block.edge_tags = io::split_fields(tags[b], ',');
          if (block.edge_tags.size() != block.vertices.size())
            throw InputError(
              prm_file + ": key 'Heat/Geometry/Boundary tags': " + block.name
              + " has " + std::to_string(block.vertices.size())
              + " vertices but " + std::to_string(block.edge_tags.size())
              + " tags (one per edge)");
          if (mats.size() == polys.size() && !mats[b].empty())
            {
              bool found = false;
              for (unsigned int m = 0; m < p.materials.size(); ++m)
                if (p.materials[m].name == mats[b])
                  block.material = m, found = true;
              if (!found)
                throw InputError(prm_file
                                 + ": key 'Heat/Geometry/Block materials': "
                                   "unknown material '"
                                 + mats[b] + "'");
            }
          p.blocks.push_back(block);
        }
      const std::string contact = prm.get("Joint contact");
      p.joint_contact
        = contact == "perfect"       ? HeatParameters::JointContact::perfect
          : contact == "conductance" ? HeatParameters::JointContact::conductance
                                     : HeatParameters::JointContact::insulated;
      p.joint_conductance = prm.get_double("Joint conductance");
      io::require(p.joint_conductance > 0.,
                  prm_file,
                  "Heat/Geometry/Joint conductance",
                  p.joint_conductance,
                  "> 0 W/(m^2 K)");
    }
    prm.leave_subsection();

    prm.enter_subsection("Mesh");
    p.degree             = prm.get_integer("Finite element degree");
    p.coarse_cell_size   = prm.get_double("Coarse cell size");
    p.global_refinements = prm.get_integer("Global refinements");
    for (const auto &t : io::split_fields(prm.get("Refine near tags"), ','))
      if (!t.empty())
        p.refine_near_tags.push_back(t);
    p.band_width             = prm.get_double("Band width");
    p.band_cell_size         = prm.get_double("Band cell size");
    p.adaptive_refinement    = prm.get_bool("Adaptive refinement");
    p.adaptive_interval      = prm.get_integer("Adaptive interval");
    p.refine_fraction        = prm.get_double("Refine fraction");
    p.coarsen_fraction       = prm.get_double("Coarsen fraction");
    p.adaptive_min_cell_size = prm.get_double("Minimum cell size");
    p.adaptive_max_cells     = prm.get_integer("Maximum cells");
    prm.leave_subsection();
    io::require(p.refine_fraction + p.coarsen_fraction <= 1.,
                prm_file,
                "Heat/Mesh/Coarsen fraction",
                p.coarsen_fraction,
                "<= 1 - Refine fraction ("
                  + io::format_number(1. - p.refine_fraction, 6) + ")");
    io::require(p.coarse_cell_size > 0.,
                prm_file,
                "Heat/Mesh/Coarse cell size",
                p.coarse_cell_size,
                "> 0 m");

    prm.enter_subsection("Time stepping");
    const std::string method = prm.get("Method");
    p.stepper    = method == "crank-nicolson"   ? TimeStepper::crank_nicolson
                   : method == "backward-euler" ? TimeStepper::backward_euler
                                                : TimeStepper::arkode;
    p.time_step  = prm.get_double("Time step");
    p.start_time = prm.get_double("Start time");
    end_time     = prm.get_double("End time");
    p.initial_temperature       = prm.get_double("Initial temperature");
    spin_up_cycles              = prm.get_integer("Spin-up cycles");
    spin_up_period              = prm.get_double("Spin-up period");
    p.rannacher_steps           = prm.get_integer("Rannacher steps");
    checkpoint_interval         = prm.get_double("Checkpoint interval");
    resume                      = prm.get_bool("Resume");
    p.oscillation_fallback      = prm.get_bool("Oscillation fallback");
    p.direct_solver             = prm.get("Linear solver") == "direct";
    p.distributed               = prm.get("Linear solver") == "amg";
    p.arkode_relative_tolerance = prm.get_double("ARKODE relative tolerance");
    p.arkode_absolute_tolerance = prm.get_double("ARKODE absolute tolerance");
    prm.leave_subsection();
    if (p.distributed && !dealii::Utilities::MPI::job_supports_mpi())
      throw InputError(prm_file
                       + ": key 'Heat/Time stepping/Linear solver' = amg "
                         "is the distributed solver and needs MPI: run "
                         "mpirun -np N rockdda FILE.prm (N >= 1), or use "
                         "direct or cg");
    io::require(p.time_step > 0.,
                prm_file,
                "Heat/Time stepping/Time step",
                p.time_step,
                "> 0 s");
    io::require(end_time > p.start_time,
                prm_file,
                "Heat/Time stepping/End time",
                end_time,
                "> Start time (" + io::format_number(p.start_time) + " s)");
    io::require(spin_up_cycles == 0 || spin_up_period > 0.,
                prm_file,
                "Heat/Time stepping/Spin-up period",
                spin_up_period,
                "> 0 s");
    io::require(p.arkode_relative_tolerance > 0.,
                prm_file,
                "Heat/Time stepping/ARKODE relative tolerance",
                p.arkode_relative_tolerance,
                "> 0");
    io::require(p.arkode_absolute_tolerance > 0.,
                prm_file,
                "Heat/Time stepping/ARKODE absolute tolerance",
                p.arkode_absolute_tolerance,
                "> 0 K");
    if (p.stepper != TimeStepper::arkode)
      {
        // The planned step counts (fixed steps): an absurd one is a
        // mistake in the keys, not a run to start.
        const std::string ts = "Heat/Time stepping/";
        const std::string dt_text
          = "'" + ts + "Time step' = " + io::format_number(p.time_step) + " s";
        const double spin
          = spin_up_cycles * io::planned_steps(0., spin_up_period, p.time_step);
        const double record
          = io::planned_steps(p.start_time, end_time, p.time_step);
        const std::string limit
          = "; at most " + io::format_number(io::max_planned_steps, 3)
            + " are allowed: raise the time step or shorten the ";
        if (spin > io::max_planned_steps)
          throw InputError(
            prm_file + ": keys '" + ts
            + "Spin-up cycles' = " + std::to_string(spin_up_cycles) + ", '" + ts
            + "Spin-up period' = " + io::format_number(spin_up_period)
            + " s and " + dt_text + " plan " + io::format_number(spin, 4)
            + " spin-up time steps (cycles x period / time step)" + limit
            + "spin-up");
        if (record > io::max_planned_steps
            || spin + record > io::max_planned_steps)
          throw InputError(
            prm_file + ": keys '" + ts
            + "Start time' = " + io::format_number(p.start_time) + " s, '" + ts
            + "End time' = " + io::format_number(end_time) + " s and " + dt_text
            + " plan " + io::format_number(record, 4)
            + " time steps ((End time - Start time) / time step)"
            + (spin > 0.
                 ? " after " + io::format_number(spin, 4) + " spin-up steps"
                 : std::string())
            + limit + "run");
      }
    p.start_time -= spin_up_cycles * spin_up_period;
    const double first_time = p.start_time;

    // Boundary conditions.
    std::vector<std::string> geometry_tags;
    for (const auto &b : p.blocks)
      for (const auto &t : b.edge_tags)
        geometry_tags.push_back(t);
    for (unsigned int k = 1; k <= max_boundary_conditions; ++k)
      {
        const std::string section = "Boundary condition " + std::to_string(k);
        const std::string where   = "Heat/" + section;
        prm.enter_subsection(section);
        BoundaryCondition bc;
        bc.tag = io::trim(prm.get("Tag"));
        if (bc.tag.empty())
          {
            prm.leave_subsection();
            continue;
          }
        if (std::find(geometry_tags.begin(), geometry_tags.end(), bc.tag)
            == geometry_tags.end())
          {
            std::string known;
            for (const auto &t : geometry_tags)
              if (known.find("'" + t + "'") == std::string::npos)
                known += (known.empty() ? "'" : ", '") + t + "'";
            throw InputError(prm_file + ": key '" + where
                             + "/Tag': unknown "
                               "boundary tag '"
                             + bc.tag + "' (Heat/Geometry/Boundary tags has: "
                             + known + ")");
          }
        const std::string type = prm.get("Type");
        bc.type = type == "temperature"  ? BoundaryCondition::Type::temperature
                  : type == "convective" ? BoundaryCondition::Type::convective
                                         : BoundaryCondition::Type::flux;
        bc.heat_transfer_coefficient
          = prm.get_double("Heat transfer coefficient");
        const std::string data        = prm.get("Data");
        const double      mean        = prm.get_double("Mean");
        std::string       description = bc.tag + ": " + type + ", ";
        if (data == "constant")
          {
            bc.value = [mean](double, double, double) { return mean; };
            description += "constant " + io::format_number(mean, 6);
          }
        else if (data == "sinusoids")
          {
            const auto terms
              = parse_sinusoids(prm.get("Sinusoids"),
                                prm_file + ": key '" + where + "/Sinusoids'");
            if (terms.empty())
              throw InputError(prm_file + ": key '" + where
                               + "/Sinusoids' is empty but 'Data' is "
                                 "sinusoids");
            bc.value = [terms, mean](double, double, double t) {
              return evaluate(terms, mean, t);
            };
            description += "mean " + io::format_number(mean, 6) + " + "
                           + std::to_string(terms.size()) + " sinusoid(s)";
            if (k == 1)
              {
                halfspace_amplitude
                  = terms.size() == 1 ? terms[0].amplitude : 0.;
                halfspace_period = terms.size() == 1 ? terms[0].period : 0.;
              }
          }
        else
          {
            const std::string file = prm.get("CSV file");
            if (io::trim(file).empty())
              throw InputError(prm_file + ": key '" + where
                               + "/CSV file' is empty but 'Data' is csv");
            const auto series = std::make_shared<TimeSeries>(read_time_series(
              io::resolve_path(io::trim(file), prm_file, where + "/CSV file"),
              prm.get_double("CSV time unit")));
            if (series->time.front() > first_time + 1e-6
                || series->time.back() < end_time - 1e-6)
              throw InputError(series->file + ": the time series covers "
                               + io::format_number(series->time.front(), 10)
                               + " to "
                               + io::format_number(series->time.back(), 10)
                               + " s but the run (with spin-up) needs "
                               + io::format_number(first_time, 10) + " to "
                               + io::format_number(end_time, 10) + " s (key '"
                               + where + "/CSV file')");
            bc.value
              = [series](double, double, double t) { return (*series)(t); };
            description += "CSV " + series->file + " ("
                           + std::to_string(series->time.size()) + " rows)";
          }
        if (bc.type == BoundaryCondition::Type::convective)
          description
            += ", h = " + io::format_number(bc.heat_transfer_coefficient, 6)
               + " W/(m^2 K)";
        for (const auto &other : p.boundary_conditions)
          if (other.tag == bc.tag)
            throw InputError(prm_file + ": key '" + where + "/Tag': tag '"
                             + bc.tag + "' already has a boundary condition");
        p.boundary_conditions.push_back(bc);
        bc_descriptions.push_back(description);
        prm.leave_subsection();
      }
    for (const auto &t : geometry_tags)
      {
        bool found = t == "adiabatic";
        for (const auto &bc : p.boundary_conditions)
          found = found || bc.tag == t;
        if (!found)
          throw InputError(prm_file + ": boundary tag '" + t
                           + "' (Heat/Geometry/Boundary tags) has no "
                             "'Boundary condition N' section; add one or "
                             "rename the tag 'adiabatic'");
      }

    prm.enter_subsection("Output");
    probes          = points(prm.get("Probes"), prm_file, "Heat/Output/Probes");
    output_interval = prm.get_double("Output interval");
    vtu_times
      = numbers(prm.get("VTU times"), prm_file, "Heat/Output/VTU times");
    prm.leave_subsection();
    io::require(output_interval > 0.,
                prm_file,
                "Heat/Output/Output interval",
                output_interval,
                "> 0 s");

    prm.enter_subsection("Half-space check");
    halfspace_check   = prm.get_bool("Enabled");
    surface_elevation = prm.get_double("Surface elevation");
    prm.leave_subsection();
    prm.leave_subsection();
    if (halfspace_check
        && (p.boundary_conditions.empty()
            || p.boundary_conditions[0].type
                 != BoundaryCondition::Type::temperature
            || !(halfspace_period > 0.)))
      throw InputError(prm_file
                       + ": Heat/Half-space check needs 'Boundary "
                         "condition 1' of type temperature with "
                         "exactly one sinusoid");
    if (halfspace_check)
      io::require(end_time - (p.start_time + spin_up_cycles * spin_up_period)
                    >= halfspace_period * (1. - 1e-9),
                  prm_file,
                  "Heat/Time stepping/End time",
                  end_time,
                  ">= Start time + one sinusoid period (half-space check)");

    // Build the solver once here to check the geometry (throws
    // InputError with the block names); it is rebuilt in run().
    HeatParameters check = p;
    check.distributed    = false; // serial check unless run by mpirun
    check.boundary_conditions.clear();
    for (auto bc : p.boundary_conditions)
      {
        bc.type  = BoundaryCondition::Type::flux;
        bc.value = [](double, double, double) { return 0.; };
        check.boundary_conditions.push_back(bc);
      }
    try
      {
        HeatSolver solver(check);
        for (const auto &q : probes)
          solver.add_probe(q[0], q[1]);
      }
    catch (const InputError &e)
      {
        throw InputError(prm_file + ": " + e.what());
      }
  }
} // namespace rockdda::thermal::internal
