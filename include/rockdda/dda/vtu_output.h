/**
 * @file
 * ParaView output of a DDA state: blocks as polygon cells and contacts as
 * line cells in VTK XML unstructured-grid files (ASCII), and PVD series.
 */
#ifndef ROCKDDA_DDA_VTU_OUTPUT_H
#define ROCKDDA_DDA_VTU_OUTPUT_H

#include <rockdda/dda/engine.h>

#include <string>
#include <utility>
#include <vector>

namespace rockdda::dda
{
  /// Blocks: cell data id, material, displacement (m), velocity (m/s),
  /// rotation (rad), stress (Pa).
  std::string
  blocks_vtu(const DdaSystem &dda);

  /// Contacts as lines from the vertex to its projection on the edge: cell
  /// data state (0 open, 1 sliding, 2 locked), normal and shear force (N/m).
  std::string
  contacts_vtu(const DdaSystem &dda);

  /// A PVD collection of (time, file name) entries.
  std::string
  pvd(const std::vector<std::pair<double, std::string>> &entries);
} // namespace rockdda::dda

#endif
