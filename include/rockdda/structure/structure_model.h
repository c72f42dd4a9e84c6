/**
 * @file
 * The "Structure" parameter section (domain, excavations, seed, bedding,
 * layered joints, statistical joint sets, cutting options) shared by the
 * "cut" analysis and any DDA scene, and the trace network it generates.
 */
#ifndef ROCKDDA_STRUCTURE_STRUCTURE_MODEL_H
#define ROCKDDA_STRUCTURE_STRUCTURE_MODEL_H

#include <rockdda/structure/block_cutter.h>
#include <rockdda/structure/generators.h>

#include <deal.II/base/parameter_handler.h>

#include <cstdint>
#include <string>
#include <vector>

namespace rockdda::structure
{
  /// Number of "Joint set N" subsections (N = 1 ... max_joint_sets).
  constexpr unsigned int max_joint_sets = 3;

  /// Everything that defines a rock structure (all lengths in m).
  struct StructureModel
  {
    Polygon                         domain;
    std::vector<Polygon>            excavations;
    std::uint64_t                   seed    = 1;
    bool                            layered = true;
    LayeredParameters               layers;
    std::vector<JointSetParameters> joint_sets; ///< enabled sets only
    CutOptions                      cut;
  };

  /// The generated traces of a model.
  struct TraceNetwork
  {
    std::vector<TaggedSegment> traces; ///< bedding and all joints
    LayeredNetwork             layers; ///< beds (empty if not layered)
  };

  /// Declare the "Structure" section (once; later calls do nothing).
  void
  declare_structure_parameters(dealii::ParameterHandler &prm);

  /**
   * Read and check the "Structure" section; InputError names @p prm_file,
   * the key and the valid range.
   */
  StructureModel
  parse_structure(dealii::ParameterHandler &prm, const std::string &prm_file);

  /**
   * Parse a polygon "x1, y1; x2, y2; ..." (m); throws InputError naming
   * @p where for malformed text, fewer than 3 vertices or self-intersection.
   */
  Polygon
  parse_polygon(const std::string &text, const std::string &where);

  /**
   * Generate the traces of @p model from its seed: the layered network
   * first (joints of set index 0 if enabled), then the statistical sets in
   * order (set indices after it), each from the same random stream.
   */
  TraceNetwork
  generate_traces(const StructureModel &model);

  /// Generate and cut: the blocks of @p model.
  BlockSet
  build_blocks(const StructureModel &model, const TraceNetwork &traces);
} // namespace rockdda::structure

#endif
