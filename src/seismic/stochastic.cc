#include <rockdda/io/output.h>
#include <rockdda/seismic/fft.h>
#include <rockdda/seismic/spectra.h>
#include <rockdda/seismic/stochastic.h>

#include <algorithm>
#include <cmath>
#include <random>
#include <stdexcept>

namespace rockdda::seismic
{
  namespace
  {
    constexpr double g_si = 9.80665;

    /// Boore & Joyner (1997), Table 3: generic rock (Vs30 = 620 m/s).
    constexpr double bj97_frequency[]
      = {0.01, 0.09, 0.16, 0.51, 0.84, 1.25, 2.26, 3.17, 6.05, 16.6, 61.2};
    constexpr double bj97_amplification[]
      = {1.00, 1.10, 1.18, 1.42, 1.58, 1.74, 2.06, 2.25, 2.58, 3.13, 4.00};

    /// Saragoni & Hart window with Boore's (2003) parameters.
    struct Window
    {
      double a, b, c, t_eta;

      Window(const StochasticParameters &p)
      {
        const double eps = p.window_epsilon, eta = p.window_eta;
        b     = -eps * std::log(eta) / (1. + eps * (std::log(eps) - 1.));
        c     = b / eps;
        a     = std::pow(std::exp(1.) / eps, b);
        t_eta = p.window_factor * motion_duration(p);
      }

      double
      operator()(const double t) const
      {
        if (t <= 0.)
          return 0.;
        const double x = t / t_eta;
        return a * std::pow(x, b) * std::exp(-c * x);
      }
    };

    /// The front and back pad (s).
    double
    pad_of(const StochasticParameters &p)
    {
      return std::max(2., 1. / corner_frequency(p));
    }

    void
    check(const StochasticParameters &p)
    {
      const bool ok
        = std::isfinite(p.magnitude) && p.distance >= 0. && p.depth >= 0.
          && p.stress_parameter > 0. && p.density > 0. && p.shear_velocity > 0.
          && p.radiation_pattern > 0. && p.free_surface > 0. && p.partition > 0.
          && p.spreading_transition > 0. && p.q0 > 0. && p.kappa >= 0.
          && p.source_duration >= 0. && p.path_duration >= 0.
          && p.window_epsilon > 0. && p.window_epsilon < 1. && p.window_eta > 0.
          && p.window_eta < 1. && p.window_factor > 0. && p.dt > 0.;
      if (!ok)
        throw std::invalid_argument("stochastic simulation: a parameter is "
                                    "out of range (see stochastic.h)");
    }
  } // namespace



  double
  seismic_moment(const double magnitude)
  {
    return std::pow(10., 1.5 * magnitude + 9.05);
  }



  double
  corner_frequency(const StochasticParameters &p)
  {
    return 0.4906 * p.shear_velocity
           * std::cbrt(p.stress_parameter / seismic_moment(p.magnitude));
  }



  double
  source_depth(const StochasticParameters &p)
  {
    return p.depth > 0. ? p.depth
                        : 1e3 * std::pow(10., -0.05 + 0.15 * p.magnitude);
  }



  double
  source_distance(const StochasticParameters &p)
  {
    const double h = source_depth(p);
    return std::sqrt(p.distance * p.distance + h * h);
  }



  double
  motion_duration(const StochasticParameters &p)
  {
    return p.source_duration / corner_frequency(p)
           + p.path_duration * source_distance(p);
  }



  double
  geometric_spreading(const StochasticParameters &p, const double r)
  {
    const double r0 = 1e3;
    if (r <= p.spreading_transition)
      return std::pow(r0 / r, p.spreading_near);
    return std::pow(r0 / p.spreading_transition, p.spreading_near)
           * std::pow(p.spreading_transition / r, p.spreading_far);
  }



  double
  crustal_amplification(const CrustalAmplification type, const double f)
  {
    if (type == CrustalAmplification::none)
      return 1.;
    constexpr std::size_t n = std::size(bj97_frequency);
    if (f <= bj97_frequency[0])
      return bj97_amplification[0];
    if (f >= bj97_frequency[n - 1])
      return bj97_amplification[n - 1];
    std::size_t k = 1;
    while (bj97_frequency[k] < f)
      ++k;
    const double w = std::log(f / bj97_frequency[k - 1])
                     / std::log(bj97_frequency[k] / bj97_frequency[k - 1]);
    return std::exp((1. - w) * std::log(bj97_amplification[k - 1])
                    + w * std::log(bj97_amplification[k]));
  }



  double
  target_fourier_amplitude(const StochasticParameters &p,
                           const double                f,
                           const bool                  with_site)
  {
    if (!(f > 0.))
      return 0.;
    const double r0 = 1e3, beta = p.shear_velocity;
    const double c = p.radiation_pattern * p.free_surface * p.partition
                     / (4. * M_PI * p.density * beta * beta * beta * r0);
    const double fc = corner_frequency(p), r = source_distance(p);
    const double w = 2. * M_PI * f;
    const double source
      = c * seismic_moment(p.magnitude) * w * w / (1. + (f / fc) * (f / fc));
    const double q = p.q0 * std::pow(f, p.q_exponent);
    const double path
      = geometric_spreading(p, r) * std::exp(-M_PI * f * r / (q * beta));
    const double site = crustal_amplification(p.crustal, f)
                        * std::exp(-M_PI * p.kappa * f)
                        * (with_site ? p.site(f) : 1.);
    return source * path * site / g_si;
  }



  double
  window_start(const StochasticParameters &p)
  {
    return pad_of(p);
  }



  Record
  simulate(const StochasticParameters &p,
           const std::uint64_t         seed,
           const bool                  with_site)
  {
    check(p);
    const Window      window(p);
    const double      pad   = pad_of(p);
    const std::size_t front = static_cast<std::size_t>(std::ceil(pad / p.dt));
    // The noise spans 1.5 t_eta: the window is below 0.4 % of its peak
    // after it (3.6e-3 for Boore's epsilon, eta).
    const std::size_t n_noise
      = static_cast<std::size_t>(std::ceil(1.5 * window.t_eta / p.dt)) + 1;
    const std::size_t n = fast_fft_size(2 * front + n_noise);

    // Unit Gaussian noise: Box-Muller on 53-bit uniforms of mt19937_64
    // (both specified exactly by the standard; std::normal_distribution is
    // not, so its numbers could differ between standard libraries).
    std::mt19937_64 engine(seed);
    const auto      uniform = [&engine]() {
      return (static_cast<double>(engine() >> 11) + 0.5) * 0x1.0p-53;
    };
    std::vector<double> x(n, 0.);
    for (std::size_t i = 0; i < n_noise; i += 2)
      {
        const double rho   = std::sqrt(-2. * std::log(uniform()));
        const double theta = 2. * M_PI * uniform();
        const double t0    = i * p.dt;
        x[front + i]       = rho * std::cos(theta) * window(t0);
        if (i + 1 < n_noise)
          x[front + i + 1] = rho * std::sin(theta) * window(t0 + p.dt);
      }
    auto Z = forward_real_fft(x, n);
    // Normalise to a unit mean square amplitude spectrum (Boore 2003).
    double sum = 0.;
    for (const auto &z : Z)
      sum += std::norm(z);
    const double rms = std::sqrt(sum / Z.size());
    const double df  = 1. / (n * p.dt);
    // |X_k| dt = A(f_k) |Z_k| / rms: the record's Fourier amplitude (dt
    // times the DFT, spectra.h) is the target times the normalised noise.
    for (std::size_t k = 0; k < Z.size(); ++k)
      Z[k] *= target_fourier_amplitude(p, k * df, with_site) / (rms * p.dt);
    Record record;
    record.dt           = p.dt;
    record.acceleration = inverse_real_fft(Z, n);
    record.name = "stochastic M " + io::format_number(p.magnitude, 4) + " Rjb "
                  + io::format_number(p.distance / 1e3, 4) + " km seed "
                  + std::to_string(seed);
    return record;
  }



  SpectrumAverager::SpectrumAverager(const StochasticParameters &p,
                                     const bool                  with_site)
      : parameters(p)
      , with_site(with_site)
  {}



  void
  SpectrumAverager::add(const Record &record)
  {
    const auto fs = fourier_amplitude_spectrum(record);
    if (count == 0)
      {
        power.assign(fs.amplitude.size(), 0.);
        df = fs.frequency.size() > 1 ? fs.frequency[1] : 0.;
      }
    if (fs.amplitude.size() != power.size())
      throw std::invalid_argument("SpectrumAverager: realisations of "
                                  "different lengths");
    for (std::size_t k = 0; k < power.size(); ++k)
      power[k] += fs.amplitude[k] * fs.amplitude[k];
    ++count;
  }



  BandSpectra
  SpectrumAverager::bands(const double       f_low,
                          const double       f_high,
                          const unsigned int per_octave) const
  {
    BandSpectra out;
    out.realisations = count;
    if (count == 0 || !(df > 0.))
      return out;
    const double half = std::pow(2., 0.5 / per_octave);
    for (unsigned int j = 0;; ++j)
      {
        const double centre = f_low * std::pow(2., double(j) / per_octave);
        if (centre > f_high * (1. + 1e-12))
          break;
        const auto k0 = static_cast<std::size_t>(std::ceil(centre / half / df));
        const auto k1 = std::min<std::size_t>(power.size(),
                                              static_cast<std::size_t>(
                                                std::ceil(centre * half / df)));
        if (k1 <= k0)
          continue;
        double sim = 0., target = 0.;
        for (std::size_t k = k0; k < k1; ++k)
          {
            const double a
              = target_fourier_amplitude(parameters, k * df, with_site);
            sim += power[k] / count;
            target += a * a;
          }
        out.frequency.push_back(centre);
        out.target.push_back(std::sqrt(target / (k1 - k0)));
        out.mean.push_back(std::sqrt(sim / (k1 - k0)));
      }
    return out;
  }



  std::string
  describe(const StochasticParameters &p)
  {
    return "M " + io::format_number(p.magnitude, 4) + ", Rjb "
           + io::format_number(p.distance / 1e3, 5) + " km, h "
           + io::format_number(source_depth(p) / 1e3, 4) + " km (R "
           + io::format_number(source_distance(p) / 1e3, 5) + " km), stress "
           + io::format_number(p.stress_parameter / 1e6, 4) + " MPa, fc "
           + io::format_number(corner_frequency(p), 4)
           + " Hz, Q = " + io::format_number(p.q0, 4) + " f^"
           + io::format_number(p.q_exponent, 3) + ", kappa "
           + io::format_number(p.kappa, 3) + " s, T_gm "
           + io::format_number(motion_duration(p), 4) + " s, dt "
           + io::format_number(p.dt, 4) + " s";
  }
} // namespace rockdda::seismic
