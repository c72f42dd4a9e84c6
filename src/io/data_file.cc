#include <rockdda/io/data_file.h>
#include <rockdda/io/error.h>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <sstream>

namespace rockdda::io
{
  std::vector<std::vector<double>>
  read_columns(const std::string &file_name,
               const unsigned int min_columns,
               const unsigned int max_columns)
  {
    std::ifstream in(file_name);
    if (!in)
      throw InputError(file_name + ": cannot open the data file");

    std::vector<std::vector<double>> columns;
    std::string                      line;
    unsigned int                     line_no = 0;
    std::vector<double>              values;
    while (std::getline(in, line))
      {
        ++line_no;
        const auto first = line.find_first_not_of(" \t\r");
        if (first == std::string::npos || line[first] == '#')
          continue;
        std::replace(line.begin(), line.end(), ',', ' ');
        std::istringstream tokens(line);
        std::string        token;
        values.clear();
        while (tokens >> token)
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
              throw InputError(file_name + ":" + std::to_string(line_no) + ": '"
                               + token + "' is not a finite number");
            values.push_back(v);
          }
        if (columns.empty())
          {
            if (values.size() < min_columns || values.size() > max_columns)
              throw InputError(file_name + ":" + std::to_string(line_no)
                               + ": found " + std::to_string(values.size())
                               + " values; expected "
                               + (min_columns == max_columns
                                    ? std::to_string(min_columns)
                                    : std::to_string(min_columns) + " to "
                                        + std::to_string(max_columns))
                               + " per line");
            columns.resize(values.size());
          }
        else if (values.size() != columns.size())
          throw InputError(file_name + ":" + std::to_string(line_no)
                           + ": found " + std::to_string(values.size())
                           + " values; every line must have "
                           + std::to_string(columns.size()));
        for (std::size_t c = 0; c < values.size(); ++c)
          columns[c].push_back(values[c]);
      }
    if (columns.empty())
      throw InputError(file_name + ": the data file has no data lines");
    return columns;
  }
} // namespace rockdda::io
