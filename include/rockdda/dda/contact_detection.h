/**
 * @file
 * Contact detection of 2D DDA: a uniform-grid broad phase on bounding boxes
 * grown by the search distance, and a vertex-to-edge narrow phase with
 * Shi's entrance rule. Emits plain records; knows nothing of contact states.
 */
#ifndef ROCKDDA_DDA_CONTACT_DETECTION_H
#define ROCKDDA_DDA_CONTACT_DETECTION_H

#include <rockdda/geometry/polygon.h>

#include <algorithm>
#include <functional>
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

  /**
   * Runs a function of the half (0, 1) for both halves, possibly on two
   * threads (LinearSolver::run_halves); empty: one after the other.
   */
  using HalvesRunner = std::function<void(const std::function<void(int)> &)>;

  /**
   * Call @p f(h, lo, hi) for the halves h = 0, 1 of the index range
   * [0, n): [0, n/2) and [n/2, n), through @p runner (or one after the
   * other if it is empty). The two calls must write disjoint data.
   */
  inline void
  for_each_half(const HalvesRunner &runner,
                const std::size_t   n,
                const std::function<void(int, std::size_t, std::size_t)> &f)
  {
    const std::function<void(int)> half
      = [&](const int h) { f(h, h == 0 ? 0 : n / 2, h == 0 ? n / 2 : n); };
    if (runner)
      runner(half);
    else
      {
        half(0);
        half(1);
      }
  }

  /**
   * Options of the detection (lengths in m). Every length is per block, so
   * that the rules do not depend on the size of the domain or on where the
   * scene sits: the pair (i, j) is searched within max(reach_i, reach_j).
   */
  struct DetectionOptions
  {
    /// Search distance of every block when @p reach is empty (m).
    double search_distance = 0.;
    /// Search distance of each block (m): how far its vertices may move
    /// in one step, times a safety factor (0 for a block that does not
    /// move, e.g. a clamped one).
    std::vector<double> reach;
    /// Scale of each block for vertex-vertex contacts (m): the reach its
    /// size allows, also for blocks that do not move. Empty: reach.
    std::vector<double> vertex_reach;
    /// Predicted displacement of each vertex of each block over the step
    /// (m; same layout as the polygons' vertices, empty = at rest). Decides
    /// the entrance of vertex-vertex contacts by the shortest path.
    std::vector<std::vector<geometry::Point>> predicted;
    /// Entrance rule of a penetrated vertex: an edge a of the vertex
    /// passes if n . a >= -sin(entrance_angle) |a| (rad). Larger than the
    /// relative rotation of two blocks in one step.
    double entrance_angle = 0.2;
    /// Runs the block pairs in two halves (see HalvesRunner).
    HalvesRunner run_halves;
    /// Two vertices closer than coincidence_fraction * vertex_distance()
    /// form a vertex-vertex contact.
    double coincidence_fraction = 0.2;

    /// Search distance of the pair (i, j) (m).
    double
    pair_distance(const int i, const int j) const
    {
      return reach.empty() ? search_distance : std::max(reach[i], reach[j]);
    }
    /// Distance within which two vertices of the pair (i, j) can meet in
    /// one step (m): the smaller block's reach, so that a large (e.g.
    /// fixed) block does not make distant corners vertex-vertex contacts.
    double
    vertex_distance(const int i, const int j) const
    {
      const auto &r = vertex_reach.empty() ? reach : vertex_reach;
      return r.empty() ? search_distance : std::min(r[i], r[j]);
    }
  };

  /**
   * Broad phase: all pairs (i < j) whose bounding boxes, grown by
   * @p distance, overlap; by a uniform grid, O(N) for blocks of similar
   * size.
   */
  std::vector<std::pair<int, int>>
  candidate_pairs(const std::vector<geometry::Polygon> &polygons,
                  const double                          distance);

  /// Broad phase with the box of block i grown by @p grow[i] on each side.
  std::vector<std::pair<int, int>>
  candidate_pairs(const std::vector<geometry::Polygon> &polygons,
                  const std::vector<double>            &grow);

  /**
   * Narrow phase for all candidate pairs (Shi 1988, ch. 4; the rules are
   * documented in doc/theory/dda.md). Only convex vertices initiate
   * contacts. A vertex outside the other block whose projection falls on
   * an edge within the search distance is in contact with that edge; near
   * a concave (reflex) corner it touches both edges. A vertex inside the
   * other block (penetrated) is in contact with the edge of shortest exit
   * that passes the entrance rule, and with both edges of a reflex corner
   * it sits in. Two convex vertices within the coincidence distance, or a
   * vertex beyond both edges of a convex corner, form a vertex-vertex
   * contact: of the four vertex-edge entrances the one that passes the
   * entrance rule with the largest predicted separation at the end of the
   * step (the shortest penetration path) is kept.
   */
  std::vector<ContactCandidate>
  detect_contacts(const std::vector<geometry::Polygon> &polygons,
                  const DetectionOptions               &options);
} // namespace rockdda::dda

#endif
