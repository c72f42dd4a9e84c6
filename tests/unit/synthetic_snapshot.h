/**
 * @file
 * A synthetic DDA snapshot whose every value follows from the block index,
 * for the collective HDF5 tests (tests/mpi/test_dda_hdf5_collective.cc) and
 * the 10^6-block output benchmark (benchmarks/dda-scaling/
 * snapshot_mpi.cc): the bricks of a running-bond wall, and a check that a
 * snapshot read back holds exactly those values.
 */
#ifndef ROCKDDA_TESTS_UNIT_SYNTHETIC_SNAPSHOT_H
#define ROCKDDA_TESTS_UNIT_SYNTHETIC_SNAPSHOT_H

#include <rockdda/dda/snapshot.h>

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

namespace rockdda::dda::test_scenes
{
  /**
   * Bricks @p first .. @p first + @p count - 1 of a running-bond wall of
   * @p columns bricks (1 m x 0.5 m) per course and @p courses courses,
   * brick b in course b / columns, odd courses shifted by half a brick, far
   * from the origin (7.1e5 m, 3.5e6 m). Each brick has its four corners
   * and, where a course lies below or above it, the midpoint of that edge
   * (the end of the joint of the neighbouring course): 4 to 6 vertices.
   * Fields: `block_id` (b), `material` (course mod 3), `displacement` (m),
   * `rotation` (rad) and `stress` (Pa), each an exact function of b.
   */
  inline Snapshot
  running_bond_blocks(const std::size_t first,
                      const std::size_t count,
                      const std::size_t columns,
                      const std::size_t courses)
  {
    Snapshot s;
    s.fields = {integer_field("block_id", {}),
                integer_field("material", {}),
                real_field("displacement", 3, {}),
                real_field("rotation", 1, {}),
                real_field("stress", 6, {})};
    s.offsets.reserve(count);
    s.xyz.reserve(count * 6 * 3);
    for (std::size_t b = first; b < first + count; ++b)
      {
        const std::size_t course = b / columns, i = b % columns;
        const double      x0
          = 7.1e5 + static_cast<double>(i) + (course % 2 == 1 ? 0.5 : 0.);
        const double y0    = 3.5e6 + 0.5 * static_cast<double>(course);
        auto         point = [&](const double x, const double y) {
          s.xyz.insert(s.xyz.end(), {x, y, 0.});
        };
        point(x0, y0);
        if (course > 0)
          point(x0 + 0.5, y0);
        point(x0 + 1., y0);
        point(x0 + 1., y0 + 0.5);
        if (course + 1 < courses)
          point(x0 + 0.5, y0 + 0.5);
        point(x0, y0 + 0.5);
        s.offsets.push_back(static_cast<std::int64_t>(s.n_points()));
        const double d = static_cast<double>(b);
        s.fields[0].integer.push_back(static_cast<std::int32_t>(b));
        s.fields[1].integer.push_back(static_cast<std::int32_t>(course % 3));
        s.fields[2].real.insert(s.fields[2].real.end(),
                                {1e-6 * d, -2e-6 * d, 0.});
        s.fields[3].real.push_back(1e-9 * d);
        s.fields[4].real.insert(s.fields[4].real.end(),
                                {-1e3 * d, -2e3 * d, 0., 5e2 * d, 0., 0.});
      }
    return s;
  }

  /**
   * The contacts of those bricks with their right neighbour in the same
   * course (the vertex block's owner writes a contact), as vertical lines
   * in the joint. Fields: `state` (b mod 3), `vertex_block` (b),
   * `edge_block` (b + 1), `normal_force` (N/m) and `normal`.
   */
  inline Snapshot
  running_bond_contacts(const std::size_t first,
                        const std::size_t count,
                        const std::size_t columns)
  {
    Snapshot s;
    s.lines  = true;
    s.fields = {integer_field("state", {}),
                integer_field("vertex_block", {}),
                integer_field("edge_block", {}),
                real_field("normal_force", 1, {}),
                real_field("normal", 3, {})};
    for (std::size_t b = first; b < first + count; ++b)
      {
        if (b % columns + 1 == columns)
          continue;
        const std::size_t course = b / columns;
        const double      x      = 7.1e5 + static_cast<double>(b % columns + 1)
                         + (course % 2 == 1 ? 0.5 : 0.);
        const double y = 3.5e6 + 0.5 * static_cast<double>(course);
        s.xyz.insert(s.xyz.end(), {x, y + 0.125, 0., x, y + 0.375, 0.});
        s.offsets.push_back(static_cast<std::int64_t>(s.n_points()));
        s.fields[0].integer.push_back(static_cast<std::int32_t>(b % 3));
        s.fields[1].integer.push_back(static_cast<std::int32_t>(b));
        s.fields[2].integer.push_back(static_cast<std::int32_t>(b + 1));
        s.fields[3].real.push_back(10. * static_cast<double>(b));
        s.fields[4].real.insert(s.fields[4].real.end(), {-1., 0., 0.});
      }
    return s;
  }

  /// The first difference between snapshot @p read (read back) and
  /// @p expected: points, offsets, kind and every field bit for bit
  /// (description and default fields are not compared); "" if none.
  inline std::string
  first_difference(const Snapshot &read, const Snapshot &expected)
  {
    if (read.lines != expected.lines)
      return "lines or polygons";
    if (read.offsets != expected.offsets)
      return "offsets (" + std::to_string(read.n_cells()) + " cells, expected "
             + std::to_string(expected.n_cells()) + ")";
    if (read.xyz != expected.xyz)
      return "points (" + std::to_string(read.n_points()) + ", expected "
             + std::to_string(expected.n_points()) + ")";
    if (read.fields.size() != expected.fields.size())
      return "number of fields";
    for (std::size_t k = 0; k < read.fields.size(); ++k)
      {
        const auto &a = read.fields[k];
        const auto &e = expected.fields[k];
        if (a.name != e.name || a.components != e.components
            || a.integer != e.integer || a.real != e.real)
          return "field " + e.name;
      }
    return "";
  }
} // namespace rockdda::dda::test_scenes

#endif
