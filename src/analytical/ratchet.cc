#include <rockdda/analytical/ratchet.h>
#include <rockdda/io/error.h>

#include <cmath>
#include <limits>
#include <sstream>
#include <string>

namespace rockdda::analytical
{
  namespace
  {
    constexpr double degree = M_PI / 180.;

    /// The key of the "Ratchet analytical" section named @p key.
    std::string
    key_of(const std::string &key)
    {
      return "Ratchet analytical/" + key;
    }

    /// A number as text, 6 significant digits.
    std::string
    to_text(const double value)
    {
      std::ostringstream s;
      s.precision(6);
      s << value;
      return s.str();
    }
  } // namespace



  void
  validate(const RatchetInput &in)
  {
    const auto positive =
      [](const std::string &key, const double value, const std::string &unit) {
        require_in_range(value > 0., key_of(key), value, "> 0 " + unit);
      };
    positive("Block length", in.block_length, "m");
    positive("Block height", in.block_height, "m");
    require_in_range(in.wedge_length >= 0.,
                     key_of("Wedge length"),
                     in.wedge_length,
                     ">= 0 m");
    positive("Density", in.density, "kg/m^3");
    positive("Gravity", in.gravity, "m/s^2");
    positive("Young's modulus", in.youngs_modulus, "Pa");
    positive("Joint shear stiffness", in.joint_shear_stiffness, "Pa/m");
    require_in_range(in.thermal_expansion >= 0.,
                     key_of("Thermal expansion coefficient"),
                     in.thermal_expansion,
                     "alpha >= 0 1/K");
    require_in_range(in.temperature_change >= 0.,
                     key_of("Temperature amplitude"),
                     0.5 * in.temperature_change,
                     ">= 0 K (Delta T_p = 2 x amplitude >= 0 K)");
    require_in_range(in.beta > 0. && in.beta <= 1.,
                     key_of("Beta"),
                     in.beta,
                     "0 < beta <= 1");
    positive("Thermal conductivity", in.conductivity, "W/(m K)");
    positive("Specific heat capacity", in.heat_capacity, "J/(kg K)");
    positive("Exposure time", in.exposure_time, "s");
    require_in_range(in.friction_angle_deg >= 0. && in.friction_angle_deg < 90.,
                     key_of("Friction angle"),
                     in.friction_angle_deg,
                     "0 <= phi < 90 deg");
    require_in_range(in.slope_deg >= 0. && in.slope_deg < 90.,
                     key_of("Slope"),
                     in.slope_deg,
                     "0 <= eta < 90 deg");
    if (!(in.slope_deg < in.friction_angle_deg))
      throw InputError(
        "key '" + key_of("Slope") + "' = " + to_text(in.slope_deg)
        + " deg is out of range; valid: 0 <= slope < friction angle ("
        + to_text(in.friction_angle_deg)
        + " deg): with slope >= friction the block is not stable without the "
          "crack (F_max = "
        + to_text(max_force(in.density * in.gravity,
                            in.block_length,
                            in.block_height,
                            in.slope_deg,
                            in.friction_angle_deg))
        + " N/m <= 0) and the ratchet model does not apply");
    const double min_height
      = 0.5 * in.block_length * std::tan(in.slope_deg * degree);
    if (!(in.block_height > min_height))
      throw InputError("key '" + key_of("Block height")
                       + "' = " + to_text(in.block_height)
                       + " m is out of range; valid: H > L_B tan(slope) / 2 = "
                       + to_text(min_height)
                       + " m (the cross-section of Eq. 5.3 must have a "
                         "positive area)");
  }



  double
  thermal_diffusivity(const double conductivity,
                      const double density,
                      const double heat_capacity)
  {
    return conductivity / (density * heat_capacity);
  }



  double
  homogenisation_time(const double length, const double diffusivity)
  {
    return 2. * length * length / diffusivity;
  }



  double
  skin_depth(const double diffusivity,
             const double exposure_time,
             const double slab_length)
  {
    if (std::isfinite(slab_length)
        && exposure_time > homogenisation_time(slab_length, diffusivity))
      return 0.5 * slab_length;
    return std::sqrt(0.5 * diffusivity * exposure_time);
  }



  double
  thermal_displacement(const double alpha,
                       const double temperature_change,
                       const double wedge_length,
                       const double beta,
                       const double skin_depth)
  {
    return alpha * temperature_change * (wedge_length + 2. * beta * skin_depth);
  }



  double
  max_force(const double unit_weight,
            const double block_length,
            const double block_height,
            const double slope_deg,
            const double friction_angle_deg)
  {
    const double eta = slope_deg * degree, phi = friction_angle_deg * degree;
    return unit_weight
           * Block1Section{block_length, block_height, slope_deg}.area()
           * (std::tan(phi) * std::cos(eta) - std::sin(eta));
  }



  double
  elastic_displacement(const double max_force,
                       const double slope_deg,
                       const double block_height,
                       const double youngs_modulus,
                       const double wedge_length,
                       const double block_length)
  {
    return max_force * std::cos(slope_deg * degree)
           / (block_height * youngs_modulus)
           * (wedge_length + 0.5 * block_length);
  }



  double
  joint_displacement(const double max_force,
                     const double slope_deg,
                     const double joint_shear_stiffness,
                     const double block_length)
  {
    return max_force * std::cos(slope_deg * degree)
           / (joint_shear_stiffness * block_length);
  }



  double
  plastic_displacement(const double thermal_displacement,
                       const double elastic_displacement,
                       const double joint_displacement)
  {
    const double excess
      = thermal_displacement - elastic_displacement - joint_displacement;
    return excess > 0. ? excess : 0.;
  }



  double
  thermal_expansion_from_field_cycle(const double joint_displacement,
                                     const double temperature_change,
                                     const double block_length,
                                     const double beta,
                                     const double skin_depth)
  {
    const std::string section = "Ratchet analytical/Field cycle/";
    require_in_range(joint_displacement >= 0.,
                     section + "Joint displacement",
                     joint_displacement,
                     ">= 0 m");
    require_in_range(temperature_change > 0.,
                     section + "Temperature change",
                     temperature_change,
                     "> 0 K");
    require_in_range(block_length > 0.,
                     section + "Block length",
                     block_length,
                     "> 0 m");
    require_in_range(beta > 0. && beta <= 1.,
                     "Ratchet analytical/Beta",
                     beta,
                     "0 < beta <= 1");
    require_in_range(skin_depth > 0.,
                     section + "Skin depth",
                     skin_depth,
                     "> 0 m");
    return joint_displacement
           / ((0.5 * block_length + beta * skin_depth) * temperature_change);
  }



  RatchetResult
  ratchet(const RatchetInput &in)
  {
    validate(in);
    RatchetResult r;
    r.diffusivity
      = thermal_diffusivity(in.conductivity, in.density, in.heat_capacity);
    r.homogenisation_time = homogenisation_time(in.block_length, r.diffusivity);
    r.homogenised         = in.exposure_time > r.homogenisation_time;
    r.skin_depth = skin_depth(r.diffusivity, in.exposure_time, in.block_length);
    r.thermal_displacement = thermal_displacement(in.thermal_expansion,
                                                  in.temperature_change,
                                                  in.wedge_length,
                                                  in.beta,
                                                  r.skin_depth);
    r.max_force            = max_force(in.density * in.gravity,
                            in.block_length,
                            in.block_height,
                            in.slope_deg,
                            in.friction_angle_deg);
    r.elastic_displacement = elastic_displacement(r.max_force,
                                                  in.slope_deg,
                                                  in.block_height,
                                                  in.youngs_modulus,
                                                  in.wedge_length,
                                                  in.block_length);
    r.joint_displacement   = joint_displacement(r.max_force,
                                              in.slope_deg,
                                              in.joint_shear_stiffness,
                                              in.block_length);
    r.excess
      = r.thermal_displacement - r.elastic_displacement - r.joint_displacement;
    r.plastic_displacement = plastic_displacement(r.thermal_displacement,
                                                  r.elastic_displacement,
                                                  r.joint_displacement);
    return r;
  }



  double
  threshold_temperature_change(const RatchetInput &input)
  {
    const RatchetResult r = ratchet(input);
    // delta_T is linear in Delta T_p; delta_sigma and delta_j do not
    // depend on it.
    const double per_kelvin = thermal_displacement(input.thermal_expansion,
                                                   1.,
                                                   input.wedge_length,
                                                   input.beta,
                                                   r.skin_depth);
    if (!(per_kelvin > 0.))
      return std::numeric_limits<double>::infinity();
    return (r.elastic_displacement + r.joint_displacement) / per_kelvin;
  }



  double
  threshold_friction_angle(const RatchetInput &input)
  {
    const RatchetResult r   = ratchet(input);
    const double        eta = input.slope_deg * degree;
    // delta_sigma + delta_j = F_max cos(eta) C, F_max = W (tan(phi) cos(eta)
    // - sin(eta)); delta_T does not depend on phi.
    const double weight
      = input.density * input.gravity * input.section().area();
    const double compliance
      = (input.wedge_length + 0.5 * input.block_length)
          / (input.block_height * input.youngs_modulus)
        + 1. / (input.joint_shear_stiffness * input.block_length);
    const double tan_phi
      = (std::sin(eta)
         + r.thermal_displacement / (weight * compliance * std::cos(eta)))
        / std::cos(eta);
    return std::atan(tan_phi) / degree;
  }



  std::vector<RatchetResult>
  ratchet_sweep(const RatchetInput &base,
                double RatchetInput::     *parameter,
                const std::vector<double> &values)
  {
    std::vector<RatchetResult> results;
    results.reserve(values.size());
    RatchetInput input = base;
    for (const double v : values)
      {
        input.*parameter = v;
        results.push_back(ratchet(input));
      }
    return results;
  }
} // namespace rockdda::analytical
