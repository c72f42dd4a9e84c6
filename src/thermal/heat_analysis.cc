/**
 * @file
 * Analysis type "heat": transient conduction in the rock blocks with the
 * "Heat" parameter sections (geometry, materials, mesh, time stepping,
 * boundary conditions, output and the periodic half-space check).
 */
#include <rockdda/io/checkpoint.h>
#include <rockdda/io/error.h>
#include <rockdda/io/interrupt.h>
#include <rockdda/io/parameters.h>
#include <rockdda/io/progress.h>
#include <rockdda/thermal/analyses.h>
#include <rockdda/thermal/boundary_data.h>
#include <rockdda/thermal/heat_cycles.h>
#include <rockdda/thermal/heat_solver.h>

#include <deal.II/base/mpi.h>

#include <chrono>
#include <cmath>
#include <limits>
#include <memory>
#include <sstream>

namespace rockdda::thermal
{
  namespace
  {
    using dealii::Patterns::Anything;


    using dealii::Patterns::Bool;
    using dealii::Patterns::Double;
    using dealii::Patterns::Integer;
    using dealii::Patterns::Selection;

    constexpr unsigned int max_boundary_conditions = 6;

    std::string
    trim(const std::string &s)
    {
      const auto a = s.find_first_not_of(" \t");
      if (a == std::string::npos)
        return "";
      return s.substr(a, s.find_last_not_of(" \t") - a + 1);
    }

    std::vector<std::string>
    split(const std::string &text, const char separator)
    {
      std::vector<std::string> parts;
      std::string              part;
      std::istringstream       in(text);
      while (std::getline(in, part, separator))
        parts.push_back(trim(part));
      if (!text.empty() && text.back() == separator)
        parts.push_back("");
      return parts;
    }

    double
    number(const std::string &text,
           const std::string &prm_file,
           const std::string &key)
    {
      std::size_t used = 0;
      double      v    = 0.;
      try
        {
          v = std::stod(trim(text), &used);
        }
      catch (const std::exception &)
        {
          used = 0;
        }
      if (used == 0 || used != trim(text).size() || !std::isfinite(v))
        throw InputError(prm_file + ": key '" + key + "': '" + text
                         + "' is not a finite number");
      return v;
    }

    /// "x, y; x, y; ..." -> points.
    std::vector<Point2>
    points(const std::string &text,
           const std::string &prm_file,
           const std::string &key)
    {
      std::vector<Point2> result;
      for (const auto &p : split(text, ';'))
        {
          if (p.empty())
            continue;
          const auto xy = split(p, ',');
          if (xy.size() != 2)
            throw InputError(prm_file + ": key '" + key + "': '" + p
                             + "' is not a point 'x, y' (m)");
          result.push_back(Point2{
            {number(xy[0], prm_file, key), number(xy[1], prm_file, key)}});
        }
      return result;
    }

    std::vector<double>
    numbers(const std::string &text,
            const std::string &prm_file,
            const std::string &key)
    {
      std::vector<double> result;
      for (const auto &v : split(text, ','))
        if (!v.empty())
          result.push_back(number(v, prm_file, key));
      return result;
    }

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



    void
    HeatAnalysis::declare_parameters(dealii::ParameterHandler &prm) const
    {
      prm.enter_subsection("Heat");
      {
        prm.enter_subsection("Geometry");
        io::declare(prm,
                    "Blocks",
                    "0, -30; 0.25, -30; 0.25, 0; 0, 0",
                    Anything(),
                    "m",
                    "Block polygons: vertices 'x, y' separated by ';', "
                    "blocks separated by '|'. y is up.");
        io::declare(prm,
                    "Boundary tags",
                    "far field, adiabatic, exposed, adiabatic",
                    Anything(),
                    "-",
                    "One tag per polygon edge (edge i from vertex i to "
                    "i+1), comma-separated, blocks separated by '|'. Each "
                    "tag needs a 'Boundary condition N' section, except "
                    "'adiabatic' (zero flux).");
        io::declare(prm,
                    "Block materials",
                    "",
                    Anything(),
                    "-",
                    "Material name per block, comma-separated; empty: the "
                    "first material for every block.");
        io::declare(prm,
                    "Joint contact",
                    "perfect",
                    Selection("perfect|conductance|insulated"),
                    "-",
                    "Conduction across edges shared by two blocks: "
                    "'perfect' (one conforming domain; shared edges must "
                    "have the same end points), 'conductance' (each block "
                    "is its own mesh; the joint passes the flux "
                    "q = h_j (T1 - T2) with h_j = 'Joint conductance'; the "
                    "tags of joint edges are not used) or 'insulated' (each "
                    "block is its own domain and joint faces use their "
                    "tags).");
        io::declare(prm,
                    "Joint conductance",
                    "1000",
                    io::DoubleInterval::positive(),
                    "W/(m^2 K)",
                    "Contact conductance h_j of the joints with 'Joint "
                    "contact = conductance'; > 0. An open joint of "
                    "aperture a filled with air (0.026 W/(m K)) has "
                    "h_j ~ 0.026 / a, e.g. 26 for a = 1 mm.");
        prm.leave_subsection();

        prm.enter_subsection("Materials");
        io::declare(prm,
                    "Names",
                    "rock",
                    Anything(),
                    "-",
                    "Material names, comma-separated.");
        io::declare(prm,
                    "Thermal conductivity",
                    "1.7",
                    Anything(),
                    "W/(m K)",
                    "lambda per material, comma-separated; > 0. Masada "
                    "dolomite: 1.7 (thesis Table 5-2).");
        io::declare(prm,
                    "Density",
                    "2600",
                    Anything(),
                    "kg/m^3",
                    "rho per material, comma-separated; > 0.");
        io::declare(prm,
                    "Specific heat capacity",
                    "810",
                    Anything(),
                    "J/(kg K)",
                    "c_p per material, comma-separated; > 0.");
        prm.leave_subsection();

        prm.enter_subsection("Mesh");
        io::declare(prm,
                    "Finite element degree",
                    "2",
                    Integer(1, 3),
                    "-",
                    "Degree p of the FE_Q elements (1 to 3).");
        io::declare(prm,
                    "Coarse cell size",
                    "1",
                    io::DoubleInterval::positive(),
                    "m",
                    "Cells are refined until their diameter is at most "
                    "about this size; > 0.");
        io::declare(prm,
                    "Global refinements",
                    "0",
                    Integer(0, 10),
                    "-",
                    "Extra uniform refinements after the coarse size.");
        io::declare(prm,
                    "Refine near tags",
                    "",
                    Anything(),
                    "-",
                    "Tags of exposed faces, comma-separated: cells within "
                    "'Band width' of them are refined to 'Band cell size'.");
        io::declare(prm,
                    "Band width",
                    "0",
                    Double(0.),
                    "m",
                    "Width of the refined band (a few skin depths); 0: "
                    "no band.");
        io::declare(prm,
                    "Band cell size",
                    "0",
                    Double(0.),
                    "m",
                    "Cell size in the band; 0: no band.");
        io::declare(prm,
                    "Adaptive refinement",
                    "false",
                    Bool(),
                    "-",
                    "Refine and coarsen the mesh during the run by the "
                    "Kelly error estimator (theta scheme only), every "
                    "'Adaptive interval' steps, transferring the field. "
                    "Cells are never coarser than 'Coarse cell size' (nor "
                    "than 'Band cell size' in the band).");
        io::declare(prm,
                    "Adaptive interval",
                    "10",
                    Integer(1, 1000000),
                    "-",
                    "Time steps between two mesh adaptations; >= 1.");
        io::declare(prm,
                    "Refine fraction",
                    "0.3",
                    Double(0., 1.),
                    "-",
                    "Cells holding this fraction of the estimated error are "
                    "refined; in [0, 1], refine + coarsen fraction <= 1.");
        io::declare(prm,
                    "Coarsen fraction",
                    "0.03",
                    Double(0., 1.),
                    "-",
                    "Cells holding this fraction of the estimated error are "
                    "coarsened; in [0, 1].");
        io::declare(prm,
                    "Minimum cell size",
                    "0",
                    Double(0.),
                    "m",
                    "Adaptive refinement stops at cells of about this size "
                    "(diameter <= 1.5 times it); >= 0, 0: no limit.");
        io::declare(prm,
                    "Maximum cells",
                    "0",
                    Integer(0),
                    "-",
                    "Upper limit of the number of cells of the adaptive "
                    "mesh; 0: no limit.");
        prm.leave_subsection();

        prm.enter_subsection("Time stepping");
        io::declare(prm,
                    "Method",
                    "crank-nicolson",
                    Selection("crank-nicolson|backward-euler|arkode"),
                    "-",
                    "'crank-nicolson' (theta = 1/2, 2nd order), "
                    "'backward-euler' (theta = 1, 1st order, L-stable), "
                    "'arkode' (SUNDIALS ARKODE DIRK, adaptive step).");
        io::declare(prm,
                    "Time step",
                    "86400",
                    io::DoubleInterval::positive(),
                    "s",
                    "Fixed step of the theta scheme; initial step of "
                    "ARKODE. > 0. With the theta scheme the run plans "
                    "(spin-up cycles x spin-up period + End time - Start "
                    "time) / Time step steps; more than 1e8 are rejected.");
        io::declare(prm,
                    "Start time",
                    "0",
                    Double(),
                    "s",
                    "Time at which recording starts (after spin-up).");
        io::declare(prm,
                    "End time",
                    "31557600",
                    Double(),
                    "s",
                    "Time at which the run ends; > start time.");
        io::declare(prm,
                    "Initial temperature",
                    "20",
                    Double(),
                    "degC",
                    "Uniform initial temperature (K differences; any "
                    "offset scale, e.g. deg C).");
        io::declare(prm,
                    "Spin-up cycles",
                    "0",
                    Integer(0, 100000),
                    "-",
                    "Cycles of 'Spin-up period' run before 'Start time' "
                    "without output, towards the periodic steady state.");
        io::declare(prm,
                    "Spin-up period",
                    "31557600",
                    Double(0.),
                    "s",
                    "Length of one spin-up cycle (one year = 31557600 s).");
        io::RunCheckpoint::declare_parameters(
          prm,
          "at the first output time or spin-up cycle end after each multiple "
          "of this interval, and at the End time (an adaptive mesh is stored "
          "too; under MPI the mesh and field go to checkpoint-mesh-0.* or "
          "-1.*)");
        io::declare(prm,
                    "Rannacher steps",
                    "2",
                    Integer(0, 100),
                    "-",
                    "Crank-Nicolson: backward-Euler steps at the start "
                    "(damp the oscillation from non-smooth initial data).");
        io::declare(prm,
                    "Oscillation fallback",
                    "true",
                    Bool(),
                    "-",
                    "Crank-Nicolson: continue with backward Euler once the "
                    "oscillation indicator fires (reported).");
        io::declare(
          prm,
          "Linear solver",
          "direct",
          Selection("direct|cg|amg"),
          "-",
          "'direct' (sparse Cholesky LDL^T, Eigen; factorised once per step "
          "size), 'cg' (CG + SSOR, relative tolerance 1e-12) or 'amg' (the "
          "distributed solver: p4est mesh, Trilinos CG + AMG, also on one "
          "MPI rank; needs mpirun). With mpirun -np N > 1 the distributed "
          "solver is used anyway: 'direct' is then Trilinos Amesos KLU and "
          "'cg'/'amg' CG + AMG.");
        io::declare(prm,
                    "ARKODE relative tolerance",
                    "1e-6",
                    io::DoubleInterval::positive(),
                    "-",
                    "Relative error tolerance of ARKODE; > 0.");
        io::declare(prm,
                    "ARKODE absolute tolerance",
                    "1e-4",
                    io::DoubleInterval::positive(),
                    "K",
                    "Absolute error tolerance of ARKODE; > 0.");
        prm.leave_subsection();

        for (unsigned int k = 1; k <= max_boundary_conditions; ++k)
          {
            prm.enter_subsection("Boundary condition " + std::to_string(k));
            io::declare(prm,
                        "Tag",
                        "",
                        Anything(),
                        "-",
                        "Boundary tag this condition applies to; empty: "
                        "unused section.");
            io::declare(prm,
                        "Type",
                        "temperature",
                        Selection("temperature|convective|flux"),
                        "-",
                        "'temperature': T = data; 'convective': lambda "
                        "dT/dn = h (data - T), data = air temperature; "
                        "'flux': lambda dT/dn = data (W/m^2 into the rock; "
                        "0 = adiabatic).");
            io::declare(prm,
                        "Data",
                        "constant",
                        Selection("constant|sinusoids|csv"),
                        "-",
                        "'constant': Mean; 'sinusoids': Mean + sum of "
                        "'Sinusoids'; 'csv': time series from 'CSV file'.");
            io::declare(prm,
                        "Mean",
                        "0",
                        Double(),
                        "degC or W/m^2",
                        "Constant value, or the mean of the sinusoids.");
            io::declare(prm,
                        "Sinusoids",
                        "",
                        Anything(),
                        "degC or W/m^2, s, rad",
                        "'amplitude, period, phase' terms separated by ';' "
                        "(e.g. annual and daily: '9, 31557600, 0; 5, 86400, "
                        "0'); value = Mean + sum A sin(2 pi t / P + phase).");
            io::declare(prm,
                        "CSV file",
                        "",
                        Anything(),
                        "-",
                        "Two columns: time, value (one header line and # "
                        "comments allowed); linear in between. Must cover "
                        "the run including spin-up.");
            io::declare(prm,
                        "CSV time unit",
                        "1",
                        Double(0.),
                        "s",
                        "Seconds per time unit of the CSV (86400 for "
                        "days).");
            io::declare(prm,
                        "Heat transfer coefficient",
                        "10",
                        Double(0.),
                        "W/(m^2 K)",
                        "h of a convective condition; >= 0.");
            prm.leave_subsection();
          }

        prm.enter_subsection("Output");
        io::declare(prm,
                    "Probes",
                    "",
                    Anything(),
                    "m",
                    "Probe points 'x, y' separated by ';'.");
        io::declare(prm,
                    "Output interval",
                    "86400",
                    io::DoubleInterval::positive(),
                    "s",
                    "Spacing of rows in statistics.csv; > 0.");
        io::declare(prm,
                    "VTU times",
                    "",
                    Anything(),
                    "s",
                    "Times at which the field is written as VTU "
                    "(comma-separated).");
        prm.leave_subsection();

        prm.enter_subsection("Half-space check");
        io::declare(prm,
                    "Enabled",
                    "false",
                    Bool(),
                    "-",
                    "Fit a sinusoid to every probe over the last period of "
                    "the run and compare with A exp(-z/d), lag z/d "
                    "(Carslaw & Jaeger 1959); needs Boundary condition 1 "
                    "of type temperature with one sinusoid.");
        io::declare(prm,
                    "Surface elevation",
                    "0",
                    Double(),
                    "m",
                    "y of the exposed surface; depth z = elevation - y.");
        prm.leave_subsection();
      }
      prm.leave_subsection();
    }



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
        const auto names = split(prm.get("Names"), ',');
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
        const auto polys = split(prm.get("Blocks"), '|');
        const auto tags  = split(prm.get("Boundary tags"), '|');
        const auto mats  = split(prm.get("Block materials"), ',');
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
            block.name     = "block " + std::to_string(b + 1);
            block.vertices = points(polys[b], prm_file, "Heat/Geometry/Blocks");
            block.edge_tags = split(tags[b], ',');
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
        p.joint_contact           = contact == "perfect"
                                      ? HeatParameters::JointContact::perfect
                                    : contact == "conductance"
                                      ? HeatParameters::JointContact::conductance
                                      : HeatParameters::JointContact::insulated;
        p.joint_conductance       = prm.get_double("Joint conductance");
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
      for (const auto &t : split(prm.get("Refine near tags"), ','))
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
          const std::string ts      = "Heat/Time stepping/";
          const std::string dt_text = "'" + ts + "Time step' = "
                                      + io::format_number(p.time_step) + " s";
          const double spin
            = spin_up_cycles
              * io::planned_steps(0., spin_up_period, p.time_step);
          const double record
            = io::planned_steps(p.start_time, end_time, p.time_step);
          const std::string limit
            = "; at most " + io::format_number(io::max_planned_steps, 3)
              + " are allowed: raise the time step or shorten the ";
          if (spin > io::max_planned_steps)
            throw InputError(
              prm_file + ": keys '" + ts
              + "Spin-up cycles' = " + std::to_string(spin_up_cycles) + ", '"
              + ts + "Spin-up period' = " + io::format_number(spin_up_period)
              + " s and " + dt_text + " plan " + io::format_number(spin, 4)
              + " spin-up time steps (cycles x period / time step)" + limit
              + "spin-up");
          if (record > io::max_planned_steps
              || spin + record > io::max_planned_steps)
            throw InputError(
              prm_file + ": keys '" + ts
              + "Start time' = " + io::format_number(p.start_time) + " s, '"
              + ts + "End time' = " + io::format_number(end_time) + " s and "
              + dt_text + " plan " + io::format_number(record, 4)
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
          bc.tag = trim(prm.get("Tag"));
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
          bc.type = type == "temperature" ? BoundaryCondition::Type::temperature
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
              if (trim(file).empty())
                throw InputError(prm_file + ": key '" + where
                                 + "/CSV file' is empty but 'Data' is csv");
              const auto series = std::make_shared<TimeSeries>(read_time_series(
                io::resolve_path(trim(file), prm_file, where + "/CSV file"),
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
      probes = points(prm.get("Probes"), prm_file, "Heat/Output/Probes");
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



    void
    HeatAnalysis::run(io::RunContext &context)
    {
      const auto wall_start = std::chrono::steady_clock::now();
      HeatSolver solver(parameters);
      const auto st0 = solver.statistics();
      context.log.line("heat: " + solver.method_description());
      context.log.line("mesh: " + std::to_string(st0.n_cells) + " cells, "
                       + std::to_string(st0.n_dofs) + " dofs, cell size "
                       + io::format_number(st0.min_cell_size, 4) + " to "
                       + io::format_number(st0.max_cell_size, 4) + " m");
      for (const auto &d : bc_descriptions)
        context.log.line("boundary " + d);
      const Material &m0 = parameters.materials[0];
      const double    sd = thesis_skin_depth(m0.diffusivity(), 180. * 86400.);
      context.log.line("material '" + m0.name + "': diffusivity "
                       + io::format_number(m0.diffusivity(), 4)
                       + " m^2/s, seasonal skin depth (thesis Eq. 5.1, 180 "
                         "days) "
                       + io::format_number(sd, 4) + " m");
      context.summary.add_text("method", solver.method_description());
      context.summary.add("cells", st0.n_cells, "-");
      context.summary.add("dofs", st0.n_dofs, "-");
      context.summary.add("skin_depth_eq_5_1", sd, "m");

      for (const auto &q : probes)
        solver.add_probe(q[0], q[1]);
      const double record_start
        = parameters.start_time + spin_up_cycles * spin_up_period;

      io::Table table;
      table.add_column("time", "s");
      for (std::size_t k = 0; k < probes.size(); ++k)
        table.add_column("probe" + std::to_string(k + 1), "degC");
      const auto n_blocks = parameters.blocks.size();
      for (std::size_t b = 0; b < n_blocks; ++b)
        {
          const std::string s = "block" + std::to_string(b + 1);
          table.add_column(s + "_mean", "degC");
          table.add_column(s + "_gradient_x", "K/m");
          table.add_column(s + "_gradient_y", "K/m");
        }
      table.add_column("stored_heat_change", "J/m");
      table.add_column("boundary_heat_in", "J/m");
      if (parameters.adaptive_refinement)
        table.add_column("cells", "-");

      // Progress of the run (all of it is in a checkpoint).
      unsigned int                     spin_up_done = 0;
      bool                             recording    = false;
      unsigned long                    n_records    = 0;
      double                           e0 = 0., q0 = 0.;
      std::vector<std::vector<double>> samples(probes.size());
      std::vector<double>              sample_times;
      std::vector<double>              vtu_pending = vtu_times;
      std::sort(vtu_pending.begin(), vtu_pending.end());
      std::string pvd = "<?xml version=\"1.0\"?>\n<VTKFile type=\"Collection\" "
                        "version=\"0.1\">\n<Collection>\n";
      unsigned int n_vtu     = 0;
      double next_checkpoint = parameters.start_time + checkpoint_interval;

      const auto record = [&]() {
        std::vector<double> row{solver.time()};
        for (std::size_t k = 0; k < probes.size(); ++k)
          {
            row.push_back(solver.probe_value(k));
            samples[k].push_back(row.back());
          }
        sample_times.push_back(solver.time());
        for (const auto &bm : solver.block_moments())
          {
            row.push_back(bm.mean);
            row.push_back(bm.gradient_x);
            row.push_back(bm.gradient_y);
          }
        row.push_back(solver.stored_heat() - e0);
        row.push_back(solver.boundary_heat_in() - q0);
        if (parameters.adaptive_refinement)
          row.push_back(solver.statistics().n_cells);
        for (const double v : row)
          if (!std::isfinite(v))
            throw std::runtime_error("heat: non-finite result at t = "
                                     + io::format_number(solver.time(), 10)
                                     + " s");
        table.add_row(row);
      };
      const auto write_vtu = [&]() {
        char name[64];
        std::snprintf(name, sizeof(name), "temperature-%04u", n_vtu++);
        // One .vtu (serial), or a .pvtu with one piece per MPI rank.
        const auto files = solver.vtu_files(name);
        for (const auto &f : files)
          context.output.write(f.first, f.second);
        if (!files.empty())
          pvd += "<DataSet timestep=\"" + io::format_number(solver.time())
                 + "\" file=\"" + files.front().first + "\"/>\n";
      };

      // Checkpoints: the solver's state and the run's progress.
      std::ostringstream fingerprint_text;
      fingerprint_text.precision(17);
      fingerprint_text << solver.method_description() << "; " << st0.n_cells
                       << " cells; start " << parameters.start_time
                       << " s; spin-up " << spin_up_cycles << " x "
                       << spin_up_period << " s; output every "
                       << output_interval << " s";
      const std::string       fingerprint = fingerprint_text.str();
      const io::RunCheckpoint checkpoint_file(context.output,
                                              "heat",
                                              fingerprint,
                                              "Heat/Time stepping");
      // The distributed solver's mesh and field (p4est files).
      const std::string mesh_files = context.output.file("checkpoint-mesh");
      double            saved_at   = std::numeric_limits<double>::quiet_NaN();
      const auto        save_checkpoint = [&]() {
        io::BinaryWriter w = checkpoint_file.begin();
        context.output.own("checkpoint-mesh*");
        w.put_string(solver.checkpoint(mesh_files));
        w.put<std::uint32_t>(spin_up_done);
        w.put<std::uint8_t>(recording ? 1 : 0);
        w.put<std::uint64_t>(n_records);
        w.put(e0);
        w.put(q0);
        io::RunCheckpoint::put_rows(w, table);
        for (const auto &series : samples)
          w.put_doubles(series);
        w.put_doubles(sample_times);
        w.put_doubles(vtu_pending);
        w.put<std::uint32_t>(n_vtu);
        w.put_string(pvd);
        w.put(next_checkpoint);
        checkpoint_file.write(w, table);
        saved_at = solver.time();
      };
      const auto checkpoint_if_due = [&]() {
        if (checkpoint_interval > 0. && solver.time() >= next_checkpoint - 1e-9)
          {
            while (next_checkpoint <= solver.time() + 1e-9)
              next_checkpoint += checkpoint_interval;
            save_checkpoint();
          }
      };
      if (resume)
        {
          const std::string bytes = checkpoint_file.read();
          io::BinaryReader  r     = checkpoint_file.reader(bytes);
          solver.restore(r.get_string(), checkpoint_file.file());
          spin_up_done = r.get<std::uint32_t>();
          recording    = r.get<std::uint8_t>() != 0;
          n_records    = r.get<std::uint64_t>();
          e0           = r.get<double>();
          q0           = r.get<double>();
          io::RunCheckpoint::get_rows(r, table);
          for (auto &series : samples)
            series = r.get_doubles();
          sample_times    = r.get_doubles();
          vtu_pending     = r.get_doubles();
          n_vtu           = r.get<std::uint32_t>();
          pvd             = r.get_string();
          next_checkpoint = r.get<double>();
          if (!r.at_end())
            throw InputError(checkpoint_file.file() + ": trailing data");
          context.log.line("resumed from " + checkpoint_file.file() + " at t = "
                           + io::format_number(solver.time(), 10) + " s");
        }

      // Planned steps from the current time to @p end (0: adaptive).
      const auto planned_to = [&](const double end) -> unsigned long {
        if (parameters.stepper == TimeStepper::arkode)
          return 0;
        return solver.statistics().n_steps
               + static_cast<unsigned long>(
                 io::planned_steps(solver.time(), end, parameters.time_step));
      };
      // Stopped early by SIGINT / SIGTERM, polled (on every MPI rank alike)
      // about 100 times per spin-up cycle (see thermal::spin_up()) and
      // between output times.
      int interrupted = 0;
      {
        io::ProgressBar progress("heat spin-up",
                                 solver.time(),
                                 record_start,
                                 planned_to(record_start));
        SpinUpCallbacks callbacks;
        callbacks.stop = [&]() {
          return (interrupted = io::interrupt_signal_all_ranks()) != 0;
        };
        callbacks.progress = [&]() {
          progress.update(solver.statistics().n_steps, solver.time());
        };
        callbacks.cycle_done = checkpoint_if_due;
        thermal::spin_up(solver,
                         parameters,
                         SpinUp{spin_up_cycles,
                                spin_up_period,
                                parameters.start_time},
                         spin_up_done,
                         callbacks);
      }
      if (spin_up_cycles > 0 && !resume && interrupted == 0)
        context.log.line("spin-up: " + std::to_string(spin_up_cycles)
                         + " cycles of " + io::format_number(spin_up_period, 8)
                         + " s");
      if (!recording && interrupted == 0)
        {
          e0        = solver.stored_heat();
          q0        = solver.boundary_heat_in();
          recording = true;
          record();
          checkpoint_if_due();
        }
      if (interrupted == 0)
        {
          io::ProgressBar progress("heat",
                                   solver.time(),
                                   end_time,
                                   planned_to(end_time));
          while (solver.time() < end_time - 1e-9 * output_interval
                 && (interrupted = io::interrupt_signal_all_ranks()) == 0)
            {
              double next
                = std::min(end_time,
                           record_start + (n_records + 1) * output_interval);
              ++n_records;
              while (!vtu_pending.empty() && vtu_pending.front() <= next)
                {
                  if (vtu_pending.front() > solver.time())
                    solver.advance_to(vtu_pending.front());
                  if (vtu_pending.front() >= record_start - 1e-9)
                    write_vtu();
                  vtu_pending.erase(vtu_pending.begin());
                }
              solver.advance_to(next);
              record();
              progress.update(solver.statistics().n_steps, solver.time());
              checkpoint_if_due();
            }
        }
      // At the End time, unless just taken there (the run can be
      // extended); a checkpoint writes statistics.csv too. An interrupted
      // run always writes one (Resume = true continues it bit for bit).
      if ((checkpoint_interval > 0. || interrupted != 0)
          && saved_at != solver.time())
        save_checkpoint();
      else if (checkpoint_interval <= 0. && interrupted == 0)
        context.output.write("statistics.csv", table.csv());
      if (interrupted != 0)
        {
          context.stopped_early = true;
          context.stopped_note
            = "heat stopped at t = " + io::format_number(solver.time(), 10)
              + " s of " + io::format_number(end_time, 10) + " s"
              + (spin_up_done < spin_up_cycles
                   ? " (spin-up cycle " + std::to_string(spin_up_done) + " of "
                       + std::to_string(spin_up_cycles) + ")"
                   : std::string())
              + "; statistics.csv so far and checkpoint.bin written (set "
                "'Heat/Time stepping/Resume' = true to continue).";
          context.log.line(context.stopped_note);
        }
      if (n_vtu > 0)
        context.output.write("temperature.pvd",
                             pvd + "</Collection>\n</VTKFile>\n");

      const auto st = solver.statistics();
      if (parameters.adaptive_refinement)
        {
          context.summary.add("adaptations", st.n_adaptations, "-");
          context.summary.add("final_cells", st.n_cells, "-");
          context.summary.add("max_cells", st.max_n_cells, "-");
          context.summary.add("mesh_transfer_heat",
                              st.mesh_transfer_heat,
                              "J/m");
          context.log.line("adaptive mesh: " + std::to_string(st.n_adaptations)
                           + " adaptations, " + std::to_string(st.n_cells)
                           + " cells at the end (at most "
                           + std::to_string(st.max_n_cells) + ")");
        }
      context.summary.add("time_steps", st.n_steps, "-");
      context.summary.add("factorizations", st.n_factorizations, "-");
      context.summary.add("stiffness_ratio", st.stiffness_ratio, "-");
      context.summary.add("oscillation_steps", st.oscillation_steps, "-");
      if (st.oscillation_steps > 0)
        context.log.line(
          "WARNING: Crank-Nicolson oscillation detected in "
          + std::to_string(st.oscillation_steps) + " steps (dt kappa / h^2 = "
          + io::format_number(st.stiffness_ratio, 3) + ")"
          + (std::isnan(st.fallback_time)
               ? std::string("; consider backward-euler or a smaller time step")
               : "; continued with backward Euler from t = "
                   + io::format_number(st.fallback_time, 8) + " s"));
      for (std::size_t k = 0; k < probes.size(); ++k)
        context.summary.add("final_probe" + std::to_string(k + 1),
                            solver.probe_value(k),
                            "degC");
      const auto moments = solver.block_moments();
      for (std::size_t b = 0; b < moments.size(); ++b)
        context.summary.add("final_block" + std::to_string(b + 1) + "_mean",
                            moments[b].mean,
                            "degC");
      bool closed = true;
      for (const auto &bc : parameters.boundary_conditions)
        closed = closed && bc.type != BoundaryCondition::Type::temperature;
      if (closed && recording && parameters.stepper != TimeStepper::arkode)
        {
          // Heat added by the (non-conservative) field transfer onto
          // adapted meshes counts as input.
          const double stored = solver.stored_heat() - e0;
          const double input  = solver.boundary_heat_in() - q0
                               + st.mesh_transfer_heat - st0.mesh_transfer_heat;
          const double rel
            = std::abs(stored - input) / std::max(std::abs(input), 1e-300);
          context.summary.add("energy_balance_relative_error", rel, "-");
          context.log.line(
            "energy balance: stored " + io::format_number(stored, 8)
            + " J/m, boundary "
              "input "
            + io::format_number(input, 8) + " J/m, relative mismatch "
            + io::format_number(rel, 3));
        }

      if (halfspace_check && interrupted == 0)
        {
          // Fit over the last whole period of the recorded samples.
          const double omega = 2. * M_PI / halfspace_period;
          const double d
            = periodic_skin_depth(m0.diffusivity(), halfspace_period);
          std::vector<double> t;
          std::size_t         first = 0;
          while (first < sample_times.size()
                 && sample_times[first] < end_time - halfspace_period + 1e-6)
            ++first;
          // Skip the duplicate end point of a whole period.
          for (std::size_t i = first; i < sample_times.size(); ++i)
            t.push_back(sample_times[i]);
          double worst_amplitude = 0., worst_lag = 0.;
          context.log.line("periodic half-space check: d = sqrt(2 kappa / "
                           "omega) = "
                           + io::format_number(d, 5) + " m");
          for (std::size_t k = 0; k < probes.size(); ++k)
            {
              const std::vector<double> v(samples[k].begin() + first,
                                          samples[k].end());
              const SinusoidFit         fit = fit_sinusoid(t, v, omega);
              const double              z   = surface_elevation - probes[k][1];
              const double amp  = halfspace_amplitude * std::exp(-z / d);
              double       lag  = -fit.phase / omega;
              const double lag0 = z / d / omega;
              // Unwrap the phase to the branch nearest the exact lag.
              while (lag < lag0 - 0.5 * halfspace_period)
                lag += halfspace_period;
              while (lag > lag0 + 0.5 * halfspace_period)
                lag -= halfspace_period;
              const double ea
                = std::abs(fit.amplitude - amp) / std::abs(halfspace_amplitude);
              const double el = std::abs(lag - lag0) / 86400.;
              worst_amplitude = std::max(worst_amplitude, ea);
              worst_lag       = std::max(worst_lag, el);
              context.log.line(
                "  z = " + io::format_number(z, 4) + " m: amplitude "
                + io::format_number(fit.amplitude, 6) + " (exact "
                + io::format_number(amp, 6) + "), lag "
                + io::format_number(lag / 86400., 5) + " days (exact "
                + io::format_number(lag0 / 86400., 5) + ")");
              context.summary.add("amplitude_probe" + std::to_string(k + 1),
                                  fit.amplitude,
                                  "K");
              context.summary.add("lag_probe" + std::to_string(k + 1),
                                  lag / 86400.,
                                  "day");
            }
          context.summary.add("halfspace_skin_depth", d, "m");
          context.summary.add("max_amplitude_error_fraction_of_A",
                              worst_amplitude,
                              "-");
          context.summary.add("max_lag_error", worst_lag, "day");
        }
      context.summary.add("solver_wall_time",
                          std::chrono::duration<double>(
                            std::chrono::steady_clock::now() - wall_start)
                            .count(),
                          "s");
      context.output.write("timing.txt", solver.timing_summary());
    }
  } // namespace



  std::vector<std::unique_ptr<io::Analysis>>
  make_analyses()
  {
    std::vector<std::unique_ptr<io::Analysis>> list;
    list.push_back(std::make_unique<HeatAnalysis>());
    return list;
  }
} // namespace rockdda::thermal
