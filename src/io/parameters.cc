#include <rockdda/io/error.h>
#include <rockdda/io/parameters.h>
#include <rockdda/io/provenance.h>

#include <algorithm>
#include <boost/property_tree/json_parser.hpp>
#include <boost/property_tree/ptree.hpp>
#include <cctype>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iomanip>
#include <limits>
#include <memory>
#include <regex>
#include <sstream>

namespace rockdda::io
{
  namespace
  {
    /// The additional-information text of a deal.II exception, on one line.
    std::string
    exception_text(const dealii::ExceptionBase &exc)
    {
      std::ostringstream s;
      exc.print_info(s);
      std::string text = s.str();
      text             = std::regex_replace(text, std::regex("\\s+"), " ");
      while (!text.empty() && text.back() == ' ')
        text.pop_back();
      if (!text.empty() && text.front() == ' ')
        text.erase(0, 1);
      return text;
    }

    /// Subsection path (a/b/c) in effect at line @p line_no of @p file.
    std::string
    section_at(const std::string &file, const int line_no)
    {
      std::ifstream            in(file);
      std::string              line;
      std::vector<std::string> stack;
      const std::regex         sub("^\\s*subsection\\s+(.*?)\\s*$");
      const std::regex         end("^\\s*end\\s*$");
      std::smatch              m;
      for (int i = 1; i < line_no && std::getline(in, line); ++i)
        {
          const auto hash = line.find('#');
          if (hash != std::string::npos)
            line.erase(hash);
          if (std::regex_match(line, m, sub))
            stack.push_back(m[1]);
          else if (std::regex_match(line, end) && !stack.empty())
            stack.pop_back();
        }
      std::string path;
      for (const auto &s : stack)
        path += (path.empty() ? "" : "/") + s;
      return path.empty() ? "top level" : "'" + path + "'";
    }

    /// Line number mentioned as "Line <N>" in a deal.II message, or 0.
    int
    line_of(const std::string &text)
    {
      std::smatch m;
      if (std::regex_search(text, m, std::regex("Line <(\\d+)>")))
        return std::stoi(m[1]);
      return 0;
    }
  } // namespace



  void
  parse_parameter_file(dealii::ParameterHandler &prm, const std::string &file)
  {
    if (!std::filesystem::is_regular_file(file))
      throw InputError(file + ": no such parameter file");
    std::ifstream in(file);
    if (!in)
      throw InputError(file + ": cannot read the parameter file");
    const std::string hint
      = " (run 'rockdda --print-parameters' for every section, key and valid "
        "value)";
    try
      {
        prm.parse_input(in, file, "", false);
      }
    catch (const dealii::ParameterHandler::ExcInvalidEntryForPattern &exc)
      {
        const std::string text = exception_text(exc);
        const int         line = line_of(text);
        std::smatch       m;
        std::string       msg = file + ":" + std::to_string(line) + ": ";
        const std::regex  pat(
          "entry value <?(.*?)>? for the entry named <?(.*?)>? does not "
           "match the given pattern:? <?(.*?)>?$");
        if (std::regex_search(text, m, pat))
          msg += "value '" + m[1].str() + "' for key '" + m[2].str()
                 + "' in section " + section_at(file, line)
                 + " is not valid; valid values: " + m[3].str();
        else
          msg += text;
        throw InputError(msg);
      }
    catch (const dealii::ParameterHandler::ExcCannotParseLine &exc)
      {
        const std::string text = exception_text(exc);
        const int         line = line_of(text);
        std::string       msg  = text;
        const auto        pos  = msg.find(">: ");
        if (pos != std::string::npos)
          msg = msg.substr(pos + 3);
        throw InputError(file + ":" + std::to_string(line) + ": in section "
                         + section_at(file, line) + ": " + msg + hint);
      }
    catch (const dealii::ParameterHandler::ExcNoSubsection &exc)
      {
        const std::string text = exception_text(exc);
        const int         line = line_of(text);
        std::smatch       m;
        std::regex_search(text,
                          m,
                          std::regex("no such subsection to be entered: (.*)"));
        throw InputError(file + ":" + std::to_string(line)
                         + ": unknown section '" + m[1].str() + "' inside "
                         + section_at(file, line) + hint);
      }
    catch (const dealii::ExceptionBase &exc)
      {
        throw InputError(file + ": " + exception_text(exc) + hint);
      }
  }



  DoubleInterval::DoubleInterval(const double lower,
                                 const bool   lower_open,
                                 const double upper,
                                 const bool   upper_open)
      : lower(lower)
      , upper(upper)
      , lower_open(lower_open)
      , upper_open(upper_open)
  {}



  DoubleInterval
  DoubleInterval::positive()
  {
    return DoubleInterval(0.,
                          true,
                          std::numeric_limits<double>::infinity(),
                          false);
  }



  DoubleInterval
  DoubleInterval::right_open(const double lower, const double upper)
  {
    return DoubleInterval(lower, false, upper, true);
  }



  bool
  DoubleInterval::match(const std::string &value) const
  {
    std::istringstream in(value);
    double             x = 0.;
    in >> x;
    if (in.fail() || !std::isfinite(x))
      return false;
    in >> std::ws;
    if (!in.eof())
      return false;
    const bool above = lower_open ? x > lower : x >= lower;
    const bool below = upper_open ? x < upper : x <= upper;
    return above && below;
  }



  std::string
  DoubleInterval::description(const OutputStyle) const
  {
    const auto number = [](const double v) {
      std::ostringstream s;
      s << std::setprecision(12) << v;
      return s.str();
    };
    std::string text = "[Double ";
    if (std::isfinite(lower) && std::isfinite(upper))
      text += number(lower) + (lower_open ? " < x " : " <= x ")
              + (upper_open ? "< " : "<= ") + number(upper);
    else if (std::isfinite(lower))
      text += std::string("x ") + (lower_open ? "> " : ">= ") + number(lower);
    else
      text += std::string("x ") + (upper_open ? "< " : "<= ") + number(upper);
    return text + "]";
  }



  std::unique_ptr<dealii::Patterns::PatternBase>
  DoubleInterval::clone() const
  {
    return std::make_unique<DoubleInterval>(*this);
  }



  void
  declare(dealii::ParameterHandler            &prm,
          const std::string                   &key,
          const std::string                   &default_value,
          const dealii::Patterns::PatternBase &pattern,
          const std::string                   &unit,
          const std::string                   &help)
  {
    prm.declare_entry(key, default_value, pattern, "[" + unit + "] " + help);
  }



  std::string
  resolve_path(const std::string &path,
               const std::string &prm_file,
               const std::string &key)
  {
    std::string      result;
    const std::regex var(
      "\\$\\{([A-Za-z_][A-Za-z0-9_]*)\\}|\\$([A-Za-z_][A-Za-z0-9_]*)");
    auto        begin = std::sregex_iterator(path.begin(), path.end(), var);
    std::size_t last  = 0;
    for (auto it = begin; it != std::sregex_iterator(); ++it)
      {
        const auto &m     = *it;
        const auto  name  = m[1].matched ? m[1].str() : m[2].str();
        const char *value = std::getenv(name.c_str());
        if (value == nullptr)
          throw InputError(prm_file + ": key '" + key + "' uses $" + name
                           + ", which is not set in the environment");
        result += path.substr(last, m.position() - last) + value;
        last = m.position() + m.length();
      }
    result += path.substr(last);
    std::filesystem::path p(result);
    if (p.is_relative())
      p = std::filesystem::path(prm_file).parent_path() / p;
    p = p.lexically_normal();
    // Recorded for parameters.prm (absolute path and checksum).
    auto &files = resolved_input_files();
    files.erase(std::remove_if(files.begin(),
                               files.end(),
                               [&key](const InputFile &f) {
                                 return f.key == key;
                               }),
                files.end());
    files.push_back(
      {key, path, std::filesystem::absolute(p).lexically_normal().string()});
    return p.string();
  }



  void
  require(const bool         ok,
          const std::string &prm_file,
          const std::string &key,
          const double       value,
          const std::string &range)
  {
    with_parameter_file(prm_file,
                        [&]() { require_in_range(ok, key, value, range); });
  }



  namespace
  {
    /// Undo deal.II's mangling of names in JSON output ("_XX" = hex byte).
    std::string
    demangle(const std::string &name)
    {
      std::string out;
      for (std::size_t i = 0; i < name.size(); ++i)
        if (name[i] == '_' && i + 2 < name.size() + 0
            && std::isxdigit(name[i + 1]) && std::isxdigit(name[i + 2]))
          {
            out += static_cast<char>(
              std::stoi(name.substr(i + 1, 2), nullptr, 16));
            i += 2;
          }
        else
          out += name[i];
      return out;
    }

    void
    print_section(const boost::property_tree::ptree &tree,
                  const std::string                 &path,
                  std::ostream                      &out)
    {
      bool header = false;
      for (const auto &[name, node] : tree)
        {
          if (node.get_child_optional("value")
              && node.get_child_optional("pattern_description"))
            {
              if (!header)
                {
                  out << "\n## " << (path.empty() ? "Top level" : path)
                      << "\n\n| key | default | valid values | unit | "
                         "description |\n|---|---|---|---|---|\n";
                  header = true;
                }
              std::string doc  = node.get<std::string>("documentation", "");
              std::string unit = "-";
              if (doc.size() > 2 && doc.front() == '[')
                {
                  const auto close = doc.find("] ");
                  if (close != std::string::npos)
                    {
                      unit = doc.substr(1, close - 1);
                      doc  = doc.substr(close + 2);
                    }
                }
              auto esc = [](std::string s) {
                std::string r;
                for (char c : s)
                  r += (c == '|')
                         ? std::string("\\|")
                         : (c == '\n' ? std::string(" ") : std::string(1, c));
                return r;
              };
              out << "| `" << esc(demangle(name)) << "` | `"
                  << esc(node.get<std::string>("default_value")) << "` | "
                  << esc(node.get<std::string>("pattern_description")) << " | "
                  << esc(unit) << " | " << esc(doc) << " |\n";
            }
        }
      for (const auto &[name, node] : tree)
        if (!(node.get_child_optional("value")
              && node.get_child_optional("pattern_description")))
          print_section(node,
                        (path.empty() ? "" : path + " / ") + demangle(name),
                        out);
    }
  } // namespace



  void
  print_parameter_reference(const dealii::ParameterHandler &prm,
                            std::ostream                   &out)
  {
    std::stringstream json;
    prm.print_parameters(json,
                         static_cast<dealii::ParameterHandler::OutputStyle>(
                           dealii::ParameterHandler::JSON
                           | dealii::ParameterHandler::KeepDeclarationOrder));
    boost::property_tree::ptree tree;
    boost::property_tree::read_json(json, tree);
    out << "# rockdda parameter reference\n\n"
        << "Generated by `rockdda --print-parameters`; do not edit by hand.\n"
        << "Every key with its default, valid values, SI unit and meaning. "
        << "A parameter file sets only what differs from the defaults.\n";
    print_section(tree, "", out);
  }
} // namespace rockdda::io
