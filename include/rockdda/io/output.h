/**
 * @file
 * What one run writes: an output folder whose files are written atomically,
 * column tables with units, and the run log.
 */
#ifndef ROCKDDA_IO_OUTPUT_H
#define ROCKDDA_IO_OUTPUT_H

#include <functional>
#include <set>
#include <sstream>
#include <string>
#include <vector>

namespace rockdda::io
{
  /**
   * The folder one run writes into. Every file goes through write(), which
   * writes a temporary file in the same folder and renames it into place, so
   * an interrupted run never leaves a half-written file that looks valid.
   *
   * Every name written is first appended to the manifest
   * rockdda-files.txt in the folder; remove_earlier_run() deletes the files
   * it lists (the driver calls it before a run that does not resume), so a
   * new run into the same folder leaves no files of the earlier one, e.g.
   * VTU snapshots beyond its own series. Files rockdda did not write are
   * never touched.
   */
  class OutputDirectory
  {
  public:
    /// Create the folder (and its parents) if it does not exist. A
    /// disabled folder (@p enabled false, e.g. on MPI ranks other than 0)
    /// creates and writes nothing.
    explicit OutputDirectory(const std::string &path,
                             const bool         enabled = true);

    /// The folder's path.
    const std::string &
    path() const
    {
      return folder;
    }

    /// Whether this process writes into the folder (see the constructor).
    bool
    writes() const
    {
      return enabled;
    }

    /// Full path of @p name inside the folder.
    std::string
    file(const std::string &name) const;

    /// Atomically replace file @p name with @p content.
    void
    write(const std::string &name, const std::string &content) const;
    /// Atomically replace file @p name with what @p writer writes to the
    /// temporary path it is given (for files written by libraries, e.g.
    /// HDF5). If @p writer throws, the temporary file is removed.
    void
    write_with(const std::string                              &name,
               const std::function<void(const std::string &)> &writer) const;

    /**
     * Record in the manifest that this run writes file @p pattern (a name
     * in the folder; a trailing '*' stands for any ending, for files
     * written by other libraries such as p4est's checkpoint files). write()
     * records its names itself.
     */
    void
    own(const std::string &pattern) const;

    /**
     * Delete the files of earlier runs into this folder that the manifest
     * lists (and their leftover temporary files), then the manifest.
     * Returns the number of files deleted.
     */
    std::size_t
    remove_earlier_run() const;

    /// The manifest's name.
    static constexpr const char *manifest_name = "rockdda-files.txt";

  private:
    std::string folder;
    bool        enabled;
    /// Names already in the manifest (by this process).
    mutable std::set<std::string> owned;
  };

  /**
   * The one CSV writer behind every table rockdda writes (statistics.csv,
   * summary.csv, the structure tables): RFC 4180 fields separated by commas,
   * one record per line ('\n'). A field that contains a comma, a double
   * quote, a line break or leading or trailing blanks is enclosed in double
   * quotes, with inner quotes doubled; numbers are written with a fixed
   * number of significant digits.
   */
  class CsvWriter
  {
  public:
    /// Append a text field to the current record.
    CsvWriter &
    field(const std::string &text);

    /// Append a number with @p digits significant digits.
    CsvWriter &
    number(const double value, const int digits = 12);

    /// End the current record (a record without fields is an empty line).
    CsvWriter &
    end_record();

    /// Append one record made of @p fields.
    CsvWriter &
    record(const std::vector<std::string> &fields);

    /// The CSV text written so far (the current record only if ended).
    std::string
    text() const
    {
      return buffer;
    }

    /// @p text as one CSV field: quoted if needed, unchanged otherwise.
    static std::string
    quote(const std::string &text);

  private:
    std::string buffer;
    bool        record_open = false;
  };

  /**
   * Split one CSV record (RFC 4180: quoted fields may hold commas and
   * doubled quotes) into its fields. The inverse of CsvWriter for a record
   * without line breaks; throws std::invalid_argument for an unterminated
   * quote.
   */
  std::vector<std::string>
  split_csv_record(const std::string &line);

  /**
   * A table of numbers whose every column carries a name and an SI unit,
   * written as CSV with a header "name_unit" per column (e.g. "time_s").
   */
  class Table
  {
  public:
    /// Add a column; @p unit is an SI unit such as "m/s" ("-" if none).
    void
    add_column(const std::string &name, const std::string &unit);

    /// Append a row; it must have one value per column.
    void
    add_row(const std::vector<double> &values);

    /// Keep only the first @p n rows (a run that rewinds).
    void
    truncate(const std::size_t n)
    {
      if (n < rows.size())
        rows.resize(n);
    }

    /// Number of rows so far.
    std::size_t
    n_rows() const
    {
      return rows.size();
    }

    /// Number of columns.
    std::size_t
    n_columns() const
    {
      return names.size();
    }

    /// Name of column @p k (without its unit, e.g. "time").
    const std::string &
    column_name(const std::size_t k) const
    {
      return names.at(k);
    }

    /// SI unit of column @p k as given to add_column() (e.g. "s", "-").
    const std::string &
    column_unit(const std::size_t k) const
    {
      return units.at(k);
    }

    /// Row @p i.
    const std::vector<double> &
    row(const std::size_t i) const
    {
      return rows.at(i);
    }

    /// The CSV text (header line, then one line per row, 12 significant
    /// digits).
    std::string
    csv() const;

  private:
    /// CSV header fields ("name_unit"), names and units of the columns.
    std::vector<std::string>         header, names, units;
    std::vector<std::vector<double>> rows;
  };

  /**
   * Key scalars of a run (summary.csv: quantity,value,unit). Regression tests
   * compare these against stored references with tolerances.
   */
  class Summary
  {
  public:
    /// Record a scalar result.
    void
    add(const std::string &quantity,
        const double       value,
        const std::string &unit);

    /// Record a text result (written in the unit column's place as text).
    void
    add_text(const std::string &quantity, const std::string &text);

    /// The CSV text.
    std::string
    csv() const;

    /// Human-readable lines for the log.
    std::string
    text() const;

  private:
    struct Entry
    {
      std::string quantity, value, unit;
    };
    std::vector<Entry> entries;
  };

  /**
   * The run log: what a run prints goes to stdout (unless quiet) and is kept
   * for log.txt.
   */
  class Log
  {
  public:
    explicit Log(const bool echo = true)
        : echo(echo)
    {}

    /// Append a line (a newline is added).
    void
    line(const std::string &text);

    /// Append a line to log.txt only, without echoing it.
    void
    record(const std::string &text);

    /// Everything logged so far.
    std::string
    text() const
    {
      return buffer.str();
    }

  private:
    bool               echo;
    std::ostringstream buffer;
  };

  /// Format a double with @p digits significant digits.
  std::string
  format_number(const double value, const int digits = 12);
} // namespace rockdda::io

#endif
