/**
 * @file
 * Reading whitespace- or comma-separated numeric data files.
 */
#ifndef ROCKDDA_IO_DATA_FILE_H
#define ROCKDDA_IO_DATA_FILE_H

#include <string>
#include <vector>

namespace rockdda::io
{
  /**
   * Read a numeric data file as columns. Values are separated by blanks or
   * commas; blank lines and lines starting with '#' are skipped; every line
   * must have the same number of values, between @p min_columns and
   * @p max_columns. A non-numeric or non-finite value, a missing file or a
   * ragged line throws InputError naming the file and the line.
   * Returns columns[c][row].
   */
  std::vector<std::vector<double>>
  read_columns(const std::string &file_name,
               const unsigned int min_columns,
               const unsigned int max_columns);
} // namespace rockdda::io

#endif
