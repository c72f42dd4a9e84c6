/**
 * @file
 * Analysis type "ratchet": N annual cycles of the coupled thermo-mechanical
 * wedging ratchet (thesis 5.4): the heat solver's periodic block
 * temperatures drive thermal eigenstrains in quasi-static DDA of a block, a
 * tension crack with infill and the cliff. Writes the per-cycle permanent
 * and cumulative displacement, the crack aperture, the infill's descent and
 * the contact states, the within-cycle loop, the steady ratchet rate next
 * to the analytical (Pasten 2012) estimate, and plots. With 'Ratchet
 * earthquakes/Catalogues' > 0 it then runs seeded earthquake catalogues on
 * the same evolving DDA state (run_ratchet_earthquakes(), issue 15 item 3)
 * against this thermal run and the earthquakes alone.
 */
#include <rockdda/analytical/ratchet.h>
#include <rockdda/coupling/analyses.h>
#include <rockdda/coupling/calibrate_analysis.h>
#include <rockdda/coupling/compare_analysis.h>
#include <rockdda/coupling/earthquakes.h>
#include <rockdda/coupling/earthquakes_analysis.h>
#include <rockdda/coupling/ratchet.h>
#include <rockdda/coupling/ratchet_earthquakes.h>
#include <rockdda/io/checkpoint.h>
#include <rockdda/io/error.h>
#include <rockdda/io/interrupt.h>
#include <rockdda/io/parameters.h>
#include <rockdda/io/plot.h>
#include <rockdda/io/progress.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>

namespace rockdda::coupling
{
  namespace
  {
    using dealii::Patterns::Bool;
    using dealii::Patterns::Double;
    using dealii::Patterns::Integer;
    using dealii::Patterns::Selection;
    using io::DoubleInterval;

    constexpr double pi = 3.14159265358979323846;

    /// The "ratchet" analysis.
    class RatchetAnalysis : public io::Analysis
    {
    public:
      std::string
      name() const override
      {
        return "ratchet";
      }

      std::string
      description() const override
      {
        return "coupled thermo-mechanical wedging ratchet: annual heat "
               "cycles drive thermal strain in DDA of a block, its tension "
               "crack with infill and the cliff";
      }

      void
      declare_parameters(dealii::ParameterHandler &prm) const override
      {
        prm.enter_subsection("Ratchet");
        const auto positive = DoubleInterval::positive();
        io::declare(prm,
                    "Block length",
                    analytical::block1_default(
                      &analytical::Block1Section::length),
                    positive,
                    "m",
                    "Length L_B of the block along the horizontal at its "
                    "base (> 0; thesis Eq. 5.3, doc/theory/block1.md).");
        io::declare(prm,
                    "Block height",
                    analytical::block1_default(
                      &analytical::Block1Section::height),
                    positive,
                    "m",
                    "Height H of the block's front (downslope) face (> 0); "
                    "the back face at the crack is H - L_B tan(eta) high "
                    "(at least 10 % of H), the area L_B (H - L_B tan(eta) "
                    "/ 2) as in thesis Eq. 5.3 (doc/theory/block1.md).");
        io::declare(prm,
                    "Slope",
                    analytical::block1_default(
                      &analytical::Block1Section::slope_deg),
                    DoubleInterval::right_open(0., 45.),
                    "deg",
                    "Dip eta of the bedding plane the block rests on "
                    "(0 <= eta < 45).");
        io::declare(prm,
                    "Crack top width",
                    "0.2",
                    positive,
                    "m",
                    "Width of the tension crack at the top of the block "
                    "(> 0; at least the bottom width: the crack narrows "
                    "downward, so that the infill can descend).");
        io::declare(prm,
                    "Crack bottom width",
                    "0.02",
                    positive,
                    "m",
                    "Width of the tension crack at the bedding plane (> 0).");
        io::declare(prm,
                    "Cliff width",
                    "8",
                    positive,
                    "m",
                    "Extent of the cliff behind the crack (> 0); its "
                    "farthest slice is fixed.");
        io::declare(prm,
                    "Base depth",
                    "3",
                    positive,
                    "m",
                    "Depth of the fixed base below the bedding plane at "
                    "the toe (> 0).");
        io::declare(prm,
                    "Toe length",
                    "3",
                    Double(0.),
                    "m",
                    "Bedding plane in front of the block's toe.");
        io::declare(prm,
                    "Infill",
                    "true",
                    Bool(),
                    "-",
                    "A wedge of rock fragments in the crack (true), or a "
                    "clean crack (false: the West-station control).");
        io::declare(prm,
                    "Infill top depth",
                    "6",
                    Double(0.),
                    "m",
                    "Depth of the infill's top below the top of the block.");
        io::declare(prm,
                    "Infill height",
                    "2",
                    positive,
                    "m",
                    "Height of the infill wedge (> 0); it must end above "
                    "the bedding plane.");
        io::declare(prm,
                    "Infill width",
                    "0",
                    Double(0.),
                    "m",
                    "Width of the infill at its top; 0 = the crack's width "
                    "there (it touches both faces). Narrower: it lies "
                    "against the cliff and drops until it wedges; wider "
                    "than the crack is an error.");
        io::declare(prm,
                    "Infill supply distance",
                    "0",
                    Double(0.),
                    "m",
                    "Supply of detritus for long runs: when the newest "
                    "infill fragment's top has descended this far below "
                    "the infill's initial top, a new fragment of the "
                    "infill's height is placed there, spanning the crack as "
                    "it is then (checked at the end of each cycle). 0 = no "
                    "supply; otherwise at least 'Infill height'.");
        io::declare(prm,
                    "Refinement depth",
                    "1",
                    positive,
                    "-",
                    "Depth, in seasonal skin depths S_d = sqrt(kappa "
                    "t_exp / 2) (t_exp half the period), within which the "
                    "block and the cliff are cut into bonded slices near "
                    "the crack faces and the block's front (> 0).");
        io::declare(prm,
                    "Slices",
                    "4",
                    Integer(0, 1000),
                    "-",
                    "Bonded slices within the refinement depth of each "
                    "exposed vertical face; 0 = the block is one DDA block "
                    "with one uniform strain.");
        io::declare(
          prm, "Density", "2600", positive, "kg/m^3", "Rock density (> 0).");
        io::declare(prm,
                    "Young's modulus",
                    "4e10",
                    positive,
                    "Pa",
                    "Young's modulus of the rock (> 0).");
        io::declare(prm,
                    "Poisson's ratio",
                    "0.2",
                    DoubleInterval::right_open(0., 0.5),
                    "-",
                    "Poisson's ratio (0 <= nu < 0.5).");
        io::declare(prm,
                    "Plane strain",
                    "true",
                    Bool(),
                    "-",
                    "Plane strain (true: the section of a long block; the "
                    "in-plane thermal strain is (1 + nu) alpha dT) or plane "
                    "stress (alpha dT).");
        io::declare(prm,
                    "Thermal expansion coefficient",
                    "8e-6",
                    Double(0.),
                    "1/K",
                    "Linear thermal expansion coefficient alpha.");
        io::declare(prm,
                    "Bedding friction angle",
                    "41",
                    DoubleInterval::right_open(0., 90.),
                    "deg",
                    "Friction angle of the bedding plane (0 <= phi < 90).");
        io::declare(prm,
                    "Bedding shear stiffness",
                    "1e9",
                    Double(0.),
                    "Pa/m",
                    "Physical shear stiffness k_j of the bedding plane; "
                    "0 = rigid (penalty only).");
        io::declare(prm,
                    "Bedding normal stiffness",
                    "0",
                    Double(0.),
                    "Pa/m",
                    "Physical normal stiffness of the bedding plane; 0 = "
                    "rigid (penalty only).");
        io::declare(prm,
                    "Crack friction angle",
                    "41",
                    DoubleInterval::right_open(0., 90.),
                    "deg",
                    "Friction angle between the infill and the crack faces "
                    "(0 <= phi < 90).");
        io::declare(prm,
                    "Cycles",
                    "10",
                    Integer(1, 1000000),
                    "-",
                    "Annual cycles to run.");
        io::declare(prm,
                    "Steps per cycle",
                    "24",
                    Integer(4, 100000),
                    "-",
                    "Temperature samples per cycle at which the DDA is "
                    "brought to equilibrium (a divisor of 'Thermal "
                    "forcing/Samples per cycle' uses its table exactly).");
        io::declare(prm,
                    "Equilibrium tolerance",
                    "1e-8",
                    positive,
                    "-",
                    "A sample is in equilibrium when a static step moves no "
                    "vertex by more than this fraction of the block height "
                    "(> 0).");
        io::declare(prm,
                    "Max steps per sample",
                    "20000",
                    Integer(1, 1000000),
                    "-",
                    "Static steps allowed per sample before the run stops "
                    "with a diagnosis. A sample usually takes 10-100; one "
                    "where the infill slides far in small static steps has "
                    "taken up to 12,000 (amplitude 15 K).");
        io::declare(prm,
                    "Pseudo time step",
                    "0",
                    DoubleInterval::right_open(
                      0., std::numeric_limits<double>::infinity()),
                    "s",
                    "Step of the static DDA steps (>= 0): only the inertia "
                    "term 2 M / dt^2 that regularises them depends on it. "
                    "0: automatic, sqrt(2 M / (1e-9 p)) with M the mass of "
                    "the heaviest block slice (kg/m) and p the normal "
                    "penalty (N/m), the quasi-static limit (about 19 s for "
                    "Block 1). A step of 1 s or less adds enough inertia to "
                    "change which contacts slide on the way to each "
                    "equilibrium, and with it the slip.");
        io::declare(prm,
                    "Contact penalty",
                    "0",
                    Double(0.),
                    "N/m",
                    "Normal contact penalty; 0 = automatic (10 E x 1 m, or "
                    "stiffer if the heaviest block needs it). The bonded "
                    "slices and the infill's contacts are penalty springs: "
                    "Block 1's rate converges from 1.18 mm/yr at 10 E to "
                    "0.74-0.76 at 1e13-2e13 N/m (250-500 E); default.prm "
                    "uses 1e13. A penalty whose round-off force "
                    "(p x 1e-12 x size) exceeds 1 % of a free block's "
                    "weight cannot resolve that block (a warning names it): "
                    "about 2.5e13 N/m for the default infill.");
        io::declare(prm,
                    "Settling steps",
                    "30",
                    Integer(0, 100000),
                    "-",
                    "Static steps under gravity before cycle 1.");
        io::declare(prm,
                    "Cycle jump",
                    "0",
                    Integer(0, 1000000),
                    "-",
                    "Most cycles one cycle jump skips, 0 = no jumps (every "
                    "cycle simulated). A jump moves every block by m times "
                    "its mean motion per cycle over the last 'Jump window' "
                    "simulated cycles (the block along the bedding plane, "
                    "each infill fragment as far as it goes without pressing "
                    "deeper into a face; stresses and contact springs kept), "
                    "then 'Jump window' + 1 cycles are simulated before the "
                    "next. m starts at 2 x 'Jump window'; a jump whose next "
                    "window's slip per cycle differs from the extrapolated "
                    "one by more than 'Jump tolerance' is undone and redone "
                    "half as long, otherwise the next doubles. A jump ends "
                    "where an infill fragment cannot follow its drift (the "
                    "crack's bottom). For long runs of a "
                    "periodic ratchet: benchmarks/ratchet/README.md, 'Cycle "
                    "jumps', gives the error against the cost. The last "
                    "cycle is always simulated; statistics.csv marks the "
                    "skipped ones (extrapolated = 1).");
        io::declare(prm,
                    "Jump tolerance",
                    "0.1",
                    DoubleInterval::right_open(
                      0., std::numeric_limits<double>::infinity()),
                    "-",
                    "Relative change of the slip per cycle between the "
                    "window a cycle jump extrapolates and the window after "
                    "it, beyond two standard errors of their difference "
                    "(the cycles' scatter), up to which the jump stands and "
                    "the next doubles; beyond it the jump is undone and "
                    "redone half as long (>= 0).");
        io::declare(prm,
                    "Jump window",
                    "4",
                    Integer(1, 1000),
                    "-",
                    "Simulated cycles whose mean motion a cycle jump "
                    "extrapolates (>= 1; the cycle after a jump, which "
                    "settles what the jump left, is not among them).");
        io::declare(prm,
                    "Jump start",
                    "10",
                    Integer(0, 1000000),
                    "-",
                    "Cycles simulated before the first cycle jump (the "
                    "infill settles into its periodic motion).");
        io::declare(prm,
                    "Checkpoint cycles",
                    "0",
                    Integer(0, 1000000),
                    "-",
                    "Write checkpoint.bin (atomically) every this many "
                    "cycles and at the end; 0 = only at the end and when "
                    "interrupted.");
        io::declare(prm,
                    "Resume",
                    "false",
                    Bool(),
                    "-",
                    "Continue from checkpoint.bin in the output directory "
                    "up to 'Cycles'.");
        prm.leave_subsection();

        prm.enter_subsection("Thermal forcing");
        io::declare(prm,
                    "Mean temperature",
                    "20",
                    Double(),
                    "degC",
                    "Mean air temperature, the stress-free reference.");
        io::declare(prm,
                    "Annual amplitude",
                    "9",
                    Double(0.),
                    "K",
                    "Amplitude of the annual air temperature (thesis "
                    "Table 5-2: 9 K; peak to peak twice that).");
        io::declare(prm,
                    "Period",
                    "31557600",
                    positive,
                    "s",
                    "Length of the cycle (> 0; a year).");
        io::declare(prm,
                    "Daily amplitude",
                    "0",
                    Double(0.),
                    "K",
                    "Amplitude of the daily air temperature.");
        io::declare(prm,
                    "Daily cycles",
                    "365",
                    Integer(1, 100000),
                    "-",
                    "Days per cycle (the daily period is Period / this).");
        io::declare(prm,
                    "Heat transfer coefficient",
                    "10",
                    positive,
                    "W/(m^2 K)",
                    "Convective exchange of the exposed faces and the "
                    "crack faces with the air (> 0).");
        io::declare(prm,
                    "Thermal conductivity",
                    "1.7",
                    positive,
                    "W/(m K)",
                    "Rock thermal conductivity lambda (> 0).");
        io::declare(prm,
                    "Specific heat capacity",
                    "810",
                    positive,
                    "J/(kg K)",
                    "Rock specific heat capacity c_p (> 0).");
        io::declare(prm,
                    "Finite element degree",
                    "2",
                    Integer(1, 3),
                    "-",
                    "Degree of the heat solver's FE_Q.");
        io::declare(prm,
                    "Cell size",
                    "1",
                    positive,
                    "m",
                    "Target coarse cell size of the heat mesh (> 0).");
        io::declare(prm,
                    "Time step",
                    "86400",
                    positive,
                    "s",
                    "Heat time step (Crank-Nicolson; rounded so that a "
                    "whole number of steps fits between samples) (> 0).");
        io::declare(prm,
                    "Spin-up cycles",
                    "4",
                    Integer(0, 1000),
                    "-",
                    "Periods solved before the recorded one, so that the "
                    "field is periodic.");
        io::declare(prm,
                    "Samples per cycle",
                    "24",
                    Integer(4, 1000000),
                    "-",
                    "Block mean temperatures recorded per period; later "
                    "cycles reuse them (the field is periodic). Only with "
                    "'Periodic solution = time stepping'.");
        io::declare(prm,
                    "Periodic solution",
                    "harmonic",
                    Selection("harmonic|time stepping"),
                    "-",
                    "How the periodic temperature field is found. "
                    "'harmonic': one complex direct solve per frequency of "
                    "the air temperature (the annual and the daily "
                    "sinusoid) gives the periodic field exactly at any time: "
                    "no spin-up, time step or samples (serial heat solver; "
                    "doc/theory/coupling.md). 'time stepping': Crank-"
                    "Nicolson over 'Spin-up cycles' periods, then a table of "
                    "'Samples per cycle' samples of the next, linear in "
                    "time between them.");
        prm.leave_subsection();

        prm.enter_subsection("Ratchet earthquakes");
        io::declare(prm,
                    "Catalogues",
                    "0",
                    Integer(0, 10000),
                    "-",
                    "Seeded Gutenberg-Richter catalogues over the run's "
                    "'Ratchet/Cycles' years (one cycle is one year), 0 to "
                    "10000; each runs as one coupled history in which its "
                    "earthquakes hit the same evolving DDA state between "
                    "cycles (dynamic steps under the event's motion, then "
                    "static thermal cycling from the state the quake left). "
                    "0 = no earthquakes: the thermal run alone. The "
                    "histories run after the thermal run and are not "
                    "checkpointed ('Resume' reruns them).");
        io::declare(prm,
                    "Seed",
                    "1",
                    Integer(0, std::numeric_limits<int>::max()),
                    "-",
                    "Seed of the first catalogue, 0 to 2147483647; "
                    "catalogue i (1-based) uses seed + i - 1.");
        io::declare(prm,
                    "Recurrence interval",
                    "300",
                    DoubleInterval::positive(),
                    "yr",
                    "Mean interval between events of at least the minimum "
                    "magnitude, > 0 yr (thesis 5.6.2: 300 yr for Mw >= 6). "
                    "A shorter interval accelerates the catalogue (more "
                    "events within a window of a few hundred cycles); the "
                    "magnitudes keep their distribution.");
        io::declare(prm,
                    "b-value",
                    "1",
                    DoubleInterval(0., true, 5., false),
                    "-",
                    "Gutenberg-Richter b-value, 0 < b <= 5 (a warning "
                    "outside the tectonic range, one half to two).");
        io::declare(prm,
                    "Minimum magnitude",
                    "6",
                    Double(3., 8.5),
                    "-",
                    "Smallest moment magnitude of the catalogue, 3 to 8.5.");
        io::declare(prm,
                    "Maximum magnitude",
                    "7.5",
                    Double(3., 8.5),
                    "-",
                    "Largest moment magnitude of the catalogue, 3 to 8.5, "
                    "above the minimum.");
        io::declare(prm,
                    "Distance",
                    "1000",
                    Double(0., 1e6),
                    "m",
                    "Joyner-Boore distance of every event, 0 to 1e6 m "
                    "(thesis: 1 km, the upper bound).");
        io::declare(prm,
                    "Masada site amplification",
                    "true",
                    Bool(),
                    "-",
                    "Amplify the synthetic motions by the Masada site "
                    "response (true) or not (false: rock).");
        io::declare(prm,
                    "Minimum PGA",
                    "0",
                    Double(0., 10.),
                    "g",
                    "Events whose site-amplified PGA is below this do not "
                    "run, 0 to 10 g; 0 = every event runs (the infill may "
                    "move below the block's yield acceleration).");
        io::declare(prm,
                    "Time step",
                    "0.005",
                    DoubleInterval(0., true, 1., false),
                    "s",
                    "Time step of the dynamic DDA steps of an earthquake, "
                    "0 < dt <= 1 s (the calibrated 0.005 s of the "
                    "'calibrate' analysis); the contact penalty stays "
                    "'Ratchet/Contact penalty'.");
        io::declare(prm,
                    "Contact damping ratio",
                    "0",
                    Double(0., 1.),
                    "-",
                    "Viscous dashpots in parallel with the closed contacts' "
                    "springs during the dynamic steps of an earthquake, as a "
                    "ratio of critical, 0 to 1 (0: none): c = 2 ratio "
                    "sqrt(k m) (N s/m), k the spring (N/m), m the lighter "
                    "free block's mass (kg); the physical damping of the "
                    "joints, chiefly the bedding joint's elastic shear mode, "
                    "which otherwise only the time step's numerical damping "
                    "(about omega dt / 4) damps, so that the episode's slip "
                    "depends on 'Time step'. Rock joints: a few per cent "
                    "(doc/theory/dda.md, Contact damping; "
                    "benchmarks/seismic-compare/README.md).");
        io::declare(prm,
                    "Rest time",
                    "2",
                    Double(0., 100.),
                    "s",
                    "Dynamic steps after the end of each record, 0 to 100 "
                    "s, in which a sliding block stops before the run "
                    "returns to static steps (which drop any motion left).");
        io::declare(prm,
                    "Earthquakes alone",
                    "true",
                    Bool(),
                    "-",
                    "Also run each catalogue's events on the scene without "
                    "thermal cycles and on Block 1 alone (no cliff, no "
                    "infill: the 'compare' analysis' seismic runs), the "
                    "seismic parts of 'combined against thermal + "
                    "seismic'.");
        io::declare(prm,
                    "Block 1 penalty",
                    "1e11",
                    DoubleInterval::positive(),
                    "N/m",
                    "Contact penalty of the runs of Block 1 alone, > 0 "
                    "(the 'compare' analysis: 100 GN/m).");
        io::declare(prm,
                    "Threads",
                    "0",
                    Integer(0, 1024),
                    "-",
                    "Runs at once, 0 to 1024 (0: one per core); each DDA "
                    "solver uses one thread.");
        prm.leave_subsection();
      }

      void
      parse_parameters(dealii::ParameterHandler &prm,
                       const std::string        &prm_file) override
      {
        prm.enter_subsection("Thermal forcing");
        forcing.mean             = prm.get_double("Mean temperature");
        forcing.annual_amplitude = prm.get_double("Annual amplitude");
        forcing.period           = prm.get_double("Period");
        forcing.daily_amplitude  = prm.get_double("Daily amplitude");
        forcing.daily_cycles     = prm.get_integer("Daily cycles");
        forcing.heat_transfer_coefficient
          = prm.get_double("Heat transfer coefficient");
        heat.material.conductivity  = prm.get_double("Thermal conductivity");
        heat.material.heat_capacity = prm.get_double("Specific heat capacity");
        heat.degree                 = prm.get_integer("Finite element degree");
        heat.cell_size              = prm.get_double("Cell size");
        heat.time_step              = prm.get_double("Time step");
        heat.spin_up_cycles         = prm.get_integer("Spin-up cycles");
        heat.samples_per_cycle      = prm.get_integer("Samples per cycle");
        heat.harmonic = prm.get("Periodic solution") == "harmonic";
        prm.leave_subsection();

        prm.enter_subsection("Ratchet");
        geometry.block.length       = prm.get_double("Block length");
        geometry.block.height       = prm.get_double("Block height");
        geometry.block.slope_deg    = prm.get_double("Slope");
        geometry.crack_top_width    = prm.get_double("Crack top width");
        geometry.crack_bottom_width = prm.get_double("Crack bottom width");
        geometry.cliff_width        = prm.get_double("Cliff width");
        geometry.base_depth         = prm.get_double("Base depth");
        geometry.toe_length         = prm.get_double("Toe length");
        geometry.infill             = prm.get_bool("Infill");
        geometry.infill_top_depth   = prm.get_double("Infill top depth");
        geometry.infill_height      = prm.get_double("Infill height");
        geometry.infill_width       = prm.get_double("Infill width");
        geometry.supply_distance    = prm.get_double("Infill supply distance");
        refinement_factor           = prm.get_double("Refinement depth");
        geometry.slices             = prm.get_integer("Slices");
        materials.rock.density      = prm.get_double("Density");
        materials.rock.young        = prm.get_double("Young's modulus");
        materials.rock.poisson      = prm.get_double("Poisson's ratio");
        materials.rock.plane_strain = prm.get_bool("Plane strain");
        alpha = prm.get_double("Thermal expansion coefficient");
        materials.bedding_friction_deg
          = prm.get_double("Bedding friction angle");
        materials.bedding_shear_stiffness
          = prm.get_double("Bedding shear stiffness");
        materials.bedding_normal_stiffness
          = prm.get_double("Bedding normal stiffness");
        materials.crack_friction_deg = prm.get_double("Crack friction angle");
        cycles                       = prm.get_integer("Cycles");
        controls.steps_per_cycle     = prm.get_integer("Steps per cycle");
        controls.equilibrium_tolerance
          = prm.get_double("Equilibrium tolerance");
        controls.max_steps_per_sample = prm.get_integer("Max steps per sample");
        controls.pseudo_time_step     = prm.get_double("Pseudo time step");
        controls.penalty              = prm.get_double("Contact penalty");
        controls.settle_steps         = prm.get_integer("Settling steps");
        controls.jump_max             = prm.get_integer("Cycle jump");
        controls.jump_tolerance       = prm.get_double("Jump tolerance");
        controls.jump_window          = prm.get_integer("Jump window");
        jump_start                    = prm.get_integer("Jump start");
        checkpoint_cycles             = prm.get_integer("Checkpoint cycles");
        resume                        = prm.get_bool("Resume");
        prm.leave_subsection();

        prm.enter_subsection("Ratchet earthquakes");
        quakes.catalogues        = prm.get_integer("Catalogues");
        quakes.first_seed        = prm.get_integer("Seed");
        quakes.gr.recurrence     = prm.get_double("Recurrence interval");
        quakes.gr.b_value        = prm.get_double("b-value");
        quakes.gr.min_magnitude  = prm.get_double("Minimum magnitude");
        quakes.gr.max_magnitude  = prm.get_double("Maximum magnitude");
        quakes.distance          = prm.get_double("Distance");
        quakes.masada_site       = prm.get_bool("Masada site amplification");
        quakes.minimum_pga       = prm.get_double("Minimum PGA");
        quakes.episode.time_step = prm.get_double("Time step");
        quakes.episode.rest_time = prm.get_double("Rest time");
        quakes.episode.contact_damping
          = prm.get_double("Contact damping ratio");
        quakes.quakes_on_scene = prm.get_bool("Earthquakes alone");
        quakes.block1_penalty  = prm.get_double("Block 1 penalty");
        quakes.threads         = prm.get_integer("Threads");
        prm.leave_subsection();
        io::require(quakes.catalogues == 0
                      || quakes.gr.max_magnitude > quakes.gr.min_magnitude,
                    prm_file,
                    "Ratchet earthquakes/Maximum magnitude",
                    quakes.gr.max_magnitude,
                    "> 'Minimum magnitude' and <= 8.5");

        io::require(controls.jump_max == 0 || quakes.catalogues == 0,
                    prm_file,
                    "Ratchet/Cycle jump",
                    controls.jump_max,
                    "0 with earthquake catalogues (a jump extrapolates "
                    "thermal cycles only; 'Ratchet earthquakes/Catalogues' = "
                      + std::to_string(quakes.catalogues) + ")");

        heat.material.density = materials.rock.density;
        skin
          = std::sqrt(0.5 * heat.material.diffusivity() * 0.5 * forcing.period);
        geometry.refinement_depth = refinement_factor * skin;
        // Build the scene now: bad geometry is an input error of the file.
        io::with_parameter_file(prm_file, [&]() {
          scene = make_ratchet_scene(geometry, materials);
        });
        file = prm_file;
      }

      std::vector<std::string>
      warnings() const override
      {
        std::vector<std::string> w;
        if (quakes.catalogues > 0
            && (quakes.gr.b_value < 0.5 || quakes.gr.b_value > 2.))
          w.push_back("key 'Ratchet earthquakes/b-value' = "
                      + io::format_number(quakes.gr.b_value, 4)
                      + " is outside 0.5-2, the range of b-values of "
                        "tectonic seismicity (Gutenberg & Richter 1944)");
        return w;
      }

      bool
      resumes() const override
      {
        return resume;
      }

      void
      run(io::RunContext &context) override
      {
        auto &log = context.log;
        log.line("ratchet scene: " + std::to_string(scene.blocks.blocks.size())
                 + " DDA blocks (" + std::to_string(scene.block_slices.size())
                 + " block slices, " + std::to_string(scene.cliff_slices.size())
                 + " cliff slices" + (scene.infill >= 0 ? ", infill" : "")
                 + "), skin depth " + io::format_number(skin, 4)
                 + " m, refinement depth "
                 + io::format_number(geometry.refinement_depth, 4) + " m");
        const auto                     t0 = std::chrono::steady_clock::now();
        const PeriodicBlockTemperature temperature(scene.heat_blocks,
                                                   forcing,
                                                   heat);
        const auto                     t1 = std::chrono::steady_clock::now();
        const double                   heat_seconds
          = std::chrono::duration<double>(t1 - t0).count();
        log.line(
          "heat: "
          + (temperature.harmonic()
               ? std::string("periodic field by harmonic solves ")
                   + (forcing.daily_amplitude != 0. ? "(annual and daily)"
                                                    : "(annual)")
               : std::to_string(heat.spin_up_cycles)
                   + " spin-up periods and one recorded ("
                   + std::to_string(temperature.n_steps) + " steps)")
          + " on " + std::to_string(temperature.n_cells) + " cells in "
          + io::format_number(heat_seconds, 3) + " s");

        RatchetRun run_(scene, temperature, forcing, alpha, controls);
        for (const auto &w : run_.dda().warnings())
          log.line("warning: " + w);
        io::Table table;
        for (const auto &[name, unit] :
             std::vector<std::pair<std::string, std::string>>{
               {"cycle", "-"},
               {"time", "year"},
               {"displacement", "m"},
               {"permanent", "m"},
               {"aperture", "m"},
               {"infill_descent", "m"},
               {"open", "-"},
               {"sliding", "-"},
               {"locked", "-"},
               {"steps", "-"},
               {"cuts", "-"},
               {"stationary_samples", "-"},
               {"chatter", "m"},
               {"fragments", "-"},
               {"stored_energy", "J/m"},
               {"extrapolated", "-"}})
          table.add_column(name, unit);
        io::Table loop;
        for (const auto &[name, unit] :
             std::vector<std::pair<std::string, std::string>>{
               {"cycle", "-"},
               {"phase", "-"},
               {"air_temperature", "degC"},
               {"block_temperature", "degC"},
               {"displacement", "m"},
               {"aperture", "m"}})
          loop.add_column(name, unit);

        const io::RunCheckpoint checkpoint_file(context.output,
                                                "ratchet",
                                                fingerprint(),
                                                "Ratchet");
        const auto              save = [&]() {
          io::BinaryWriter w = checkpoint_file.begin();
          w.put_string(run_.checkpoint());
          io::RunCheckpoint::put_rows(w, table);
          io::RunCheckpoint::put_rows(w, loop);
          checkpoint_file.write(w, table);
        };
        if (resume)
          {
            const std::string bytes = checkpoint_file.read();
            io::BinaryReader  r     = checkpoint_file.reader(bytes);
            run_.restore(r.get_string(), checkpoint_file.file());
            io::RunCheckpoint::get_rows(r, table);
            io::RunCheckpoint::get_rows(r, loop);
            if (!r.at_end())
              throw InputError(checkpoint_file.file() + ": trailing data");
            log.line("resumed from " + checkpoint_file.file() + " after cycle "
                     + std::to_string(run_.cycles()));
          }

        unsigned int              saved_at = run_.cycles();
        io::ProgressBar           progress("ratchet", cycles);
        std::vector<SampleRecord> samples;
        while (run_.cycles() < cycles)
          {
            const bool record_loop
              = run_.cycles() == 0 || run_.cycles() + 1 == cycles;
            const CycleRecord r
              = run_.run_cycle(record_loop ? &samples : nullptr);
            table.add_row({static_cast<double>(r.cycle),
                           r.cycle * forcing.period / 31557600.,
                           r.displacement,
                           r.permanent,
                           r.aperture,
                           r.infill_descent,
                           static_cast<double>(r.n_open),
                           static_cast<double>(r.n_sliding),
                           static_cast<double>(r.n_locked),
                           static_cast<double>(r.steps),
                           static_cast<double>(r.cuts),
                           static_cast<double>(r.stationary_samples),
                           r.chatter,
                           static_cast<double>(r.fragments),
                           r.stored_energy,
                           0.});
            if (record_loop)
              for (const auto &s : samples)
                loop.add_row({static_cast<double>(r.cycle),
                              s.phase,
                              s.air,
                              s.block_mean,
                              s.displacement,
                              s.aperture});
            // A cycle jump (the last cycle is always simulated): one row
            // per skipped cycle, the state interpolated linearly.
            // A jump whose next window changed its slip per cycle by more
            // than the jump tolerance beyond the windows' scatter is undone
            // (RatchetRun::review_jump); its rows go too.
            double change = 0.;
            if (controls.jump_max > 0 && run_.review_jump(&change))
              {
                const double back = run_.cycles();
                const auto   keep = [back](io::Table &t) {
                  std::size_t k = 0;
                  while (k < t.n_rows() && t.row(k)[0] <= back)
                    ++k;
                  t.truncate(k);
                };
                keep(table);
                keep(loop);
                log.line("cycle jump after cycle " + io::format_number(back, 8)
                         + " undone: the slip "
                         + "per cycle after it changed by "
                         + io::format_number(100. * change, 3)
                         + " %; jumping half as far");
              }
            if (controls.jump_max > 0 && run_.cycles() >= jump_start
                && run_.cycles() + 1 < cycles)
              {
                const JumpRecord    j = run_.jump(cycles - run_.cycles() - 1);
                std::vector<double> last = table.row(table.n_rows() - 1);
                for (unsigned int k = 1; k <= j.cycles; ++k)
                  {
                    const double f  = static_cast<double>(k) / j.cycles;
                    const auto   at = [f](const double a, const double b) {
                      return a + f * (b - a);
                    };
                    std::vector<double> row = last;
                    row[0]                  = last[0] + k;
                    row[1] = row[0] * forcing.period / 31557600.;
                    row[2] = at(j.displacement_before, j.displacement_after);
                    row[3] = (j.displacement_after - j.displacement_before)
                             / j.cycles;
                    row[4] = at(j.aperture_before, j.aperture_after);
                    row[5] = at(j.descent_before, j.descent_after);
                    for (const int c : {9, 10, 11, 12})
                      row[c] = 0.;
                    row[15] = 1.;
                    table.add_row(row);
                  }
                if (j.cycles > 0)
                  log.line("cycle jump after cycle "
                           + io::format_number(last[0], 8) + ": "
                           + std::to_string(j.cycles) + " cycles, slip "
                           + io::format_number(j.displacement_after
                                                 - j.displacement_before,
                                               4)
                           + " m, infill moved "
                           + io::format_number(j.infill_fraction, 4)
                           + " of its extrapolated descent, offset "
                           + io::format_number(j.infill_offset, 3));
              }
            progress.update(run_.cycles(), run_.cycles());
            if (checkpoint_cycles > 0
                && run_.cycles() / checkpoint_cycles
                     > saved_at / checkpoint_cycles)
              {
                save();
                saved_at = run_.cycles();
              }
            if (io::interrupt_signal() != 0 && run_.cycles() < cycles)
              {
                save();
                context.stopped_early = true;
                context.stopped_note  = "checkpoint.bin after cycle "
                                       + std::to_string(run_.cycles())
                                       + "; rerun with 'set Resume = true'";
                break;
              }
          }
        const auto   t2 = std::chrono::steady_clock::now();
        const double dda_seconds
          = std::chrono::duration<double>(t2 - t1).count();
        if (!context.stopped_early)
          save();
        context.output.write("statistics.csv", table.csv());
        context.output.write("cycle_loop.csv", loop.csv());

        // The steady rate: the mean permanent displacement of the second
        // half of the cycles (the first cycles settle the infill).
        const std::size_t n     = table.n_rows();
        const std::size_t first = n / 2;
        double            rate  = 0.;
        for (std::size_t k = first; k < n; ++k)
          rate += table.row(k)[3];
        rate /= std::max<std::size_t>(1, n - first);
        const double years = forcing.period / 31557600.;
        context.summary.add("ratchet_rate", 1e3 * rate / years, "mm/yr");
        context.summary.add("displacement",
                            n > 0 ? table.row(n - 1)[2] : 0.,
                            "m");
        context.summary.add("cycles", static_cast<double>(n), "-");
        {
          double simulated = 0.;
          for (std::size_t k = 0; k < n; ++k)
            simulated += table.row(k)[15] == 0. ? 1. : 0.;
          context.summary.add("simulated_cycles", simulated, "-");
        }
        context.summary.add("skin_depth", skin, "m");
        context.summary.add("dda_blocks",
                            static_cast<double>(scene.blocks.blocks.size()),
                            "-");
        context.summary.add("heat_cells",
                            static_cast<double>(temperature.n_cells),
                            "-");
        context.summary.add("heat_seconds", heat_seconds, "s");
        context.summary.add("dda_seconds", dda_seconds, "s");
        context.summary.add("pseudo_time_step", run_.time_step(), "s");
        context.summary.add("dda_steps",
                            static_cast<double>(run_.dda().n_steps),
                            "-");
        {
          // Samples whose equilibrium was a stationary switching of one
          // contact (RatchetRun::equilibrate), over all cycles.
          double stationary = 0., chatter = 0.;
          for (std::size_t i = 0; i < table.n_rows(); ++i)
            {
              stationary += table.row(i)[11];
              chatter = std::max(chatter, table.row(i)[12]);
            }
          context.summary.add("stationary_samples", stationary, "-");
          context.summary.add("chatter_max", chatter, "m");
          if (stationary > 0.)
            log.line("note: " + io::format_number(stationary, 6)
                     + " samples reached equilibrium with one contact "
                       "switching between sliding and locked (largest "
                       "vertex motion per step "
                     + io::format_number(chatter, 3)
                     + " m) while the slip and the aperture stayed within "
                       "the equilibrium tolerance over 100 steps");
        }

        // The analytical estimate (Pasten 2012, thesis Eqs. 5.1-5.6) for
        // the same block, wedge = the crack width at the infill's middle,
        // beta = 0.45.
        analytical::RatchetInput a;
        a.set_section(geometry.block);
        a.wedge_length          = geometry.infill ? infill_width() : 0.;
        a.friction_angle_deg    = materials.bedding_friction_deg;
        a.density               = materials.rock.density;
        a.youngs_modulus        = materials.rock.young;
        a.joint_shear_stiffness = materials.bedding_shear_stiffness > 0.
                                    ? materials.bedding_shear_stiffness
                                    : 1e9;
        a.thermal_expansion     = alpha;
        a.temperature_change    = 2. * forcing.annual_amplitude;
        a.conductivity          = heat.material.conductivity;
        a.heat_capacity         = heat.material.heat_capacity;
        a.exposure_time         = 0.5 * forcing.period;
        try
          {
            const analytical::RatchetResult p = analytical::ratchet(a);
            context.summary.add("analytical_rate_beta_0.45",
                                1e3 * p.plastic_displacement / years,
                                "mm/yr");
            a.beta = 0.7;
            context.summary.add("analytical_rate_beta_0.7",
                                1e3
                                  * analytical::ratchet(a).plastic_displacement
                                  / years,
                                "mm/yr");
          }
        catch (const InputError &e)
          {
            log.line(std::string("note: no analytical estimate: ") + e.what());
          }
        log.line("ratchet: " + std::to_string(n) + " cycles, steady rate "
                 + io::format_number(1e3 * rate / years, 5) + " mm/yr, heat "
                 + io::format_number(heat_seconds, 3) + " s, DDA "
                 + io::format_number(dda_seconds, 3) + " s");
        if (quakes.catalogues > 0 && !context.stopped_early)
          run_earthquakes(context, temperature, table);
        io::run_plot_script(context.output,
                            context.log,
                            "plot_ratchet_cycles.py",
                            {"ratchet.png"});
      }

    private:
      /**
       * The earthquake catalogues inside the ratchet
       * (run_ratchet_earthquakes()): per catalogue the coupled history,
       * the thermal run alone (@p thermal, the cycles' table: column 2 is
       * the displacement) and the earthquakes alone, written to
       * earthquake_events.csv, earthquake_histories.csv and
       * earthquake_yearly.csv, with their spreads in the summary and
       * ratchet_earthquakes.png.
       */
      void
      run_earthquakes(io::RunContext                 &context,
                      const PeriodicBlockTemperature &temperature,
                      const io::Table                &thermal)
      {
        auto              &log   = context.log;
        const unsigned int n     = thermal.n_rows();
        const double       alone = n > 0 ? thermal.row(n - 1)[2] : 0.;
        Block1Geometry     b1;
        static_cast<analytical::Block1Section &>(b1) = geometry.block;
        Block1Materials b1m;
        b1m.rock         = materials.rock;
        b1m.friction_deg = materials.bedding_friction_deg;
        log.line("earthquakes: " + std::to_string(quakes.catalogues)
                 + " catalogues over " + std::to_string(n)
                 + " cycles (one a year), Mw "
                 + io::format_number(quakes.gr.min_magnitude, 3) + "-"
                 + io::format_number(quakes.gr.max_magnitude, 3)
                 + ", one every " + io::format_number(quakes.gr.recurrence, 4)
                 + " yr on average, at " + io::format_number(quakes.distance, 4)
                 + " m");
        const RatchetEarthquakeResult r = run_ratchet_earthquakes(
          scene, temperature, forcing, alpha, controls, n, b1, b1m, quakes);
        io::Table events;
        for (const auto &[name, unit] :
             std::vector<std::pair<std::string, std::string>>{
               {"catalogue", "-"},
               {"time", "yr"},
               {"magnitude", "-"},
               {"motion_seed", "-"},
               {"pga", "g"},
               {"runs", "-"},
               {"coupled_slip", "m"},
               {"coupled_dynamic_slip", "m"},
               {"coupled_aperture", "m"},
               {"coupled_infill_descent", "m"},
               {"coupled_energy_gain", "J/m"},
               {"coupled_dynamic_steps", "-"},
               {"alone_slip", "m"},
               {"alone_energy_gain", "J/m"},
               {"alone_energy_scale", "J/m"},
               {"block1_slip", "m"},
               {"block1_analytical", "m"}})
          events.add_column(name, unit);
        for (const auto &q : r.quakes)
          events.add_row({static_cast<double>(q.catalogue + 1),
                          q.event.time,
                          q.event.magnitude,
                          static_cast<double>(q.event.motion_seed),
                          q.pga,
                          q.runs ? 1. : 0.,
                          q.coupled.slip,
                          q.coupled.dynamic_slip,
                          q.coupled.aperture,
                          q.coupled.infill_descent,
                          q.coupled.energy_gain,
                          static_cast<double>(q.coupled.dynamic_steps),
                          q.alone.slip,
                          q.alone.energy_gain,
                          q.alone.energy_scale,
                          q.block1,
                          q.block1_analytical});
        context.output.write("earthquake_events.csv", events.csv());
        // Physics of the episodes: the ledger's largest gain over the
        // dynamic steps relative to the energy in play (the integration
        // only dissipates), and the smallest slip (upslope < 0).
        double       gain       = -std::numeric_limits<double>::infinity();
        double       least_slip = std::numeric_limits<double>::infinity();
        unsigned int episodes   = 0;
        for (const auto &q : r.quakes)
          if (q.runs && q.coupled.dynamic_steps > 0)
            {
              ++episodes;
              gain       = std::max(gain,
                              q.coupled.energy_gain
                                / std::max(q.coupled.energy_scale, 1e-300));
              least_slip = std::min(least_slip, q.coupled.slip);
            }
        context.summary.add("quake_episodes", episodes, "-");
        if (episodes > 0)
          {
            context.summary.add("quake_episode_energy_gain_max", gain, "-");
            context.summary.add("quake_episode_slip_min", least_slip, "m");
          }

        io::Table per, yearly;
        for (const auto &[name, unit] :
             std::vector<std::pair<std::string, std::string>>{
               {"catalogue", "-"},
               {"events", "-"},
               {"episodes", "-"},
               {"coupled", "m"},
               {"thermal", "m"},
               {"coupled_episodes", "m"},
               {"quakes_scene", "m"},
               {"quakes_block1", "m"},
               {"coupled_over_sum_scene", "-"},
               {"coupled_over_sum_block1", "-"},
               {"wall_time", "s"}})
          per.add_column(name, unit);
        yearly.add_column("catalogue", "-");
        yearly.add_column("year", "-");
        yearly.add_column("displacement", "m");
        for (unsigned int y = 0; y < n; ++y)
          yearly.add_row({0., y + 1., thermal.row(y)[2]});
        std::vector<double> ratio_scene, ratio_block1, coupled, quake_sum;
        unsigned int        failed = 0;
        for (const auto &h : r.histories)
          {
            const double rs = h.coupled / (alone + h.quakes_scene);
            const double rb = h.coupled / (alone + h.quakes_block1);
            per.add_row({h.catalogue + 1.,
                         static_cast<double>(h.events),
                         static_cast<double>(h.episodes),
                         h.coupled,
                         alone,
                         h.coupled_episodes,
                         h.quakes_scene,
                         h.quakes_block1,
                         rs,
                         rb,
                         h.wall_time});
            for (std::size_t y = 0; y < h.yearly.size(); ++y)
              yearly.add_row({h.catalogue + 1., y + 1., h.yearly[y]});
            if (!h.failure.empty())
              {
                ++failed;
                log.line("catalogue " + std::to_string(h.catalogue + 1) + ": "
                         + h.failure);
                continue;
              }
            ratio_scene.push_back(rs);
            ratio_block1.push_back(rb);
            coupled.push_back(h.coupled);
            quake_sum.push_back(h.quakes_scene);
          }
        context.output.write("earthquake_histories.csv", per.csv());
        context.output.write("earthquake_yearly.csv", yearly.csv());
        const Spread sc = spread(coupled), sq = spread(quake_sum),
                     rs = spread(ratio_scene), rb = spread(ratio_block1);
        context.summary.add("quake_catalogues", quakes.catalogues, "-");
        context.summary.add("quake_events",
                            static_cast<double>(r.quakes.size()),
                            "-");
        context.summary.add("quake_failed_catalogues", failed, "-");
        context.summary.add("quake_thermal_only", alone, "m");
        context.summary.add("quake_coupled_median", sc.median, "m");
        context.summary.add("quake_alone_scene_median", sq.median, "m");
        context.summary.add("quake_coupled_over_sum_median", rs.median, "-");
        context.summary.add("quake_coupled_over_sum_p16", rs.p16, "-");
        context.summary.add("quake_coupled_over_sum_p84", rs.p84, "-");
        context.summary.add("quake_coupled_over_sum_block1_median",
                            rb.median,
                            "-");
        context.summary.add("quake_concurrent_runs", r.threads, "-");
        context.summary.add("quake_motion_seconds", r.motion_seconds, "s");
        context.summary.add("quake_dda_seconds", r.dda_seconds, "s");
        log.line(
          "earthquakes: " + std::to_string(r.quakes.size()) + " events in "
          + std::to_string(quakes.catalogues) + " catalogues, "
          + std::to_string(failed) + " failed; thermal alone "
          + io::format_number(alone, 4) + " m, coupled (median) "
          + io::format_number(sc.median, 4) + " m, earthquakes alone on "
          + "the scene " + io::format_number(sq.median, 4)
          + " m; coupled / (thermal + seismic) "
          + io::format_number(rs.median, 4) + " ("
          + io::format_number(rs.p16, 4) + "-" + io::format_number(rs.p84, 4)
          + "), with Block 1 alone as the seismic part "
          + io::format_number(rb.median, 4) + "; DDA "
          + io::format_number(r.dda_seconds, 4) + " s on "
          + std::to_string(r.threads) + " threads");
        // A catalogue whose DDA stopped is recorded (its row in
        // earthquake_histories.csv, NaN) and left out of the spreads, as the
        // 'compare' analysis does with its failed runs.
        if (failed > 0)
          log.record("WARNING: " + std::to_string(failed) + " of "
                     + std::to_string(quakes.catalogues)
                     + " catalogue(s) stopped (DDA could not continue; see "
                       "above); the spreads are over the others");
        io::run_plot_script(context.output,
                            context.log,
                            "plot_ratchet_earthquakes.py",
                            {"ratchet_earthquakes.png"});
      }

      /// Width of the infill at its mid-height (m).
      double
      infill_width() const
      {
        const auto &v = scene.blocks.blocks[scene.infill].polygon.vertices;
        return 0.5 * ((v[1] - v[0]).norm() + (v[2] - v[3]).norm());
      }

      /// The controls a resumed run must share.
      std::string
      fingerprint() const
      {
        // "H front": the block's height is that of its front face (a
        // checkpoint of the earlier back-face geometry does not resume).
        std::string f = "H front;";
        for (const double v : {geometry.block.length,
                               geometry.block.height,
                               geometry.block.slope_deg,
                               geometry.crack_top_width,
                               geometry.crack_bottom_width,
                               geometry.infill ? 1. : 0.,
                               geometry.supply_distance,
                               geometry.refinement_depth,
                               static_cast<double>(geometry.slices),
                               alpha,
                               forcing.annual_amplitude,
                               forcing.daily_amplitude,
                               static_cast<double>(controls.steps_per_cycle),
                               controls.equilibrium_tolerance,
                               controls.penalty,
                               materials.bedding_friction_deg,
                               materials.bedding_shear_stiffness,
                               static_cast<double>(controls.jump_max),
                               static_cast<double>(controls.jump_window),
                               controls.jump_tolerance,
                               static_cast<double>(jump_start)})
          f += io::format_number(v, 17) + ";";
        return f;
      }

      RatchetGeometry          geometry;
      RatchetMaterials         materials;
      SeasonalForcing          forcing;
      HeatControls             heat;
      RatchetControls          controls;
      RatchetEarthquakeOptions quakes;
      RatchetScene             scene;
      double                   alpha = 8e-6, refinement_factor = 1., skin = 0.;
      unsigned int             cycles = 10, checkpoint_cycles = 0;
      /// Cycles simulated before the first cycle jump.
      unsigned int jump_start = 10;
      bool         resume     = false;
      std::string  file;
    };
  } // namespace



  std::vector<std::unique_ptr<io::Analysis>>
  make_analyses()
  {
    std::vector<std::unique_ptr<io::Analysis>> list;
    list.push_back(std::make_unique<RatchetAnalysis>());
    list.push_back(make_calibrate_analysis());
    list.push_back(make_earthquakes_analysis());
    list.push_back(make_compare_analysis());
    return list;
  }
} // namespace rockdda::coupling
