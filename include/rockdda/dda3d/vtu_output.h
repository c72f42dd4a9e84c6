/**
 * @file
 * ParaView output of 3D DDA blocks: each block one VTK_POLYHEDRON cell
 * (type 42, with the `faces` / `faceoffsets` arrays of the VTK XML
 * unstructured-grid format) in an ASCII .vtu file.
 */
#ifndef ROCKDDA_DDA3D_VTU_OUTPUT_H
#define ROCKDDA_DDA3D_VTU_OUTPUT_H

#include <rockdda/dda3d/block_system.h>

#include <string>

namespace rockdda::dda3d
{
  /**
   * The blocks of @p system as a VTK XML unstructured grid (ASCII). Points
   * are the blocks' vertices plus @p origin (global coordinates, m). Cell
   * data:
   * - `block_id` (Int32): the block's id;
   * - `material` (Int32): the user's material id (the index if none);
   * - `displacement` (m): centroid now minus centroid at t = 0;
   * - `velocity` (m/s): the centroid's velocity (u0, v0, w0 rates);
   * - `stress` (Pa, tension positive): symmetric tensor, 6 components in
   *   ParaView's order XX, YY, ZZ, XY, YZ, XZ;
   * - `volume` (m^3).
   */
  std::string
  blocks_vtu(const BlockSystem &system, const Point &origin = Point::Zero());
} // namespace rockdda::dda3d

#endif
