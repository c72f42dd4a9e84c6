/**
 * @file
 * Masada Block 1 without infill under seismic input (thesis 5.5.2): one
 * rigid-ish block on its bedding plane over a fixed base, as a DDA scene,
 * and the matching analytical sliding-block (Newmark 1965) solution of a
 * block on a plane loaded by a horizontal acceleration. Used by the
 * "calibrate" analysis (penalty and time step against Eq. 5.10) and its
 * tests. doc/theory/calibration.md describes the geometry.
 */
#ifndef ROCKDDA_COUPLING_BLOCK1_SEISMIC_H
#define ROCKDDA_COUPLING_BLOCK1_SEISMIC_H

#include <rockdda/analytical/block1.h>
#include <rockdda/dda/block_system.h>
#include <rockdda/dda/engine.h>
#include <rockdda/seismic/record.h>

#include <functional>
#include <string>

namespace rockdda::coupling
{
  /**
   * Block 1 on its bedding plane (m, deg): the block's cross-section
   * (analytical::Block1Section: L_B, H at the front face, dip; thesis
   * Eq. 5.3) and the fixed base it stands on. x is horizontal, pointing
   * downslope (east), y up; the bedding plane passes through the block's
   * heel at the origin and descends towards +x.
   */
  struct Block1Geometry : analytical::Block1Section
  {
    /// Horizontal length of the bedding plane beyond the toe (m), > 0: room
    /// for the block to slide.
    double toe_length = 10.;
    /// Horizontal length of the bedding plane behind the heel (m), > 0.
    double heel_length = 2.;
    /// Depth of the fixed base below the bedding plane at its lower end
    /// (m), > 0.
    double base_depth = 3.;
  };

  /// Materials of the Block 1 scene (thesis Table 5-2).
  struct Block1Materials
  {
    /// Intact dolomite: 2600 kg/m^3, E = 40 GPa, nu = 0.2, plane strain.
    dda::BlockMaterial rock{2600., 4e10, 0.2, true, -1};
    /// Friction angle of the bedding plane (deg), in [0, 90).
    double friction_deg = 41.;
  };

  /// The scene and what is measured on it.
  struct Block1Scene
  {
    dda::BlockSystem blocks;
    /// DDA indices of the fixed base and of the block.
    int base = 0, block = 1;
    /// Index of the measurement point at the middle of the block's base.
    int base_point = 0;
    /// Unit vector down the bedding plane.
    geometry::Point downslope;
  };

  /**
   * Build the scene: the fixed base (clamped at three corners; it follows
   * the ground in displacement mode) and the block,
   * analytical::Block1Section::polygon() with its heel at the origin, with a
   * rigid joint (penalty only) of friction Block1Materials::friction_deg on
   * every face. Without infill the tension crack never closes on a block that
   * slides downslope, so the cliff behind it is left out. Throws InputError
   * naming the key ('@p section/...') for an impossible geometry.
   */
  Block1Scene
  make_block1_seismic_scene(const Block1Geometry  &geometry,
                            const Block1Materials &materials,
                            const std::string     &section = "Calibration");

  /// Slip (m) of the middle of the block's base relative to the base
  /// block, along the bedding plane, positive downslope.
  double
  block1_slip(const dda::DdaSystem &dda, const Block1Scene &scene);

  /// What one DDA run of Block 1 under a record gives.
  struct Block1Run
  {
    /// Slip along the bedding plane at the end (m), + downslope.
    double slip = 0.;
    /// Largest |rotation| of the block (rad) over the run.
    double max_rotation = 0.;
    /// Wall time of the run (s), settling included.
    double wall_time = 0.;
    /// Accepted steps and step cuts.
    unsigned long steps = 0, cuts = 0;
    /// True if Block1RunControls::stop ended the run before @p duration.
    bool stopped = false;
  };

  /**
   * How run_block1_dda() runs DDA and names the keys of its errors. The
   * calibration and the earthquake analyses differ only in these values.
   */
  struct Block1RunControls
  {
    /// Inertial (loading) or displacement mode.
    dda::SeismicInput::Mode mode = dda::SeismicInput::Mode::inertial;
    /// Normal contact penalty (N/m), > 0, and time step (s), > 0.
    double penalty = 1e11, dt = 0.005;
    /// Static settling steps under gravity before t = 0.
    unsigned int settle_steps = 50;
    /// Accepted steps allowed per time step dt on average (room for step
    /// cuts), > 0; DDA stops with DdaFailure beyond them.
    double max_steps_per_dt = 200.;
    /// Wall-time limit of one run (s), checked after every interval dt
    /// (some stick-slip runs creep with ever smaller steps); 0: none.
    double wall_time_limit = 0.;
    /// Polled after every interval dt: true stops the run there with
    /// Block1Run::stopped set (e.g. on SIGINT); empty: never.
    std::function<bool()> stop;
    /// Key names in the errors: the penalty, the time step, and the section
    /// of the geometry keys ('<section>/Block length', ...).
    std::string penalty_key   = "Calibration/Penalties";
    std::string time_step_key = "Calibration/Time steps";
    std::string section       = "Calibration";
  };

  /**
   * Run Block 1 in DDA under the horizontal ground acceleration @p record
   * (g, positive towards +x, i.e. downslope) until @p duration (s) with
   * the controls @p controls, the linear solver on one thread. The scene
   * first settles under gravity. Throws InputError naming the key for a
   * penalty or time step <= 0, dda::DdaFailure if the run cannot continue
   * or the step budget is used up, std::runtime_error when the wall-time
   * limit is reached.
   */
  Block1Run
  run_block1_dda(const Block1Geometry    &geometry,
                 const Block1Materials   &materials,
                 const seismic::Record   &record,
                 const Block1RunControls &controls,
                 const double             duration);

  /// run_block1_dda() with the default controls but @p mode, @p penalty
  /// (N/m), @p dt (s) and @p settle_steps.
  inline Block1Run
  run_block1_dda(const Block1Geometry         &geometry,
                 const Block1Materials        &materials,
                 const seismic::Record        &record,
                 const dda::SeismicInput::Mode mode,
                 const double                  penalty,
                 const double                  dt,
                 const double                  duration,
                 const unsigned int            settle_steps = 50)
  {
    Block1RunControls c;
    c.mode         = mode;
    c.penalty      = penalty;
    c.dt           = dt;
    c.settle_steps = settle_steps;
    return run_block1_dda(geometry, materials, record, c, duration);
  }

  /**
   * The analytical solution for the same input: a rigid block on a plane of
   * dip Block1Geometry::slope_deg with Coulomb friction
   * Block1Materials::friction_deg under the horizontal acceleration
   * @p record, two-way (Newmark 'plane' yield model, Kamai & Hatzor 2008),
   * integrated at @p time_step (s) up to @p duration (s). Returns the slip
   * along the plane (m), + downslope, with the sign convention of
   * run_block1_dda(): a ground acceleration towards +x drives the block
   * upslope (it lags behind, i.e. it feels -a g).
   */
  double
  block1_analytical_slip(const Block1Geometry  &geometry,
                         const Block1Materials &materials,
                         const seismic::Record &record,
                         const double           duration,
                         const double           time_step = 1e-4);

  /// Horizontal yield acceleration (g) of the block towards downslope
  /// (pseudo-static, Goodman & Seed 1966): tan(phi - dip).
  double
  block1_yield_acceleration(const Block1Geometry  &geometry,
                            const Block1Materials &materials);

  /**
   * Horizontal acceleration (g) towards downslope at which the resultant of
   * gravity and the inertial force through the block's centroid passes
   * through its toe (pseudo-static rocking about the toe, rigid block,
   * Shenton 1996): (x_toe - x_c) / (y_c - y_toe). Below
   * block1_yield_acceleration() the block rocks before it slides; Block 1
   * (19 deg, L_B 7 m, H 15 m) has 0.42 g against ky = 0.404 g.
   */
  double
  block1_rocking_acceleration(const Block1Geometry &geometry);

  /// A sinusoid A sin(2 pi f t) (g) from t = 0 to @p duration (s), sampled
  /// at @p dt (s).
  seismic::Record
  sinusoid_record(const double amplitude,
                  const double frequency,
                  const double duration,
                  const double dt);
} // namespace rockdda::coupling

#endif
