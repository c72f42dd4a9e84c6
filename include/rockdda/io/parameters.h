/**
 * @file
 * Parameter files: parsing with clear errors, paths, and the parameter
 * reference.
 */
#ifndef ROCKDDA_IO_PARAMETERS_H
#define ROCKDDA_IO_PARAMETERS_H

#include <rockdda/io/error.h>

#include <deal.II/base/parameter_handler.h>

#include <ostream>
#include <string>

namespace rockdda::io
{
  /**
   * Parse @p file into @p prm. Any problem (a missing file, an unknown section
   * or key, a value that does not match its pattern or range, unbalanced
   * subsections) becomes one InputError whose message names the file, the
   * line, the key and the valid values.
   */
  void
  parse_parameter_file(dealii::ParameterHandler &prm, const std::string &file);

  /**
   * The valid values of a real-valued key whose range has an open end, as
   * its help text states it (e.g. "> 0", "0 <= dip < 90"):
   * dealii::Patterns::Double only has closed ends, so that a key documented
   * as "> 0" would accept 0. A value outside is rejected while the
   * parameter file is read, with a message naming the file, line, key and
   * this range. Shown as e.g. "[Double x > 0]" or "[Double 0 <= x < 90]".
   */
  class DoubleInterval : public dealii::Patterns::PatternBase
  {
  public:
    /// The interval between @p lower and @p upper; an end is excluded if
    /// its flag is true; an infinite end is unbounded.
    DoubleInterval(const double lower,
                   const bool   lower_open,
                   const double upper,
                   const bool   upper_open);

    /// x > 0.
    static DoubleInterval
    positive();

    /// @p lower <= x < @p upper.
    static DoubleInterval
    right_open(const double lower, const double upper);

    bool
    match(const std::string &value) const override;

    std::string
    description(const OutputStyle style = Machine) const override;

    std::unique_ptr<dealii::Patterns::PatternBase>
    clone() const override;

  private:
    double lower, upper;
    bool   lower_open, upper_open;
  };

  /**
   * Declare an entry whose help text starts with its SI unit in brackets, e.g.
   * declare(prm, "Time step", "0.01", Patterns::Double(0), "s", "...").
   * Use "-" for dimensionless values, names and choices. The unit then shows
   * in --print-parameters and doc/parameters.md.
   */
  void
  declare(dealii::ParameterHandler            &prm,
          const std::string                   &key,
          const std::string                   &default_value,
          const dealii::Patterns::PatternBase &pattern,
          const std::string                   &unit,
          const std::string                   &help);

  /**
   * Resolve a file name given in parameter file @p prm_file: $VAR and ${VAR}
   * are replaced by environment variables (an unset variable is an error
   * naming @p key), and a relative path is taken relative to the parameter
   * file's folder.
   */
  std::string
  resolve_path(const std::string &path,
               const std::string &prm_file,
               const std::string &key);

  /**
   * Throw an InputError for @p key (with its section path) in @p prm_file
   * unless @p ok; @p range describes the valid values, e.g. "0 <= dip < 90
   * deg".
   */
  void
  require(const bool         ok,
          const std::string &prm_file,
          const std::string &key,
          const double       value,
          const std::string &range);

  /**
   * Run @p f; an InputError it throws (from a module that does not know the
   * parameter file) is re-thrown with @p prm_file in front of its message.
   */
  template <typename F>
  void
  with_parameter_file(const std::string &prm_file, F &&f);

  /**
   * Write the reference of every declared parameter as Markdown: section,
   * key, default, valid values, SI unit and help text.
   */
  void
  print_parameter_reference(const dealii::ParameterHandler &prm,
                            std::ostream                   &out);

  template <typename F>
  void
  with_parameter_file(const std::string &prm_file, F &&f)
  {
    try
      {
        f();
      }
    catch (const InputError &e)
      {
        throw InputError(prm_file + ": " + e.what());
      }
  }
} // namespace rockdda::io

#endif
