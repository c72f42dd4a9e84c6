#include <rockdda/io/error.h>
#include <rockdda/io/output.h>
#include <rockdda/seismic/fft.h>
#include <rockdda/seismic/processing.h>
#include <rockdda/seismic/site_amplification.h>

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstdlib>
#include <fstream>

namespace rockdda::seismic
{
  namespace
  {
    /// "file:line: " for messages.
    std::string
    where(const std::string &source, const unsigned int line)
    {
      return line > 0 ? source + ":" + std::to_string(line) + ": "
                      : source + ": ";
    }

    /// The fields of a line separated by blanks, commas or semicolons.
    std::vector<std::string>
    fields_of(const std::string &line)
    {
      std::vector<std::string> out;
      std::string              current;
      for (const char c : line)
        if (c == ' ' || c == '\t' || c == ',' || c == ';' || c == '\r')
          {
            if (!current.empty())
              out.push_back(current);
            current.clear();
          }
        else
          current += c;
      if (!current.empty())
        out.push_back(current);
      return out;
    }

    /// Parse the whole of @p text as a number.
    bool
    parse(const std::string &text, double &value)
    {
      char *end = nullptr;
      errno     = 0;
      value     = std::strtod(text.c_str(), &end);
      return end != text.c_str() && *end == '\0' && errno != ERANGE;
    }

    /// Unit-peak resonance of centre @p f0 whose excess is half its peak
    /// at two frequencies @p w apart: the squared magnitude of a
    /// second-order band-pass, 1 / (1 + Q^2 (f/f0 - f0/f)^2), Q = f0 / w.
    double
    resonance(const double f, const double f0, const double w)
    {
      if (!(f > 0.))
        return 0.;
      const double x = (f0 / w) * (f / f0 - f0 / f);
      return 1. / (1. + x * x);
    }

    /// Solve the small dense system A x = b (Gaussian elimination with
    /// partial pivoting); false if it is singular.
    bool
    solve(std::vector<std::vector<double>> a, std::vector<double> &b)
    {
      const std::size_t n = b.size();
      for (std::size_t k = 0; k < n; ++k)
        {
          std::size_t p = k;
          for (std::size_t i = k + 1; i < n; ++i)
            if (std::abs(a[i][k]) > std::abs(a[p][k]))
              p = i;
          if (!(std::abs(a[p][k]) > 1e-12))
            return false;
          std::swap(a[p], a[k]);
          std::swap(b[p], b[k]);
          for (std::size_t i = k + 1; i < n; ++i)
            {
              const double m = a[i][k] / a[k][k];
              for (std::size_t j = k; j < n; ++j)
                a[i][j] -= m * a[k][j];
              b[i] -= m * b[k];
            }
        }
      for (std::size_t k = n; k-- > 0;)
        {
          for (std::size_t j = k + 1; j < n; ++j)
            b[k] -= a[k][j] * b[j];
          b[k] /= a[k][k];
        }
      return true;
    }
  } // namespace



  SiteAmplification
  SiteAmplification::from_table(const std::vector<double>       &frequency,
                                const std::vector<double>       &amplification,
                                const std::string               &source,
                                const std::vector<unsigned int> &lines)
  {
    const auto line_of
      = [&](const std::size_t i) { return i < lines.size() ? lines[i] : 0u; };
    if (frequency.size() != amplification.size() || frequency.size() < 2)
      throw InputError(source
                       + ": a site amplification table needs at least 2 "
                         "points (frequency in Hz, amplification)");
    SiteAmplification s;
    s.kind = Kind::table;
    for (std::size_t i = 0; i < frequency.size(); ++i)
      {
        if (!(frequency[i] > 0.) || !std::isfinite(frequency[i]))
          throw InputError(where(source, line_of(i)) + "frequency "
                           + io::format_number(frequency[i], 6)
                           + " Hz is out of range; valid: f > 0 Hz");
        if (i > 0 && !(frequency[i] > frequency[i - 1]))
          throw InputError(where(source, line_of(i)) + "frequency "
                           + io::format_number(frequency[i], 6)
                           + " Hz does not increase (previous point "
                           + io::format_number(frequency[i - 1], 6)
                           + " Hz); list the points by increasing frequency");
        if (!(amplification[i] >= 0.) || !std::isfinite(amplification[i]))
          throw InputError(where(source, line_of(i)) + "amplification "
                           + io::format_number(amplification[i], 6)
                           + " is out of range; valid: A >= 0 (a finite "
                             "ratio of Fourier amplitudes)");
        s.log_f.push_back(std::log(frequency[i]));
        s.values.push_back(amplification[i]);
      }
    s.text = "table " + source + " (" + std::to_string(frequency.size())
             + " points, " + io::format_number(frequency.front(), 4) + "-"
             + io::format_number(frequency.back(), 4) + " Hz)";
    return s;
  }



  SiteAmplification
  SiteAmplification::read_table(const std::string &file_name)
  {
    std::ifstream in(file_name);
    if (!in)
      throw InputError(file_name
                       + ": cannot open the site amplification table");
    std::vector<double>       f, a;
    std::vector<unsigned int> lines;
    std::string               line;
    unsigned int              line_no     = 0;
    bool                      header_seen = false;
    while (std::getline(in, line))
      {
        ++line_no;
        const auto first = line.find_first_not_of(" \t\r");
        if (first == std::string::npos || line[first] == '#')
          continue;
        const auto fields = fields_of(line);
        double     x = 0., y = 0.;
        if (f.empty() && !header_seen && !parse(fields[0], x))
          {
            header_seen = true; // a line of column names
            continue;
          }
        if (fields.size() != 2)
          throw InputError(where(file_name, line_no) + "found "
                           + std::to_string(fields.size())
                           + " values; a site amplification table has two "
                             "columns: frequency (Hz) and amplification (-)");
        if (!parse(fields[0], x) || !parse(fields[1], y))
          throw InputError(where(file_name, line_no) + "'" + line
                           + "' is not two numbers (frequency in Hz, "
                             "amplification)");
        f.push_back(x);
        a.push_back(y);
        lines.push_back(line_no);
      }
    return from_table(f, a, file_name, lines);
  }



  SiteAmplification
  SiteAmplification::from_modes(const std::vector<ResonantMode> &modes,
                                const double                     cut_frequency,
                                const unsigned int               cut_order)
  {
    if (modes.empty())
      throw InputError("site amplification: no resonant mode given");
    if (!(cut_frequency >= 0.) || !std::isfinite(cut_frequency)
        || cut_order == 0)
      throw InputError("site amplification: the cut frequency "
                       + io::format_number(cut_frequency, 6)
                       + " Hz is out of range; valid: >= 0 Hz (0: no cut), "
                         "order >= 1");
    SiteAmplification s;
    s.kind              = Kind::modes;
    s.mode_list         = modes;
    s.cut               = cut_frequency;
    s.cut_order         = cut_order;
    const std::size_t n = modes.size();
    for (std::size_t i = 0; i < n; ++i)
      {
        const auto       &m    = modes[i];
        const std::string name = "site amplification mode "
                                 + std::to_string(i + 1) + " ("
                                 + io::format_number(m.frequency, 6) + " Hz)";
        if (!(m.frequency > 0.) || !std::isfinite(m.frequency))
          throw InputError(name
                           + ": frequency is out of range; valid: > 0 "
                             "Hz");
        if (!(m.peak > 0.) || !std::isfinite(m.peak))
          throw InputError(name + ": peak amplification "
                           + io::format_number(m.peak, 6)
                           + " is out of range; valid: > 0");
        if (!(m.width > 0.) || !std::isfinite(m.width))
          throw InputError(name + ": width " + io::format_number(m.width, 6)
                           + " Hz is out of range; valid: > 0 Hz");
        for (std::size_t j = 0; j < i; ++j)
          if (modes[j].frequency == m.frequency)
            throw InputError(name + ": two modes at the same frequency");
        if (cut_frequency > 0.
            && low_pass_gain(m.frequency, cut_frequency, cut_order) < 1e-3)
          throw InputError(name + ": the cut at "
                           + io::format_number(cut_frequency, 6)
                           + " Hz removes this mode; valid: modes below the "
                             "cut");
      }
    // Excesses c such that A(f_j) = p_j exactly.
    std::vector<std::vector<double>> matrix(n, std::vector<double>(n));
    std::vector<double>              rhs(n);
    for (std::size_t j = 0; j < n; ++j)
      {
        const double gain
          = cut_frequency > 0.
              ? low_pass_gain(modes[j].frequency, cut_frequency, cut_order)
              : 1.;
        rhs[j] = modes[j].peak / gain - 1.;
        for (std::size_t i = 0; i < n; ++i)
          matrix[j][i]
            = resonance(modes[j].frequency, modes[i].frequency, modes[i].width);
      }
    if (!solve(matrix, rhs))
      throw InputError("site amplification: the modes overlap so much that "
                       "their peaks cannot be matched; separate the "
                       "frequencies or narrow the widths");
    s.excess = rhs;
    // A negative excess (a trough, or a peak lowered to match a neighbour's
    // tail) could make the sum negative: check on a grid finer than the
    // narrowest mode.
    double f_max = 0., w_min = 1e300;
    for (const auto &m : modes)
      {
        f_max = std::max(f_max, m.frequency + 10. * m.width);
        w_min = std::min(w_min, m.width);
      }
    if (*std::min_element(s.excess.begin(), s.excess.end()) < 0.)
      {
        const std::size_t steps = std::min<std::size_t>(
          200000, static_cast<std::size_t>(std::ceil(40. * f_max / w_min)));
        for (std::size_t k = 0; k <= steps; ++k)
          {
            const double f = f_max * k / steps;
            if (s.mode_sum(f) < 0.)
              throw InputError("site amplification: the modes give a "
                               "negative amplification "
                               + io::format_number(s.mode_sum(f), 4) + " at "
                               + io::format_number(f, 4)
                               + " Hz; valid: A(f) >= 0 everywhere (raise "
                                 "the troughs' peaks or narrow them)");
          }
      }
    s.text = std::to_string(n) + (n == 1 ? " mode (" : " modes (");
    for (std::size_t i = 0; i < n; ++i)
      s.text += (i ? ", " : "") + io::format_number(modes[i].frequency, 4)
                + " Hz x " + io::format_number(modes[i].peak, 4) + " width "
                + io::format_number(modes[i].width, 4) + " Hz";
    s.text += ")";
    if (cut_frequency > 0.)
      s.text += ", cut " + io::format_number(cut_frequency, 4) + " Hz (order "
                + std::to_string(cut_order) + ")";
    return s;
  }



  std::vector<ResonantMode>
  SiteAmplification::masada_modes()
  {
    return {{1.3, 2.5, 0.8}, {3.8, 3.0, 1.2}, {6.5, 2.0, 1.5}};
  }



  SiteAmplification
  SiteAmplification::masada()
  {
    SiteAmplification s = from_modes(masada_modes(), masada_cut_frequency, 8);
    s.text = "Masada top (thesis Fig. 5-14B, approximated): " + s.text;
    return s;
  }



  double
  SiteAmplification::mode_sum(const double f) const
  {
    double a = 1.;
    for (std::size_t i = 0; i < mode_list.size(); ++i)
      a += excess[i] * resonance(f, mode_list[i].frequency, mode_list[i].width);
    return a;
  }



  double
  SiteAmplification::operator()(const double f) const
  {
    switch (kind)
      {
        case Kind::unity:
          return 1.;
        case Kind::modes:
          {
            const double a = std::max(0., mode_sum(f));
            return cut > 0. ? a * low_pass_gain(f, cut, cut_order) : a;
          }
        case Kind::table:
          {
            if (!(f > 0.))
              return values.front();
            const double x = std::log(f);
            if (x <= log_f.front())
              return values.front();
            if (x >= log_f.back())
              return values.back();
            const std::size_t k
              = std::upper_bound(log_f.begin(), log_f.end(), x) - log_f.begin();
            const double w  = (x - log_f[k - 1]) / (log_f[k] - log_f[k - 1]);
            const double a0 = values[k - 1], a1 = values[k];
            if (a0 > 0. && a1 > 0.)
              return std::exp((1. - w) * std::log(a0) + w * std::log(a1));
            return (1. - w) * a0 + w * a1;
          }
      }
    return 1.;
  }



  Record
  apply_site_amplification(const Record            &record,
                           const SiteAmplification &amplification)
  {
    Record out = record;
    if (amplification.is_unity() || record.acceleration.empty())
      return out;
    const std::size_t n  = fast_fft_size(2 * record.acceleration.size());
    auto              X  = forward_real_fft(record.acceleration, n);
    const double      df = 1. / (n * record.dt);
    for (std::size_t k = 0; k < X.size(); ++k)
      X[k] *= amplification(k * df);
    const auto x = inverse_real_fft(X, n);
    std::copy(x.begin(),
              x.begin() + record.acceleration.size(),
              out.acceleration.begin());
    return out;
  }
} // namespace rockdda::seismic
