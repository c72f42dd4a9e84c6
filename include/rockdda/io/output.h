/**
 * @file
 * What one run writes: an output folder whose files are written atomically,
 * column tables with units, and the run log.
 */
#ifndef ROCKDDA_IO_OUTPUT_H
#define ROCKDDA_IO_OUTPUT_H

#include <sstream>
#include <string>
#include <vector>

namespace rockdda::io
{
  /**
   * The folder one run writes into. Every file goes through write(), which
   * writes a temporary file in the same folder and renames it into place, so
   * an interrupted run never leaves a half-written file that looks valid.
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

    /// Full path of @p name inside the folder.
    std::string
    file(const std::string &name) const;

    /// Atomically replace file @p name with @p content.
    void
    write(const std::string &name, const std::string &content) const;

  private:
    std::string folder;
    bool        enabled;
  };

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

    /// Number of rows so far.
    std::size_t
    n_rows() const
    {
      return rows.size();
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
    std::vector<std::string>         header;
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
