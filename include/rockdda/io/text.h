/**
 * @file
 * Reading the lists of a parameter's text: "x, y; x, y" split at ';' and
 * then at ',' into trimmed fields, and a text file read whole. deal.II-free.
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
  /// The whole contents of the file @p file_name; InputError "WHAT
  /// 'FILE': cannot open it" (@p what, e.g. "block file") if it cannot be
  /// read.
  std::string
  read_text_file(const std::string &file_name, const std::string &what);
} // namespace rockdda::io

#endif
