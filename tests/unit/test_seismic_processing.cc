/**
 * @file
 * The seismic input chain (issue 14, items 1-3): record readers and units,
 * intensity measures, FFTW spectra, the Nigam-Jennings response spectrum,
 * baseline correction, acausal Butterworth filters, resampling and BJF97.
 */
#include <rockdda/io/error.h>
#include <rockdda/seismic/attenuation.h>
#include <rockdda/seismic/fft.h>
#include <rockdda/seismic/intensity.h>
#include <rockdda/seismic/processing.h>
#include <rockdda/seismic/record.h>
#include <rockdda/seismic/spectra.h>

#include <gtest/gtest.h>

#include "test_files.h"
#include <cmath>
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

  constexpr double g_si = 9.80665;



  /// a(t) = amplitude sin(2 pi f t) (g), n samples at dt.
  Record
  sine(const double      amplitude,
       const double      f,
       const double      dt,
       const std::size_t n)
  {
    Record r;
    r.name = "sine";
    r.dt   = dt;
    r.acceleration.resize(n);
    for (std::size_t i = 0; i < n; ++i)
      r.acceleration[i] = amplitude * std::sin(2. * M_PI * f * i * dt);
    return r;
  }

  /// A deterministic broadband record: a sum of sines of incommensurate
  /// frequencies in a smooth envelope, plus an offset that makes it drift.
  Record
  broadband(const double dt, const std::size_t n, const double offset = 0.)
  {
    Record r;
    r.name = "broadband";
    r.dt   = dt;
    r.acceleration.resize(n);
    const double T = dt * (n - 1);
    for (std::size_t i = 0; i < n; ++i)
      {
        const double t   = i * dt;
        const double env = std::pow(std::sin(M_PI * t / T), 2);
        double       a   = 0.;
        for (int k = 1; k <= 12; ++k)
          a += std::sin(2. * M_PI * 0.37 * k * std::sqrt(k) * t + k) / k;
        r.acceleration[i] = 0.2 * env * a + offset;
      }
    return r;
  }
} // namespace



// ---------------------------------------------------------------------------
// BJF97

TEST(SeismicBjf97, IssueValues)
{
  // The issue's values, to 1e-6 relative (the formula in double precision
  // is exact to ~1e-15; the references are given to 7 digits, so 1e-6
  // leaves their rounding, at most 5e-8 / 0.19 = 2.6e-7).
  Bjf97Scenario s;
  s.magnitude   = 6.;
  s.distance_km = 10.;
  s.vs30        = 360.;
  s.mechanism   = FaultMechanism::unspecified;
  EXPECT_NEAR(bjf97_pga(s) / 0.1948114 - 1., 0., 1e-6) << bjf97_pga(s);
  s.magnitude   = 7.;
  s.distance_km = 20.;
  EXPECT_NEAR(bjf97_pga(s) / 0.2076427 - 1., 0., 1e-6) << bjf97_pga(s);
  EXPECT_TRUE(bjf97_warnings(s).empty());
  // One sigma multiplies by exp(0.495); mechanisms by exp(b1 difference).
  Bjf97Scenario up = s;
  up.n_sigma       = 1.;
  EXPECT_NEAR(bjf97_pga(up) / bjf97_pga(s), std::exp(0.495), 1e-12);
  Bjf97Scenario rv = s;
  rv.mechanism     = FaultMechanism::reverse;
  EXPECT_NEAR(bjf97_pga(rv) / bjf97_pga(s), std::exp(-0.117 + 0.242), 1e-12);
}

TEST(SeismicBjf97, WarnsOutsideItsData)
{
  Bjf97Scenario s;
  s.magnitude = 8.5;
  auto w      = bjf97_warnings(s);
  ASSERT_EQ(w.size(), 1u);
  EXPECT_NE(w[0].find("magnitude M = 8.5"), std::string::npos) << w[0];
  EXPECT_NE(w[0].find("4 <= M <= 8"), std::string::npos) << w[0];
  s.magnitude   = 3.5;
  s.distance_km = 100.;
  w             = bjf97_warnings(s);
  ASSERT_EQ(w.size(), 2u);
  EXPECT_NE(w[1].find("Rjb <= 80 km"), std::string::npos) << w[1];
  s.magnitude   = 4.;
  s.distance_km = 80.;
  EXPECT_TRUE(bjf97_warnings(s).empty());
}

// ---------------------------------------------------------------------------
// Intensity measures

TEST(SeismicIntensity, SineAgainstClosedForm)
{
  // a = A sin(2 pi f t) over whole cycles: v = A g/(2 pi f) (1 - cos), so
  // PGV = A g / (pi f); Arias = pi/(2g) (A g)^2 T/2. The trapezoidal rule
  // errs by O((2 pi f dt)^2 / 12) = 3e-5 here (f = 1 Hz, dt = 5 ms); 1e-4.
  const double A = 0.3, f = 1., dt = 0.005, T = 10.;
  const Record r  = sine(A, f, dt, static_cast<std::size_t>(T / dt) + 1);
  const auto   im = intensity_measures(r);
  EXPECT_NEAR(im.pga / A, 1., 1e-9);
  EXPECT_NEAR(im.pgv / (A * g_si / (M_PI * f)), 1., 1e-4);
  EXPECT_NEAR(im.arias / (M_PI / (2. * g_si) * std::pow(A * g_si, 2) * T / 2.),
              1.,
              1e-4);
  // The Husid function of a steady sine is nearly linear: D5-95 = 0.9 T
  // within a quarter period's ripple.
  EXPECT_NEAR(im.d5_95, 0.9 * T, 0.25 / f);
  // Displacement drifts: d = A g/(2 pi f) t - ... : final = A g T/(2 pi f).
  EXPECT_NEAR(im.final_displacement / (A * g_si * T / (2. * M_PI * f)),
              1.,
              1e-3);
}

// ---------------------------------------------------------------------------
// Spectra

TEST(SeismicSpectra, FourierAmplitudeOfASine)
{
  // A bin-centred sine of amplitude A over N samples: |X| dt = A N dt / 2.
  const std::size_t n  = 1000;
  const double      dt = 0.01, f = 5. / (n * dt) * 10.; // bin 50
  const Record      r = sine(0.2, f, dt, n);
  const auto        s = fourier_amplitude_spectrum(r);
  ASSERT_EQ(s.frequency.size(), n / 2 + 1); // 1000 = 2^3 5^3 is fast
  EXPECT_NEAR(s.frequency[50], f, 1e-12);
  EXPECT_NEAR(s.amplitude[50], 0.2 * n * dt / 2., 1e-10);
  EXPECT_NEAR(s.amplitude[49], 0., 1e-10);
  // FFTW round trip.
  const auto X = forward_real_fft(r.acceleration, n);
  const auto x = inverse_real_fft(X, n);
  for (std::size_t i = 0; i < n; ++i)
    ASSERT_NEAR(x[i], r.acceleration[i], 1e-14);
}

TEST(SeismicSpectra, ShortPeriodTendsToPga)
{
  // As T -> 0 the oscillator follows the ground: w^2 u -> -a, so PSA ->
  // PGA. The exact recursion leaves w^2 u = -a + 2 zeta a'/w, i.e. a
  // relative excess of about 2 zeta |da| / (w dt PGA) <= 2e-4 at T = 1 ms
  // and dt = 10 ms; within 1e-3 (issue).
  const Record r   = broadband(0.01, 3000);
  const auto   rs  = response_spectrum(r, {1e-4, 1e-3}, 0.05);
  const double pga = r.peak();
  for (const double psa : rs.pseudo_acceleration)
    EXPECT_NEAR(psa / pga, 1., 1e-3) << psa << " " << pga;
}

TEST(SeismicSpectra, HarmonicSteadyStateMatchesClosedForm)
{
  // a = A sin(W t): after the transient (it decays as exp(-zeta w t):
  // e^-18 after the first 150 s at T = 2.5 s) the relative displacement has
  // the amplitude
  // A g / w^2 / sqrt((1 - r^2)^2 + (2 zeta r)^2), r = W/w. Errors: the
  // piecewise-linear input has a fundamental smaller by (W dt)^2/12 = 8e-5
  // and peaks between samples are missed by up to (W dt)^2/8 = 1.2e-4
  // (W = 2 pi, dt = 5 ms): 1e-3 is well inside the issue's 1 %.
  const double A = 0.2, zeta = 0.05, dt = 0.005, duration = 200.;
  for (const double period : {0.3, 1.0, 2.5})
    {
      const double W = 2. * M_PI * 1.0, w = 2. * M_PI / period, q = W / w;
      const Record rec
        = sine(A, 1.0, dt, static_cast<std::size_t>(duration / dt) + 1);
      const auto r = oscillator_response(rec, period, zeta, 1);
      double     u = 0.;
      for (std::size_t i = r.displacement.size() * 3 / 4;
           i < r.displacement.size();
           ++i)
        u = std::max(u, std::abs(r.displacement[i]));
      const double exact
        = A * g_si / (w * w)
          / std::sqrt(std::pow(1. - q * q, 2) + std::pow(2. * zeta * q, 2));
      EXPECT_NEAR(u / exact, 1., 1e-3) << "T = " << period;
    }
}

TEST(SeismicSpectra, SubdivisionsOnlySharpenPeaks)
{
  // The recursion is exact for the piecewise-linear input: values at the
  // common sample times agree to round-off for any number of sub-steps.
  const Record r  = broadband(0.02, 1500);
  const auto   r1 = oscillator_response(r, 0.15, 0.05, 1);
  const auto   r4 = oscillator_response(r, 0.15, 0.05, 4);
  double       m  = 0.;
  for (std::size_t i = 0; i < r1.displacement.size(); ++i)
    m = std::max(m, std::abs(r1.displacement[i] - r4.displacement[4 * i]));
  EXPECT_LT(m, 1e-12);
  const auto s1 = response_spectrum(r, {0.05}, 0.05, 1);
  const auto s8 = response_spectrum(r, {0.05}, 0.05, 8);
  EXPECT_GE(s8.displacement[0], s1.displacement[0]);
}

// ---------------------------------------------------------------------------
// Processing

TEST(SeismicProcessing, ButterworthIsMinus3DbAtTheCorner)
{
  // Order n here is the gain of an order-n Butterworth, 1/sqrt(1 +
  // (f/fc)^(2n)), applied with zero phase: -10 log10(2) = -3.0103 dB at fc.
  for (const unsigned int n : {1u, 2u, 4u, 8u})
    {
      EXPECT_NEAR(20. * std::log10(low_pass_gain(2., 2., n)), -3.0103, 1e-4);
      EXPECT_NEAR(20. * std::log10(high_pass_gain(0.1, 0.1, n)), -3.0103, 1e-4);
    }
  // Measured on a filtered signal: a long sine at the corner comes out at
  // -3 dB within 0.1 dB (issue). Leakage of the finite sine across the
  // gain's slope and the zero pads perturbs the amplitude in the middle by
  // far less than 0.1 dB (measured ~1e-3 dB).
  for (const unsigned int n : {2u, 4u})
    for (const bool high : {false, true})
      {
        const double fc = high ? 0.5 : 5.;
        Record       r  = sine(1., fc, 0.005, 40001); // 200 s
        filter_acausal(r, high ? fc : 0., high ? 0. : fc, n, false);
        double a = 0.;
        for (std::size_t i = 15000; i < 25000; ++i)
          a = std::max(a, std::abs(r.acceleration[i]));
        EXPECT_NEAR(20. * std::log10(a), -3.0103, 0.1)
          << (high ? "high" : "low") << "-pass, order " << n;
      }
}

TEST(SeismicProcessing, ZeroPhaseFilterIntroducesNoLag)
{
  // The cross-correlation of input and output peaks at zero shift: the
  // gains are real, so no frequency is delayed.
  const Record in  = broadband(0.01, 4000);
  Record       out = in;
  filter_acausal(out, 0.2, 5., 4, false);
  int    best = 99;
  double cmax = -1e300;
  for (int shift = -50; shift <= 50; ++shift)
    {
      double c = 0.;
      for (std::size_t i = 100; i + 100 < in.acceleration.size(); ++i)
        c += in.acceleration[i] * out.acceleration[i + shift];
      if (c > cmax)
        {
          cmax = c;
          best = shift;
        }
    }
  EXPECT_EQ(best, 0);
}

TEST(SeismicProcessing, BaselineCorrectionZeroesFinalVelocity)
{
  // A record with a constant offset drifts (v grows by offset g T); after
  // the correction of each degree the final velocity is below 1e-6 PGV
  // (the constraint holds to round-off, ~1e-13 relative).
  for (const unsigned int degree : {0u, 1u, 2u})
    {
      Record r = broadband(0.01, 4000, 0.003);
      EXPECT_GT(std::abs(intensity_measures(r).final_velocity),
                0.1 * intensity_measures(r).pgv);
      remove_baseline(r, degree);
      const auto im = intensity_measures(r);
      EXPECT_LT(std::abs(im.final_velocity), 1e-6 * im.pgv)
        << "degree " << degree;
    }
}

TEST(SeismicProcessing, FilterPaddingFollowsBooreAndBommer)
{
  // T_pad = 1.5 n / fc in total, half at each end.
  EXPECT_DOUBLE_EQ(filter_padding(0.1, 25., 4), 30.);
  EXPECT_DOUBLE_EQ(filter_padding(0., 2., 2), 0.75);
  Record       r = broadband(0.01, 1000);
  const double p = filter_acausal(r, 0.1, 0., 4, true);
  EXPECT_DOUBLE_EQ(p, 30.);
  EXPECT_EQ(r.acceleration.size(), 1000u + 2 * 3000u);
}

TEST(SeismicProcessing, FourierResamplingIsExactForBandLimitedRecords)
{
  // A band-limited record (all energy well below 25 Hz) resampled 0.01 ->
  // 0.005 -> 0.01 s returns to itself, and the 0.005 s samples agree with
  // the analytic signal. The round trip loses only the interpolant's
  // ringing into the zero pad beyond the record's end (cut at the last
  // sample): measured 1.5e-8 of the peak; 1e-7.
  const Record r  = broadband(0.01, 2001);
  const Record up = resample(r, 0.005, ResampleMethod::fourier);
  ASSERT_EQ(up.acceleration.size(), 4001u);
  const Record exact = broadband(0.005, 4001);
  double       e1 = 0., e2 = 0.;
  for (std::size_t i = 0; i < up.acceleration.size(); ++i)
    e1 = std::max(e1, std::abs(up.acceleration[i] - exact.acceleration[i]));
  const Record back = resample(up, 0.01, ResampleMethod::fourier);
  ASSERT_EQ(back.acceleration.size(), 2001u);
  for (std::size_t i = 0; i < back.acceleration.size(); ++i)
    e2 = std::max(e2, std::abs(back.acceleration[i] - r.acceleration[i]));
  EXPECT_LT(e1, 1e-3 * r.peak()); // broadband() is not strictly band-limited
  EXPECT_LT(e2, 1e-7 * r.peak());
  // Linear resampling reproduces the samples it keeps.
  const Record lin = resample(r, 0.02, ResampleMethod::linear);
  EXPECT_DOUBLE_EQ(lin.acceleration[7], r.acceleration[14]);
  EXPECT_NE(error_of([&]() {
              resample(r, 0.0123457, ResampleMethod::fourier);
            }).find("ratio of integers"),
            std::string::npos);
}

// ---------------------------------------------------------------------------
// Readers

TEST(SeismicRecords, ReadsEachFormatAndUnit)
{
  const auto dir = scratch("formats");
  write_file(dir / "one.txt", "# SLAMMER\n0.1\n-0.2\n0.05\n");
  write_file(dir / "two.csv", "time_s,acc\n0,98.0665\n0.02,-196.133\n0.04,0\n");
  write_file(dir / "multi.txt", "0 1 0.5\n0.01 2 -0.25\n0.02 3 0.125\n");
  write_file(dir / "r.AT2",
             "PEER NGA STRONG MOTION DATABASE RECORD\n"
             "TEST EVENT, STATION, 000\n"
             "ACCELERATION TIME HISTORY IN UNITS OF G\n"
             "NPTS=     5, DT=   .0050 SEC\n"
             "  .1000000E+00 -.2000000E+00  .3000000E+00\n"
             "  .0000000E+00 -.1000000E-01\n");
  write_file(dir / "old.at2",
             "PEER STRONG MOTION DATABASE RECORD\n"
             "EVENT\n"
             "ACCELEROGRAM IN UNITS OF CM/S/S\n"
             " 3 .0100 NPTS, DT\n"
             "9.80665 0 -19.6133\n");

  RecordFileOptions o;
  o.dt         = 0.01;
  const auto a = read_record((dir / "one.txt").string(), o);
  EXPECT_EQ(a.acceleration.size(), 3u);
  EXPECT_DOUBLE_EQ(a.dt, 0.01);
  EXPECT_DOUBLE_EQ(a.acceleration[1], -0.2);

  o.unit       = AccelerationUnit::centimetre_per_second2;
  const auto b = read_record((dir / "two.csv").string(), o);
  EXPECT_NEAR(b.dt, 0.02, 1e-15);
  EXPECT_NEAR(b.acceleration[0], 0.1, 1e-15);
  EXPECT_NEAR(b.acceleration[1], -0.2, 1e-15);

  o.unit       = AccelerationUnit::metre_per_second2;
  o.column     = 3;
  const auto c = read_record((dir / "multi.txt").string(), o);
  EXPECT_NEAR(c.acceleration[1], -0.25 / g_si, 1e-15);

  o.unit       = AccelerationUnit::g;
  o.column     = 2;
  const auto d = read_record((dir / "r.AT2").string(), o);
  EXPECT_EQ(d.acceleration.size(), 5u);
  EXPECT_DOUBLE_EQ(d.dt, 0.005);
  EXPECT_DOUBLE_EQ(d.acceleration[4], -0.01);

  o.unit       = AccelerationUnit::centimetre_per_second2;
  const auto e = read_record((dir / "old.at2").string(), o);
  EXPECT_DOUBLE_EQ(e.dt, 0.01);
  EXPECT_NEAR(e.acceleration[2], -0.02, 1e-15);
  // The old reader keeps working.
  EXPECT_EQ(read_record((dir / "one.txt").string(), 0.02).acceleration.size(),
            3u);
}

TEST(SeismicRecords, ErrorsNameFileAndLine)
{
  const auto dir = scratch("errors");
  write_file(dir / "nan.txt", "0.1\n0.2\nnan\n0.3\n");
  write_file(dir / "bad.AT2",
             "PEER NGA STRONG MOTION DATABASE RECORD\nEV\n"
             "ACCELERATION TIME HISTORY IN UNITS OF G\n"
             "NUMBER OF POINTS 4000\n0.1 0.2\n");
  write_file(dir / "short.AT2",
             "PEER NGA STRONG MOTION DATABASE RECORD\nEV\n"
             "ACCELERATION TIME HISTORY IN UNITS OF G\n"
             "NPTS=  4, DT= .01 SEC\n0.1 0.2\n0.3\n");
  write_file(dir / "vel.AT2",
             "PEER NGA STRONG MOTION DATABASE RECORD\nEV\n"
             "VELOCITY TIME HISTORY IN UNITS OF CM/S\n"
             "NPTS=  2, DT= .01 SEC\n0.1 0.2\n");
  write_file(dir / "uneven.csv", "0 0.1\n0.01 0.2\n0.03 0.1\n0.04 0\n");
  RecordFileOptions o;
  o.dt           = 0.01;
  const auto err = [&](const std::string &f) {
    return error_of([&]() { read_record((dir / f).string(), o); });
  };
  EXPECT_NE(err("nan.txt").find("nan.txt:3: 'nan' is not a finite"),
            std::string::npos)
    << err("nan.txt");
  EXPECT_NE(err("bad.AT2").find("bad.AT2:4: expected the PEER AT2 header"),
            std::string::npos)
    << err("bad.AT2");
  EXPECT_NE(err("short.AT2").find("NPTS = 4"), std::string::npos)
    << err("short.AT2");
  EXPECT_NE(err("vel.AT2").find("vel.AT2:3:"), std::string::npos)
    << err("vel.AT2");
  EXPECT_NE(err("uneven.csv")
              .find("uneven.csv:3: the time column is not "
                    "uniform"),
            std::string::npos)
    << err("uneven.csv");
  // An AT2 file in g read with Units = cm/s^2: line 3 and the key named.
  write_file(dir / "g.AT2",
             "PEER NGA STRONG MOTION DATABASE RECORD\nEV\n"
             "ACCELERATION TIME HISTORY IN UNITS OF G\n"
             "NPTS=  2, DT= .01 SEC\n0.1 0.2\n");
  o.unit = AccelerationUnit::centimetre_per_second2;
  EXPECT_NE(err("g.AT2").find("g.AT2:3: the file states units 'g'"),
            std::string::npos)
    << err("g.AT2");
}

TEST(SeismicRecords, ImplausiblePgaForItsUnitsIsRejected)
{
  // El Centro's 0.31 g written in cm/s^2 (307 cm/s^2) and read as g.
  Record r;
  r.name              = "cm.txt";
  r.dt                = 0.01;
  r.acceleration      = {0., 306.8, -120.};
  const std::string e = error_of([&]() {
    check_units_plausible(r,
                          AccelerationUnit::g,
                          "cm.txt",
                          "Ground motion/Units");
  });
  EXPECT_NE(e.find("cm.txt: PGA 306.8 g"), std::string::npos) << e;
  EXPECT_NE(e.find("'Ground motion/Units'"), std::string::npos) << e;
  EXPECT_NE(e.find("0.3128 g if the file were in cm/s^2"), std::string::npos)
    << e;
  // The same file read as cm/s^2 is plausible.
  scale(r, factor_to_g(AccelerationUnit::centimetre_per_second2));
  EXPECT_EQ(check_units_plausible(
              r, AccelerationUnit::centimetre_per_second2, "cm.txt", "U"),
            "");
  // A record in g read as cm/s^2 is tiny: a warning.
  Record tiny = r;
  scale(tiny, 1e-3);
  EXPECT_NE(check_units_plausible(
              tiny, AccelerationUnit::centimetre_per_second2, "x.txt", "U")
              .find("below 1e-3 g"),
            std::string::npos);
}

TEST(SeismicRecords, SlammerStepFromRecordsCsv)
{
  // The SLAMMER library lists each one-column file's dt in records.csv.
  const std::string dir
    = std::string(ROCKDDA_SHARED_DATA) + "/ground-motions/slammer/";
  unsigned int line = 0;
  EXPECT_DOUBLE_EQ(listed_time_step(dir + "Chi-Chi_Taiwan_1999_TCU068-090.txt",
                                    line),
                   0.005);
  EXPECT_EQ(line, 3u);
  EXPECT_DOUBLE_EQ(listed_time_step(dir + "Imperial_Valley_1940_ELC-180.txt",
                                    line),
                   0.01);
  EXPECT_EQ(listed_time_step(dir + "not_listed.txt", line), 0.);
  const auto tmp = scratch("unlisted");
  EXPECT_EQ(listed_time_step((tmp / "a.txt").string(), line), 0.);
}
