#include <rockdda/io/data_file.h>
#include <rockdda/io/error.h>
#include <rockdda/seismic/record.h>

#include <algorithm>
#include <cmath>
#include <filesystem>

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
    const double      x = t / dt;
    const std::size_t i = static_cast<std::size_t>(std::floor(x));
    if (i + 1 >= acceleration.size())
      return (i + 1 == acceleration.size() && x - i < 1e-9)
               ? acceleration.back()
               : 0.;
    const double w = x - i;
    return (1. - w) * acceleration[i] + w * acceleration[i + 1];
  }



  Record
  read_record(const std::string &file_name, const double dt, const double to_g)
  {
    const auto columns = io::read_columns(file_name, 1, 2);
    Record     record;
    record.name         = std::filesystem::path(file_name).filename().string();
    record.acceleration = columns.back();
    for (double &a : record.acceleration)
      a *= to_g;
    if (record.acceleration.size() < 2)
      throw InputError(file_name + ": the record has fewer than 2 samples");

    if (columns.size() == 2)
      {
        const auto &times = columns[0];
        record.dt         = (times.back() - times.front()) / (times.size() - 1);
        if (!(record.dt > 0.))
          throw InputError(file_name
                           + ": the time column must increase (dt > 0 s)");
        for (std::size_t i = 1; i < times.size(); ++i)
          if (std::abs(times[i] - times[i - 1] - record.dt) > 1e-6 * record.dt)
            throw InputError(file_name
                             + ": the time column is not uniform near sample "
                             + std::to_string(i + 1)
                             + " (resample the record to a constant dt)");
      }
    else
      {
        if (!(dt > 0.) || !std::isfinite(dt))
          throw InputError(file_name
                           + ": a one-column record needs a time step dt > 0 s "
                             "(given "
                           + std::to_string(dt) + " s)");
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
      throw InputError(record.name
                       + ": cannot scale a record whose peak is zero");
    scale(record, target_pga / p);
  }
} // namespace rockdda::seismic
