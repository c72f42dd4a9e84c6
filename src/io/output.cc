#include <rockdda/io/error.h>
#include <rockdda/io/output.h>

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iomanip>
#include <iostream>
#include <unistd.h>

namespace rockdda::io
{
  OutputDirectory::OutputDirectory(const std::string &path, const bool enabled)
      : folder(path.empty() ? std::string(".") : path)
      , enabled(enabled)
  {
    if (!enabled)
      return;
    std::error_code ec;
    std::filesystem::create_directories(folder, ec);
    if (ec)
      throw InputError("Output directory '" + folder + "': cannot create it ("
                       + ec.message() + ")");
  }



  std::string
  OutputDirectory::file(const std::string &name) const
  {
    return (std::filesystem::path(folder) / name).string();
  }



  void
  OutputDirectory::write(const std::string &name,
                         const std::string &content) const
  {
    if (!enabled)
      return;
    const std::string target = file(name);
    const std::string tmp
      = target + ".tmp." + std::to_string(static_cast<long>(::getpid()));
    {
      std::ofstream out(tmp, std::ios::binary | std::ios::trunc);
      out << content;
      out.flush();
      if (!out)
        {
          std::remove(tmp.c_str());
          throw std::runtime_error("cannot write " + tmp);
        }
    }
    std::error_code ec;
    std::filesystem::rename(tmp, target, ec);
    if (ec)
      {
        std::remove(tmp.c_str());
        throw std::runtime_error("cannot rename " + tmp + " to " + target + ": "
                                 + ec.message());
      }
  }



  std::string
  format_number(const double value, const int digits)
  {
    std::ostringstream s;
    s << std::setprecision(digits) << value;
    return s.str();
  }



  void
  Table::add_column(const std::string &name, const std::string &unit)
  {
    std::string u = unit;
    for (char &c : u)
      if (c == '/')
        c = '_';
      else if (c == '^')
        c = 'p';
    header.push_back(unit == "-" ? name : name + "_" + u);
  }



  void
  Table::add_row(const std::vector<double> &values)
  {
    if (values.size() != header.size())
      throw std::logic_error("Table::add_row: wrong number of values");
    rows.push_back(values);
  }



  std::string
  Table::csv() const
  {
    std::ostringstream s;
    for (std::size_t c = 0; c < header.size(); ++c)
      s << (c ? "," : "") << header[c];
    s << '\n' << std::setprecision(12);
    for (const auto &row : rows)
      {
        for (std::size_t c = 0; c < row.size(); ++c)
          s << (c ? "," : "") << row[c];
        s << '\n';
      }
    return s.str();
  }



  void
  Summary::add(const std::string &quantity,
               const double       value,
               const std::string &unit)
  {
    entries.push_back({quantity, format_number(value, 15), unit});
  }



  void
  Summary::add_text(const std::string &quantity, const std::string &text)
  {
    entries.push_back({quantity, text, "text"});
  }



  std::string
  Summary::csv() const
  {
    std::string s = "quantity,value,unit\n";
    for (const auto &e : entries)
      s += e.quantity + "," + e.value + "," + e.unit + "\n";
    return s;
  }



  std::string
  Summary::text() const
  {
    std::size_t width = 0;
    for (const auto &e : entries)
      width = std::max(width, e.quantity.size());
    std::ostringstream s;
    for (const auto &e : entries)
      s << "  " << std::left << std::setw(width + 2) << e.quantity << e.value
        << (e.unit == "text" || e.unit == "-" ? "" : " " + e.unit) << '\n';
    return s.str();
  }



  void
  Log::line(const std::string &text)
  {
    buffer << text << '\n';
    if (echo)
      std::cout << text << std::endl;
  }
} // namespace rockdda::io
