/**
 * @file
 * Checkpoint files of runs.
 */
#include <rockdda/io/checkpoint.h>
#include <rockdda/io/error.h>
#include <rockdda/io/parameters.h>

#include <fstream>
#include <iterator>

namespace rockdda::io
{
  RunCheckpoint::RunCheckpoint(const OutputDirectory &output,
                               const std::string     &kind,
                               const std::string     &fingerprint,
                               const std::string     &section)
      : output(output)
      , magic("rockdda " + kind + " run checkpoint 1")
      , fingerprint(fingerprint)
      , section(section)
      , path(output.file("checkpoint.bin"))
  {}



  BinaryWriter
  RunCheckpoint::begin() const
  {
    BinaryWriter w;
    w.put_string(magic);
    w.put_string(fingerprint);
    return w;
  }



  void
  RunCheckpoint::write(const BinaryWriter &data, const Table &statistics) const
  {
    output.write("statistics.csv", statistics.csv());
    output.write("checkpoint.bin", data.bytes);
  }



  std::string
  RunCheckpoint::read() const
  {
    std::ifstream in(path, std::ios::binary);
    if (!in)
      throw InputError(
        "key '" + section + "/Resume' is true but there is no checkpoint "
        + path + " (run once with '" + section + "/Checkpoint interval' > 0)");
    return std::string((std::istreambuf_iterator<char>(in)),
                       std::istreambuf_iterator<char>());
  }



  BinaryReader
  RunCheckpoint::reader(const std::string &bytes) const
  {
    BinaryReader r(bytes, path);
    if (r.get_string() != magic)
      throw InputError(path + ": not the checkpoint of a run of this kind ("
                       + magic + ")");
    const std::string saved = r.get_string();
    if (saved != fingerprint)
      throw InputError(path + ": written for another run (" + saved
                       + "); this parameter file has " + fingerprint);
    return r;
  }



  void
  RunCheckpoint::declare_parameters(dealii::ParameterHandler &prm,
                                    const std::string        &when)
  {
    declare(prm,
            "Checkpoint interval",
            "0",
            dealii::Patterns::Double(0.),
            "s",
            "Model time between checkpoints: checkpoint.bin (the full "
            "state, for 'Resume') and statistics.csv so far are written "
            "atomically into the output directory "
              + when
              + "; 0 = no checkpoints. A run stopped by SIGINT or SIGTERM "
                "writes one too.");
    declare(prm,
            "Resume",
            "false",
            dealii::Patterns::Bool(),
            "-",
            "Continue from checkpoint.bin in the output directory, written "
            "by an earlier run of this parameter file with a 'Checkpoint "
            "interval'; the run continues bit for bit (the End time may be "
            "raised).");
  }



  void
  RunCheckpoint::put_rows(BinaryWriter &w, const Table &table)
  {
    w.put<std::uint64_t>(table.n_rows());
    for (std::size_t i = 0; i < table.n_rows(); ++i)
      w.put_doubles(table.row(i));
  }



  void
  RunCheckpoint::get_rows(BinaryReader &r, Table &table)
  {
    const auto n = r.get<std::uint64_t>();
    for (std::uint64_t i = 0; i < n; ++i)
      table.add_row(r.get_doubles());
  }
} // namespace rockdda::io
