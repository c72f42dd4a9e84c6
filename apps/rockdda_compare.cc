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
    std::string line;
    std::getline(in, line); // header
    while (std::getline(in, line))
      {
        std::stringstream s(line);
        std::string       name, value;
        std::getline(s, name, ',');
        std::getline(s, value, ',');
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
