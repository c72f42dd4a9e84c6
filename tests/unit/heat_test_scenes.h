/**
 * @file
 * Pieces of heat-solver test scenes shared by the unit tests.
 */
#ifndef ROCKDDA_TESTS_HEAT_TEST_SCENES_H
#define ROCKDDA_TESTS_HEAT_TEST_SCENES_H

#include <rockdda/thermal/heat_solver.h>

#include <vector>

namespace rockdda::thermal::test_scenes
{
  /// Fixed temperatures @p tl on the faces tagged "left end" and @p tr on
  /// "right end" (K), as for steady conduction along a bar.
  inline std::vector<BoundaryCondition>
  fixed_end_temperatures(const double tl, const double tr)
  {
    BoundaryCondition left, right;
    left.tag    = "left end";
    left.type   = BoundaryCondition::Type::temperature;
    left.value  = [tl](double, double, double) { return tl; };
    right       = left;
    right.tag   = "right end";
    right.value = [tr](double, double, double) { return tr; };
    return {left, right};
  }
} // namespace rockdda::thermal::test_scenes

#endif
