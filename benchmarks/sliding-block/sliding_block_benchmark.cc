/**
 * @file
 * Sliding-block benchmark: error against wall time while sweeping the time
 * step, for the harmonic case (closed form) and one SLAMMER record (fine-step
 * reference), and the throughput of the 90-case SLAMMER suite.
 *
 *   sliding_block_benchmark OUTPUT_DIR
 *
 * Writes OUTPUT_DIR/results.csv and OUTPUT_DIR/suite.csv. Times are medians
 * of several repetitions (steady_clock).
 */
#include <rockdda/analytical/newmark.h>
#include <rockdda/io/output.h>
#include <rockdda/seismic/record.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <fstream>
#include <iostream>
#include <sstream>
#include <string>
#include <vector>

using namespace rockdda;

namespace
{
  /// Median wall time (s) of @p repeats calls of f, and f's last result.
  template <typename F>
  double
  median_time(const unsigned int repeats, F &&f)
  {
    std::vector<double> t;
    for (unsigned int r = 0; r < repeats; ++r)
      {
        const auto start = std::chrono::steady_clock::now();
        f();
        t.push_back(std::chrono::duration<double>(
                      std::chrono::steady_clock::now() - start)
                      .count());
      }
    std::sort(t.begin(), t.end());
    return t[t.size() / 2];
  }

  const char *
  method_name(const analytical::NewmarkOptions::EventLocation e)
  {
    return e == analytical::NewmarkOptions::EventLocation::within_step
             ? "within-step"
             : "at-samples";
  }

  /// A record sampled at @p dt from @p source (linear interpolation).
  seismic::Record
  resample(const seismic::Record &source, const double dt)
  {
    seismic::Record r;
    r.name = source.name;
    r.dt   = dt;
    const auto n
      = static_cast<std::size_t>(std::floor(source.duration() / dt + 1e-9)) + 1;
    for (std::size_t i = 0; i < n; ++i)
      r.acceleration.push_back(source.at(i * dt));
    return r;
  }
} // namespace



int
main(int argc, char **argv)
{
  const std::string         out_dir = argc > 1 ? argv[1] : ".";
  const std::string         data    = ROCKDDA_SHARED_DATA;
  const std::vector<double> dts     = {1e-5,
                                       2e-5,
                                       5e-5,
                                       1e-4,
                                       2e-4,
                                       5e-4,
                                       1e-3,
                                       2e-3,
                                       5e-3,
                                       1e-2,
                                       2e-2,
                                       5e-2,
                                       1e-1};
  const std::vector<analytical::NewmarkOptions::EventLocation> methods
    = {analytical::NewmarkOptions::EventLocation::within_step,
       analytical::NewmarkOptions::EventLocation::at_samples};

  io::CsvWriter csv;
  csv.record(
    {"case", "method", "dt_s", "relative_error", "wall_time_s", "steps"});

  // Harmonic: a = 0.5 g sin(2 pi t), ky = 0.2 g, 10 s (10 cycles).
  {
    const double A = 0.5, omega = 2. * M_PI, ky = 0.2, T = 10.;
    const double exact
      = 9.80665 * analytical::harmonic_sliding_displacement(A, omega, ky, T);
    for (const auto method : methods)
      for (const double dt : dts)
        {
          seismic::Record rec;
          rec.name     = "harmonic";
          rec.dt       = dt;
          const auto n = static_cast<std::size_t>(std::llround(T / dt)) + 1;
          for (std::size_t i = 0; i < n; ++i)
            rec.acceleration.push_back(A * std::sin(omega * i * dt));
          analytical::NewmarkOptions o;
          o.ky              = ky;
          o.event_location  = method;
          o.output_interval = T; // keep the history small
          analytical::NewmarkResult r;
          const double              t = median_time(dt < 1e-4 ? 3 : 7, [&]() {
            r = analytical::newmark_sliding(rec, o);
          });
          const double err = std::abs(r.final_displacement - exact) / exact;
          csv.field("harmonic").field(method_name(method)).number(dt);
          csv.number(err).number(t).number(r.n_steps).end_record();
          std::cout << "harmonic " << method_name(method) << " dt " << dt
                    << " error " << err << " time " << t << " s\n";
        }
  }

  // One SLAMMER record: Kobe 1995 TAK-090 scaled to 0.5 g, ky = 0.1 g.
  // Reference: within-step events, dt = 1e-6 s on the linearly interpolated
  // record. Coarser steps resample the record (the input itself then loses
  // detail, which is part of the error a user trades).
  {
    auto rec = seismic::read_record(
      data + "/ground-motions/slammer/Kobe_Japan_1995_TAK-090.txt", 0.01);
    seismic::scale_to_pga(rec, 0.5);
    analytical::NewmarkOptions o;
    o.ky              = 0.1;
    o.output_interval = 1e9;
    o.time_step       = 1e-6;
    const double ref  = analytical::newmark_sliding(rec, o).final_displacement;
    std::cout << "Kobe reference displacement " << ref << " m\n";
    for (const auto method : methods)
      for (const double dt : dts)
        {
          const seismic::Record input   = dt > rec.dt ? resample(rec, dt) : rec;
          analytical::NewmarkOptions oo = o;
          oo.time_step                  = dt > rec.dt ? 0. : dt;
          oo.event_location             = method;
          analytical::NewmarkResult r;
          const double              t = median_time(dt < 1e-4 ? 3 : 7, [&]() {
            r = analytical::newmark_sliding(input, oo);
          });
          const double err = std::abs(r.final_displacement - ref) / ref;
          csv.field("kobe").field(method_name(method)).number(dt);
          csv.number(err).number(t).number(r.n_steps).end_record();
          std::cout << "kobe " << method_name(method) << " dt " << dt
                    << " error " << err << " time " << t << " s\n";
        }
  }
  io::OutputDirectory(out_dir).write("results.csv", csv.text());

  // Throughput of the whole 90-case SLAMMER suite (both polarities).
  {
    std::ifstream in(data
                     + "/ground-motions/slammer/rigid_newmark_reference.csv");
    std::string   line;
    std::getline(in, line);
    struct Case
    {
      seismic::Record record;
      double          ky;
    };
    std::vector<Case> cases;
    std::ifstream     meta(data + "/ground-motions/slammer/records.csv");
    std::vector<std::pair<std::string, double>> dt_of;
    std::getline(meta, line);
    while (std::getline(meta, line))
      {
        // file is the first field, dt_s the second-last one.
        const auto first = line.find(',');
        const auto last  = line.rfind(',');
        const auto prev  = line.rfind(',', last - 1);
        dt_of.emplace_back(line.substr(0, first),
                           std::stod(line.substr(prev + 1, last - prev - 1)));
      }
    while (std::getline(in, line))
      {
        std::stringstream s(line);
        std::string       file, pga, ky;
        std::getline(s, file, ',');
        std::getline(s, pga, ',');
        std::getline(s, ky, ',');
        double dt = 0.;
        for (const auto &[f, d] : dt_of)
          if (f == file)
            dt = d;
        Case c{seismic::read_record(data + "/ground-motions/slammer/" + file,
                                    dt),
               std::stod(ky)};
        seismic::scale_to_pga(c.record, std::stod(pga));
        cases.push_back(std::move(c));
      }
    analytical::NewmarkOptions o;
    o.event_location   = analytical::NewmarkOptions::EventLocation::at_samples;
    o.output_interval  = 1e9;
    double        sink = 0.;
    const double  t    = median_time(7, [&]() {
      for (const auto &c : cases)
        for (const double sign : {1., -1.})
          {
            seismic::Record r = c.record;
            seismic::scale(r, sign);
            o.ky = c.ky;
            sink += analytical::newmark_sliding(r, o).final_displacement;
          }
    });
    io::CsvWriter suite;
    suite.record(
      {"cases", "runs", "median_wall_time_s", "cases_per_s", "runs_per_s"});
    suite.number(cases.size()).number(2. * cases.size()).number(t);
    suite.number(cases.size() / t).number(2. * cases.size() / t).end_record();
    io::OutputDirectory(out_dir).write("suite.csv", suite.text());
    std::cout << "SLAMMER suite: " << cases.size()
              << " cases (x2 polarities) in " << t
              << " s (median of 7) = " << cases.size() / t
              << " cases/s; checksum " << sink << "\n";
  }
  return 0;
}
