/**
 * @file
 * rockdda-compare SUMMARY.csv REFERENCE.ref
 *
 * Compares the key scalars of a run (summary.csv: quantity,value,unit) with
 * a reference file whose lines read
 *   quantity  reference_value  relative_tolerance  absolute_tolerance  # why
 * A quantity passes if |value - reference| <= max(rel * |reference|, abs).
 * Lines starting with '#' are comments. Exits 0 if all pass, 1 otherwise.
 */
#include <cmath>
#include <fstream>
#include <iostream>
#include <map>
#include <sstream>
#include <string>
#include <vector>

namespace
{
  /// The fields of one CSV record (RFC 4180 quoting, as written by rockdda's
  /// CsvWriter); false for an unterminated quote.
  bool
  split_record(const std::string &line, std::vector<std::string> &fields)
  {
    fields.assign(1, std::string());
    bool quoted = false;
    for (std::size_t i = 0; i < line.size(); ++i)
      {
        const char c = line[i];
        if (quoted && c == '"' && i + 1 < line.size() && line[i + 1] == '"')
          {
            fields.back() += '"';
            ++i;
          }
        else if (c == '"')
          quoted = !quoted;
        else if (c == ',' && !quoted)
          fields.emplace_back();
        else if (c != '\r' || quoted)
          fields.back() += c;
      }
    return !quoted;
  }
} // namespace



int
main(int argc, char **argv)
{
  if (argc != 3)
    {
      std::cerr << "usage: rockdda-compare SUMMARY.csv REFERENCE.ref\n";
      return 2;
    }
  std::map<std::string, double> values;
  {
    std::ifstream in(argv[1]);
    if (!in)
      {
        std::cerr << argv[1] << ": cannot open\n";
        return 2;
      }
    // summary.csv must be valid CSV (RFC 4180) with three fields per
    // record: quantity, value, unit.
    std::string              line;
    std::vector<std::string> fields;
    int                      summary_line = 1;
    std::getline(in, line);
    if (!split_record(line, fields)
        || fields != std::vector<std::string>{"quantity", "value", "unit"})
      {
        std::cerr << argv[1] << ":1: the header is not 'quantity,value,unit'\n";
        return 1;
      }
    while (std::getline(in, line))
      {
        ++summary_line;
        if (!split_record(line, fields) || fields.size() != 3)
          {
            std::cerr << argv[1] << ":" << summary_line
                      << ": not a valid CSV record of 3 fields (quantity, "
                         "value, unit; a field with commas must be "
                         "quoted): "
                      << line << "\n";
            return 1;
          }
        const std::string &name = fields[0], &value = fields[1];
        try
          {
            values[name] = std::stod(value);
          }
        catch (const std::exception &)
          {
            // text results are not compared numerically
          }
      }
  }
  std::ifstream in(argv[2]);
  if (!in)
    {
      std::cerr << argv[2] << ": cannot open\n";
      return 2;
    }
  std::string line;
  int         failures = 0, checked = 0, line_no = 0;
  while (std::getline(in, line))
    {
      ++line_no;
      const auto hash = line.find('#');
      if (hash != std::string::npos)
        line.erase(hash);
      std::istringstream s(line);
      std::string        name;
      double             ref = 0., rel = 0., abs = 0.;
      if (!(s >> name))
        continue;
      if (!(s >> ref >> rel >> abs))
        {
          std::cerr << argv[2] << ":" << line_no
                    << ": expected 'quantity value rel_tol abs_tol'\n";
          return 2;
        }
      ++checked;
      const auto it = values.find(name);
      if (it == values.end())
        {
          std::cerr << "FAIL " << name << ": not in " << argv[1] << "\n";
          ++failures;
          continue;
        }
      const double tol = std::max(rel * std::abs(ref), abs);
      const double err = std::abs(it->second - ref);
      const bool   ok  = err <= tol && std::isfinite(it->second);
      std::cout << (ok ? "ok   " : "FAIL ") << name << " = " << it->second
                << " (reference " << ref << ", |diff| " << err << ", tolerance "
                << tol << ")\n";
      failures += !ok;
    }
  if (checked == 0)
    {
      std::cerr << argv[2] << ": no reference values\n";
      return 2;
    }
  return failures == 0 ? 0 : 1;
}
