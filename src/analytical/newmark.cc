#include <rockdda/analytical/newmark.h>
#include <rockdda/io/error.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>
#include <stdexcept>
#include <string>

namespace rockdda::analytical
{
  namespace
  {
    /// A number as text for messages (shortest form).
    std::string
    to_text(const double x)
    {
      std::ostringstream out;
      out << x;
      return out.str();
    }



    /**
     * Root of a continuous function in [lo, hi], where f(lo) and f(hi) differ
     * in sign (or one is zero): Newton steps, replaced by bisection whenever
     * they leave the current bracket. @p fdf(x, f, df) evaluates the function
     * and its derivative. Converges to machine precision.
     */
    template <typename Function>
    double
    safeguarded_newton(const Function &fdf, double lo, double hi)
    {
      double f_lo = 0., f_hi = 0., df = 0.;
      fdf(lo, f_lo, df);
      if (f_lo == 0.)
        return lo;
      fdf(hi, f_hi, df);
      if (f_hi == 0.)
        return hi;
      // Orient the bracket so that f(neg) < 0 < f(pos).
      double neg = lo, pos = hi;
      if (f_lo > 0.)
        std::swap(neg, pos);

      const double eps = std::numeric_limits<double>::epsilon();
      double       x   = 0.5 * (lo + hi);
      for (unsigned int it = 0; it < 200; ++it)
        {
          double f = 0.;
          fdf(x, f, df);
          if (f == 0.)
            return x;
          (f < 0. ? neg : pos) = x;
          const double a = std::min(neg, pos), b = std::max(neg, pos);
          double       x_new = (df != 0.) ? x - f / df : 0.5 * (a + b);
          if (!(x_new > a && x_new < b))
            x_new = 0.5 * (a + b);
          const double scale = std::max(std::abs(a), std::abs(b));
          if (std::abs(x_new - x) <= 2. * eps * scale
              || b - a <= 4. * eps * scale)
            return x_new;
          x = x_new;
        }
      return x;
    }



    /**
     * Evaluates the sliding model of NewmarkOptions: the relative (block
     * minus ground) acceleration along the slope, in m/s^2, for an input k
     * (g), sliding direction dir (+1 down, -1 up), slip speed (m/s) and
     * cumulative sliding distance s (m).
     */
    class SlidingModel
    {
    public:
      explicit SlidingModel(const NewmarkOptions &options)
          : options(options)
          , plane(options.yield_model == NewmarkOptions::YieldModel::plane)
          , sin_dip(std::sin(options.dip_deg * M_PI / 180.))
          , cos_dip(std::cos(options.dip_deg * M_PI / 180.))
          , mu_static(options.friction.static_coefficient())
          , rate_dependent(
              plane && options.friction.type == FrictionLaw::Type::steady_state
              && options.friction.a_minus_b != 0.)
      {}

      /// Yield acceleration (g) at sliding distance s (constant and table).
      double
      yield(const double s) const
      {
        if (options.yield_model == NewmarkOptions::YieldModel::constant)
          return options.ky;
        const auto &d = options.table_displacement;
        const auto &k = options.table_ky;
        if (s <= d.front())
          return k.front();
        if (s >= d.back())
          return k.back();
        const std::size_t i
          = std::upper_bound(d.begin(), d.end(), s) - d.begin() - 1;
        const double w = (s - d[i]) / (d[i + 1] - d[i]);
        return (1. - w) * k[i] + w * k[i + 1];
      }

      /// Normal force per unit weight on the plane (-); 1 for the non-plane
      /// models.
      double
      normal(const double k) const
      {
        return plane ? cos_dip - k * sin_dip : 1.;
      }

      /// Relative acceleration (m/s^2) with friction coefficient mu (plane).
      double
      relative_mu(const double k,
                  const int    dir,
                  const double mu,
                  const double s) const
      {
        if (plane)
          return options.g
                 * ((sin_dip + k * cos_dip)
                    - dir * mu * (cos_dip - k * sin_dip));
        return options.g * (k - dir * yield(s));
      }

      /// Relative acceleration (m/s^2) when sliding at speed @p speed (m/s).
      double
      relative(const double k,
               const int    dir,
               const double speed,
               const double s) const
      {
        return relative_mu(k,
                           dir,
                           plane ? options.friction.coefficient(speed) : 0.,
                           s);
      }

      /// Relative acceleration (m/s^2) at rest, with the static resistance:
      /// sliding in direction dir starts where dir * at_rest > 0.
      double
      at_rest(const double k, const int dir, const double s) const
      {
        return relative_mu(k, dir, mu_static, s);
      }

      /// Derivative of the friction coefficient with respect to the slip
      /// speed (s/m).
      double
      dmu_dspeed(const double speed) const
      {
        const FrictionLaw &f = options.friction;
        if (!rate_dependent || speed <= f.v_cutoff
            || f.coefficient(speed) <= 0.)
          return 0.;
        return f.a_minus_b / speed;
      }

      const NewmarkOptions &options;
      const bool            plane;
      const double          sin_dip, cos_dip, mu_static;
      const bool            rate_dependent;
    };
  } // namespace



  void
  validate(const NewmarkOptions &o)
  {
    const std::string who = "Newmark sliding: ";
    if (!(o.time_step >= 0.) || !std::isfinite(o.time_step))
      throw InputError(who
                       + "time step must be >= 0 s (0 = the record's "
                         "dt); given "
                       + to_text(o.time_step));
    if (!(o.output_interval >= 0.) || !std::isfinite(o.output_interval))
      throw InputError(who
                       + "output interval must be >= 0 s (0 = every "
                         "step); given "
                       + to_text(o.output_interval));
    if (!(o.g > 0.) || !std::isfinite(o.g))
      throw InputError(who
                       + "gravitational acceleration g must be > 0 m/s^2; "
                         "given "
                       + to_text(o.g));
    switch (o.yield_model)
      {
        case NewmarkOptions::YieldModel::constant:
          if (!(o.ky >= 0.) || !std::isfinite(o.ky))
            throw InputError(who
                             + "yield acceleration ky must be finite and "
                               ">= 0 g; given "
                             + to_text(o.ky));
          break;
        case NewmarkOptions::YieldModel::table:
          {
            const auto &d = o.table_displacement;
            const auto &k = o.table_ky;
            if (d.empty() || d.size() != k.size())
              throw InputError(who
                               + "the ky table needs the same number (>= 1) of "
                                 "displacements and yield accelerations; given "
                               + std::to_string(d.size()) + " and "
                               + std::to_string(k.size()));
            for (std::size_t i = 0; i < d.size(); ++i)
              {
                if (!std::isfinite(d[i]) || (i > 0 && !(d[i] > d[i - 1])))
                  throw InputError(
                    who
                    + "ky table displacements must be finite and "
                      "strictly increasing (m); entry "
                    + std::to_string(i + 1) + " is " + to_text(d[i]));
                if (!(k[i] >= 0.) || !std::isfinite(k[i]))
                  throw InputError(who
                                   + "ky table yield accelerations must "
                                     "be finite and >= 0 g; entry "
                                   + std::to_string(i + 1) + " is "
                                   + to_text(k[i]));
              }
            break;
          }
        case NewmarkOptions::YieldModel::plane:
          {
            if (!(o.dip_deg >= 0. && o.dip_deg < 90.))
              throw InputError(who
                               + "dip of the sliding plane must be in "
                                 "[0, 90) deg; given "
                               + to_text(o.dip_deg));
            const FrictionLaw &f = o.friction;
            if (!(f.mu0 >= 0.) || !(std::atan(f.mu0) < 0.5 * M_PI))
              throw InputError(who
                               + "friction coefficient mu0 = tan(phi) "
                                 "must be finite and >= 0 (friction "
                                 "angle in [0, 90) deg); given "
                               + to_text(f.mu0));
            if (f.type == FrictionLaw::Type::steady_state)
              {
                if (!std::isfinite(f.a_minus_b))
                  throw InputError(who
                                   + "friction rate dependence A - B "
                                     "must be finite; given "
                                   + to_text(f.a_minus_b));
                if (!(f.v0 > 0.) || !std::isfinite(f.v0))
                  throw InputError(who
                                   + "friction reference slip rate V0 "
                                     "must be finite and > 0 m/s; given "
                                   + to_text(f.v0));
                if (!(f.v_cutoff > 0.) || !std::isfinite(f.v_cutoff))
                  throw InputError(who
                                   + "friction cutoff slip rate must be "
                                     "finite and > 0 m/s; given "
                                   + to_text(f.v_cutoff));
              }
            break;
          }
      }
  }



  NewmarkResult
  newmark_sliding(const seismic::Record &input, const NewmarkOptions &options)
  {
    validate(options);
    const std::string &name = input.name.empty() ? "record" : input.name;
    if (!(input.dt > 0.) || !std::isfinite(input.dt))
      throw InputError(name
                       + ": the time step of the record must be > 0 s; "
                         "given "
                       + to_text(input.dt));
    if (input.acceleration.size() < 2)
      throw InputError(name + ": the record needs at least 2 samples");
    for (std::size_t i = 0; i < input.acceleration.size(); ++i)
      if (!std::isfinite(input.acceleration[i]))
        throw InputError(name + ": sample " + std::to_string(i + 1)
                         + " is not a finite number");

    const SlidingModel model(options);
    const bool         two_way
      = options.direction == NewmarkOptions::Direction::two_way;
    const bool at_samples
      = options.event_location == NewmarkOptions::EventLocation::at_samples;

    // Time grid: the record's samples, or a uniform sub-step with the last
    // step shortened to end exactly at the end of the record.
    const double duration = input.duration();
    const bool   native
      = options.time_step == 0. || options.time_step == input.dt;
    const double        step = native ? input.dt : options.time_step;
    const unsigned long n_steps
      = native ? input.acceleration.size() - 1
               : static_cast<unsigned long>(
                 std::max(1., std::ceil(duration / step - 1e-9)));
    const auto time_of = [&](const unsigned long n) {
      return native ? n * input.dt : std::min(n * step, duration);
    };
    const auto input_of = [&](const unsigned long n) {
      return native ? input.acceleration[n] : input.at(time_of(n));
    };

    NewmarkResult result;
    result.n_steps = n_steps;
    const std::size_t n_out
      = options.output_interval > 0.
          ? static_cast<std::size_t>(duration / options.output_interval) + 2
          : n_steps + 1;
    result.time.reserve(n_out);
    result.acceleration.reserve(n_out);
    result.velocity.reserve(n_out);
    result.displacement.reserve(n_out);
    result.state.reserve(n_out);

    double v   = 0.; // relative velocity (m/s)
    double x   = 0.; // relative displacement (m)
    double s   = 0.; // cumulative sliding distance (m)
    double r   = 0.; // relative acceleration at the current time (m/s^2)
    int    dir = 0;

    double     t0          = 0.;
    double     k0          = input_of(0);
    double     next_output = 0.;
    const auto store       = [&](const double t, const double k) {
      result.time.push_back(t);
      result.acceleration.push_back(k);
      result.velocity.push_back(v);
      result.displacement.push_back(x);
      result.state.push_back(dir);
    };
    const auto check_contact = [&](const double t, const double k) {
      if (!(model.normal(k) > 0.))
        throw std::runtime_error(
          "Newmark sliding: the block lifts off the plane at t = " + to_text(t)
          + " s (input " + to_text(k)
          + " g gives a normal force <= 0; the input must stay below "
            "cot(dip))");
    };
    check_contact(0., k0);
    store(0., k0);
    next_output += options.output_interval;

    for (unsigned long n = 0; n < n_steps; ++n)
      {
        const double t1 = time_of(n + 1);
        const double k1 = input_of(n + 1);
        const double h  = t1 - t0;
        check_contact(t1, k1);

        // Walk through the step in sub-intervals separated by the events
        // (start, stop) located within it.
        double tau = 0.; // time into the step (s)
        double ka  = k0; // input at tau (g)
        for (unsigned int event = 0; tau < h; ++event)
          {
            const double length = h - tau;
            if (event > 8)
              {
                // Chattering at a tangency: stay at rest for the rest.
                dir = 0;
                v   = 0.;
                break;
              }
            if (dir == 0)
              {
                // At rest: does the driving exceed the static resistance at
                // tau, or where within [tau, h]?  The excess is linear in
                // the input, hence in time. (SLAMMER mode: only the sample
                // at the end of the step is tested, and sliding starts at
                // tau with zero relative acceleration.)
                int    new_dir = 0;
                double sigma   = length;
                for (const int d : {+1, -1})
                  {
                    if (d == -1 && !two_way)
                      break;
                    const double ea = d * model.at_rest(ka, d, s);
                    const double eb = d * model.at_rest(k1, d, s);
                    double       sd = length;
                    if (at_samples)
                      {
                        if (!(eb > 0.))
                          continue;
                        sd = 0.;
                      }
                    else if (ea > 0.)
                      sd = 0.;
                    else if (eb > 0.)
                      sd = length * ea / (ea - eb);
                    else
                      continue;
                    if (new_dir == 0 || sd < sigma)
                      {
                        new_dir = d;
                        sigma   = sd;
                      }
                  }
                if (new_dir == 0)
                  break;
                if (at_samples)
                  r = 0.;
                else if (sigma > 0.)
                  {
                    // Crossing within the step: relative acceleration 0.
                    ka += (k1 - ka) * sigma / length;
                    tau += sigma;
                    r = 0.;
                  }
                else
                  r = model.at_rest(ka, new_dir, s);
                dir = new_dir;
                v   = 0.;
                ++result.n_slip_events;
                continue;
              }

            // Sliding on [tau, h]: average-acceleration update.
            double r1 = 0., v1 = 0.;
            bool   stops = false;
            if (!model.rate_dependent)
              {
                r1    = model.relative(k1, dir, std::abs(v), s);
                v1    = v + 0.5 * length * (r + r1);
                stops = !(dir * v1 > 0.);
              }
            else
              {
                // Implicit in the end speed w = dir * v1 >= 0:
                // F(w) = w - dir (v + L/2 (r + r1(w))) = 0.
                const double c
                  = dir * (v + 0.5 * length * r); // explicit part (m/s)
                const auto residual
                  = [&](const double w, double &f, double &df) {
                      f = w - c
                          - 0.5 * length * dir * model.relative(k1, dir, w, s);
                      df = 1.
                           + 0.5 * length * options.g * model.normal(k1)
                               * model.dmu_dspeed(w);
                    };
                double f0 = 0., df0 = 0.;
                residual(0., f0, df0);
                if (f0 >= 0.)
                  {
                    // Even at the static friction the velocity reverses:
                    // the block stops within the step.
                    stops = true;
                    r1    = model.at_rest(k1, dir, s);
                    v1    = v + 0.5 * length * (r + r1);
                  }
                else
                  {
                    const double driving = std::abs(
                      std::sin(options.dip_deg * M_PI / 180.)
                      + k1 * std::cos(options.dip_deg * M_PI / 180.));
                    const double hi = std::max(0., c)
                                      + 0.5 * length * options.g * driving
                                      + std::abs(f0) + 1e-12;
                    const double w = safeguarded_newton(residual, 0., hi);
                    v1             = dir * w;
                    r1             = model.relative(k1, dir, w, s);
                    stops          = !(w > 0.);
                  }
              }

            if (!stops)
              {
                // Exact integral of the velocity for a relative acceleration
                // linear across the step (SLAMMER: trapezoidal rule).
                const double dx
                  = at_samples ? 0.5 * length * (v + v1)
                               : length * (v + length * (2. * r + r1) / 6.);
                x += dx;
                s += std::abs(dx);
                result.sliding_duration += length;
                v   = v1;
                r   = r1;
                tau = h;
                break;
              }

            // The velocity returns to zero within [tau, h]: with the relative
            // acceleration linear in time, v(sigma) = v + r sigma +
            // (r1 - r) sigma^2 / (2 L).
            const double curvature = 0.5 * (r1 - r) / length;
            const auto   speed = [&](const double sg, double &f, double &df) {
              f  = dir * (v + sg * (r + curvature * sg));
              df = dir * (r + 2. * curvature * sg);
            };
            double f_end = 0., df_end = 0.;
            speed(length, f_end, df_end);
            double sigma = length;
            if (f_end > 0. || at_samples)
              sigma = length;
            else if (dir * v > 0.)
              sigma = safeguarded_newton(speed, 0., length);
            else
              // Started at tau (v = 0): the other root of v(sigma) = 0.
              sigma = (dir * r > 0. && dir * curvature < 0.)
                        ? std::min(length, -r / curvature)
                        : 0.;
            const double dx
              = at_samples
                  ? 0.5 * sigma * v
                  : sigma * (v + sigma * (r + curvature * sigma / 1.5) / 2.);
            x += dx;
            s += std::abs(dx);
            result.sliding_duration += sigma;
            ka += (k1 - ka) * sigma / length;
            tau += sigma;
            v   = 0.;
            r   = 0.;
            dir = 0;
          }

        if (!std::isfinite(v) || !std::isfinite(x))
          throw std::runtime_error("Newmark sliding: non-finite velocity or "
                                   "displacement at t = "
                                   + to_text(t1) + " s");
        result.max_velocity = std::max(result.max_velocity, std::abs(v));
        t0                  = t1;
        k0                  = k1;

        if (options.output_interval == 0. || n + 1 == n_steps
            || t1 >= next_output - 1e-9 * step)
          {
            store(t1, k1);
            while (options.output_interval > 0.
                   && next_output <= t1 + 1e-9 * step)
              next_output += options.output_interval;
          }
      }

    result.final_displacement = x;
    return result;
  }



  namespace
  {
    /// Check the arguments of the harmonic solutions.
    void
    check_harmonic(const double amplitude, const double omega, const double ky)
    {
      if (!(amplitude > 0.) || !std::isfinite(amplitude))
        throw InputError("harmonic sliding: amplitude A must be finite and "
                         "> 0; given "
                         + to_text(amplitude));
      if (!(omega > 0.) || !std::isfinite(omega))
        throw InputError("harmonic sliding: angular frequency omega must be "
                         "finite and > 0 rad/s; given "
                         + to_text(omega));
      if (!(ky >= 0.) || !std::isfinite(ky))
        throw InputError("harmonic sliding: yield acceleration ky must be "
                         "finite and >= 0; given "
                         + to_text(ky));
    }



    /// Displacement tau (s) after the start of sliding, for
    /// u = omega t_start (rad) (doc/theory/newmark-harmonic.md, Eq. D).
    double
    harmonic_partial(const double amplitude,
                     const double omega,
                     const double ky,
                     const double u,
                     const double tau)
    {
      const double half = 0.5 * omega * tau;
      return amplitude / omega * std::cos(u) * tau
             - 2. * amplitude / (omega * omega) * std::cos(u + half)
                 * std::sin(half)
             - 0.5 * ky * tau * tau;
    }
  } // namespace



  HarmonicSliding
  harmonic_sliding_cycle(const double amplitude,
                         const double omega,
                         const double ky)
  {
    check_harmonic(amplitude, omega, ky);
    const double inf = std::numeric_limits<double>::infinity();
    if (ky >= amplitude)
      return {inf, inf, 0.};
    const double period = 2. * M_PI / omega;
    if (ky == 0.)
      // v = (A/omega)(1 - cos omega t) >= 0 touches zero at t = T.
      return {0., period, amplitude * period / omega};

    const double u  = std::asin(ky / amplitude);
    const double t1 = u / omega;
    // Relative velocity tau after the start and its derivative; it
    // decreases strictly on [pi/omega - 2 t1, T], where it changes sign.
    const auto velocity = [&](const double tau, double &f, double &df) {
      const double half = 0.5 * omega * tau;
      f = 2. * amplitude / omega * std::sin(u + half) * std::sin(half)
          - ky * tau;
      df = amplitude * std::sin(u + omega * tau) - ky;
    };
    const double tau2
      = safeguarded_newton(velocity, M_PI / omega - 2. * t1, period);
    return {t1, t1 + tau2, harmonic_partial(amplitude, omega, ky, u, tau2)};
  }



  double
  harmonic_sliding_displacement(const double amplitude,
                                const double omega,
                                const double ky,
                                const double t)
  {
    if (!std::isfinite(t))
      throw InputError("harmonic sliding: time must be finite; given "
                       + to_text(t));
    const HarmonicSliding cycle = harmonic_sliding_cycle(amplitude, omega, ky);
    if (cycle.displacement_per_cycle == 0. || t <= cycle.t_start)
      return 0.;
    const double period = 2. * M_PI / omega;
    const double n      = std::floor((t - cycle.t_start) / period);
    const double tau
      = std::min(t - cycle.t_start - n * period, cycle.t_stop - cycle.t_start);
    return n * cycle.displacement_per_cycle
           + harmonic_partial(
             amplitude, omega, ky, omega * cycle.t_start, std::max(0., tau));
  }
} // namespace rockdda::analytical
