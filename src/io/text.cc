/**
 * @file
 * Splitting a parameter's list text into trimmed fields (see text.h).
 */
#include <rockdda/io/error.h>
#include <rockdda/io/text.h>

#include <fstream>
#include <sstream>

namespace rockdda::io
{
  std::string
  trim(const std::string &text)
  {
    const auto first = text.find_first_not_of(" \t\r");
    if (first == std::string::npos)
      return "";
    return text.substr(first, text.find_last_not_of(" \t\r") - first + 1);
  }



  std::vector<std::string>
  split_fields(const std::string &text, const char separator)
  {
    std::vector<std::string> fields;
    std::string              field;
    std::istringstream       in(text);
    while (std::getline(in, field, separator))
      fields.push_back(trim(field));
    if (!text.empty() && text.back() == separator)
      fields.emplace_back();
    return fields;
  }


  std::string
  read_text_file(const std::string &file_name, const std::string &what)
  {
    std::ifstream in(file_name);
    if (!in)
      throw InputError(what + " '" + file_name + "': cannot open it");
    std::ostringstream s;
    s << in.rdbuf();
    return s.str();
  }
} // namespace rockdda::io
