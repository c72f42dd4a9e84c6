/**
 * @file
 * Trace generators: Shi & Goodman statistical joint sets and the
 * mechanically layered network (beds with confined joints, FSI).
 */
#ifndef ROCKDDA_STRUCTURE_GENERATORS_H
#define ROCKDDA_STRUCTURE_GENERATORS_H

#include <rockdda/structure/block_set.h>

#include <random>
#include <vector>

namespace rockdda::structure
{
  /// The random number engine of every generator (reproducible by seed).
  using Random = std::mt19937_64;

  /**
   * One statistical joint set after Shi & Goodman (1989): parallel scan
   * lines at spacing s, on each line joints of length L separated by rock
   * bridges b. Each of s, L and b is drawn independently and uniformly from
   * [mean (1 - DR), mean (1 + DR)], so its mean is exact and it never
   * deviates by more than DR x mean.
   */
  struct JointSetParameters
  {
    double dip                  = 90.;  ///< deg, counter-clockwise from +x
    double mean_length          = 5.;   ///< L, m
    double mean_bridge          = 1.;   ///< b, m
    double mean_spacing         = 0.54; ///< s, m
    double degree_of_randomness = 0.5;  ///< DR in [0, 1]

    /// Throw InputError (naming @p where) for invalid values.
    void
    check(const std::string &where) const;
  };

  /**
   * Traces of one joint set covering the bounding box @p box (xmin, ymin,
   * xmax, ymax) of the domain, tagged (joint, @p set). The first line lies
   * at a uniformly random offset in [0, s) below the box's extent along the
   * set normal, and each line's joint-bridge sequence starts at a uniformly
   * random phase in [0, L + b) before the box, so the pattern is stationary.
   * Traces are not clipped (the cutter discards what lies outside).
   * If @p lines is given it receives, per line, the indices of its traces
   * in order (for statistics of L, b and s).
   */
  std::vector<TaggedSegment>
  generate_joint_set(const JointSetParameters              &set,
                     const int                              set_index,
                     const Eigen::Vector4d                 &box,
                     Random                                &random,
                     std::vector<std::vector<std::size_t>> *lines = nullptr);

  /**
   * A mechanically layered rock mass. Bed thickness t follows a lognormal
   * law truncated below at t_min (drawn again while below): the untruncated
   * law has arithmetic mean 10^log10_mean m and arithmetic standard
   * deviation 10^log10_deviation m (how we read the thesis's "log[mean(m)]
   * = 0, log[deviation(m)] = -0.2", i.e. 1 m and 0.631 m, in FRACMAN's
   * convention), so ln t ~ N(mu, sigma) with sigma^2 = ln(1 + d^2/m^2) and
   * mu = ln m - sigma^2 / 2.
   *
   * Joints in each bed of thickness t are confined to the bed (from one
   * bedding plane to the next, overshooting each by 1e-6 t so that they
   * surely cut; the overshoot is dangling and removed by the cutter). Their
   * positions along the bed form a renewal process: the spacings are
   * i.i.d. lognormal with median t / FSI and log-standard deviation
   * spacing_log_deviation (0 gives regular spacing), the first joint at a
   * uniformly random fraction of a spacing before the domain.
   */
  struct LayeredParameters
  {
    double bedding_dip           = 0.;   ///< deg, counter-clockwise from +x
    double log10_mean            = 0.;   ///< log10 of the mean, log10(m)
    double log10_deviation       = -0.2; ///< log10 of the deviation
    double min_thickness         = 0.7;  ///< m
    bool   confined_joints       = true;
    double fsi                   = 1.3;  ///< bed thickness / median spacing
    double joint_dip             = 90.;  ///< deg, counter-clockwise from +x
    double spacing_log_deviation = 0.25; ///< natural-log deviation, -

    /**
     * 3D option (FRACMAN-like, thesis Sec. 3.2): instead of the renewal
     * process along the section, each bed holds rectangular fractures
     * normal to the bedding and spanning the bed, with horizontal length
     * uniform in [0.5, 1.5] x fracture_length, strike uniform in
     * fracture_strike +- strike_spread, and centres a Poisson process in
     * the bed plane. The vertical trace plane at section_azimuth (the
     * section's x axis) cuts them into traces. The intensity is chosen so
     * that the median trace spacing along the section is thickness / FSI
     * (crossings of a Poisson field of segments form a Poisson process on
     * the line, rate lambda E[l |sin(strike - azimuth)|], median spacing
     * ln 2 / rate).
     */
    bool   three_d         = false;
    double fracture_length = 5.;  ///< m
    double fracture_strike = 90.; ///< deg, from the section's x axis
    double strike_spread   = 0.;  ///< deg
    double section_azimuth = 0.;  ///< deg

    /// Throw InputError (naming @p where) for invalid values.
    void
    check(const std::string &where) const;

    /// mu and sigma of ln t (untruncated).
    std::pair<double, double>
    log_parameters() const;
  };

  /// The beds and confined joints of a layered network.
  struct LayeredNetwork
  {
    std::vector<double>        bedding_offsets; ///< along the normal, m
    std::vector<double>        thicknesses;     ///< of each bed, m
    std::vector<TaggedSegment> bedding;         ///< tagged bedding
    std::vector<TaggedSegment> joints;          ///< tagged (joint, set)
    /// Per bed, positions (m along the bedding) of its joints, sorted.
    std::vector<std::vector<double>> joint_positions;
  };

  /**
   * Beds covering the domain's bounding box @p box (throws InputError if
   * the minimum thickness exceeds the box's extent across the beds) with,
   * if enabled, joints of set @p joint_set confined to each bed.
   */
  LayeredNetwork
  generate_layered(const LayeredParameters &p,
                   const int                joint_set,
                   const Eigen::Vector4d   &box,
                   Random                  &random);

  /**
   * 3D option: positions (m along the section, sorted, within [a_min,
   * a_max]) where the fractures of one bed of @p thickness cross the trace
   * plane (see LayeredParameters::three_d).
   */
  std::vector<double>
  section_crossings(const LayeredParameters &p,
                    const double             thickness,
                    const double             a_min,
                    const double             a_max,
                    Random                  &random);

  /// Draw one bed thickness (m) from the truncated lognormal law.
  double
  draw_thickness(const LayeredParameters &p, Random &random);
} // namespace rockdda::structure

#endif
