/**
 * @file
 * The checkpoint file of a run (checkpoint.bin in its output directory):
 * a header that names the kind of run and a fingerprint of its controls,
 * then the analysis's own data; statistics.csv is written with it.
 */
#ifndef ROCKDDA_IO_CHECKPOINT_H
#define ROCKDDA_IO_CHECKPOINT_H

#include <rockdda/io/binary_stream.h>
#include <rockdda/io/output.h>

#include <deal.II/base/parameter_handler.h>

#include <string>

namespace rockdda::io
{
  /// Writes and reads the checkpoint file of one run.
  class RunCheckpoint
  {
  public:
    /**
     * @p kind names the analysis ("DDA", "heat"), @p fingerprint the
     * controls a resumed run must share, @p section the parameter
     * subsection of the 'Checkpoint interval' and 'Resume' keys (for
     * messages).
     */
    RunCheckpoint(const OutputDirectory &output,
                  const std::string     &kind,
                  const std::string     &fingerprint,
                  const std::string     &section);

    /// A writer with the header already written.
    BinaryWriter
    begin() const;

    /// Write @p data atomically as checkpoint.bin, and @p statistics as
    /// statistics.csv.
    void
    write(const BinaryWriter &data, const Table &statistics) const;

    /// The checkpoint's bytes; throws InputError if there is none.
    std::string
    read() const;

    /// A reader of @p bytes (from read(), kept alive by the caller) past
    /// the header; throws InputError if the file belongs to another kind
    /// of run or to other controls.
    BinaryReader
    reader(const std::string &bytes) const;

    /**
     * Declare 'Checkpoint interval' (s) and 'Resume' in the current
     * subsection of @p prm; @p when says when checkpoints are taken.
     */
    static void
    declare_parameters(dealii::ParameterHandler &prm, const std::string &when);

    /// Append the rows of @p table to @p w.
    static void
    put_rows(BinaryWriter &w, const Table &table);

    /// Add the rows written by put_rows() to @p table.
    static void
    get_rows(BinaryReader &r, Table &table);

    /// The file's path.
    const std::string &
    file() const
    {
      return path;
    }

  private:
    const OutputDirectory &output;
    std::string            magic, fingerprint, section, path;
  };
} // namespace rockdda::io

#endif
