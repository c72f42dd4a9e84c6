/**
 * @file
 * A vector-valued function of time read from a parameter: three
 * expressions of t separated by ';'.
 */
#ifndef ROCKDDA_IO_TIME_EXPRESSION_H
#define ROCKDDA_IO_TIME_EXPRESSION_H

#include <Eigen/Core>

#include <functional>
#include <string>

namespace rockdda::io
{
  /**
   * The three expressions of t (s) in @p expr, separated by ';' (deal.II's
   * FunctionParser; the constant pi is defined), as a function of t. Throws
   * InputError naming @p prm_file, @p key and the valid form (with
   * @p example) when they do not parse or are not finite at t = 0.
   */
  std::function<Eigen::Vector3d(double)>
  parse_time_expressions(const std::string &expr,
                         const std::string &prm_file,
                         const std::string &key,
                         const std::string &example);
} // namespace rockdda::io

#endif
