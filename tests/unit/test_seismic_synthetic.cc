/**
 * @file
 * The seismic input chain (issue 14, items 4 and 5): site amplification
 * functions (tables, resonant modes, Masada) applied to records, and
 * synthetic motion by the stochastic point-source method (Boore 2003)
 * against BJF97 and its own target spectrum.
 */
#include <rockdda/io/error.h>
#include <rockdda/seismic/attenuation.h>
#include <rockdda/seismic/fft.h>
#include <rockdda/seismic/record.h>
#include <rockdda/seismic/site_amplification.h>
#include <rockdda/seismic/spectra.h>
#include <rockdda/seismic/stochastic.h>

#include <gtest/gtest.h>

#include "test_files.h"
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <functional>
#include <unistd.h>

using namespace rockdda;
using namespace rockdda::seismic;

using namespace rockdda::test_files;

namespace
{
  namespace fs = std::filesystem;



  /// A unit sinusoid of frequency @p f sampled at @p dt over @p duration.
  Record
  sinusoid(const double f, const double dt, const double duration)
  {
    Record r;
    r.dt         = dt;
    const auto n = static_cast<std::size_t>(std::llround(duration / dt));
    for (std::size_t i = 0; i < n; ++i)
      r.acceleration.push_back(std::sin(2. * M_PI * f * i * dt));
    return r;
  }

  /// Largest |a| over the middle third of @p r (away from the transients
  /// at the ends).
  double
  middle_peak(const Record &r)
  {
    const std::size_t n = r.acceleration.size();
    double            m = 0.;
    for (std::size_t i = n / 3; i < 2 * n / 3; ++i)
      m = std::max(m, std::abs(r.acceleration[i]));
    return m;
  }

  /// Median of @p v.
  double
  median(std::vector<double> v)
  {
    std::sort(v.begin(), v.end());
    const std::size_t n = v.size();
    return n % 2 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
  }

  /// Median PGA (g) of @p n realisations (seeds 1..n) of @p p.
  double
  median_pga(const StochasticParameters &p, const unsigned int n)
  {
    std::vector<double> pga;
    for (unsigned int s = 1; s <= n; ++s)
      pga.push_back(simulate(p, s).peak());
    return median(pga);
  }

  /// BJF97 median PGA (g) for the scenario of @p p on generic rock.
  double
  bjf97_of(const StochasticParameters &p)
  {
    Bjf97Scenario s;
    s.magnitude   = p.magnitude;
    s.distance_km = p.distance / 1e3;
    s.vs30        = 620.;
    return bjf97_pga(s);
  }
} // namespace



// A unit sinusoid at each Masada mode frequency comes out amplified by
// that mode's peak. The function equals the peak at f_i exactly (the mode
// excesses are solved for it); what is left is the spectral leakage of a
// 200 s sinusoid (its spectrum is 1/200 s = 0.005 Hz wide, the narrowest
// mode 0.8 Hz: the curvature error is ~(0.005/0.8)^2 ~ 4e-5) and the
// sampling of the peak (at 0.01 s and 6.5 Hz a sample misses the crest by
// at most 1 - cos(pi 6.5 0.01) = 2e-3: measured over many cycles the crest
// is hit to ~1e-5). 1 % is the tolerance; measured < 1e-4.
TEST(SiteAmplification, SinusoidAtModeAmplifiedByPeak)
{
  const auto site = SiteAmplification::masada();
  for (const auto &m : SiteAmplification::masada_modes())
    {
      EXPECT_NEAR(site(m.frequency), m.peak, 1e-12 * m.peak);
      const Record in            = sinusoid(m.frequency, 0.01, 200.);
      const Record out           = apply_site_amplification(in, site);
      const double amplification = middle_peak(out) / middle_peak(in);
      std::printf("mode %.1f Hz: peak %.3f, sinusoid amplified %.6f "
                  "(relative error %.2e)\n",
                  m.frequency,
                  m.peak,
                  amplification,
                  amplification / m.peak - 1.);
      EXPECT_NEAR(amplification, m.peak, 0.01 * m.peak);
    }
  // Above the cut: 20 Hz is 1/(1 + 2^16)^0.5 = 3.9e-3 of the baseline.
  EXPECT_LT(site(20.), 5e-3);
  // Far below the modes the rock is not amplified.
  EXPECT_NEAR(site(0.01), 1., 0.01);
}



// Overlapping modes still give their peaks at their frequencies; a single
// mode is 1 + (p - 1) L: half its excess at f0 (+-1 + sqrt(1 + 4 Q^2)) / (2
// Q), Q = f0 / w, which are w apart; A = 1 at f = 0.
TEST(SiteAmplification, ModesShape)
{
  const auto   one = SiteAmplification::from_modes({{2., 3., 0.4}});
  const double q = 2. / 0.4, root = std::sqrt(1. + 4. * q * q);
  const double f_plus  = 2. * (1. + root) / (2. * q),
               f_minus = 2. * (-1. + root) / (2. * q);
  EXPECT_DOUBLE_EQ(one(2.), 3.);
  EXPECT_NEAR(f_plus - f_minus, 0.4, 1e-14);
  EXPECT_NEAR(one(f_plus), 2., 1e-12);
  EXPECT_NEAR(one(f_minus), 2., 1e-12);
  EXPECT_DOUBLE_EQ(one(0.), 1.);
  const auto two = SiteAmplification::from_modes({{1., 4., 1.}, {1.5, 2., 1.}});
  EXPECT_NEAR(two(1.), 4., 1e-12);
  EXPECT_NEAR(two(1.5), 2., 1e-12);
  // Two deep troughs whose sum dips below zero between them are rejected.
  EXPECT_NE(
    error_of([] {
      SiteAmplification::from_modes({{1., 0.05, 0.5}, {1.2, 0.05, 0.5}});
    }).find("negative amplification"),
    std::string::npos);
}



// Log-log interpolation of a table: a power law between two points is
// reproduced exactly; constant beyond the ends; zeros interpolate linearly.
TEST(SiteAmplification, TableInterpolation)
{
  const auto s = SiteAmplification::from_table({1., 10., 20., 40.},
                                               {1., 4., 0., 2.},
                                               "test");
  // A = f^(log10 4) between 1 and 10 Hz.
  for (const double f : {1., 2., 3.3, 7., 10.})
    EXPECT_NEAR(s(f), std::pow(f, std::log10(4.)), 1e-12);
  EXPECT_DOUBLE_EQ(s(0.1), 1.);
  EXPECT_DOUBLE_EQ(s(0.), 1.);
  EXPECT_DOUBLE_EQ(s(100.), 2.);
  // Linear in A against log f where an end is 0.
  EXPECT_NEAR(s(std::sqrt(10. * 20.)), 2., 1e-12);
  EXPECT_NEAR(s(std::sqrt(20. * 40.)), 1., 1e-12);
}



// A table file: header line and comments skipped; a negative amplification
// is an error naming the file and its line; so are bad numbers, decreasing
// frequencies and a missing file.
TEST(SiteAmplification, TableFileErrors)
{
  const auto dir  = scratch("table");
  const auto file = (dir / "site.csv").string();
  std::ofstream(file) << "# a site function\nfrequency_Hz,amplification\n"
                         "0.5,1.0\n1.0,2.5\n\n2.0,3.0\n";
  const auto s = SiteAmplification::read_table(file);
  EXPECT_NEAR(s(1.), 2.5, 1e-12);
  EXPECT_NEAR(s(std::sqrt(2.)), std::sqrt(2.5 * 3.), 1e-12);

  std::ofstream(file) << "f A\n0.5 1.0\n1.0 -2.5\n2.0 3.0\n";
  const std::string e1 = error_of([&] { SiteAmplification::read_table(file); });
  EXPECT_NE(e1.find(file
                    + ":3: amplification -2.5 is out of range; valid: "
                      "A >= 0"),
            std::string::npos)
    << e1;
  std::ofstream(file) << "0.5 1.0\n0.4 2.5\n";
  EXPECT_NE(error_of([&] {
              SiteAmplification::read_table(file);
            }).find(file + ":2: frequency 0.4 Hz does not increase"),
            std::string::npos);
  std::ofstream(file) << "0.5 1.0\n1.0 x\n";
  EXPECT_NE(error_of([&] {
              SiteAmplification::read_table(file);
            }).find(file + ":2:"),
            std::string::npos);
  EXPECT_NE(error_of([&] {
              SiteAmplification::read_table((dir / "none.csv").string());
            }).find("cannot open"),
            std::string::npos);
  fs::remove_all(dir);
}



// The SMSIM median PGA against BJF97 (generic rock, Vs30 = 620 m/s, the
// site of the crustal amplification) over 50 seeds for M 6-7.5 at Rjb
// 10-50 km: within the factor 1.5 with the default parameters
// (measured 0.71-1.27; the residual is the point source's 1/R spreading
// against BJF97's r^-0.778 and its magnitude scaling). With Atkinson &
// Silva's Q0 = 180 the ratio falls to 0.48 at M 6, 50 km (printed, not
// asserted). The seeds are fixed, so the medians are reproducible bit for
// bit; their sampling scatter (sigma_ln ~ 0.15 / sqrt(50) x 1.25 ~ 3 %)
// is what a different seed range would change.
TEST(Stochastic, MedianPgaAgainstBjf97)
{
  const auto start = std::chrono::steady_clock::now();
  for (const double q0 : {600., 180.})
    {
      StochasticParameters p;
      p.q0      = q0;
      double lo = 1e300, hi = 0.;
      for (const double m : {6., 6.5, 7., 7.5})
        for (const double r : {10e3, 30e3, 50e3})
          {
            p.magnitude    = m;
            p.distance     = r;
            const double s = median_pga(p, 50), b = bjf97_of(p);
            lo = std::min(lo, s / b);
            hi = std::max(hi, s / b);
            std::printf("Q0 %3.0f M %.1f Rjb %2.0f km: median PGA %.4f g, "
                        "BJF97 %.4f g, ratio %.3f\n",
                        q0,
                        m,
                        r / 1e3,
                        s,
                        b,
                        s / b);
            if (q0 == StochasticParameters().q0)
              {
                EXPECT_GT(s / b, 1. / 1.5);
                EXPECT_LT(s / b, 1.5);
              }
          }
      std::printf("Q0 %3.0f: ratios %.3f to %.3f\n", q0, lo, hi);
    }
  std::printf("1200 realisations in %.2f s\n",
              std::chrono::duration<double>(std::chrono::steady_clock::now()
                                            - start)
                .count());
}



// The quadratic mean of 50 realisations' Fourier amplitude spectra matches
// the target within 10 % in 0.5-10 Hz, in 1/3-octave bands. By construction
// each bin is the target times the normalised noise spectrum, whose power
// has expectation 1 and a spread of about 100 % per bin (|Z|^2 of a
// Gaussian is exponential-like). Neighbouring bins are correlated over
// about 1 / (window length ~ 20 s) = 0.05 Hz, so the 1/3-octave band at
// 0.5 Hz (0.12 Hz wide) holds ~2-3 independent values per seed: over 50
// seeds a relative standard error of the power of ~8 %, 4 % in amplitude
// (less at higher bands), and 10 % is ~2.5 standard errors at the lowest
// band. The scenario carries the
// Masada site function so that its peaks and cut are in the target too.
TEST(Stochastic, MeanSpectrumMatchesTarget)
{
  StochasticParameters p;
  p.magnitude = 7.;
  p.distance  = 20e3;
  p.site      = SiteAmplification::masada();
  SpectrumAverager averager(p, true);
  for (unsigned int s = 1; s <= 50; ++s)
    averager.add(simulate(p, s));
  // Bands centred on 0.5 2^(j/3) Hz up to 10.08 Hz (the last spans
  // 8.98-11.3 Hz).
  const auto b     = averager.bands(0.5, 10.1, 3);
  double     worst = 0.;
  for (std::size_t j = 0; j < b.frequency.size(); ++j)
    {
      const double e = b.mean[j] / b.target[j] - 1.;
      std::printf("%6.3f Hz: target %.4e g s, mean %.4e g s, %+.2f %%\n",
                  b.frequency[j],
                  b.target[j],
                  b.mean[j],
                  100. * e);
      worst = std::max(worst, std::abs(e));
    }
  EXPECT_EQ(b.frequency.size(), 14u);
  EXPECT_LT(worst, 0.10);
  std::printf("largest deviation in 0.5-10 Hz: %.2f %%\n", 100. * worst);
}



// The same seed gives the same record bit for bit; other seeds differ. The
// record's length is an FFT size; its amplitude spectrum is the target
// times the normalised noise (checked at one bin against the noise alone).
TEST(Stochastic, SeedsReproducible)
{
  StochasticParameters p;
  p.magnitude    = 6.5;
  p.distance     = 15e3;
  const Record a = simulate(p, 42), b = simulate(p, 42), c = simulate(p, 43);
  ASSERT_EQ(a.acceleration.size(), b.acceleration.size());
  EXPECT_TRUE(a.acceleration == b.acceleration);
  EXPECT_FALSE(a.acceleration == c.acceleration);
  EXPECT_EQ(fast_fft_size(a.acceleration.size()), a.acceleration.size());
  // The motion is inside its window: the pads hold < 1 % of the peak.
  const std::size_t front
    = static_cast<std::size_t>(0.5 * window_start(p) / p.dt);
  double pad_peak = 0.;
  for (std::size_t i = 0; i < front; ++i)
    pad_peak = std::max(pad_peak, std::abs(a.acceleration[i]));
  EXPECT_LT(pad_peak, 0.01 * a.peak());
  // A record with and without the site shares its noise: their spectra
  // differ by A(f) exactly.
  p.site             = SiteAmplification::masada();
  const auto with    = fourier_amplitude_spectrum(simulate(p, 7, true));
  const auto without = fourier_amplitude_spectrum(simulate(p, 7, false));
  for (const std::size_t k : {100u, 500u, 1000u})
    EXPECT_NEAR(with.amplitude[k],
                p.site(with.frequency[k]) * without.amplitude[k],
                1e-9 * without.amplitude[k]);
}



// The target spectrum's pieces: Brune's corner, the omega-squared rise and
// the 1/R and 1/sqrt(R) spreading.
TEST(Stochastic, TargetSpectrumPieces)
{
  StochasticParameters p;
  p.magnitude = 6.;
  // fc = 0.4906 beta (stress / M0)^(1/3), M0 = 10^18.05 N m.
  EXPECT_NEAR(corner_frequency(p),
              0.4906 * 3500. * std::cbrt(7e6 / std::pow(10., 18.05)),
              1e-12);
  EXPECT_NEAR(source_depth(p), 1e3 * std::pow(10., 0.85), 1e-9);
  EXPECT_NEAR(geometric_spreading(p, 20e3), 1. / 20., 1e-15);
  EXPECT_NEAR(geometric_spreading(p, 160e3), 1. / 40. * 0.5, 1e-15);
  // Far below fc, A ~ f^2 (the path and site terms change slowly there).
  p.crustal = CrustalAmplification::none;
  p.kappa   = 0.;
  p.q0      = 1e5;
  const double r
    = target_fourier_amplitude(p, 0.002) / target_fourier_amplitude(p, 0.001);
  EXPECT_NEAR(r, 4., 4e-4);
  // Boore & Joyner (1997) generic rock at its table points.
  EXPECT_NEAR(crustal_amplification(CrustalAmplification::generic_rock, 2.26),
              2.06,
              1e-12);
  EXPECT_NEAR(crustal_amplification(CrustalAmplification::generic_rock, 100.),
              4.0,
              1e-12);
}



// benchmarks/seismic-chain/synthetic: with ROCKDDA_SYNTHETIC_OUT set to a
// folder, write the data of the benchmark's plots and tables (skipped
// otherwise): the PGA of 50 seeds per M and Rjb for Q0 = 600 and 180, El
// Centro before and after the Masada site amplification, the Masada
// function as a table, and the error against cost of the seeds and the
// time step.
TEST(SyntheticBenchmark, Study)
{
  const char *out_env = std::getenv("ROCKDDA_SYNTHETIC_OUT");
  if (out_env == nullptr)
    GTEST_SKIP() << "set ROCKDDA_SYNTHETIC_OUT to write the benchmark data";
  const fs::path out(out_env);
  fs::create_directories(out);
  using clock              = std::chrono::steady_clock;
  const auto seconds_since = [](const clock::time_point t0) {
    return std::chrono::duration<double>(clock::now() - t0).count();
  };

  {
    std::ofstream f(out / "pga_grid.csv");
    f << "q0,magnitude,distance_km,seed,pga_g,bjf97_g\n";
    const auto t0 = clock::now();
    for (const double q0 : {600., 180.})
      for (const double m : {6., 6.5, 7., 7.5})
        for (const double r : {10e3, 30e3, 50e3})
          {
            StochasticParameters p;
            p.q0        = q0;
            p.magnitude = m;
            p.distance  = r;
            for (unsigned int s = 1; s <= 50; ++s)
              f << q0 << ',' << m << ',' << r / 1e3 << ',' << s << ','
                << simulate(p, s).peak() << ',' << bjf97_of(p) << '\n';
          }
    std::printf("grid: 1200 realisations in %.2f s\n", seconds_since(t0));
  }

  {
    const auto    site = SiteAmplification::masada();
    std::ofstream f(out / "masada_table.csv");
    f << "frequency_Hz,amplification\n";
    std::vector<double> fs;
    for (int k = 0; k <= 120; ++k)
      fs.push_back(0.05 * std::pow(600., k / 120.));
    for (const auto &m : SiteAmplification::masada_modes())
      fs.push_back(m.frequency);
    std::sort(fs.begin(), fs.end());
    for (const double x : fs)
      f << x << ',' << site(x) << '\n';
  }

  {
    const Record in = read_record(
      std::string(ROCKDDA_SHARED_DATA)
        + "/ground-motions/slammer/Imperial_Valley_1940_ELC-180.txt",
      0.01);
    const auto   t0 = clock::now();
    const Record amp
      = apply_site_amplification(in, SiteAmplification::masada());
    std::printf("El Centro (%zu samples) amplified in %.4f s: PGA %.4f -> "
                "%.4f g (x%.3f)\n",
                in.acceleration.size(),
                seconds_since(t0),
                in.peak(),
                amp.peak(),
                amp.peak() / in.peak());
    std::ofstream f(out / "el_centro.csv");
    f << "time_s,before_g,after_g\n";
    for (std::size_t i = 0; i < in.acceleration.size(); ++i)
      f << i * in.dt << ',' << in.acceleration[i] << ',' << amp.acceleration[i]
        << '\n';
    const auto    a = fourier_amplitude_spectrum(in);
    const auto    b = fourier_amplitude_spectrum(amp);
    std::ofstream g(out / "el_centro_fourier.csv");
    g << "frequency_Hz,before_g_s,after_g_s\n";
    for (std::size_t k = 1; k < a.frequency.size(); ++k)
      g << a.frequency[k] << ',' << a.amplitude[k] << ',' << b.amplitude[k]
        << '\n';
  }

  {
    std::ofstream f(out / "cost.csv");
    f << "knob,value,median_pga_g,error,seconds\n";
    StochasticParameters p;
    p.magnitude = 7.;
    p.distance  = 20e3;
    // Seeds: the scatter of the median of n seeds over 20 disjoint groups
    // (seeds 1..20n), as a standard deviation of ln(median).
    for (const unsigned int n : {5u, 10u, 20u, 50u, 100u})
      {
        std::vector<double> lm;
        const auto          t0 = clock::now();
        for (unsigned int g = 0; g < 20; ++g)
          {
            std::vector<double> pga;
            for (unsigned int s = 1; s <= n; ++s)
              pga.push_back(simulate(p, g * n + s).peak());
            lm.push_back(std::log(median(pga)));
          }
        const double seconds = seconds_since(t0) / 20. / n;
        double       mean = 0., var = 0.;
        for (const double x : lm)
          mean += x / lm.size();
        for (const double x : lm)
          var += (x - mean) * (x - mean) / (lm.size() - 1);
        f << "seeds," << n << ',' << std::exp(mean) << ',' << std::sqrt(var)
          << ',' << seconds << '\n';
      }
    // Time step: median of 200 seeds against dt = 0.00125 s (the noise
    // differs with dt, so the difference holds a sampling scatter of about
    // 0.9 %, the scatter of a 200-seed median, besides the effect of dt;
    // the time is per realisation).
    std::vector<std::pair<double, double>> rows;
    for (const double dt : {0.00125, 0.0025, 0.005, 0.01, 0.02})
      {
        p.dt            = dt;
        const auto   t0 = clock::now();
        const double m  = median_pga(p, 200);
        rows.emplace_back(m, seconds_since(t0) / 200.);
      }
    const double ref   = rows[0].first;
    const double dts[] = {0.00125, 0.0025, 0.005, 0.01, 0.02};
    for (std::size_t i = 0; i < rows.size(); ++i)
      f << "time step," << dts[i] << ',' << rows[i].first << ','
        << rows[i].first / ref - 1. << ',' << rows[i].second << '\n';
  }
}
