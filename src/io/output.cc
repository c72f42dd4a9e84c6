#include <rockdda/io/error.h>
#include <rockdda/io/output.h>

#include <cctype>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iomanip>
#include <iostream>
#include <stdexcept>
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
  OutputDirectory::own(const std::string &pattern) const
  {
    if (!enabled || !owned.insert(pattern).second)
      return;
    std::ofstream out(file(manifest_name), std::ios::app);
    if (out.tellp() == 0)
      out << "# Files written by rockdda runs into this folder; the next run "
             "that does not resume deletes them.\n";
    out << pattern << "\n";
    if (!out)
      throw std::runtime_error("cannot write " + file(manifest_name));
  }



  std::size_t
  OutputDirectory::remove_earlier_run() const
  {
    if (!enabled)
      return 0;
    std::ifstream in(file(manifest_name));
    if (!in)
      return 0;
    // Patterns: exact names, or a prefix (trailing '*'); each also covers
    // its leftover temporary files (NAME.tmp.PID).
    std::vector<std::string> exact, prefixes;
    std::string              line;
    while (std::getline(in, line))
      {
        if (line.empty() || line[0] == '#'
            || line.find('/') != std::string::npos || line == "."
            || line == "..")
          continue;
        if (line.back() == '*')
          prefixes.push_back(line.substr(0, line.size() - 1));
        else
          exact.push_back(line);
      }
    in.close();
    std::size_t     removed = 0;
    std::error_code ec;
    for (const auto &entry : std::filesystem::directory_iterator(folder, ec))
      {
        if (!entry.is_regular_file(ec))
          continue;
        const std::string name = entry.path().filename().string();
        bool              ours = false;
        for (const auto &p : prefixes)
          ours = ours || (!p.empty() && name.rfind(p, 0) == 0);
        for (const auto &e : exact)
          ours = ours || name == e || name.rfind(e + ".tmp.", 0) == 0;
        if (ours && std::filesystem::remove(entry.path(), ec))
          ++removed;
      }
    std::filesystem::remove(file(manifest_name), ec);
    owned.clear();
    return removed;
  }



  void
  OutputDirectory::write(const std::string &name,
                         const std::string &content) const
  {
    write_with(name, [&content](const std::string &tmp) {
      std::ofstream out(tmp, std::ios::binary | std::ios::trunc);
      out << content;
      out.flush();
      if (!out)
        throw std::runtime_error("cannot write " + tmp);
    });
  }



  void
  OutputDirectory::write_with(
    const std::string                              &name,
    const std::function<void(const std::string &)> &writer) const
  {
    if (!enabled)
      return;
    own(name);
    const std::string target = file(name);
    const std::string tmp
      = target + ".tmp." + std::to_string(static_cast<long>(::getpid()));
    try
      {
        writer(tmp);
      }
    catch (...)
      {
        std::remove(tmp.c_str());
        throw;
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



  CsvWriter &
  CsvWriter::field(const std::string &text)
  {
    if (record_open)
      buffer += ',';
    buffer += quote(text);
    record_open = true;
    return *this;
  }



  CsvWriter &
  CsvWriter::number(const double value, const int digits)
  {
    return field(format_number(value, digits));
  }



  CsvWriter &
  CsvWriter::end_record()
  {
    buffer += '\n';
    record_open = false;
    return *this;
  }



  CsvWriter &
  CsvWriter::record(const std::vector<std::string> &fields)
  {
    for (const auto &f : fields)
      field(f);
    return end_record();
  }



  std::string
  CsvWriter::quote(const std::string &text)
  {
    const bool needs_quotes
      = text.find_first_of(",\"\r\n") != std::string::npos
        || (!text.empty()
            && (std::isspace(static_cast<unsigned char>(text.front()))
                || std::isspace(static_cast<unsigned char>(text.back()))));
    if (!needs_quotes)
      return text;
    std::string q = "\"";
    for (const char c : text)
      {
        if (c == '"')
          q += '"';
        q += c;
      }
    return q + '"';
  }



  std::vector<std::string>
  split_csv_record(const std::string &line)
  {
    std::vector<std::string> fields(1);
    bool                     quoted = false;
    for (std::size_t i = 0; i < line.size(); ++i)
      {
        const char c = line[i];
        if (quoted)
          {
            if (c == '"' && i + 1 < line.size() && line[i + 1] == '"')
              {
                fields.back() += '"';
                ++i;
              }
            else if (c == '"')
              quoted = false;
            else
              fields.back() += c;
          }
        else if (c == '"')
          quoted = true;
        else if (c == ',')
          fields.emplace_back();
        else if (c != '\r')
          fields.back() += c;
      }
    if (quoted)
      throw std::invalid_argument("CSV record with an unterminated quote: "
                                  + line);
    return fields;
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
    names.push_back(name);
    units.push_back(unit);
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
    CsvWriter w;
    w.record(header);
    for (const auto &row : rows)
      {
        for (const double v : row)
          w.number(v);
        w.end_record();
      }
    return w.text();
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
    CsvWriter w;
    w.record({"quantity", "value", "unit"});
    for (const auto &e : entries)
      w.record({e.quantity, e.value, e.unit});
    return w.text();
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



  void
  Log::record(const std::string &text)
  {
    buffer << text << '\n';
  }
} // namespace rockdda::io
