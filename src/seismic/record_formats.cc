/**
 * @file
 * Record files: the SLAMMER one-column format, time/acceleration columns and
 * the PEER NGA AT2 format, in g, m/s^2 or cm/s^2.
 */
#include <rockdda/io/error.h>
#include <rockdda/io/output.h>
#include <rockdda/seismic/record.h>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>

namespace rockdda::seismic
{
  namespace
  {
    constexpr double standard_gravity = 9.80665;

    /// "FILE:LINE: " for messages.
    std::string
    where(const std::string &file_name, const unsigned int line)
    {
      return file_name + ":" + std::to_string(line) + ": ";
    }

    /// Upper-case copy.
    std::string
    upper(std::string s)
    {
      for (char &c : s)
        c = static_cast<char>(std::toupper(static_cast<unsigned char>(c)));
      return s;
    }

    /// Split a line at blanks, commas and semicolons.
    std::vector<std::string>
    tokens_of(std::string line)
    {
      std::replace_if(
        line.begin(),
        line.end(),
        [](const char c) { return c == ',' || c == ';'; },
        ' ');
      std::istringstream       in(line);
      std::vector<std::string> tokens;
      std::string              t;
      while (in >> t)
        tokens.push_back(t);
      return tokens;
    }

    /// The number in @p token, or false if it is not one number.
    bool
    parse_number(const std::string &token, double &value)
    {
      const char *begin = token.c_str();
      char       *end   = nullptr;
      value             = std::strtod(begin, &end);
      return end != begin && *end == '\0';
    }

    /// The number in @p token; an InputError naming the file and line if it
    /// is not a finite number.
    double
    finite_number(const std::string &token,
                  const std::string &file_name,
                  const unsigned int line)
    {
      double v = 0.;
      if (!parse_number(token, v))
        throw InputError(where(file_name, line) + "'" + token
                         + "' is not a number");
      if (!std::isfinite(v))
        throw InputError(where(file_name, line) + "'" + token
                         + "' is not a finite acceleration (NaN or inf); "
                           "remove or repair the sample");
      return v;
    }

    /// True for a blank line or a '#' comment.
    bool
    skipped(const std::string &line)
    {
      const auto first = line.find_first_not_of(" \t\r");
      return first == std::string::npos || line[first] == '#';
    }

    /// Check a time column for a uniform step and return it.
    double
    uniform_step(const std::vector<double>       &times,
                 const std::vector<unsigned int> &lines,
                 const std::string               &file_name)
    {
      const double dt = (times.back() - times.front()) / (times.size() - 1);
      if (!(dt > 0.))
        throw InputError(file_name
                         + ": the time column must increase (dt > 0 s)");
      // Each step against the first: the first line that breaks the rhythm
      // is the one named.
      const double first = times[1] - times[0];
      for (std::size_t i = 1; i < times.size(); ++i)
        if (std::abs(times[i] - times[i - 1] - first) > 1e-6 * std::abs(first))
          throw InputError(where(file_name, lines[i])
                           + "the time column is not uniform (dt "
                           + io::format_number(first, 6) + " s expected, "
                           + io::format_number(times[i] - times[i - 1], 6)
                           + " s found); resample the record to a constant "
                             "dt");
      return dt;
    }

    /// One value per line, or time and acceleration columns.
    Record
    read_plain(const std::string       &file_name,
               const RecordFileOptions &options,
               const bool               one_column)
    {
      std::ifstream in(file_name);
      if (!in)
        throw InputError(file_name + ": cannot open the record file");
      Record                    record;
      std::vector<double>       times;
      std::vector<unsigned int> lines;
      std::string               line;
      unsigned int              line_no = 0, n_data = 0;
      const unsigned int        column = one_column ? 1 : options.column;
      while (std::getline(in, line))
        {
          ++line_no;
          if (skipped(line))
            continue;
          const auto tokens = tokens_of(line);
          // A header line of names ("time_s,acceleration_g") before the
          // first data line.
          double dummy = 0.;
          if (n_data == 0 && !one_column && !parse_number(tokens[0], dummy))
            {
              ++n_data;
              continue;
            }
          ++n_data;
          if (one_column && tokens.size() != 1)
            throw InputError(where(file_name, line_no) + "found "
                             + std::to_string(tokens.size())
                             + " values; a one-column record has one value "
                               "per line (set 'Record format' to columns "
                               "for time/acceleration files)");
          if (tokens.size() < column)
            throw InputError(where(file_name, line_no) + "found "
                             + std::to_string(tokens.size())
                             + " values; the acceleration is in column "
                             + std::to_string(column));
          for (const auto &t : tokens)
            finite_number(t, file_name, line_no);
          if (!one_column)
            times.push_back(finite_number(tokens[0], file_name, line_no));
          record.acceleration.push_back(
            finite_number(tokens[column - 1], file_name, line_no));
          lines.push_back(line_no);
        }
      if (record.acceleration.size() < 2)
        throw InputError(file_name + ": the record has fewer than 2 samples");
      if (one_column)
        {
          if (!(options.dt > 0.) || !std::isfinite(options.dt))
            throw InputError(file_name
                             + ": a one-column record needs a time step dt > "
                               "0 s (given "
                             + io::format_number(options.dt, 6) + " s)");
          record.dt = options.dt;
        }
      else
        record.dt = uniform_step(times, lines, file_name);
      return record;
    }

    /// The unit an AT2 header's third line states, if it states one.
    bool
    at2_unit(const std::string &line, AccelerationUnit &unit)
    {
      const std::string u = upper(line);
      if (u.find("CM/S") != std::string::npos
          || u.find("CM/SEC") != std::string::npos
          || u.find("GAL") != std::string::npos)
        unit = AccelerationUnit::centimetre_per_second2;
      else if (u.find("M/S") != std::string::npos)
        unit = AccelerationUnit::metre_per_second2;
      else if (u.find("UNITS OF G") != std::string::npos
               || u.find(" G ") != std::string::npos
               || (u.size() >= 2 && u.substr(u.size() - 2) == " G"))
        unit = AccelerationUnit::g;
      else
        return false;
      return true;
    }

    /// PEER NGA AT2 (NGA-West2 'NPTS= N, DT= dt SEC' or the older
    /// 'N dt NPTS, DT' fourth line).
    Record
    read_at2(const std::string &file_name, const RecordFileOptions &options)
    {
      std::ifstream in(file_name);
      if (!in)
        throw InputError(file_name + ": cannot open the record file");
      std::string header[4];
      for (unsigned int l = 0; l < 4; ++l)
        if (!std::getline(in, header[l]))
          throw InputError(where(file_name, l + 1)
                           + "the file ends inside the PEER AT2 header (4 "
                             "lines: title, event, units, NPTS and DT)");
      const std::string units_line = upper(header[2]);
      if (units_line.find("ACCEL") == std::string::npos)
        throw InputError(where(file_name, 3)
                         + "a PEER AT2 header states 'ACCELERATION TIME "
                           "HISTORY IN UNITS OF G' here; found '"
                         + header[2] + "' (a velocity or displacement file?)");
      AccelerationUnit stated = options.unit;
      if (at2_unit(header[2], stated) && stated != options.unit)
        throw InputError(
          where(file_name, 3) + "the file states units '" + unit_name(stated)
          + "' but the parameter file says '" + unit_name(options.unit)
          + "'; set 'Ground motion/Units' to " + unit_name(stated));

      // Fourth line: NPTS and DT.
      const std::string l4   = upper(header[3]);
      double            npts = -1., dt = -1.;
      const auto        npos = l4.find("NPTS"), dpos = l4.find("DT");
      if (npos != std::string::npos && dpos != std::string::npos
          && l4.find('=') != std::string::npos)
        {
          // NPTS= 4000, DT= .0100 SEC
          const auto value_after = [&](const std::size_t pos) {
            auto        eq = l4.find('=', pos);
            std::string rest
              = eq == std::string::npos ? std::string() : l4.substr(eq + 1);
            // The number right after '=' ("DT= .0050 SEC", "DT=.005SEC").
            const char  *begin = rest.c_str();
            char        *end   = nullptr;
            const double v     = std::strtod(begin, &end);
            return end == begin ? -1. : v;
          };
          npts = value_after(npos);
          dt   = value_after(dpos);
        }
      else if (npos != std::string::npos && dpos != std::string::npos)
        {
          // 4000   .0100   NPTS, DT
          const auto t = tokens_of(l4.substr(0, std::min(npos, dpos)));
          if (t.size() >= 2)
            {
              parse_number(t[0], npts);
              parse_number(t[1], dt);
            }
        }
      if (!(npts >= 2.) || npts != std::floor(npts) || !(dt > 0.)
          || !std::isfinite(dt))
        throw InputError(where(file_name, 4)
                         + "expected the PEER AT2 header line 'NPTS= N, DT= "
                           "dt SEC' with N >= 2 samples and dt > 0 s; found '"
                         + header[3] + "'");

      Record       record;
      std::string  line;
      unsigned int line_no = 4;
      record.dt            = dt;
      record.acceleration.reserve(static_cast<std::size_t>(npts));
      while (std::getline(in, line))
        {
          ++line_no;
          for (const auto &t : tokens_of(line))
            {
              if (record.acceleration.size() >= npts)
                throw InputError(
                  where(file_name, line_no) + "more samples than NPTS = "
                  + std::to_string(static_cast<long>(npts)) + " (line 4)");
              record.acceleration.push_back(
                finite_number(t, file_name, line_no));
            }
        }
      if (record.acceleration.size() != npts)
        throw InputError(where(file_name, line_no) + "the file has "
                         + std::to_string(record.acceleration.size())
                         + " samples but its header (line 4) says NPTS = "
                         + std::to_string(static_cast<long>(npts)));
      return record;
    }

    /// The format of @p file_name for RecordFormat::automatic.
    RecordFormat
    detect_format(const std::string &file_name)
    {
      std::string ext = upper(std::filesystem::path(file_name).extension());
      if (ext == ".AT2")
        return RecordFormat::peer_at2;
      std::ifstream in(file_name);
      if (!in)
        throw InputError(file_name + ": cannot open the record file");
      std::string line;
      bool        first = true;
      while (std::getline(in, line))
        {
          if (first && upper(line).find("PEER") != std::string::npos)
            return RecordFormat::peer_at2;
          first = false;
          if (skipped(line))
            continue;
          return tokens_of(line).size() == 1 ? RecordFormat::one_column
                                             : RecordFormat::columns;
        }
      return RecordFormat::one_column;
    }
  } // namespace



  double
  factor_to_g(const AccelerationUnit unit)
  {
    switch (unit)
      {
        case AccelerationUnit::g:
          return 1.;
        case AccelerationUnit::metre_per_second2:
          return 1. / standard_gravity;
        case AccelerationUnit::centimetre_per_second2:
          return 0.01 / standard_gravity;
      }
    return 1.;
  }



  std::string
  unit_name(const AccelerationUnit unit)
  {
    switch (unit)
      {
        case AccelerationUnit::g:
          return "g";
        case AccelerationUnit::metre_per_second2:
          return "m/s^2";
        case AccelerationUnit::centimetre_per_second2:
          return "cm/s^2";
      }
    return "g";
  }



  Record
  read_record(const std::string &file_name, const RecordFileOptions &options)
  {
    if (options.column < 2)
      throw InputError(file_name
                       + ": the acceleration column must be >= 2 (column 1 "
                         "is the time)");
    const RecordFormat format = options.format == RecordFormat::automatic
                                  ? detect_format(file_name)
                                  : options.format;
    Record             record
      = format == RecordFormat::peer_at2
          ? read_at2(file_name, options)
          : read_plain(file_name, options, format == RecordFormat::one_column);
    record.name       = std::filesystem::path(file_name).filename().string();
    const double to_g = factor_to_g(options.unit);
    for (double &a : record.acceleration)
      a *= to_g;
    return record;
  }



  double
  listed_time_step(const std::string &file_name, unsigned int &line)
  {
    const auto    path  = std::filesystem::path(file_name);
    const auto    index = path.parent_path() / "records.csv";
    std::ifstream in(index);
    line = 0;
    if (!in)
      return 0.;
    std::string              text;
    std::vector<std::string> header;
    std::size_t              file_col = 0, dt_col = 0;
    unsigned int             n = 0;
    while (std::getline(in, text))
      {
        ++n;
        if (!text.empty() && text.back() == '\r')
          text.pop_back();
        std::vector<std::string> fields;
        try
          {
            fields = io::split_csv_record(text);
          }
        catch (const std::exception &)
          {
            continue;
          }
        if (n == 1)
          {
            header       = fields;
            const auto f = std::find(header.begin(), header.end(), "file");
            const auto d = std::find(header.begin(), header.end(), "dt_s");
            if (f == header.end() || d == header.end())
              return 0.;
            file_col = f - header.begin();
            dt_col   = d - header.begin();
            continue;
          }
        if (fields.size() <= std::max(file_col, dt_col)
            || fields[file_col] != path.filename().string())
          continue;
        double dt = 0.;
        if (!parse_number(fields[dt_col], dt) || !(dt > 0.)
            || !std::isfinite(dt))
          throw InputError(where(index.string(), n) + "dt_s '" + fields[dt_col]
                           + "' of " + fields[file_col]
                           + " is not a number > 0 s");
        line = n;
        return dt;
      }
    return 0.;
  }



  std::string
  check_units_plausible(const Record          &record,
                        const AccelerationUnit unit,
                        const std::string     &file_name,
                        const std::string     &unit_key)
  {
    const double pga = record.peak();
    const auto   in  = [&](const AccelerationUnit u) {
      return io::format_number(pga / factor_to_g(unit) * factor_to_g(u), 4)
             + " g if the file were in " + unit_name(u);
    };
    if (pga > 5.)
      {
        std::string others;
        for (const auto u : {AccelerationUnit::g,
                             AccelerationUnit::metre_per_second2,
                             AccelerationUnit::centimetre_per_second2})
          if (u != unit)
            others += (others.empty() ? "" : ", ") + in(u);
        throw InputError(file_name + ": PGA " + io::format_number(pga, 4)
                         + " g with key '" + unit_key + "' = " + unit_name(unit)
                         + " is implausible (the largest recorded are about "
                           "4 g; valid: PGA <= 5 g); check the units: "
                         + others);
      }
    if (pga < 1e-3)
      return file_name + ": PGA " + io::format_number(pga, 4) + " g with key '"
             + unit_key + "' = " + unit_name(unit)
             + " is below 1e-3 g: a weak motion, or a record in g read as "
               "cm/s^2 ("
             + in(AccelerationUnit::g) + ")";
    return std::string();
  }
} // namespace rockdda::seismic
