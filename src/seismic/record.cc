#include <rockdda/io/error.h>
#include <rockdda/seismic/record.h>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <sstream>

namespace rockdda::seismic
{
  double
  Record::duration() const
  {
    return acceleration.empty() ? 0. : dt * (acceleration.size() - 1);
  }



  double
  Record::peak() const
  {
    double p = 0.;
    for (const double a : acceleration)
      p = std::max(p, std::abs(a));
    return p;
  }



  double
  Record::at(const double t) const
  {
    if (acceleration.empty() || t < 0.)
      return 0.;
    const double       x = t / dt;
    const std::size_t i = static_cast<std::size_t>(std::floor(x));
    if (i + 1 >= acceleration.size())
      return (i + 1 == acceleration.size() && x - i < 1e-9) ?
               acceleration.back() :
               0.;
    const double w = x - i;
    return (1. - w) * acceleration[i] + w * acceleration[i + 1];
  }



  namespace
  {
    /// Parse all numbers on a line; throws with file and line on junk.
    std::vector<double>
    parse_numbers(const std::string &line,
                  const std::string &file_name,
                  const unsigned int line_no)
    {
      std::vector<double> values;
      std::string         text = line;
      std::replace(text.begin(), text.end(), ',', ' ');
      std::istringstream in(text);
      std::string        token;
      while (in >> token)
        {
          std::size_t used = 0;
          double      v    = 0.;
          try
            {
              v = std::stod(token, &used);
            }
          catch (const std::exception &)
            {
              used = 0;
            }
          if (used != token.size() || !std::isfinite(v))
            throw InputError(file_name + ":" + std::to_string(line_no) +
                             ": '" + token +
                             "' is not a finite number (expected one "
                             "acceleration value, or time and acceleration, "
                             "per line)");
          values.push_back(v);
        }
      return values;
    }
  } // namespace



  Record
  read_record(const std::string &file_name, const double dt, const double to_g)
  {
    std::ifstream in(file_name);
    if (!in)
      throw InputError(file_name + ": cannot open the record file");

    std::vector<double> times;
    Record              record;
    std::size_t         pos = file_name.find_last_of('/');
    record.name = pos == std::string::npos ? file_name : file_name.substr(pos + 1);

    std::string  line;
    unsigned int line_no = 0, columns = 0;
    while (std::getline(in, line))
      {
        ++line_no;
        const auto first = line.find_first_not_of(" \t\r");
        if (first == std::string::npos || line[first] == '#')
          continue;
        const auto values = parse_numbers(line, file_name, line_no);
        if (columns == 0)
          columns = values.size();
        if (values.size() != columns || columns > 2)
          throw InputError(file_name + ":" + std::to_string(line_no) +
                           ": expected " +
                           std::to_string(columns > 2 ? 2 : columns) +
                           " column(s), found " +
                           std::to_string(values.size()));
        if (columns == 2)
          times.push_back(values[0]);
        record.acceleration.push_back(values.back() * to_g);
      }
    if (record.acceleration.size() < 2)
      throw InputError(file_name +
                       ": the record has fewer than 2 samples");

    if (columns == 2)
      {
        record.dt = (times.back() - times.front()) / (times.size() - 1);
        if (!(record.dt > 0.))
          throw InputError(file_name +
                           ": the time column must increase (dt > 0 s)");
        for (std::size_t i = 1; i < times.size(); ++i)
          if (std::abs(times[i] - times[i - 1] - record.dt) > 1e-6 * record.dt)
            throw InputError(file_name + ": the time column is not uniform "
                             "near sample " + std::to_string(i + 1) +
                             " (resample the record to a constant dt)");
      }
    else
      {
        if (!(dt > 0.) || !std::isfinite(dt))
          throw InputError(file_name + ": one-column record needs a time "
                           "step dt > 0 s (given " + std::to_string(dt) + ")");
        record.dt = dt;
      }
    return record;
  }



  void
  scale(Record &record, const double factor)
  {
    for (double &a : record.acceleration)
      a *= factor;
  }



  void
  scale_to_pga(Record &record, const double target_pga)
  {
    const double p = record.peak();
    if (!(p > 0.))
      throw InputError(record.name +
                       ": cannot scale a record whose peak is zero");
    scale(record, target_pga / p);
  }
} // namespace rockdda::seismic
