/**
 * @file
 * The 3D DDA block file: materials, polyhedral blocks (vertices and
 * faces), fixed, load and measurement points, initial velocities. The
 * format is documented in doc/block-file-format-dda3d.md.
 */
#ifndef ROCKDDA_DDA3D_BLOCK_FILE_H
#define ROCKDDA_DDA3D_BLOCK_FILE_H

#include <rockdda/dda3d/block_system.h>

#include <string>

namespace rockdda::dda3d
{
  /**
   * Read a 3D block file. Throws InputError naming the file and line (and
   * the block and face) for an unknown keyword, a malformed number, a
   * duplicate or undefined id, a material out of range (density,
   * Young's modulus, Poisson's ratio), a polyhedron that is not closed,
   * has inward normals or a non-planar face (polyhedron_defect()), and a
   * point outside its block. The scene is returned validated
   * (validate_and_prepare()).
   */
  BlockSystem
  read_block_file(const std::string &file_name);

  /// Parse block-file text; @p name is used in messages.
  BlockSystem
  parse_block_text(const std::string &text, const std::string &name);

  /// The text of @p system in the block-file format (full precision).
  std::string
  block_text(const BlockSystem &system);
} // namespace rockdda::dda3d

#endif
