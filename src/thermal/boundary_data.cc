#include <rockdda/io/error.h>
#include <rockdda/io/output.h>
#include <rockdda/io/text.h>
#include <rockdda/thermal/boundary_data.h>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <sstream>
#include <stdexcept>

namespace rockdda::thermal
{
  namespace
  {
    bool
    to_double(const std::string &text, double &v)
    {
      const std::string token = io::trim(text);
      if (token.empty())
        return false;
      std::size_t used = 0;
      try
        {
          v = std::stod(token, &used);
        }
      catch (const std::exception &)
        {
          return false;
        }
      return used == token.size() && std::isfinite(v);
    }
  } // namespace



  std::vector<Sinusoid>
  parse_sinusoids(const std::string &text, const std::string &where)
  {
    std::vector<Sinusoid> terms;
    for (const auto &term : io::split_fields(text, ';'))
      {
        if (term.find_first_not_of(" \t") == std::string::npos)
          continue;
        const auto parts = io::split_fields(term, ',');
        Sinusoid   s;
        if (parts.size() != 3 || !to_double(parts[0], s.amplitude)
            || !to_double(parts[1], s.period) || !to_double(parts[2], s.phase))
          throw InputError(where + ": sinusoid '" + term
                           + "' must be 'amplitude, period, phase' (K or "
                             "W/m^2, s, rad), terms separated by ';'");
        if (!(s.period > 0.))
          throw InputError(where + ": sinusoid '" + term
                           + "' has period <= 0 s (must be > 0)");
        terms.push_back(s);
      }
    return terms;
  }



  double
  evaluate(const std::vector<Sinusoid> &terms,
           const double                 mean,
           const double                 t)
  {
    double v = mean;
    for (const auto &s : terms)
      v += s.amplitude * std::sin(2. * M_PI * t / s.period + s.phase);
    return v;
  }



  double
  TimeSeries::operator()(const double t) const
  {
    const double tol = 1e-9 * std::max(1., time.back() - time.front());
    if (t < time.front() - tol || t > time.back() + tol)
      throw std::runtime_error(
        file + ": the time series covers " + io::format_number(time.front(), 8)
        + " to " + io::format_number(time.back(), 8)
        + " s but the run needs t = " + io::format_number(t, 8) + " s");
    const auto it = std::upper_bound(time.begin(), time.end(), t);
    if (it == time.begin())
      return value.front();
    if (it == time.end())
      return value.back();
    const std::size_t i = it - time.begin();
    const double      s = (t - time[i - 1]) / (time[i] - time[i - 1]);
    return (1. - s) * value[i - 1] + s * value[i];
  }



  TimeSeries
  read_time_series(const std::string &file_name, const double time_unit)
  {
    std::ifstream in(file_name);
    if (!in)
      throw InputError(file_name
                       + ": cannot open the temperature time "
                         "series file");
    TimeSeries series;
    series.file = file_name;
    std::string  line;
    unsigned int line_no = 0;
    bool         first   = true;
    while (std::getline(in, line))
      {
        ++line_no;
        const auto start = line.find_first_not_of(" \t\r");
        if (start == std::string::npos || line[start] == '#')
          continue;
        const std::string original = line.substr(start);
        std::replace(line.begin(), line.end(), ',', ' ');
        std::istringstream       tokens(line);
        std::vector<std::string> fields;
        std::string              f;
        while (tokens >> f)
          fields.push_back(f);
        double     t = 0., v = 0.;
        const bool numeric = fields.size() == 2 && to_double(fields[0], t)
                             && to_double(fields[1], v);
        if (!numeric)
          {
            const bool header
              = first && !fields.empty()
                && std::isalpha(static_cast<unsigned char>(fields[0][0]));
            first = false;
            if (header)
              continue;
            throw InputError(
              file_name + ":" + std::to_string(line_no) + ": '" + original
              + "' is not 'time, temperature' (two finite numbers)");
          }
        first = false;
        t *= time_unit;
        if (!series.time.empty() && !(t > series.time.back()))
          throw InputError(file_name + ":" + std::to_string(line_no) + ": time "
                           + io::format_number(t, 10)
                           + " s does not increase (previous "
                           + io::format_number(series.time.back(), 10) + " s)");
        series.time.push_back(t);
        series.value.push_back(v);
      }
    if (series.time.size() < 2)
      throw InputError(file_name
                       + ": the time series needs at least two "
                         "data lines");
    return series;
  }
} // namespace rockdda::thermal
