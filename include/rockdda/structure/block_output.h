/**
 * @file
 * Writing and reading the block file of the DDA engine
 * (doc/block-file-format.md), and VTU files of blocks and tagged edges.
 */
#ifndef ROCKDDA_STRUCTURE_BLOCK_OUTPUT_H
#define ROCKDDA_STRUCTURE_BLOCK_OUTPUT_H

#include <rockdda/structure/block_set.h>

#include <string>

namespace rockdda::structure
{
  /// The block file text (format "rockdda-blocks 1", coordinates in m).
  std::string
  block_file_text(const BlockSet &blocks);

  /**
   * The blocks in the scene format of the dda analysis
   * (doc/block-file-format-dda.md): one material (thesis Table 3-2: 2300
   * kg/m^3, 15.3 GPa, 0.21) and one joint (30 deg) for every block; the
   * per-edge tags are only in the rockdda block file. The blocks listed in
   * @p fixed get a 'fixed-block' line.
   */
  std::string
  dda_block_file_text(const BlockSet                 &blocks,
                      const std::vector<std::size_t> &fixed = {});

  /**
   * Blocks with an edge on the outer domain boundary (EdgeKind::boundary)
   * whose outward normal points down (@p bottom: n_y < -cos 45 deg) or
   * sideways (@p sides: |n_x| > cos 45 deg), plus the blocks whose
   * centroid lies inside @p region (if it has vertices). Sorted, once each.
   */
  std::vector<std::size_t>
  boundary_blocks(const BlockSet &blocks,
                  const bool      bottom,
                  const bool      sides,
                  const Polygon  &region = {});

  /**
   * Read a block file; throws InputError naming @p file_name and the line
   * for anything malformed (bad counts, vertex index out of range, unknown
   * edge kind, a block with fewer than 3 vertices or non-positive area).
   */
  BlockSet
  read_block_file(const std::string &file_name);

  /// Parse block file text (as read_block_file; @p name for messages).
  BlockSet
  parse_block_file(const std::string &text, const std::string &name);

  /// VTU (ParaView) of the blocks: polygons with cell data block id, area
  /// (m^2), width (m) along @p bedding_dip_deg.
  std::string
  blocks_vtu(const BlockSet &blocks, const double bedding_dip_deg);

  /// VTU of the block edges as lines with cell data kind (EdgeKind as int),
  /// set, block id.
  std::string
  edges_vtu(const BlockSet &blocks);
} // namespace rockdda::structure

#endif
