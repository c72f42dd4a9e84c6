/**
 * @file
 * Flexible sliding mass (Rathje & Bray 2000): the first-mode response of a
 * 1D shear beam (linear-elastic or equivalent-linear site response) and the
 * decoupled and coupled sliding-block analyses, with the conventions of USGS
 * SLAMMER (Jibson, Rathje, Jibson & Lee 2013, Techniques and Methods 12-B1).
 *
 * See doc/theory/flexible-sliding.md for the equations, the conventions and
 * the verification against SLAMMER.
 */
#ifndef ROCKDDA_SEISMIC_FLEXIBLE_SLIDING_H
#define ROCKDDA_SEISMIC_FLEXIBLE_SLIDING_H

#include <rockdda/seismic/record.h>

#include <vector>

namespace rockdda::seismic
{
  /**
   * The sliding mass as a uniform shear beam of height H and shear-wave
   * velocity Vs on a base of shear-wave velocity Vr, represented by its
   * first mode (period 4H/Vs). SI units; damping ratios and strains are
   * fractions.
   */
  struct SiteResponseOptions
  {
    /// How the properties of the sliding mass are obtained.
    enum class Model
    {
      /// Vs and damping as given (plus the base-impedance damping).
      linear_elastic,
      /// Strain-compatible Vs and damping from a hyperbolic modulus
      /// reduction curve and the Darendeli (2001) damping curve, iterated
      /// on the effective strain of the first mode (as SLAMMER).
      equivalent_linear
    };

    Model model = Model::linear_elastic;
    /// Height H of the sliding mass (m), > 0.
    double height = 10.;
    /// Shear-wave velocity of the sliding mass (m/s), > 0 (small-strain
    /// value for the equivalent-linear model).
    double vs_slope = 300.;
    /// Shear-wave velocity of the base (m/s), > 0.
    double vs_base = 600.;
    /// Damping ratio of the sliding mass (-), in [-1, 1]; the base-impedance
    /// damping is added to it. Equivalent-linear: used in the first
    /// iteration only, then replaced by the strain-compatible soil damping.
    /// SLAMMER accepts a negative value; the total must stay >= 0.
    double damping = 0.05;
    /// Reference shear strain gamma_r of the modulus reduction curve
    /// G/Gmax = 1 / (1 + gamma / gamma_r) (-), > 0 (5e-4 = 0.05 %).
    double reference_strain = 5e-4;
    /// Equivalent-linear: iterate until the relative changes of G and of the
    /// soil damping between iterations are both <= this (-), > 0.
    double tolerance = 0.05;
    /// Equivalent-linear: most site-response iterations, >= 1.
    unsigned int max_iterations = 100;
    /// Integration steps per sample of the record, >= 1 (1 = SLAMMER).
    /// With more, the record is interpolated linearly and every history is
    /// given at the sub-steps. Use it for a stiff mass (period 4H/Vs below
    /// about ten samples): the schemes then converge to the rigid block.
    unsigned int substeps = 1;
    /// Gravitational acceleration (m/s^2), > 0.
    double g = 9.80665;
  };

  /// Result of a site-response analysis: final properties and the history
  /// of the average acceleration k(t) of the sliding mass.
  struct SiteResponse
  {
    /// Final (strain-compatible for equivalent-linear) Vs of the mass (m/s).
    double vs = 0.;
    /// Final total damping ratio (-): base-impedance plus soil damping.
    double damping = 0.;
    /// Base-impedance part of the damping ratio (-).
    double base_damping = 0.;
    /// Fundamental period 4H/Vs with the final Vs (s).
    double period = 0.;
    /// Effective shear strain 0.65 gamma_max of the last iteration (-);
    /// 0 for linear-elastic.
    double effective_strain = 0.;
    /// Signed peak of k(t) (g): the larger of max k and -min k in magnitude.
    double kmax = 0.;
    /// Number of equivalent-linear iterations (0 for linear-elastic).
    unsigned int iterations = 0;
    /// False if the equivalent-linear iteration hit max_iterations.
    bool converged = true;
    /// The options the response was computed with.
    SiteResponseOptions options;
    /// Integration time step: the record's dt / substeps (s).
    double dt = 0.;
    /// Average (horizontal, downslope-positive) acceleration of the sliding
    /// mass at each integration step (g), the first at t = 0.
    std::vector<double> k;
  };

  /**
   * First-mode response of the sliding mass to the base acceleration
   * @p input (g), from rest, the ground at rest before the first sample.
   * Throws InputError for invalid options (see validate()) or an empty
   * record, std::runtime_error for a non-finite response.
   */
  SiteResponse
  site_response(const Record &input, const SiteResponseOptions &options);

  /**
   * Check @p options; throws InputError naming the quantity and its valid
   * range.
   */
  void
  validate(const SiteResponseOptions &options);

  /// Options of a flexible sliding-mass analysis (downslope sliding only,
  /// constant yield acceleration).
  struct FlexibleSlidingOptions
  {
    /// How sliding and the dynamic response interact.
    enum class Coupling
    {
      /// The rigid-block analysis of k(t) (Makdisi & Seed 1978).
      decoupled,
      /// Sliding limits the base force of the deforming mass (Rathje &
      /// Bray 2000).
      coupled
    };

    Coupling coupling = Coupling::decoupled;
    /// Yield acceleration ky (g), >= 0.
    double ky = 0.1;
    /// The sliding mass.
    SiteResponseOptions site;
  };

  /// History and summary of a flexible sliding-mass analysis.
  struct FlexibleSlidingResult
  {
    /// Site response (properties and k(t)).
    SiteResponse site;
    /// Times of the integration steps (s).
    std::vector<double> time;
    /// Driving acceleration of the sliding interface (g): k(t) for the
    /// decoupled analysis, the base force per unit weight the mass would
    /// need to follow the ground for the coupled one.
    std::vector<double> driving;
    /// Sliding velocity (m/s), + downslope.
    std::vector<double> velocity;
    /// Sliding displacement (m), + downslope.
    std::vector<double> displacement;
    /// 1 sliding, 0 stuck.
    std::vector<int> state;
    /// Displacement at the end of the record (m).
    double final_displacement = 0.;
    /// Largest sliding velocity (m/s).
    double max_velocity = 0.;
    /// Number of times sliding started.
    unsigned int n_slip_events = 0;
    /// Time spent sliding (s).
    double sliding_duration = 0.;
  };

  /**
   * Permanent downslope displacement of a flexible sliding mass under the
   * base acceleration @p input (g, positive drives the mass downslope;
   * multiply the record by -1 for the inverse polarity). The site response
   * is computed first (equivalent-linear properties come from the response
   * without sliding, as SLAMMER does). Throws InputError for invalid options.
   */
  FlexibleSlidingResult
  flexible_sliding(const Record &input, const FlexibleSlidingOptions &options);

  /**
   * As flexible_sliding(), with the site response @p site of the same
   * @p input already computed (it fixes Vs, damping and, for the decoupled
   * analysis, k(t)); only options.coupling and options.ky are read.
   */
  FlexibleSlidingResult
  flexible_sliding(const Record                 &input,
                   const SiteResponse           &site,
                   const FlexibleSlidingOptions &options);

  /**
   * The site response of the record multiplied by -1, from that of the
   * record: k(t) changes sign, the properties do not (the response is
   * linear and the equivalent-linear strain depends on |u| only).
   */
  SiteResponse
  inverted(const SiteResponse &site);
} // namespace rockdda::seismic

#endif
