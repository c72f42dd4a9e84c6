#include <rockdda/seismic/fft.h>
#include <rockdda/seismic/spectra.h>

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace rockdda::seismic
{
  namespace
  {
    constexpr double standard_gravity = 9.80665;
  }



  FourierSpectrum
  fourier_amplitude_spectrum(const Record &record, const std::size_t min_length)
  {
    const std::size_t n
      = fast_fft_size(std::max(record.acceleration.size(), min_length));
    const auto      X = forward_real_fft(record.acceleration, n);
    FourierSpectrum s;
    s.frequency.resize(X.size());
    s.amplitude.resize(X.size());
    for (std::size_t k = 0; k < X.size(); ++k)
      {
        s.frequency[k] = k / (n * record.dt);
        s.amplitude[k] = record.dt * std::abs(X[k]);
      }
    return s;
  }



  OscillatorResponse
  oscillator_response(const Record      &record,
                      const double       period,
                      const double       damping,
                      const unsigned int subdivisions)
  {
    if (!(period > 0.) || !(damping >= 0. && damping < 1.) || subdivisions < 1)
      throw std::invalid_argument("oscillator_response: needs period > 0, "
                                  "0 <= damping < 1, subdivisions >= 1");
    // Work in g units (u in g s^2), convert at the end.
    const double w  = 2. * M_PI / period;
    const double z  = damping;
    const double wd = w * std::sqrt(1. - z * z);
    const double h  = record.dt / subdivisions;
    // Free vibration over one step h (the homogeneous part of the exact
    // solution): [u; v](h) = A [u; v](0).
    const double e   = std::exp(-z * w * h);
    const double s   = std::sin(wd * h);
    const double c   = std::cos(wd * h);
    const double q   = z / std::sqrt(1. - z * z);
    const double a11 = e * (c + q * s);
    const double a12 = e * s / wd;
    const double a21 = -e * w * s / std::sqrt(1. - z * z);
    const double a22 = e * (c - q * s);

    const auto        &a = record.acceleration;
    const std::size_t  n = a.empty() ? 0 : (a.size() - 1) * subdivisions + 1;
    OscillatorResponse r;
    r.dt = h;
    r.displacement.assign(n, 0.);
    r.velocity.assign(n, 0.);
    double u = 0., v = 0.;
    for (std::size_t i = 0; i + 1 < a.size(); ++i)
      for (unsigned int k = 0; k < subdivisions; ++k)
        {
          // Input over the sub-step: -a(tau) = p0 + p1 tau (linear).
          const double a0 = a[i] + (a[i + 1] - a[i]) * k / subdivisions;
          const double a1 = a[i] + (a[i + 1] - a[i]) * (k + 1.) / subdivisions;
          const double p0 = -a0, p1 = -(a1 - a0) / h;
          // Particular solution u_p = p1/w^2 tau + p0/w^2 - 2 zeta p1/w^3;
          // the rest is free vibration from the difference (Nigam &
          // Jennings 1969: exact for piecewise-linear input).
          const double up0 = p0 / (w * w) - 2. * z * p1 / (w * w * w);
          const double vp  = p1 / (w * w);
          const double du = u - up0, dv = v - vp;
          u                   = up0 + vp * h + a11 * du + a12 * dv;
          v                   = vp + a21 * du + a22 * dv;
          const std::size_t j = i * subdivisions + k + 1;
          r.displacement[j]   = standard_gravity * u;
          r.velocity[j]       = standard_gravity * v;
        }
    return r;
  }



  ResponseSpectrum
  response_spectrum(const Record              &record,
                    const std::vector<double> &periods,
                    const double               damping,
                    const unsigned int         subdivisions)
  {
    ResponseSpectrum s;
    s.damping = damping;
    s.period  = periods;
    for (const double T : periods)
      {
        // Automatic: at least 20 output points per oscillator period.
        const unsigned int m
          = subdivisions > 0 ? subdivisions
                             : static_cast<unsigned int>(
                               std::max(1., std::ceil(20. * record.dt / T)));
        const auto r  = oscillator_response(record, T, damping, m);
        double     sd = 0.;
        for (const double u : r.displacement)
          sd = std::max(sd, std::abs(u));
        const double w = 2. * M_PI / T;
        s.displacement.push_back(sd);
        s.pseudo_velocity.push_back(w * sd);
        s.pseudo_acceleration.push_back(w * w * sd / standard_gravity);
      }
    return s;
  }



  std::vector<double>
  log_spaced_periods(const double       first,
                     const double       last,
                     const unsigned int n)
  {
    if (!(first > 0.) || !(last >= first) || n < 1)
      throw std::invalid_argument("log_spaced_periods: needs 0 < first <= "
                                  "last and n >= 1");
    std::vector<double> T(n);
    for (unsigned int i = 0; i < n; ++i)
      T[i]
        = n == 1 ? first : first * std::pow(last / first, double(i) / (n - 1));
    return T;
  }
} // namespace rockdda::seismic
