/**
 * @file
 * Contact detection of 2D DDA: a uniform-grid broad phase on bounding boxes
 * grown by the search distance, and a vertex-to-edge narrow phase with
 * Shi's entrance rule. Emits plain records; knows nothing of contact states.
 */
#ifndef ROCKDDA_DDA_CONTACT_DETECTION_H
#define ROCKDDA_DDA_CONTACT_DETECTION_H

#include <rockdda/geometry/polygon.h>

#include <utility>
#include <vector>

namespace rockdda::dda
{
  /**
   * A geometric contact candidate: vertex @p vertex of block @p block_i
   * near edge @p edge of block @p block_j (the edge from vertex e to vertex
   * e+1 of j). @p normal is the unit outward normal of the edge (pointing
   * out of j), @p xi the parameter of the vertex's projection on the edge
   * (0 at its start, 1 at its end, clamped to [0, 1]) and @p gap the signed
   * distance of the vertex from the edge's line along the normal (m,
   * negative = penetration).
   */
  struct ContactCandidate
  {
    int             block_i = 0, vertex = 0, block_j = 0, edge = 0;
    geometry::Point normal = geometry::Point::Zero();
    double          xi = 0., gap = 0.;
  };

  /// Options of the detection (lengths in m).
  struct DetectionOptions
  {
    /// Pairs and vertex-edge candidates closer than this are reported.
    double search_distance = 0.;
    /// Entrance-rule tolerance: an edge a of the vertex passes if
    /// n . a >= -angle_tolerance |a|.
    double angle_tolerance = 1e-3;
    /// Deepest penetration (m) of a vertex behind an edge that is still
    /// taken as a contact (deeper vertices belong to other edges).
    double penetration_limit = 0.;
    /// Vertices within this distance count as coincident (m).
    double coincidence_tolerance = 0.;
  };

  /**
   * Broad phase: all pairs (i < j) whose bounding boxes, grown by
   * @p distance, overlap; by a uniform grid, O(N) for blocks of similar
   * size.
   */
  std::vector<std::pair<int, int>>
  candidate_pairs(const std::vector<geometry::Polygon> &polygons,
                  const double                          distance);

  /**
   * Narrow phase for all candidate pairs: convex vertices of one block
   * against the edges of the other. A candidate passes the entrance rule
   * when both edges a of the vertex satisfy n . a >= -tol |a| (the vertex's
   * wedge is not behind the edge). Concave (and straight) vertices do not
   * initiate contacts. A vertex on (near) an edge end is a vertex-vertex
   * contact; of the candidates that coincident vertex pairs produce in both
   * directions only one is kept (the one whose wedge is most open with
   * respect to the edge; on a tie the lower block owns the vertex), so that
   * stacks of equal-width blocks get one contact per corner.
   */
  std::vector<ContactCandidate>
  detect_contacts(const std::vector<geometry::Polygon> &polygons,
                  const DetectionOptions               &options);
} // namespace rockdda::dda

#endif
