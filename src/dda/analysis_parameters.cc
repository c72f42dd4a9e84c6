/**
 * @file
 * The run controls shared by the 2D and 3D DDA analyses.
 */
#include <rockdda/dda/analysis_parameters.h>
#include <rockdda/io/error.h>
#include <rockdda/io/output.h>
#include <rockdda/io/parameters.h>
#include <rockdda/io/progress.h>

#include <deal.II/base/mpi.h>

#include <cmath>
#include <limits>

namespace rockdda::dda
{
  template <int dim>
  std::string
  AnalysisParameters<dim>::section()
  {
    return dim == 2 ? "DDA" : "DDA 3d";
  }



  template <int dim>
  void
  AnalysisParameters<dim>::declare_parameters(dealii::ParameterHandler &prm)
  {
    using dealii::Patterns::Double;
    using dealii::Patterns::Integer;
    io::declare(prm,
                "Block file",
                "",
                dealii::Patterns::Anything(),
                "-",
                dim == 2
                  ? "Scene file (doc/block-file-format-dda.md): materials, "
                    "joints, blocks, fixed, load and measurement points. "
                    "Relative to this parameter file; $VAR is expanded."
                  : "Scene file (doc/block-file-format-dda3d.md): materials, "
                    "joints, polyhedral blocks, fixed, load and measurement "
                    "points, initial velocities. Relative to this parameter "
                    "file; $VAR is expanded.");
    io::declare(prm,
                "End time",
                "1",
                io::DoubleInterval::positive(),
                "s",
                "Simulated duration, > 0.");
    io::declare(prm,
                "Time step",
                "0.001",
                io::DoubleInterval::positive(),
                "s",
                "Largest (and initial) time step, > 0. A step is cut by 3 "
                "when the open-close iteration does not converge or a vertex "
                "moves too far, and grows back by 1.3 after good steps. End "
                "time / Time step (the planned steps) must be at most 1e8.");
    io::declare(prm,
                "Dynamic control",
                "1",
                Double(0., 1.),
                "-",
                "Fraction of the velocity carried into the next step, in "
                "[0, 1]: 0 static relaxation, 1 fully dynamic.");
    io::declare(prm,
                "Strain damping",
                "0",
                Double(0.),
                "s",
                "Kelvin-Voigt viscous time eta of the blocks' strain, >= 0 s "
                "(0: none): the stress is C (strain + eta strain rate), so a "
                "strain mode of angular frequency omega (rad/s) is damped at "
                "the ratio eta omega / 2 of critical; rigid motions "
                "(translation, rotation, sliding) are not damped. The "
                "dissipated energy is booked in the energy ledger. Only in "
                "dynamic steps. E.g. 5e-3 s damps the 245 rad/s strain mode "
                "of Table 4-1's 1 m, 20 MPa block at 0.61 of critical "
                "(benchmarks/dda3d/README.md).");
    io::declare(prm,
                "Contact damping ratio",
                "0",
                Double(0.),
                "-",
                "Viscous dashpot in parallel with each spring of a closed "
                "contact (the normal one, and the shear one while it is "
                "locked), as a ratio of critical, >= 0 (0: none): "
                "c = 2 ratio sqrt(k m) (N s/m), k the spring (N/m; a "
                "joint's stiffness over the contact's share of the joint "
                "in series with the penalty), m the lighter free block's "
                "mass (kg). A single contact rebounds with the restitution "
                "coefficient exp(-ratio pi / sqrt(1 - ratio^2)) (ratio < 1); "
                "a block on n such contacts in parallel (n = 2 on a face in "
                "2D) has sqrt(n) x the ratio in its mode on them. Physical: "
                "rock "
                "joints a few per cent. The energy it dissipates is booked in "
                "the energy ledger (damping). Only in dynamic steps; the "
                "contact states and friction use the spring forces alone ("
                  + std::string(dim == 2 ? "doc/theory/dda.md"
                                         : "doc/theory/dda3d.md")
                  + ", Contact damping).");
    io::declare(prm,
                "Contact step damping",
                "0",
                Double(0.),
                "-",
                "Numerical dashpot beta k dt / 2 (N s/m) in parallel "
                "with each spring k (N/m) of a closed contact as the "
                "above, >= 0 (0: none), dt the step (s): a contact mode "
                "the step resolves (omega dt << 1) is damped at the "
                "ratio beta omega dt / 4 (vanishing with dt, as the "
                "scheme's own numerical damping), a stiff one (omega dt "
                ">> 1, where Shi's velocity update has amplification "
                "-1) gets the amplification -1 / (1 + beta) per step; "
                "1 removes it in one step, above 1 the contact creeps. "
                "Booked with the above.");
    io::declare(prm,
                "Maximum open-close iterations",
                "12",
                Integer(1, 100),
                "-",
                "Open-close iterations that change contact states before the "
                "time step is cut, in [1, 100]; iterations that only update "
                "friction forces may add as many again. A step is accepted "
                "only when the states and the friction forces have "
                "converged.");
    // The engines measure a step's displacement differently (2D: against
    // the domain, with a cap per block; 3D: against each block).
    io::declare(prm,
                "Maximum displacement ratio",
                "0.01",
                io::DoubleInterval(0., true, 1., false),
                "-",
                std::string("Largest vertex displacement per step as a "
                            "fraction of ")
                  + (dim == 2
                       ? "the domain size (twice the largest distance of a "
                         "vertex from the mean vertex), 0 < ratio <= 1; a "
                         "block's own limit is also at most 0.05 x its size. "
                         "The contact search distance of a block is 2.5 "
                         "times its limit."
                       : "its block's size, 0 < ratio <= 1; a step that "
                         "moves a vertex further is cut. The contact "
                         "distance is 2.5 x this."));
    io::declare(prm,
                "Shear penalty ratio",
                "0.4",
                io::DoubleInterval::positive(),
                "-",
                "Shear penalty / normal penalty, > 0 (in series with a "
                "joint's shear stiffness, if it has one), unless 'Shear "
                "penalty' is set.");
    io::declare(prm,
                "Shear penalty",
                "0",
                io::DoubleInterval(
                  0., false, std::numeric_limits<double>::infinity(), false),
                "N/m",
                std::string("Shear penalty spring of every contact, >= 0 "
                            "N/m, independent of the normal penalty; 0: the "
                            "Shear penalty ratio x the normal penalty. A "
                            "locked contact's shear spring much stiffer than "
                            "its blocks (above ~E L, E the Young modulus, L "
                            "the block size")
                  + (dim == 2 ? " (per m)" : "")
                  + ") locks their elastic (Poisson) deformation into a "
                    "self-stress between the contacts: in a wedge it raises "
                    "the normal forces and delays the onset of sliding. "
                    "0.05 E L keeps that below 0.3 % while the locked "
                    "elastic slip W / p_s stays negligible (benchmarks/"
                    "dda3d-shaking-table, 'Shear penalty').");
    io::declare(prm,
                "Inexact solve factor",
                "1",
                dealii::Patterns::Double(1., 1e6),
                "-",
                "While the contact states settle, CG solves to this factor x "
                "Solver tolerance (inexact Newton); the settled states are "
                "then confirmed by a solve to Solver tolerance, so the "
                "accepted step is unchanged. 1 (the default): every solve to "
                "Solver tolerance; in 2D 1000 halved the CG iterations on a "
                "wall from rest but, once the first solve of each step is "
                "exact, no longer saves time and costs extra iterations on "
                "large walls; in 3D it saved 0.5 % of the CG iterations on "
                "a 4 x 4 wall from rest. No effect with the direct solver.");
    io::declare(prm,
                "Penetration limit",
                "0.01",
                io::DoubleInterval(0., true, 0.1, false),
                "-",
                "Sanity check of every accepted step: a closed contact's "
                "numerical penetration (normal force / Contact penalty, m) "
                "deeper than this fraction of the smaller block's size "
                "cuts the step, and stops the run with the diagnosis if "
                "cutting does not help; 0 < ratio <= 0.1. The default 0.01 "
                "keeps the penalty method's overlap below 1 % of a block; "
                "a soft penalty (the thesis's 0.1 GN/m for 15 GPa rock, "
                "Table 3-2) reaches it under an arch's thrust. Raising the "
                "limit accepts that overlap; raising the penalty removes "
                "it.");
    io::declare(prm,
                "Contact force tolerance",
                "1e-4",
                io::DoubleInterval(1e-8, false, 0.1, false),
                "-",
                "Accuracy knob of the open-close iteration: a contact's state "
                "change is numerical noise below this fraction of the "
                "lighter block's weight W (its mass times |gravity + the "
                "seismic acceleration|, N"
                  + std::string(dim == 2 ? "/m" : "")
                  + "). An accepted step's closed contacts carry at most "
                    "this tension, penetration force or shear beyond their "
                    "strength (up to 100x it for a chattering or held "
                    "contact). 1e-8 <= fraction <= 0.1; a looser value "
                    "takes fewer iterations and step cuts on scenes that "
                    "move (benchmarks/dda-scaling, section 8).");
    io::declare(prm,
                "Fixed point penalty",
                "0",
                Double(0.),
                "N/m",
                "Stiffness of the springs of fixed points of a block held by "
                "one or two of them, >= 0; 0 = 10 x the contact penalty. A "
                "block with three or more fixed points that are not "
                "collinear is clamped (its motion prescribed, no spring: at "
                "rest, or the ground's in the displacement mode).");
    io::declare(prm,
                "Settling steps",
                "0",
                Integer(0, 100000),
                "-",
                "Static steps (dynamic control 0) under gravity before t = "
                "0, in [0, 100000], without seismic input and without "
                "advancing the time; the settled state is the reference for "
                "displacements. Blocks given touching start with zero "
                "penetration and, without settling, bounce on their contact "
                "springs (amplitude W / k_n, damped only by Shi's scheme at a "
                "ratio of about omega dt / 4).");
    io::declare(prm,
                "Gravity",
                "9.80665",
                Double(0.),
                "m/s^2",
                dim == 2 ? "Gravitational acceleration, >= 0, acting towards "
                           "-y."
                         : "Gravitational acceleration, >= 0, acting towards "
                           "-z (x east, y north, z up).");
    io::declare(prm,
                "Output interval",
                "0.1",
                Double(0.),
                "s",
                dim == 2 ? "Spacing of snapshots (see Snapshot format), >= 0; "
                           "0 = no snapshots."
                         : "Spacing of the VTU snapshots of the blocks "
                           "(blocks-NNNNN.vtu, series blocks.pvd) and the "
                           "contacts (contacts-NNNNN.vtu, series "
                           "contacts.pvd), >= 0; 0 = no snapshots.");
    io::declare(prm,
                "Statistics interval",
                "0",
                Double(0.),
                "s",
                "Spacing of rows in statistics.csv, >= 0; 0 = every step.");
    io::declare(
      prm,
      "Snapshot format",
      "vtu",
      dealii::Patterns::Selection("vtu|hdf5"),
      "-",
      std::string(
        dim == 2
          ? "'vtu': blocks-NNNNN.vtu and contacts-NNNNN.vtu with the series "
            "blocks.pvd and contacts.pvd (small scenes); 'hdf5': one "
            "snapshot-NNNNN.h5 per snapshot (groups /blocks and /contacts, "
            "binary arrays) with the XDMF series blocks.xdmf and "
            "contacts.xdmf that ParaView opens as time series (large scenes: "
            "uncompressed, 4-6x faster to write than the zlib-compressed VTU "
            "and 4-5x larger: 1.1 kB per block with its contacts). Same "
            "fields in both; see doc/user-guide.md. "
          : "'vtu': blocks-NNNNN.vtu (polyhedra, ASCII) and "
            "contacts-NNNNN.vtu with the series blocks.pvd and contacts.pvd "
            "(small scenes); 'hdf5': one snapshot-NNNNN.h5 per snapshot "
            "with the XDMF series blocks.xdmf and contacts.xdmf (large "
            "scenes), each block as its closed surface, one polygon cell "
            "per face carrying the block's fields (XDMF has no polyhedron "
            "cell ParaView reads); same fields otherwise. ")
        + "With 'hdf5' the rows of statistics.csv are also written as "
          "statistics.h5 (one dataset per column, with its unit), rewritten "
          "atomically with statistics.csv.");
    io::declare(
      prm,
      "Friction velocity dependence",
      "0",
      Double(-1., 1.),
      "-",
      "Steady-state velocity dependence A - B of the friction coefficient "
      "of every joint of the block file, in [-1, 1] (Dieterich 1979, Ruina "
      "1983; thesis Sec. 4.7.3, 4.8): a closed contact slipping at the rate "
      "V (its shear displacement increment in the previous step over the "
      "step's length) has the friction coefficient mu(V) = tan(phi) + (A - "
      "B) ln(max(V, V_min) / V0), at least 0, with phi the joint's friction "
      "angle. < 0: velocity weakening (the thesis's fit to all its data, "
      "Fig. 4-10: -0.0174); 0 = constant friction tan(phi). Static steps "
      "(Dynamic control 0, Settling steps) have no velocity and keep "
      "tan(phi).");
    io::declare(prm,
                "Reference slip rate",
                "1e-6",
                io::DoubleInterval::positive(),
                "m/s",
                "Reference slip rate V0 of the friction law (Friction "
                "velocity dependence), > 0: the slip rate at which the "
                "friction coefficient is tan(phi).");
    io::declare(prm,
                "Minimum slip rate",
                "1e-6",
                io::DoubleInterval::positive(),
                "m/s",
                "Velocity floor V_min of the friction law (Friction velocity "
                "dependence), > 0 and at most the Reference slip rate V0: "
                "contacts slipping slower, or at rest, have the friction "
                "coefficient mu(V_min); V_min = V0 keeps the static "
                "friction tan(phi).");
  }



  template <int dim>
  void
  AnalysisParameters<dim>::parse_parameters(dealii::ParameterHandler &prm,
                                            const std::string        &prm_file)
  {
    const std::string s    = section() + "/";
    const std::string file = prm.get("Block file");
    end_time               = prm.get_double("End time");
    time_step              = prm.get_double("Time step");
    dynamic                = prm.get_double("Dynamic control");
    strain_damping         = prm.get_double("Strain damping");
    contact_damping        = prm.get_double("Contact damping ratio");
    contact_step_damping   = prm.get_double("Contact step damping");
    max_open_close         = prm.get_integer("Maximum open-close iterations");
    max_displacement_ratio = prm.get_double("Maximum displacement ratio");
    shear_ratio            = prm.get_double("Shear penalty ratio");
    shear_penalty          = prm.get_double("Shear penalty");
    force_tolerance        = prm.get_double("Contact force tolerance");
    inexact_factor         = prm.get_double("Inexact solve factor");
    penetration_ratio      = prm.get_double("Penetration limit");
    fixed_penalty          = prm.get_double("Fixed point penalty");
    settling_steps         = prm.get_integer("Settling steps");
    gravity                = prm.get_double("Gravity");
    output_interval        = prm.get_double("Output interval");
    statistics_interval    = prm.get_double("Statistics interval");
    hdf5_output            = prm.get("Snapshot format") == "hdf5";
    a_minus_b              = prm.get_double("Friction velocity dependence");
    reference_velocity     = prm.get_double("Reference slip rate");
    min_velocity           = prm.get_double("Minimum slip rate");

    io::require(end_time > 0., prm_file, s + "End time", end_time, "> 0 s");
    io::require(time_step > 0., prm_file, s + "Time step", time_step, "> 0 s");
    {
      // The planned step count (cuts add more): an absurd one is a mistake
      // in the keys, not a run to start.
      const double n = io::planned_steps(0., end_time, time_step);
      if (n > io::max_planned_steps)
        throw InputError(prm_file + ": keys '" + s + "End time' = "
                         + io::format_number(end_time) + " s and '" + s
                         + "Time step' = " + io::format_number(time_step)
                         + " s plan " + io::format_number(n, 4)
                         + " time steps (End time / Time step); at most "
                         + io::format_number(io::max_planned_steps, 3)
                         + " are allowed: raise the time step or shorten the "
                           "run");
    }
    io::require(strain_damping >= 0. && std::isfinite(strain_damping),
                prm_file,
                s + "Strain damping",
                strain_damping,
                ">= 0 s");
    io::require(contact_damping >= 0. && std::isfinite(contact_damping),
                prm_file,
                s + "Contact damping ratio",
                contact_damping,
                ">= 0");
    io::require(contact_step_damping >= 0.
                  && std::isfinite(contact_step_damping),
                prm_file,
                s + "Contact step damping",
                contact_step_damping,
                ">= 0");
    io::require(max_displacement_ratio > 0. && max_displacement_ratio <= 1.,
                prm_file,
                s + "Maximum displacement ratio",
                max_displacement_ratio,
                "0 < ratio <= 1");
    io::require(shear_ratio > 0.,
                prm_file,
                s + "Shear penalty ratio",
                shear_ratio,
                "> 0");
    io::require(shear_penalty >= 0. && std::isfinite(shear_penalty),
                prm_file,
                s + "Shear penalty",
                shear_penalty,
                ">= 0 N/m");
    io::require(force_tolerance >= 1e-8 && force_tolerance <= 0.1,
                prm_file,
                s + "Contact force tolerance",
                force_tolerance,
                "1e-8 <= fraction <= 0.1");
    io::require(a_minus_b >= -1. && a_minus_b <= 1.,
                prm_file,
                s + "Friction velocity dependence",
                a_minus_b,
                "-1 <= A - B <= 1");
    io::require(reference_velocity > 0.,
                prm_file,
                s + "Reference slip rate",
                reference_velocity,
                "> 0 m/s");
    io::require(min_velocity > 0. && min_velocity <= reference_velocity,
                prm_file,
                s + "Minimum slip rate",
                min_velocity,
                "0 < V_min <= V0 (Reference slip rate = "
                  + io::format_number(reference_velocity) + " m/s)");
    if (file.empty())
      throw InputError(prm_file + ": key '" + s
                       + "Block file' is empty; give the scene's block file");
    block_file = io::resolve_path(file, prm_file, s + "Block file");
  }



  template <int dim>
  void
  AnalysisParameters<dim>::apply_friction_law(
    std::vector<JointMaterial> &joints) const
  {
    for (auto &j : joints)
      {
        j.a_minus_b          = a_minus_b;
        j.reference_velocity = reference_velocity;
        j.min_velocity       = min_velocity;
      }
  }



  template <int dim>
  void
  SolverParameters<dim>::declare_parameters(dealii::ParameterHandler &prm)
  {
    using dealii::Patterns::Double;
    using dealii::Patterns::Integer;
    using dealii::Patterns::Selection;
    if (dim == 2)
      {
        io::declare(prm,
                    "Linear solver",
                    "automatic",
                    Selection("automatic|direct|iterative|distributed"),
                    "-",
                    "'direct': sparse LDL^T; 'iterative': preconditioned CG "
                    "with warm start; 'distributed' (mpirun -np N only): CG "
                    "whose block rows are split over the ranks ('Distributed "
                    "preconditioner'; doc/theory/dda-mpi.md); 'automatic': "
                    "direct up to 60 blocks, above that iterative on one "
                    "process and distributed on several MPI ranks.");
        io::declare(prm,
                    "Distributed preconditioner",
                    "dilu",
                    Selection("dilu|ilu|block-jacobi|amg"),
                    "-",
                    "Preconditioner of the distributed solver: 'dilu' (the "
                    "block D-ILU of the serial solver with one subdomain per "
                    "rank and their separator eliminated last; from 300 "
                    "blocks on, 2 ranks do the serial solver's arithmetic "
                    "and take its steps bit for bit; the fastest on the "
                    "brick walls), or from Trilinos on an Epetra "
                    "matrix: 'ilu' (Ifpack ILU(0) on each rank's rows, "
                    "additive Schwarz without overlap), 'block-jacobi' "
                    "(Ifpack, the 6x6 blocks of the blocks) or 'amg' (ML "
                    "smoothed aggregation); doc/theory/dda-mpi.md.");
      }
    else
      io::declare(prm,
                  "Linear solver",
                  "automatic",
                  Selection("automatic|direct|iterative"),
                  "-",
                  "The 2D engine's solvers on 12x12 blocks: 'direct': sparse "
                  "LDL^T; 'iterative': preconditioned CG with warm start; "
                  "'automatic': direct up to 60 blocks, iterative above "
                  "(benchmarks/dda3d). No distributed solver in 3D.");
    io::declare(prm,
                "Preconditioner",
                "block-dilu",
                Selection("block-dilu|block-jacobi"),
                "-",
                dim == 2 ? "Preconditioner of the iterative solver: "
                           "'block-dilu' (6x6-block diagonal ILU with "
                           "Eisenstat's trick, about 2.4x fewer CG "
                           "iterations) or 'block-jacobi'."
                         : "Preconditioner of the iterative solver: "
                           "'block-dilu' (12x12-block diagonal ILU with "
                           "Eisenstat's trick, 2.2x fewer CG iterations on "
                           "a shaken wall, test Dda3dSolvers) or "
                           "'block-jacobi'.");
    io::declare(prm,
                "Solver tolerance",
                "1e-8",
                io::DoubleInterval(0., true, 1., true),
                "-",
                "Relative tolerance of the iterative solver (on the "
                "preconditioned residual), 0 < tolerance < 1. 1e-8 keeps "
                "block positions within ~1e-11 m of the direct solver on "
                "the 2D brick-wall test; each decade tighter costs ~25 % "
                "more CG iterations.");
    io::declare(prm,
                "Threads",
                "0",
                Integer(0, 1024),
                "-",
                "Threads of the run (a TBB task arena): contact "
                "detection, contact kinematics and state checks run in "
                "chunks on all of them (2D and 3D); the block-dilu CG from "
                "300 blocks on orders the blocks as two subdomains and "
                "their separator and sweeps the two in parallel (at most 2 "
                "threads there). 0 = one per core. Results do not depend "
                "on it.");
  }



  template <int dim>
  SolverOptions
  SolverParameters<dim>::parse_parameters(dealii::ParameterHandler &prm,
                                          const std::string        &prm_file)
  {
    const std::string s = AnalysisParameters<dim>::section() + "/";
    SolverOptions     o;
    const std::string solver = prm.get("Linear solver");
    o.type                   = solver == "direct"        ? SolverType::direct
                               : solver == "iterative"   ? SolverType::iterative
                               : solver == "distributed" ? SolverType::distributed
                                                         : SolverType::automatic;
    if (dim == 2)
      {
        const std::string dpc = prm.get("Distributed preconditioner");
        o.distributed_preconditioner
          = dpc == "dilu"  ? DistributedPreconditioner::dilu
            : dpc == "amg" ? DistributedPreconditioner::amg
            : dpc == "ilu" ? DistributedPreconditioner::ilu
                           : DistributedPreconditioner::block_jacobi;
      }
    if (o.type == SolverType::distributed
        && !dealii::Utilities::MPI::job_supports_mpi())
      throw InputError(prm_file + ": key '" + s
                       + "Linear solver' = 'distributed' needs a run under "
                         "MPI (mpirun -np N rockdda FILE.prm); valid here: "
                         "automatic, direct, iterative");
    o.tolerance      = prm.get_double("Solver tolerance");
    o.threads        = prm.get_integer("Threads");
    o.preconditioner = prm.get("Preconditioner") == "block-jacobi"
                         ? Preconditioner::block_jacobi
                         : Preconditioner::block_dilu;
    return o;
  }



  template struct AnalysisParameters<2>;
  template struct AnalysisParameters<3>;
  template struct SolverParameters<2>;
  template struct SolverParameters<3>;
} // namespace rockdda::dda
