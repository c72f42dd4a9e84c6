/**
 * @file
 * The analytical thermal ratchet (wedging) model of Pasten (2012), thesis
 * Chapter 5.4, Eqs. 5.1-5.6 and 5.9: a block on a plane behind a tension
 * crack filled with a wedge of rock fragments. Each seasonal cycle the
 * block, the wedge and the rock mass expand by delta_T; the part not taken
 * up by the elastic compression delta_sigma and the elastic shear of the
 * sliding joint delta_j under the largest force the joint can carry, F_max,
 * is the permanent slip delta_p of that cycle. Theory and assumptions:
 * doc/theory/ratchet.md.
 */
#ifndef ROCKDDA_ANALYTICAL_RATCHET_H
#define ROCKDDA_ANALYTICAL_RATCHET_H

#include <rockdda/analytical/block1.h>

#include <vector>

namespace rockdda::analytical
{
  /**
   * Inputs of the ratchet model, SI units, angles in degrees. The defaults
   * are Masada Block 1 (thesis Table 5-2, Fig. 5-9 with L_B = 7 m and
   * H = 15 m, beta = 0.45, alpha = 8e-6 1/K, wedge 200 mm).
   */
  struct RatchetInput
  {
    /// Length L_B of the sliding block (m), Eqs. 5.3-5.5 (Block1Section).
    double block_length = Block1Section().length;
    /// Height H of the block's front (downslope) face (m), Eqs. 5.3-5.4;
    /// the back face at the tension crack is H - L_B tan(eta) high
    /// (Block1Section).
    double block_height = Block1Section().height;
    /// Length L_W of the wedge in the tension crack (m), Eqs. 5.2, 5.4.
    double wedge_length = 0.2;
    /// Dip eta of the sliding plane (deg).
    double slope_deg = Block1Section().slope_deg;
    /// Friction angle phi of the sliding plane (deg).
    double friction_angle_deg = 41.;
    /// Mass density rho (kg/m^3).
    double density = 2600.;
    /// Gravitational acceleration g (m/s^2); gamma = rho g.
    double gravity = 9.80665;
    /// Young's modulus E of the intact rock (Pa).
    double youngs_modulus = 40e9;
    /// Shear stiffness k_j of the sliding joint (Pa/m).
    double joint_shear_stiffness = 1e9;
    /// Linear thermal expansion coefficient alpha (1/K).
    double thermal_expansion = 8e-6;
    /// Seasonal temperature change Delta T_p, peak to peak (K): twice the
    /// annual amplitude (Table 5-2: 9 K amplitude, 18 K peak to peak).
    double temperature_change = 18.;
    /// Coefficient beta of the non-uniform temperature distribution,
    /// 0 < beta <= 1 (Eq. 5.2).
    double beta = 0.45;
    /// Thermal conductivity lambda (W/(m K)).
    double conductivity = 1.7;
    /// Specific heat capacity c_p (J/(kg K)).
    double heat_capacity = 810.;
    /// Exposure time t_exp of one heating season (s); 180 days.
    double exposure_time = 180. * 86400.;

    /// The block's cross-section (L_B, H, eta) whose area Eq. 5.3 uses.
    Block1Section
    section() const
    {
      return Block1Section{block_length, block_height, slope_deg};
    }

    /// Set L_B, H and eta from @p section.
    void
    set_section(const Block1Section &section)
    {
      block_length = section.length;
      block_height = section.height;
      slope_deg    = section.slope_deg;
    }
  };

  /// Every quantity of Eqs. 5.1-5.6 for one RatchetInput.
  struct RatchetResult
  {
    /// Thermal diffusivity D_T = lambda / (rho c_p) (m^2/s).
    double diffusivity = 0.;
    /// Homogenisation time t* = 2 L_B^2 / D_T (s).
    double homogenisation_time = 0.;
    /// True if t_exp > t*, so that S_d = L_B / 2.
    bool homogenised = false;
    /// Thermal skin depth S_d (m), Eq. 5.1.
    double skin_depth = 0.;
    /// Unconstrained thermal expansion delta_T per cycle (m), Eq. 5.2.
    double thermal_displacement = 0.;
    /// Largest force along the plane the joint can carry, F_max (N per m
    /// of block width), Eq. 5.3.
    double max_force = 0.;
    /// Elastic compression delta_sigma of wedge and block (m), Eq. 5.4.
    double elastic_displacement = 0.;
    /// Elastic shear displacement delta_j of the joint (m), Eq. 5.5.
    double joint_displacement = 0.;
    /// delta_T - delta_sigma - delta_j (m): negative means no ratchet.
    double excess = 0.;
    /// Permanent (plastic) displacement delta_p per cycle (m), Eq. 5.6.
    double plastic_displacement = 0.;
  };

  /**
   * Check @p input: every length, modulus, stiffness and thermal property
   * > 0, alpha >= 0, Delta T_p >= 0, 0 < beta <= 1, 0 <= slope < friction
   * < 90 deg (otherwise the block is not stable without the crack, F_max
   * <= 0) and H > L_B tan(eta) / 2 (the cross-section of Eq. 5.3 has a
   * positive area). Throws InputError naming the key of the
   * "Ratchet analytical" section and its valid range.
   */
  void
  validate(const RatchetInput &input);

  /// Thermal diffusivity D_T = lambda / (rho c_p) (m^2/s).
  double
  thermal_diffusivity(const double conductivity,
                      const double density,
                      const double heat_capacity);

  /// Homogenisation time t* = 2 L^2 / D_T (s) of a slab of length @p length.
  double
  homogenisation_time(const double length, const double diffusivity);

  /**
   * Thermal skin depth S_d of Eq. 5.1: sqrt(D_T t_exp / 2) if
   * t_exp <= t* = 2 L^2 / D_T, and L / 2 (the slab is homogenised) if
   * t_exp > t*. An infinite @p slab_length gives the half-space value.
   */
  double
  skin_depth(const double diffusivity,
             const double exposure_time,
             const double slab_length);

  /// Unconstrained expansion delta_T = alpha Delta T_p (L_W + 2 beta S_d)
  /// per cycle (m), Eq. 5.2.
  double
  thermal_displacement(const double alpha,
                       const double temperature_change,
                       const double wedge_length,
                       const double beta,
                       const double skin_depth);

  /**
   * F_max = gamma L_B (H - L_B tan(eta) / 2) (tan(phi) cos(eta) - sin(eta))
   * (N per m of width), Eq. 5.3: the frictional resistance of the plane
   * less the down-slope weight component of the block of cross-section
   * Block1Section::area() = L_B (H - L_B tan(eta) / 2), H the front face.
   * Negative if eta > phi.
   */
  double
  max_force(const double unit_weight,
            const double block_length,
            const double block_height,
            const double slope_deg,
            const double friction_angle_deg);

  /// delta_sigma = F_max cos(eta) (L_W + L_B / 2) / (H E) (m), Eq. 5.4.
  double
  elastic_displacement(const double max_force,
                       const double slope_deg,
                       const double block_height,
                       const double youngs_modulus,
                       const double wedge_length,
                       const double block_length);

  /// delta_j = F_max cos(eta) / (k_j L_B) (m), Eq. 5.5.
  double
  joint_displacement(const double max_force,
                     const double slope_deg,
                     const double joint_shear_stiffness,
                     const double block_length);

  /// delta_p = max(delta_T - delta_sigma - delta_j, 0) (m), Eq. 5.6.
  double
  plastic_displacement(const double thermal_displacement,
                       const double elastic_displacement,
                       const double joint_displacement);

  /**
   * Thermal expansion coefficient from a field cycle without ratchet,
   * Eq. 5.9: alpha = dL / ((L_B / 2 + beta S_d) dT) (1/K), for joint
   * displacement @p joint_displacement (m) over temperature change
   * @p temperature_change (K) across a block of length @p block_length (m).
   * Throws InputError unless dL >= 0, dT > 0, L_B > 0, 0 < beta <= 1 and
   * S_d > 0.
   */
  double
  thermal_expansion_from_field_cycle(const double joint_displacement,
                                     const double temperature_change,
                                     const double block_length,
                                     const double beta,
                                     const double skin_depth);

  /// Eqs. 5.1-5.6 for @p input (validated first).
  RatchetResult
  ratchet(const RatchetInput &input);

  /**
   * The peak-to-peak temperature change (K) below which delta_p = 0:
   * Delta T_p* = (delta_sigma + delta_j) / (alpha (L_W + 2 beta S_d)),
   * closed form; +infinity if alpha = 0.
   */
  double
  threshold_temperature_change(const RatchetInput &input);

  /**
   * The friction angle (deg) above which delta_p = 0: delta_T =
   * delta_sigma + delta_j solved for phi in closed form,
   * tan(phi*) = (sin(eta) + delta_T / (W C cos(eta))) / cos(eta) with
   * W = gamma L_B (H - L_B tan(eta) / 2) and
   * C = (L_W + L_B / 2) / (H E) + 1 / (k_j L_B). Equals eta if
   * delta_T = 0. The friction angle of @p input is not used.
   */
  double
  threshold_friction_angle(const RatchetInput &input);

  /**
   * The model for @p base with the member @p parameter (e.g.
   * &RatchetInput::beta) set to each of @p values in turn.
   */
  std::vector<RatchetResult>
  ratchet_sweep(const RatchetInput &base,
                double RatchetInput::     *parameter,
                const std::vector<double> &values);
} // namespace rockdda::analytical

#endif
