/**
 * @file
 * Helpers shared by the coupled ratchet tests (test_ratchet_coupled.cc,
 * test_ratchet_earthquakes.cc): a cheap heat solution and the check that a
 * call throws an InputError naming a key.
 */
#ifndef ROCKDDA_TESTS_UNIT_RATCHET_TEST_HELPERS_H
#define ROCKDDA_TESTS_UNIT_RATCHET_TEST_HELPERS_H

#include <rockdda/coupling/thermal_load.h>
#include <rockdda/io/error.h>

#include <gtest/gtest.h>

#include <string>

namespace rockdda::coupling::test_helpers
{
  /// A cheap heat solution for the tests: one Crank-Nicolson step per
  /// sample (15 days), degree 1 (the mechanics is what is tested).
  inline HeatControls
  cheap_heat()
  {
    HeatControls h;
    h.degree            = 1;
    h.time_step         = 31557600. / 24.;
    h.spin_up_cycles    = 3;
    h.samples_per_cycle = 24;
    return h;
  }

  /// Expect an InputError whose message names @p key.
  template <typename F>
  void
  expect_error_naming(F &&f, const std::string &key)
  {
    try
      {
        f();
        ADD_FAILURE() << "no error for " << key;
      }
    catch (const InputError &e)
      {
        EXPECT_NE(std::string(e.what()).find(key), std::string::npos)
          << e.what();
      }
  }
} // namespace rockdda::coupling::test_helpers

#endif
