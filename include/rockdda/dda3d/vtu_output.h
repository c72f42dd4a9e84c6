/**
 * @file
 * ParaView output of 3D DDA blocks: each block one VTK_POLYHEDRON cell
 * (type 42, with the `faces` / `faceoffsets` arrays of the VTK XML
 * unstructured-grid format) in an ASCII .vtu file; contacts as line cells,
 * written by the 2D engine's binary writer (dda::vtu()).
 */
#ifndef ROCKDDA_DDA3D_VTU_OUTPUT_H
#define ROCKDDA_DDA3D_VTU_OUTPUT_H

#include <rockdda/dda/snapshot.h>
#include <rockdda/dda3d/block_system.h>
#include <rockdda/dda3d/engine.h>

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

  /**
   * The blocks of @p system as a dda::Snapshot of polygon cells, one per
   * face of every block (its own points, the block's vertices plus @p
   * origin, m, counter-clockwise seen from outside), for the HDF5 + XDMF
   * writer of large scenes (dda::Hdf5Series; XDMF has no polyhedron cell
   * that ParaView reads, so a block is drawn as its closed surface). Each
   * face carries its block's cell data of blocks_vtu(): `block_id`,
   * `material`, `displacement`, `velocity`, `stress`, `volume`.
   */
  dda::Snapshot
  blocks_snapshot(const BlockSystem &system,
                  const Point       &origin = Point::Zero());

  /**
   * The contacts of @p engine (Engine::contacts(), the last accepted step)
   * as a dda::Snapshot of line cells, one per contact, from its point on
   * block i (vertex, or edge point) to its point on block j, both as
   * detected at the start of the step (global coordinates, m). Cell data:
   * - `state` (Int32): 0 open, 1 sliding, 2 locked;
   * - `type` (Int32): 0 vertex-face, 1 edge-edge;
   * - `block_i`, `block_j` (Int32): the block ids (i owns the vertex or
   *   the first edge, j the face or the second edge);
   * - `normal_gap` (m): the gap at detection, negative = penetration;
   * - `normal_force` (N, compression positive), `shear_force` (N, on block
   *   i, 3 components) of the last solve;
   * - `normal` (-): the contact normal, out of block j;
   * - `area` (m^2): the contact's share of the touching faces' overlap.
   */
  dda::Snapshot
  contacts_snapshot(const Engine &engine);

  /// contacts_snapshot() as a binary VTK XML unstructured grid.
  std::string
  contacts_vtu(const Engine &engine);
} // namespace rockdda::dda3d

#endif
