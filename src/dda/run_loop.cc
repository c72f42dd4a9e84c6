/**
 * @file
 * The part of a DDA run's checkpoint beyond the engine's state, and the
 * fingerprint of its controls.
 */
#include <rockdda/dda/run_loop.h>

#include <cstdint>
#include <sstream>

namespace rockdda::dda
{
  std::string
  run_fingerprint(const std::size_t  n_blocks,
                  const double       time_step,
                  const double       penalty,
                  const double       dynamic,
                  const unsigned int settling_steps,
                  const std::string &seismic_input)
  {
    std::ostringstream f;
    f.precision(17);
    f << "blocks " << n_blocks << ", time step " << time_step << " s, penalty "
      << penalty << " N/m, dynamic control " << dynamic << ", settling steps "
      << settling_steps << ", seismic input " << seismic_input;
    return f.str();
  }



  void
  RunProgress::put(io::BinaryWriter &w) const
  {
    for (const auto *files : {&block_files, &contact_files})
      {
        w.put<std::uint64_t>(files->size());
        for (const auto &[time, name] : *files)
          {
            w.put(time);
            w.put_string(name);
          }
      }
    for (const double v : {next_output, next_row, next_checkpoint})
      w.put(v);
    w.put<std::uint32_t>(max_iterations);
    w.put<std::uint64_t>(iterations_total);
    w.put<std::uint64_t>(cuts_reported);
    for (const double v : {balance0, created_max, energy_in_play})
      w.put(v);
  }



  void
  RunProgress::get(io::BinaryReader &r)
  {
    for (auto *files : {&block_files, &contact_files})
      {
        files->clear();
        // Each entry takes at least 16 bytes (time and name length).
        const auto n = r.get_count(16, "snapshot files");
        for (std::uint64_t i = 0; i < n; ++i)
          {
            const double time = r.get<double>();
            files->emplace_back(time, r.get_string());
          }
      }
    for (double *v : {&next_output, &next_row, &next_checkpoint})
      *v = r.get<double>();
    max_iterations   = r.get<std::uint32_t>();
    iterations_total = r.get<std::uint64_t>();
    cuts_reported    = r.get<std::uint64_t>();
    for (double *v : {&balance0, &created_max, &energy_in_play})
      *v = r.get<double>();
  }
} // namespace rockdda::dda
