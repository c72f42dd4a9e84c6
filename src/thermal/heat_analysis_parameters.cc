/**
 * @file
 * The parameters of the analysis type "heat": the "Heat" sections
 * (geometry, materials, mesh, time stepping, boundary conditions, output
 * and the periodic half-space check) with their defaults, patterns and
 * help texts.
 */
#include <rockdda/io/checkpoint.h>

#include "heat_analysis.h"
#include <string>

namespace rockdda::thermal::internal
{
  using dealii::Patterns::Anything;
  using dealii::Patterns::Bool;
  using dealii::Patterns::Double;
  using dealii::Patterns::Integer;
  using dealii::Patterns::Selection;

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
} // namespace rockdda::thermal::internal
