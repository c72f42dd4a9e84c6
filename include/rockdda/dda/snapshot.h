/**
 * @file
 * One DDA snapshot as plain arrays: the blocks as polygons or the contacts
 * as lines, with named cell fields. The VTU and the HDF5/XDMF writers both
 * write a Snapshot, so the two formats carry the same fields.
 */
#ifndef ROCKDDA_DDA_SNAPSHOT_H
#define ROCKDDA_DDA_SNAPSHOT_H

#include <rockdda/dda/engine.h>

#include <cstdint>
#include <string>
#include <utility>
#include <vector>

namespace rockdda::dda
{
  /// A named cell field of a Snapshot: integer or real, 1, 3 or 6 values
  /// per cell (cell-major).
  struct SnapshotField
  {
    std::string               name;
    int                       components = 1;
    std::vector<double>       real;
    std::vector<std::int32_t> integer;
    /// Names of the components (VTK ComponentNameN); empty: none.
    std::vector<std::string> component_names;
    /// Number of cells.
    std::size_t
    size() const
    {
      return (integer.empty() ? real.size() : integer.size())
             / static_cast<std::size_t>(components);
    }
  };

  /**
   * Cells of one kind (polygons or lines) in global coordinates (m, z = 0)
   * and their fields. Cell c uses the points offsets[c - 1] .. offsets[c] -
   * 1 (offsets[-1] = 0), each point once, in order.
   */
  struct Snapshot
  {
    /// Points, 3 coordinates each (m).
    std::vector<double> xyz;
    /// End of each cell's points (exclusive).
    std::vector<std::int64_t> offsets;
    /// Polygons (blocks) or two-point lines (contacts).
    bool lines = false;
    /// What the file holds, with units (an XML comment / attribute).
    std::string                description;
    std::vector<SnapshotField> fields;
    /// The default scalar, vector and tensor fields (ParaView).
    std::string scalars, vectors, tensors;

    std::size_t
    n_points() const
    {
      return xyz.size() / 3;
    }
    std::size_t
    n_cells() const
    {
      return offsets.size();
    }
  };

  /// A real field of @p components values per cell (cell-major).
  inline SnapshotField
  real_field(const std::string  &name,
             const int           components,
             std::vector<double> v)
  {
    SnapshotField f;
    f.name       = name;
    f.components = components;
    f.real       = std::move(v);
    return f;
  }

  /// An integer field of one value per cell.
  inline SnapshotField
  integer_field(const std::string &name, std::vector<std::int32_t> v)
  {
    SnapshotField f;
    f.name    = name;
    f.integer = std::move(v);
    return f;
  }

  /**
   * Blocks as polygons. Fields: `block_id` (block file id), `material`
   * (block file material id), `displacement` (m) and `velocity` (m/s) of
   * the centroid (3 components, z = 0), `rotation` (rad, cumulative) and
   * `stress` (Pa, tension positive; XX YY ZZ XY YZ XZ, the out-of-plane
   * components 0).
   */
  Snapshot
  blocks_snapshot(const DdaSystem &dda);

  /**
   * Contacts as lines from the contact vertex to its projection on the
   * contact edge (current geometry). Fields: `state` (0 open, 1 sliding, 2
   * locked), `vertex_block` and `edge_block` (block file ids),
   * `normal_gap` (m, negative = penetration), `shear_slip` (m),
   * `normal_force` (N/m, compression positive), `shear_force` (N/m),
   * `normal` (unit outward normal of the edge). See vtu_output.h.
   */
  Snapshot
  contacts_snapshot(const DdaSystem &dda);
} // namespace rockdda::dda

#endif
