/**
 * @file
 * Reading the lists of a parameter's text: "x, y; x, y" split at ';' and
 * then at ',' into trimmed fields. deal.II-free.
 */
#ifndef ROCKDDA_IO_TEXT_H
#define ROCKDDA_IO_TEXT_H

#include <string>
#include <vector>

namespace rockdda::io
{
  /// @p text without its leading and trailing blanks (spaces, tabs, CR).
  std::string
  trim(const std::string &text);

  /**
   * Split @p text at every @p separator into fields, each trimmed. A
   * trailing separator gives a last, empty field (so that a count check
   * sees it); an empty @p text gives no field.
   */
  std::vector<std::string>
  split_fields(const std::string &text, const char separator);
} // namespace rockdda::io

#endif
