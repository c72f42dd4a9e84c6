/**
 * @file
 * Line-by-line reader of the keyword text files (the 2D and 3D block
 * files): '#' starts a comment, blank lines are skipped, each line is a
 * keyword and its words, and conversion errors name the file and line.
 */
#ifndef ROCKDDA_IO_KEYWORD_READER_H
#define ROCKDDA_IO_KEYWORD_READER_H

#include <sstream>
#include <string>
#include <utility>
#include <vector>

namespace rockdda::io
{
  /// Reads a keyword text file one non-empty line at a time.
  class KeywordReader
  {
  public:
    /// @p text is the file's contents, @p what its name in messages (e.g.
    /// "block file 'x.dda'").
    KeywordReader(const std::string &text, const std::string &what);

    /// Advance to the next line with a keyword; false at the end.
    bool
    next();

    /// The word @p k after the keyword as a finite number; InputError
    /// naming the file and line if it is missing or not a number.
    double
    number(const std::size_t k) const;

    /// The word @p k as an integer (|v| <= 2e9); InputError as number().
    int
    integer(const std::size_t k) const;

    /// A line "KEYWORD ID X1 ... X(n-1)": exactly @p n words (else
    /// InputError "'KEYWORD' takes n values"), the integer id and the
    /// numbers after it.
    std::pair<int, std::vector<double>>
    id_and_numbers(const std::size_t n) const;

    /// The current line's keyword and the words after it.
    std::string              keyword;
    std::vector<std::string> words;
    /// Its line number (from 1) and the message prefix "WHAT, line N: ".
    int         line = 0;
    std::string where;

  private:
    std::istringstream in;
    std::string        what;
  };
} // namespace rockdda::io

#endif
