/**
 * @file
 * The DDA block file: a simple text description of a scene (materials,
 * joints, blocks, fixed, load and measurement points, initial velocities).
 * The format is documented in doc/block-file-format-dda.md.
 */
#ifndef ROCKDDA_DDA_BLOCK_FILE_H
#define ROCKDDA_DDA_BLOCK_FILE_H

#include <rockdda/dda/block_system.h>
#include <rockdda/io/keyword_reader.h>

#include <string>
#include <utility>

namespace rockdda::dda
{
  /**
   * Read a block file into a scene (gravity and seismic input are left at
   * their defaults). Throws InputError naming the file and line for an
   * unknown keyword, a malformed number, a duplicate or unknown id, a
   * negative joint stiffness (naming the joint), or a block with fewer
   * than 3 vertices.
   */
  BlockSystem
  read_block_file(const std::string &file_name);

  /// Parse block-file text; @p name is used in messages.
  BlockSystem
  parse_block_text(const std::string &text, const std::string &name);

  /**
   * The joint line "joint ID FRICTION_DEG COHESION TENSILE [KN KS]" that
   * @p reader stands on (2D and 3D block files): its id and material.
   * Throws InputError naming the line (and the joint) for a wrong word
   * count (5 words: both stiffnesses or neither), a malformed number or a
   * stiffness that is negative or not finite. Ranges of the friction
   * angle, cohesion and tension are checked with the scene.
   */
  std::pair<int, JointMaterial>
  joint_line(const io::KeywordReader &reader);

  /**
   * Words after the keyword of a point line of a @p dim-dimensional block
   * file (2D and 3D share the keywords): "fixed ID X..." and "measure ID
   * X..." 1 + dim, "load ID X... F..." 1 + 2 dim, "velocity ID V... W..."
   * 1 + dim + dim (dim - 1) / 2 (the rotation components), "fixed-block
   * ID" 1; 0 for any other keyword.
   */
  inline std::size_t
  point_line_words(const std::string &keyword, const std::size_t dim)
  {
    if (keyword == "fixed" || keyword == "measure")
      return 1 + dim;
    if (keyword == "load")
      return 1 + 2 * dim;
    if (keyword == "velocity")
      return 1 + dim + dim * (dim - 1) / 2;
    if (keyword == "fixed-block")
      return 1;
    return 0;
  }
} // namespace rockdda::dda

#endif
