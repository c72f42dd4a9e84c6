/**
 * @file
 * Flexible sliding mass: first-mode site response (linear-elastic and
 * equivalent-linear) and the decoupled and coupled sliding analyses of
 * Rathje & Bray (2000), with the numerical conventions of USGS SLAMMER
 * (Jibson, Rathje, Jibson & Lee 2013). Theory: doc/theory/flexible-sliding.md.
 */
#include <rockdda/io/error.h>
#include <rockdda/seismic/flexible_sliding.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>
#include <stdexcept>
#include <string>

namespace rockdda::seismic
{
  namespace
  {
    /// A number as text for messages.
    std::string
    to_text(const double x)
    {
      std::ostringstream out;
      out << x;
      return out.str();
    }

    /// Modal participation factor L/M of the first mode phi = sin(pi y/2H)
    /// of a uniform shear beam (y up from the base): (2 rho H/pi)/(rho H/2).
    constexpr double participation = 4. / M_PI;
    /// Average of phi over the height, L/(rho H): the average relative
    /// acceleration of the mass is this times the modal acceleration.
    constexpr double mean_shape = 2. / M_PI;
    /// Modal mass factor while the mass slides, 1 - L^2/(M M_total)
    /// (Rathje & Bray 2000).
    constexpr double sliding_mass = 1. - 8. / (M_PI * M_PI);
    /// Effective strain from the modal displacement u: 0.65 gamma_max with
    /// gamma_max = (pi/2) u / H at the base; SLAMMER takes pi/2 as 1.57.
    constexpr double strain_factor = 0.65 * 1.57;

    /// Base-impedance (radiation) damping ratio (-) for a mass of shear-wave
    /// velocity vs on a base of vs_base (Rathje & Bray 2000, as SLAMMER):
    /// 0.55016 (Vr/Vs)^-0.9904, at most 0.20.
    double
    impedance_damping(const double vs_base, const double vs)
    {
      return std::min(0.20, 0.55016 * std::pow(vs_base / vs, -0.9904));
    }

    /// Masing damping (-) of the hyperbolic stress-strain curve
    /// G/Gmax = 1/(1 + x) at x = gamma/gamma_r (Darendeli 2001):
    /// (1/pi) [4 (x - ln(1 + x)) (1 + x) / x^2 - 2]; a series for small x.
    double
    masing_damping(const double x)
    {
      if (x < 1e-4)
        return (2. / 3. * x - x * x / 3.) / M_PI;
      return (4. * (x - std::log1p(x)) * (1. + x) / (x * x) - 2.) / M_PI;
    }

    /// Soil damping ratio (-) at x = gamma/gamma_r (Darendeli 2001 with
    /// b = 0.62, exponent 0.1 and a small-strain damping of 1 %, as SLAMMER).
    double
    soil_damping(const double x)
    {
      const double modulus_ratio = 1. / (1. + x);
      return 0.62 * std::pow(modulus_ratio, 0.1) * masing_damping(x) + 0.01;
    }

    /// State of the first-mode oscillator: modal displacement (m), velocity
    /// (m/s) and acceleration (m/s^2).
    struct ModalState
    {
      double u = 0., v = 0., a = 0.;
    };

    /**
     * One step of the incremental average-acceleration Newmark method
     * (beta = 1/4, gamma = 1/2; Chopra 2012, Table 5.4.2) for
     * m u'' + c u' + k u = -(L/M) b, from base accelerations b1 to b2
     * (m/s^2). The increments of u and u' come from the incremental form
     * (which assumes equilibrium at the start of the step); the acceleration
     * at the end is then taken from equilibrium with mass factor m, as
     * SLAMMER does, so that a change of m or of the load at the start or
     * end of sliding enters as it does there.
     */
    void
    newmark_step(ModalState  &s,
                 const double dt,
                 const double m,
                 const double c,
                 const double k,
                 const double b1,
                 const double b2)
    {
      const double k_hat = k + 2. * c / dt + 4. * m / (dt * dt);
      const double dp    = -participation * (b2 - b1)
                        + (4. * m / dt + 2. * c) * s.v + 2. * m * s.a;
      const double du = dp / k_hat;
      const double dv = 2. * du / dt - 2. * s.v;
      s.u += du;
      s.v += dv;
      s.a = (-participation * b2 - c * s.v - k * s.u) / m;
    }

    /// Linear first-mode response to the base acceleration x (m/s^2), from
    /// rest with zero acceleration before the first sample; stores the
    /// average acceleration of the mass (g) in k_out (if not null) and
    /// returns max |u| (m).
    double
    linear_response(const std::vector<double> &x,
                    const double               dt,
                    const double               omega,
                    const double               damping,
                    const double               g,
                    std::vector<double>       *k_out)
    {
      const double c = 2. * damping * omega, k = omega * omega;
      ModalState   s;
      double       u_max = 0.;
      if (k_out)
        k_out->resize(x.size());
      for (std::size_t j = 0; j < x.size(); ++j)
        {
          newmark_step(s, dt, 1., c, k, j == 0 ? 0. : x[j - 1], x[j]);
          u_max = std::max(u_max, std::abs(s.u));
          if (k_out)
            (*k_out)[j] = (x[j] + mean_shape * s.a) / g;
        }
      if (!std::isfinite(u_max))
        throw std::runtime_error("site response: the modal response is not "
                                 "finite (check Vs, height and damping)");
      return u_max;
    }

    /// Signed peak: the larger in magnitude of max and min (max wins ties).
    double
    signed_peak(const std::vector<double> &k)
    {
      if (k.empty())
        return 0.;
      const auto [lo, hi] = std::minmax_element(k.begin(), k.end());
      return std::abs(*hi) >= std::abs(*lo) ? *hi : *lo;
    }

    /// Input acceleration in m/s^2 at the integration steps: the samples,
    /// or @p substeps steps per sample with linear interpolation.
    std::vector<double>
    to_si(const Record &input, const double g, const unsigned int substeps)
    {
      const auto         &a = input.acceleration;
      std::vector<double> x;
      x.reserve((a.size() - 1) * substeps + 1);
      for (std::size_t i = 0; i + 1 < a.size(); ++i)
        for (unsigned int q = 0; q < substeps; ++q)
          x.push_back(g * (a[i] + (a[i + 1] - a[i]) * q / substeps));
      x.push_back(g * a.back());
      return x;
    }



    /// Decoupled analysis: rigid-block sliding on k(t), downslope only,
    /// with SLAMMER's discretization (Jibson et al. 2013): sliding starts at
    /// the first sample with k > ky and is integrated from there with the
    /// relative acceleration linear across each step; a step at whose end
    /// the velocity is <= 0 ends the sliding and contributes no
    /// displacement.
    void
    decoupled(const SiteResponse    &site,
              const double           ky,
              FlexibleSlidingResult &r)
    {
      const double g = site.options.g, dt = site.dt;
      const auto  &k = site.k;
      double       v = 0., s = 0.;
      bool         sliding = false;
      for (std::size_t j = 0; j < k.size(); ++j)
        {
          bool stopped = false;
          if (j > 0 && sliding)
            {
              const double r0 = g * (k[j - 1] - ky), r1 = g * (k[j] - ky);
              const double v1 = v + 0.5 * dt * (r0 + r1);
              if (v1 <= 0.)
                {
                  sliding = false;
                  stopped = true;
                  v       = 0.;
                }
              else
                {
                  s += dt * (v + dt * (2. * r0 + r1) / 6.);
                  v = v1;
                  r.sliding_duration += dt;
                }
            }
          if (!sliding && !stopped && k[j] > ky)
            {
              sliding = true;
              ++r.n_slip_events;
            }
          r.driving[j]      = k[j];
          r.velocity[j]     = v;
          r.displacement[j] = s;
          r.state[j]        = sliding ? 1 : 0;
          r.max_velocity    = std::max(r.max_velocity, v);
        }
      r.final_displacement = s;
    }



    /**
     * Coupled analysis (Rathje & Bray 2000): while the mass sticks, the
     * first mode is driven by the ground acceleration; while it slides, the
     * base force is limited to ky times the weight, the modal mass factor
     * drops to 1 - L^2/(M M_total) and the mode is driven by the constant
     * base acceleration ky g. The discretization is SLAMMER's: sliding
     * starts at the sample where the base force per unit mass,
     * a_g + (2/pi) u'', first exceeds ky g, with zero sliding acceleration;
     * the load increment of the first sliding step is zero; the sliding
     * acceleration is integrated with the trapezoidal rule; when the
     * sliding velocity becomes <= 0 within a step, the end of sliding is
     * placed where it crosses zero (linear velocity), and the mode is
     * carried from the end of that step over the remaining part of it with
     * the sticking mass and the ground acceleration.
     */
    void
    coupled(const std::vector<double> &x,
            const SiteResponse        &site,
            const double               ky,
            FlexibleSlidingResult     &r)
    {
      const double g = site.options.g, dt = site.dt;
      const double omega = M_PI * site.vs / (2. * site.options.height);
      const double c = 2. * site.damping * omega, k = omega * omega;
      const double yield = ky * g;

      ModalState mode;
      bool       sliding = false;
      double     s = 0., v = 0., a = 0.; // sliding state at the step start
      for (std::size_t j = 0; j < x.size(); ++j)
        {
          const double x1 = j == 0 ? 0. : x[j - 1], x2 = x[j];
          if (sliding)
            newmark_step(mode, dt, sliding_mass, c, k, yield, yield);
          else
            newmark_step(mode, dt, 1., c, k, x1, x2);
          const double drive = x2 + mean_shape * mode.a;

          double s2 = s, v2 = v, a2 = a;
          if (sliding)
            {
              a2 = drive - yield;
              v2 = v + 0.5 * dt * (a2 + a);
              s2 = s + 0.5 * dt * (v2 + v);
              r.sliding_duration += dt;
            }

          if (!sliding)
            {
              if (drive > yield)
                {
                  sliding = true;
                  ++r.n_slip_events;
                }
            }
          else if (v2 <= 0.)
            {
              const double fraction = (v2 == v) ? 0. : v / (v - v2);
              if (!(fraction > 0.))
                {
                  // Sliding started at the beginning of this step and the
                  // velocity is already <= 0 at its end: no sliding.
                  // (SLAMMER keeps the trapezoidal increment, which is <= 0
                  // here, and reports |s|; the difference is below 0.02 cm
                  // on its 2,520 cases.)
                  s2 = s;
                  r.sliding_duration -= dt;
                }
              else
                {
                  // Sliding up to the zero crossing of the velocity.
                  const double tau = fraction * dt;
                  const double a_stop
                    = x1 + fraction * (x2 - x1) - yield + mean_shape * mode.a;
                  const double v_stop = v + 0.5 * tau * (a_stop + a);
                  s2                  = s + 0.5 * tau * (v + v_stop);
                  r.sliding_duration -= dt - tau;

                  // The mode sticks again for the rest of the step: one
                  // average-acceleration step of length (1 - fraction) dt in
                  // acceleration form, from the sliding equilibrium (mass
                  // factor sliding_mass, load ky g) to the sticking one
                  // (mass 1, load a_g).
                  const double h     = dt - tau;
                  const double k_hat = 1. + c * h / 2. + k * h * h / 4.;
                  const double coeff
                    = sliding_mass - c * h / 2. - k * h * h / 4.;
                  const double a_new = (-participation * (x2 - yield)
                                        + coeff * mode.a - k * h * mode.v)
                                       / k_hat;
                  mode.u += mode.v * h + h * h / 4. * (mode.a + a_new);
                  mode.v += h / 2. * (mode.a + a_new);
                  mode.a = a_new;
                }
              sliding = false;
              v2      = 0.;
              a2      = 0.;
            }
          s = s2;
          v = v2;
          a = a2;

          r.driving[j]      = drive / g;
          r.velocity[j]     = v;
          r.displacement[j] = s;
          r.state[j]        = sliding ? 1 : 0;
          r.max_velocity    = std::max(r.max_velocity, v);
        }
      if (!std::isfinite(s))
        throw std::runtime_error("coupled sliding: the displacement is not "
                                 "finite");
      r.final_displacement = s;
    }
  } // namespace



  void
  validate(const SiteResponseOptions &o)
  {
    const std::string who = "site response: ";
    const auto        check
      = [&](const bool ok, const std::string &what, const double value) {
          if (!ok || !std::isfinite(value))
            throw InputError(who + what + "; given " + to_text(value));
        };
    check(o.height > 0., "height H must be > 0 m", o.height);
    check(o.vs_slope > 0.,
          "shear-wave velocity of the sliding mass must be > 0 m/s",
          o.vs_slope);
    check(o.vs_base > 0.,
          "shear-wave velocity of the base must be > 0 m/s",
          o.vs_base);
    check(o.damping >= -1. && o.damping <= 1.,
          "damping ratio must be in [-1, 1]",
          o.damping);
    check(o.damping + impedance_damping(o.vs_base, o.vs_slope) >= 0.,
          "damping ratio plus the base-impedance damping ("
            + to_text(impedance_damping(o.vs_base, o.vs_slope))
            + ") must be >= 0",
          o.damping);
    check(o.reference_strain > 0.,
          "reference shear strain must be > 0 (a fraction: 5e-4 = 0.05 %)",
          o.reference_strain);
    check(o.tolerance > 0., "iteration tolerance must be > 0", o.tolerance);
    check(o.max_iterations >= 1,
          "at most iterations must be >= 1",
          o.max_iterations);
    check(o.substeps >= 1, "substeps per sample must be >= 1", o.substeps);
    check(o.g > 0., "gravitational acceleration g must be > 0 m/s^2", o.g);
  }



  SiteResponse
  site_response(const Record &input, const SiteResponseOptions &options)
  {
    validate(options);
    if (input.acceleration.empty() || !(input.dt > 0.))
      throw InputError("site response: the record '" + input.name
                       + "' is empty or has dt <= 0");

    SiteResponse site;
    site.options = options;
    site.dt      = input.dt / options.substeps;

    const std::vector<double> x = to_si(input, options.g, options.substeps);
    const double              H = options.height;
    const auto omega_of = [&](const double vs) { return M_PI * vs / (2. * H); };

    site.vs           = options.vs_slope;
    site.base_damping = impedance_damping(options.vs_base, site.vs);
    site.damping      = options.damping + site.base_damping;

    if (options.model == SiteResponseOptions::Model::equivalent_linear)
      {
        // Iterate on the properties (SLAMMER): the response with the
        // current Vs and damping gives the effective strain, which gives
        // G/Gmax = 1/(1 + gamma/gamma_r) and the soil damping; stop when G
        // and the soil damping change by at most the tolerance.
        const double vs0              = options.vs_slope;
        double       previous_damping = 0.;
        site.converged                = false;
        for (unsigned int it = 1; it <= options.max_iterations; ++it)
          {
            const double u_max = linear_response(
              x, site.dt, omega_of(site.vs), site.damping, options.g, nullptr);
            site.iterations       = it;
            site.effective_strain = strain_factor * u_max / H;
            const double ratio
              = site.effective_strain / options.reference_strain;
            const double vs_new  = vs0 / std::sqrt(1. + ratio);
            const double xi_soil = soil_damping(ratio);
            const double dG      = std::abs(site.vs * site.vs - vs_new * vs_new)
                              / (site.vs * site.vs);
            const double dD
              = previous_damping > 0.
                  ? std::abs(previous_damping - xi_soil) / previous_damping
                  : std::numeric_limits<double>::infinity();
            site.vs           = vs_new;
            site.base_damping = impedance_damping(options.vs_base, site.vs);
            site.damping      = site.base_damping + xi_soil;
            previous_damping  = xi_soil;
            if (dG <= options.tolerance && dD <= options.tolerance)
              {
                site.converged = true;
                break;
              }
          }
      }

    linear_response(
      x, site.dt, omega_of(site.vs), site.damping, options.g, &site.k);
    site.period = 4. * H / site.vs;
    site.kmax   = signed_peak(site.k);
    return site;
  }



  SiteResponse
  inverted(const SiteResponse &site)
  {
    SiteResponse result = site;
    for (double &k : result.k)
      k = -k;
    result.kmax = signed_peak(result.k);
    return result;
  }



  FlexibleSlidingResult
  flexible_sliding(const Record &input, const FlexibleSlidingOptions &options)
  {
    return flexible_sliding(input, site_response(input, options.site), options);
  }



  FlexibleSlidingResult
  flexible_sliding(const Record                 &input,
                   const SiteResponse           &site,
                   const FlexibleSlidingOptions &options)
  {
    if (!(options.ky >= 0.) || !std::isfinite(options.ky))
      throw InputError("flexible sliding: yield acceleration ky must be "
                       "finite and >= 0 g; given "
                       + to_text(options.ky));
    if (input.acceleration.empty())
      throw InputError("flexible sliding: the record '" + input.name
                       + "' is empty");
    const std::vector<double> x
      = to_si(input, site.options.g, site.options.substeps);
    if (site.k.size() != x.size()
        || std::abs(site.dt * site.options.substeps - input.dt)
             > 1e-12 * input.dt)
      throw InputError("flexible sliding: the site response was computed for "
                       "another record than '"
                       + input.name + "'");

    FlexibleSlidingResult r;
    r.site       = site;
    const auto n = x.size();
    r.time.resize(n);
    for (std::size_t j = 0; j < n; ++j)
      r.time[j] = j * site.dt;
    r.driving.resize(n);
    r.velocity.resize(n);
    r.displacement.resize(n);
    r.state.resize(n);

    if (options.coupling == FlexibleSlidingOptions::Coupling::decoupled)
      decoupled(site, options.ky, r);
    else
      coupled(x, site, options.ky, r);
    return r;
  }
} // namespace rockdda::seismic
