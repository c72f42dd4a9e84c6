/**
 * @file
 * ParaView output of a DDA state: blocks as polygon cells and contacts as
 * line cells in VTK XML unstructured-grid files, and PVD series.
 *
 * The files are binary: every DataArray is format="binary" (base64 inline),
 * zlib-compressed (compressor="vtkZLibDataCompressor", header_type UInt64)
 * when deal.II was built with zlib, uncompressed otherwise. The fields,
 * their units and the contact state codes are listed in an XML comment at
 * the top of each file and in doc/user-guide.md (section "ParaView output
 * of dda"). scripts/read_vtu.py reads them with the Python standard
 * library.
 */
#ifndef ROCKDDA_DDA_VTU_OUTPUT_H
#define ROCKDDA_DDA_VTU_OUTPUT_H

#include <rockdda/dda/engine.h>
#include <rockdda/dda/snapshot.h>

#include <string>
#include <utility>
#include <vector>

namespace rockdda::dda
{
  /// A snapshot as one VTK XML unstructured-grid file.
  std::string
  vtu(const Snapshot &snapshot);

  /**
   * Blocks as polygons (points in global coordinates, m). Cell data:
   * - `block_id` (Int32): the block's id from the block file;
   * - `material` (Int32): the user's material id from the block file (a
   *   scene built in code without ids: the index of the material);
   * - `displacement` (m) and `velocity` (m/s) of the centroid, 3 components
   *   (z = 0);
   * - `rotation` (rad), cumulative;
   * - `stress` (Pa, tension positive): symmetric tensor of 6 components in
   *   ParaView's order XX, YY, ZZ, XY, YZ, XZ; the in-plane values are the
   *   engine's (sigma_x, sigma_y, tau_xy), ZZ, YZ and XZ are written as 0.
   */
  std::string
  blocks_vtu(const DdaSystem &dda);

  /**
   * Contacts as lines from the contact vertex to its projection on the
   * contact edge, with the current block geometry. Cell data:
   * - `state` (Int32): 0 open, 1 sliding, 2 locked (ContactState);
   * - `vertex_block`, `edge_block` (Int32): the block ids (from the block
   *   file) of the block whose vertex touches and of the block whose edge
   *   is touched;
   * - `normal_gap` (m): signed distance of the vertex from the edge's line,
   *   along the edge's outward normal; negative = penetration (a
   *   compressed contact);
   * - `shear_slip` (m): displacement of the vertex along the edge (in the
   *   edge's direction) from the contact's shear reference point. Locked:
   *   the elastic displacement of the shear spring (shear force = shear
   *   penalty x slip); sliding: the slip of the last step (the reference
   *   of a sliding contact is its position at the start of the step);
   *   open: 0;
   * - `normal_force` (N/m, compression positive) and `shear_force` (N/m)
   *   of the last solve;
   * - `normal` (-): the edge's unit outward normal, 3 components (z = 0).
   */
  std::string
  contacts_vtu(const DdaSystem &dda);

  /// A PVD collection of (time, file name) entries.
  std::string
  pvd(const std::vector<std::pair<double, std::string>> &entries);
} // namespace rockdda::dda

#endif
