/**
 * @file
 * benchmarks/seismic-chain: accuracy against cost of the record chain's
 * knobs (response-spectrum sub-steps, resampling method), the BJF97 check
 * values and the filter's corner gain, printed as Markdown tables.
 *   seismic_chain [SLAMMER_DIR]
 * Exits 1 if a check of the issue fails.
 */
#include <rockdda/seismic/attenuation.h>
#include <rockdda/seismic/intensity.h>
#include <rockdda/seismic/processing.h>
#include <rockdda/seismic/record.h>
#include <rockdda/seismic/spectra.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <string>
#include <tuple>
#include <utility>

using namespace rockdda::seismic;

namespace
{
  /// Wall time of @p f in seconds (best of @p repeats).
  template <typename F>
  double
  seconds(F &&f, const int repeats = 3)
  {
    double best = 1e300;
    for (int r = 0; r < repeats; ++r)
      {
        const auto t0 = std::chrono::steady_clock::now();
        f();
        best = std::min(best,
                        std::chrono::duration<double>(
                          std::chrono::steady_clock::now() - t0)
                          .count());
      }
    return best;
  }

  /// A band-limited record (sines at 0.3-8 Hz in a sin^2 envelope) sampled
  /// at @p dt over 40 s: the exact values are known at any step.
  Record
  band_limited(const double dt)
  {
    Record r;
    r.name              = "band-limited";
    r.dt                = dt;
    const std::size_t n = static_cast<std::size_t>(std::llround(40. / dt)) + 1;
    const double      T = 40.;
    r.acceleration.resize(n);
    for (std::size_t i = 0; i < n; ++i)
      {
        const double t = i * dt, env = std::pow(std::sin(M_PI * t / T), 2);
        double       a = 0.;
        for (int k = 0; k < 10; ++k)
          a += std::sin(2. * M_PI * (0.3 + 0.77 * k) * t + k) / (1. + 0.3 * k);
        r.acceleration[i] = 0.1 * env * a;
      }
    return r;
  }

  double
  max_relative(const std::vector<double> &a, const std::vector<double> &b)
  {
    double e = 0.;
    for (std::size_t i = 0; i < a.size(); ++i)
      e = std::max(e, std::abs(a[i] / b[i] - 1.));
    return e;
  }
} // namespace



int
main(int argc, char **argv)
{
  const std::string dir
    = argc > 1 ? argv[1]
               : std::string(ROCKDDA_SHARED_DATA) + "/ground-motions/slammer";
  bool ok = true;

  // BJF97.
  std::printf("## BJF97 check values\n\n| M | Rjb (km) | Vs30 (m/s) | "
              "mechanism | rockdda PGA (g) | issue (g) | relative error |\n"
              "|---|---|---|---|---|---|---|\n");
  for (const auto &[m, r, ref] :
       {std::tuple{6., 10., 0.1948114}, std::tuple{7., 20., 0.2076427}})
    {
      Bjf97Scenario s;
      s.magnitude    = m;
      s.distance_km  = r;
      s.vs30         = 360.;
      const double p = bjf97_pga(s), e = std::abs(p / ref - 1.);
      ok = ok && e < 1e-6;
      std::printf("| %g | %g | 360 | unspecified | %.7f | %.7f | %.1e |\n",
                  m,
                  r,
                  p,
                  ref,
                  e);
    }

  // El Centro through the chain.
  RecordFileOptions o;
  o.format         = RecordFormat::one_column;
  o.dt             = 0.01;
  const Record raw = read_record(dir + "/Imperial_Valley_1940_ELC-180.txt", o);
  ProcessingOptions p;
  p.baseline_degree = 0;
  p.high_pass       = 0.1;
  p.low_pass        = 25.;
  Record       processed;
  const double t_process = seconds([&]() { processed = process(raw, p); }, 10);
  const auto   periods   = log_spaced_periods(0.01, 10., 200);
  std::printf("\n## El Centro 1940 (3949 samples, dt = 0.01 s): mean "
              "baseline, 0.1-25 Hz order 4, pads kept\n\n");
  const auto im0 = intensity_measures(raw), im = intensity_measures(processed);
  std::printf(
    "| | PGA (g) | PGV (m/s) | PGD (m) | Arias (m/s) | D5-95 (s) | "
    "final v (m/s) | final d (m) |\n|---|---|---|---|---|---|---|---|\n");
  for (const auto &[name, m] :
       {std::pair{"unprocessed", im0}, std::pair{"processed", im}})
    std::printf("| %s | %.5f | %.5f | %.5f | %.5f | %.3f | %.2e | %.2e |\n",
                name,
                m.pga,
                m.pgv,
                m.pgd,
                m.arias,
                m.d5_95,
                m.final_velocity,
                m.final_displacement);
  std::printf("\nProcessing (FFTW, %zu samples with pads): %.2f ms.\n",
              processed.acceleration.size(),
              1e3 * t_process);

  // Response spectrum sub-steps against the 64-sub-step spectrum.
  std::printf("\n## Response spectrum: sub-steps per sample against 64 "
              "(El Centro processed, 200 periods 0.01-10 s, 5 %%)\n\n"
              "| sub-steps | max relative PSA error | median | time (ms) |\n"
              "|---|---|---|---|\n");
  const auto reference = response_spectrum(processed, periods, 0.05, 64);
  for (const unsigned int m : {1u, 2u, 4u, 8u, 16u, 0u})
    {
      ResponseSpectrum s;
      const double     t = seconds(
        [&]() { s = response_spectrum(processed, periods, 0.05, m); });
      std::vector<double> e(periods.size());
      for (std::size_t i = 0; i < e.size(); ++i)
        e[i] = std::abs(
          s.pseudo_acceleration[i] / reference.pseudo_acceleration[i] - 1.);
      const double emax = *std::max_element(e.begin(), e.end());
      std::nth_element(e.begin(), e.begin() + e.size() / 2, e.end());
      const std::string label
        = m == 0 ? std::string("0 (auto, T/20)") : std::to_string(m);
      std::printf("| %s | %.2e | %.2e | %.1f |\n",
                  label.c_str(),
                  emax,
                  e[e.size() / 2],
                  1e3 * t);
    }
  const double psa0
    = response_spectrum(processed, {1e-3}, 0.05, 1).pseudo_acceleration[0];
  std::printf("\nPSA(T = 1 ms) / PGA - 1 = %.1e (issue: within 1e-3).\n",
              psa0 / im.pga - 1.);
  ok = ok && std::abs(psa0 / im.pga - 1.) < 1e-3;

  // Resampling: a band-limited record sampled at 0.02 s, resampled to
  // 0.005 s, against the same record sampled at 0.005 s.
  std::printf("\n## Resampling 0.02 s -> 0.005 s against exact samples "
              "(band-limited record, 0.3-7.2 Hz, 40 s)\n\n"
              "| method | max sample error / PGA | max PSA error (T 0.02-10 "
              "s) | time (ms) |\n|---|---|---|---|\n");
  const Record coarse = band_limited(0.02), fine = band_limited(0.005);
  const auto   rp    = log_spaced_periods(0.02, 10., 100);
  const auto   exact = response_spectrum(fine, rp, 0.05, 1);
  for (const auto method : {ResampleMethod::fourier, ResampleMethod::linear})
    {
      Record       r;
      const double t
        = seconds([&]() { r = resample(coarse, 0.005, method); }, 10);
      double e = 0.;
      for (std::size_t i = 0; i < fine.acceleration.size(); ++i)
        e = std::max(e, std::abs(r.acceleration[i] - fine.acceleration[i]));
      const auto   s = response_spectrum(r, rp, 0.05, 1);
      const double es
        = max_relative(s.pseudo_acceleration, exact.pseudo_acceleration);
      std::printf("| %s | %.2e | %.2e | %.2f |\n",
                  method == ResampleMethod::fourier ? "Fourier" : "linear",
                  e / fine.peak(),
                  es,
                  1e3 * t);
    }

  // Corner gain measured on a filtered sine.
  std::printf(
    "\n## Butterworth gain at the corner (sine at fc, 200 s, "
    "middle third)\n\n| filter | order | gain (dB) | error vs -3.0103 "
    "dB |\n|---|---|---|---|\n");
  for (const bool high : {true, false})
    for (const unsigned int n : {2u, 4u, 8u})
      {
        const double fc = high ? 0.1 : 5.;
        Record       r;
        r.dt = 0.005;
        r.acceleration.resize(40001);
        for (std::size_t i = 0; i < r.acceleration.size(); ++i)
          r.acceleration[i] = std::sin(2. * M_PI * fc * i * r.dt);
        filter_acausal(r, high ? fc : 0., high ? 0. : fc, n, false);
        double a = 0.;
        for (std::size_t i = 13334; i < 26667; ++i)
          a = std::max(a, std::abs(r.acceleration[i]));
        const double db = 20. * std::log10(a);
        ok              = ok && std::abs(db + 3.0103) < 0.1;
        std::printf("| %s-pass %g Hz | %u | %.4f | %.1e |\n",
                    high ? "high" : "low",
                    fc,
                    n,
                    db,
                    std::abs(db + 3.0103));
      }
  std::printf("\n%s\n", ok ? "all checks pass" : "A CHECK FAILED");
  return ok ? 0 : 1;
}
