/**
 * @file
 * Three expressions of t from a parameter.
 */
#include <rockdda/io/error.h>
#include <rockdda/io/time_expression.h>

#include <deal.II/base/function_parser.h>

#include <cmath>
#include <map>
#include <memory>

namespace rockdda::io
{
  std::function<Eigen::Vector3d(double)>
  parse_time_expressions(const std::string &expr,
                         const std::string &prm_file,
                         const std::string &key,
                         const std::string &example)
  {
    auto parser = std::make_shared<dealii::FunctionParser<1>>(3);
    try
      {
        parser->initialize("x,t",
                           expr,
                           std::map<std::string, double>{{"pi", M_PI}},
                           true);
        parser->set_time(0.);
        for (unsigned int c = 0; c < 3; ++c)
          if (!std::isfinite(parser->value(dealii::Point<1>(), c)))
            throw InputError("not finite at t = 0");
      }
    catch (const std::exception &)
      {
        throw InputError(prm_file + ": key '" + key + "' = '" + expr
                         + "' is not valid; valid: three expressions of t (s) "
                           "separated by ';' (e.g. '"
                         + example + "')");
      }
    return [parser](const double t) {
      parser->set_time(t);
      return Eigen::Vector3d(parser->value(dealii::Point<1>(), 0),
                             parser->value(dealii::Point<1>(), 1),
                             parser->value(dealii::Point<1>(), 2));
    };
  }
} // namespace rockdda::io
