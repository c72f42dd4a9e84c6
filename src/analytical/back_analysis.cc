#include <rockdda/analytical/back_analysis.h>
#include <rockdda/io/error.h>

#include <algorithm>
#include <cmath>
#include <sstream>
#include <stdexcept>
#include <string>

namespace rockdda::analytical
{
  namespace
  {
    /// Linear interpolation of the measured history at @p t (inside it).
    double
    interpolate(const DisplacementHistory &h, const double t)
    {
      const auto upper = std::upper_bound(h.time.begin(), h.time.end(), t);
      if (upper == h.time.begin())
        return h.displacement.front();
      if (upper == h.time.end())
        return h.displacement.back();
      const std::size_t i = (upper - h.time.begin()) - 1;
      const double      w = (t - h.time[i]) / (h.time[i + 1] - h.time[i]);
      return (1. - w) * h.displacement[i] + w * h.displacement[i + 1];
    }
  } // namespace



  ForwardModel
  plane_sliding_forward_model(const seismic::Record &record,
                              const double           dip_deg,
                              const double           time_step,
                              const double           gravity)
  {
    require_in_range(dip_deg >= 0. && dip_deg < 90.,
                     "back_analysis.dip",
                     dip_deg,
                     "0 <= dip < 90 (degrees)");
    require_in_range(time_step > 0.,
                     "back_analysis.time_step",
                     time_step,
                     "> 0 (s)");
    require_in_range(gravity > 0.,
                     "back_analysis.gravity",
                     gravity,
                     "> 0 (m/s^2)");
    const double alpha = dip_deg * M_PI / 180.;
    const double sin_a = std::sin(alpha);
    const double cos_a = std::cos(alpha);

    return [record, sin_a, cos_a, time_step, gravity](const double phi_deg,
                                                      const SlidingState &start,
                                                      const double t_begin,
                                                      const double t_end) {
      const double mu = std::tan(phi_deg * M_PI / 180.);
      // Downslope acceleration of a sliding block (m/s^2), Coulomb friction.
      const auto acceleration = [&](const double t) {
        const double k      = record.at(t);
        const double normal = cos_a - k * sin_a;
        if (!(normal > 0.))
          {
            std::ostringstream message;
            message << "plane sliding: the normal force vanishes at t = " << t
                    << " s (k = " << k << " g): the block lifts off";
            throw std::domain_error(message.str());
          }
        return gravity * ((sin_a + k * cos_a) - mu * normal);
      };

      SlidingState state = start;
      if (!(t_end > t_begin))
        return state;
      const auto n_steps = static_cast<unsigned long>(
        std::max(1., std::ceil((t_end - t_begin) / time_step - 1e-9)));
      const double h  = (t_end - t_begin) / n_steps;
      double       a0 = acceleration(t_begin);
      for (unsigned long i = 1; i <= n_steps; ++i)
        {
          const double t1 = (i == n_steps) ? t_end : t_begin + i * h;
          const double a1 = acceleration(t1);
          const double v  = std::max(state.velocity, 0.);
          if (v == 0. && a0 <= 0. && a1 <= 0.)
            {
              state.velocity = 0.; // sticking
            }
          else
            {
              const double v_new = v + 0.5 * h * (a0 + a1);
              if (v_new > 0.)
                {
                  state.displacement += 0.5 * h * (v + v_new);
                  state.velocity = v_new;
                }
              else
                {
                  // Stops at s h, s = v/(v - v_new) (linear v), after
                  // sliding v s h / 2.
                  if (v > 0.)
                    state.displacement += 0.5 * h * v * v / (v - v_new);
                  state.velocity = 0.;
                }
            }
          a0 = a1;
        }
      return state;
    };
  }



  std::vector<SegmentFit>
  back_analyse_friction_angles(const DisplacementHistory  &measured,
                               const std::vector<double>  &boundaries,
                               const ForwardModel         &forward,
                               const BackAnalysisSettings &settings)
  {
    if (!forward)
      throw std::invalid_argument(
        "back_analyse_friction_angles: empty forward model");
    // Measured history.
    if (measured.time.size() != measured.displacement.size())
      throw InputError("back_analysis: the measured history has "
                       + std::to_string(measured.time.size()) + " times but "
                       + std::to_string(measured.displacement.size())
                       + " displacements; expected equal sizes");
    if (measured.time.size() < 2)
      throw InputError("back_analysis: the measured history has "
                       + std::to_string(measured.time.size())
                       + " samples; expected at least 2");
    for (std::size_t i = 0; i < measured.time.size(); ++i)
      {
        require_in_range(std::isfinite(measured.time[i]),
                         "back_analysis.measured.time[" + std::to_string(i)
                           + "]",
                         measured.time[i],
                         "a finite number (s)");
        require_in_range(std::isfinite(measured.displacement[i]),
                         "back_analysis.measured.displacement["
                           + std::to_string(i) + "]",
                         measured.displacement[i],
                         "a finite number (m)");
        if (i > 0)
          require_in_range(measured.time[i] > measured.time[i - 1],
                           "back_analysis.measured.time[" + std::to_string(i)
                             + "]",
                           measured.time[i],
                           "strictly increasing sample times (> "
                             + std::to_string(measured.time[i - 1]) + " s)");
      }
    // Segments.
    if (boundaries.size() < 2)
      throw InputError("back_analysis.segments: "
                       + std::to_string(boundaries.size())
                       + " boundaries given; expected at least 2 (one "
                         "segment)");
    for (std::size_t i = 0; i < boundaries.size(); ++i)
      {
        require_in_range(std::isfinite(boundaries[i]),
                         "back_analysis.segments[" + std::to_string(i) + "]",
                         boundaries[i],
                         "a finite time (s)");
        if (i > 0)
          require_in_range(boundaries[i] > boundaries[i - 1],
                           "back_analysis.segments[" + std::to_string(i) + "]",
                           boundaries[i],
                           "strictly increasing segment boundaries (> "
                             + std::to_string(boundaries[i - 1]) + " s)");
      }
    require_in_range(boundaries.front() >= measured.time.front(),
                     "back_analysis.segments[0]",
                     boundaries.front(),
                     ">= the first measured time "
                       + std::to_string(measured.time.front()) + " s");
    require_in_range(
      boundaries.back() <= measured.time.back(),
      "back_analysis.segments[" + std::to_string(boundaries.size() - 1) + "]",
      boundaries.back(),
      "<= the last measured time " + std::to_string(measured.time.back())
        + " s (the measured history is shorter than the segments)");
    // Settings.
    require_in_range(settings.phi_lower_deg >= 0.
                       && settings.phi_lower_deg < 90.,
                     "back_analysis.phi_lower",
                     settings.phi_lower_deg,
                     "0 <= phi_lower < 90 (degrees)");
    require_in_range(settings.phi_upper_deg > settings.phi_lower_deg
                       && settings.phi_upper_deg < 90.,
                     "back_analysis.phi_upper",
                     settings.phi_upper_deg,
                     "phi_lower < phi_upper < 90 (degrees)");
    require_in_range(settings.tolerance_deg > 0.,
                     "back_analysis.tolerance",
                     settings.tolerance_deg,
                     "> 0 (degrees)");
    require_in_range(std::isfinite(settings.initial_velocity),
                     "back_analysis.initial_velocity",
                     settings.initial_velocity,
                     "a finite number (m/s)");

    std::vector<SegmentFit> fits;
    SlidingState            state;
    state.displacement = interpolate(measured, boundaries.front());
    state.velocity     = settings.initial_velocity;
    for (std::size_t k = 0; k + 1 < boundaries.size(); ++k)
      {
        SegmentFit fit;
        fit.t_begin                 = boundaries[k];
        fit.t_end                   = boundaries[k + 1];
        fit.measured_displacement   = interpolate(measured, fit.t_end);
        const double start_measured = interpolate(measured, fit.t_begin);
        fit.average_velocity = (fit.measured_displacement - start_measured)
                               / (fit.t_end - fit.t_begin);
        fit.moved = fit.measured_displacement > start_measured;

        const auto displacement = [&](const double phi) {
          return forward(phi, state, fit.t_begin, fit.t_end).displacement;
        };
        const double target = fit.measured_displacement;
        double       lower  = settings.phi_lower_deg;
        double       upper  = settings.phi_upper_deg;
        if (displacement(lower) < target)
          {
            fit.bracketed = false; // slides less than measured even at lower
            upper         = lower;
          }
        else if (displacement(upper) > target)
          {
            fit.bracketed = false; // slides more than measured even at upper
            lower         = upper;
          }
        else
          {
            // Invariant: d(lower) >= target >= d(upper); converges to the
            // smallest phi with d(phi) <= target.
            while (upper - lower > settings.tolerance_deg)
              {
                const double middle = 0.5 * (lower + upper);
                if (middle <= lower || middle >= upper)
                  break; // bracket at floating-point resolution
                if (displacement(middle) > target)
                  lower = middle;
                else
                  upper = middle;
              }
          }
        fit.phi_deg = 0.5 * (lower + upper);
        state       = forward(fit.phi_deg, state, fit.t_begin, fit.t_end);
        fit.computed_displacement = state.displacement;
        fits.push_back(fit);
      }
    return fits;
  }



  SteadyStateFrictionFit
  fit_steady_state_friction(const std::vector<double> &velocity,
                            const std::vector<double> &mu,
                            const double               v0)
  {
    if (velocity.size() != mu.size())
      throw InputError("friction fit: " + std::to_string(velocity.size())
                       + " velocities but " + std::to_string(mu.size())
                       + " friction coefficients; expected equal sizes");
    if (velocity.size() < 3)
      throw InputError("friction fit: " + std::to_string(velocity.size())
                       + " data points; expected at least 3");
    require_in_range(v0 > 0., "friction_fit.v0", v0, "v0 > 0 (m/s)");
    const std::size_t   n = velocity.size();
    std::vector<double> x(n);
    double              x_mean = 0., y_mean = 0.;
    for (std::size_t i = 0; i < n; ++i)
      {
        require_in_range(velocity[i] > 0.,
                         "friction_fit.velocity[" + std::to_string(i) + "]",
                         velocity[i],
                         "V > 0 (m/s)");
        require_in_range(std::isfinite(mu[i]),
                         "friction_fit.mu[" + std::to_string(i) + "]",
                         mu[i],
                         "a finite number");
        x[i] = std::log(velocity[i] / v0);
        x_mean += x[i];
        y_mean += mu[i];
      }
    x_mean /= n;
    y_mean /= n;
    double sxx = 0., sxy = 0., syy = 0.;
    for (std::size_t i = 0; i < n; ++i)
      {
        sxx += (x[i] - x_mean) * (x[i] - x_mean);
        sxy += (x[i] - x_mean) * (mu[i] - y_mean);
        syy += (mu[i] - y_mean) * (mu[i] - y_mean);
      }
    if (!(sxx > 0.))
      throw InputError("friction fit: all velocities are equal; expected at "
                       "least two distinct velocities");

    SteadyStateFrictionFit fit;
    fit.v0        = v0;
    fit.n_points  = n;
    fit.a_minus_b = sxy / sxx;
    fit.mu0       = y_mean - fit.a_minus_b * x_mean;
    double ssr    = 0.;
    for (std::size_t i = 0; i < n; ++i)
      {
        const double r = mu[i] - (fit.mu0 + fit.a_minus_b * x[i]);
        ssr += r * r;
      }
    const double s2              = ssr / (n - 2);
    fit.a_minus_b_standard_error = std::sqrt(s2 / sxx);
    fit.mu0_standard_error = std::sqrt(s2 * (1. / n + x_mean * x_mean / sxx));
    fit.r_squared          = (syy > 0.) ? std::max(0., 1. - ssr / syy) : 1.;
    return fit;
  }
} // namespace rockdda::analytical
