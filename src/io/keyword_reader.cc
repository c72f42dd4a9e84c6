/**
 * @file
 * KeywordReader: the block files' line tokeniser.
 */
#include <rockdda/io/error.h>
#include <rockdda/io/keyword_reader.h>

#include <cmath>
#include <cstdlib>

namespace rockdda::io
{
  KeywordReader::KeywordReader(const std::string &text, const std::string &what)
      : in(text)
      , what(what)
  {}



  bool
  KeywordReader::next()
  {
    std::string text;
    while (std::getline(in, text))
      {
        ++line;
        const auto hash = text.find('#');
        if (hash != std::string::npos)
          text.erase(hash);
        std::istringstream tokens(text);
        if (!(tokens >> keyword))
          continue;
        where = what + ", line " + std::to_string(line) + ": ";
        words.clear();
        for (std::string w; tokens >> w;)
          words.push_back(w);
        return true;
      }
    return false;
  }



  double
  KeywordReader::number(const std::size_t k) const
  {
    if (k >= words.size())
      throw InputError(where + "'" + keyword + "' needs more values");
    char        *end = nullptr;
    const double v   = std::strtod(words[k].c_str(), &end);
    if (end == words[k].c_str() || *end != '\0' || !std::isfinite(v))
      throw InputError(where + "'" + words[k] + "' is not a number");
    return v;
  }



  int
  KeywordReader::integer(const std::size_t k) const
  {
    const double v = number(k);
    if (v != std::floor(v) || std::abs(v) > 2e9)
      throw InputError(where + "'" + words[k] + "' is not an integer");
    return static_cast<int>(v);
  }


  std::pair<int, std::vector<double>>
  KeywordReader::id_and_numbers(const std::size_t n) const
  {
    if (words.size() != n)
      throw InputError(where + "'" + keyword + "' takes " + std::to_string(n)
                       + " values");
    const int           id = integer(0);
    std::vector<double> values;
    for (std::size_t k = 1; k < n; ++k)
      values.push_back(number(k));
    return {id, values};
  }
} // namespace rockdda::io
