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
#include <iterator>
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
    /// The vertex's projection on the edge's line, as a fraction of the
    /// edge from its start: xi before clamping to [0, 1]. Outside [0, 1]
    /// for a vertex coming round a reflex corner (beyond the edge's end).
    /// A contact that locks takes its shear reference here, where the
    /// vertex is, not at the clamped end: otherwise the shear spring starts
    /// stretched by the vertex's distance beyond the end.
    double projection = 0.;
  };

  /**
   * Runs @p f(lo, hi) for the chunks [k g, min(n, (k + 1) g)) of the index
   * range [0, n), g = grain, possibly concurrently (the engine's threads,
   * LinearSolver::for_chunks). The chunks depend only on n and g, so a
   * loop whose chunks write disjoint data gives the same result on any
   * number of threads.
   */
  using ChunkRunner = std::function<
    void(std::size_t                                                n,
         std::size_t                                                grain,
         const std::function<void(std::size_t lo, std::size_t hi)> &f)>;

  /**
   * Run @p f(lo, hi) over the chunks of [0, n) of @p grain items through
   * @p runner, or one after the other (in order) if it is empty.
   */
  inline void
  for_each_chunk(const ChunkRunner                                   &runner,
                 const std::size_t                                    n,
                 const std::size_t                                    grain,
                 const std::function<void(std::size_t, std::size_t)> &f)
  {
    if (runner)
      {
        runner(n, grain, f);
        return;
      }
    for (std::size_t lo = 0; lo < n; lo += grain)
      f(lo, std::min(n, lo + grain));
  }

  /**
   * Run @p f(lo, hi, out) over the chunks of [0, n) of @p grain items
   * through @p runner (for_each_chunk), each chunk appending its results to
   * its own vector @p out, and return the chunks' results joined in order:
   * the same list on any number of threads.
   */
  template <typename T, typename Function>
  std::vector<T>
  joined_chunks(const ChunkRunner &runner,
                const std::size_t  n,
                const std::size_t  grain,
                const Function    &f)
  {
    std::vector<std::vector<T>> part((n + grain - 1) / grain);
    for_each_chunk(runner,
                   n,
                   grain,
                   [&](const std::size_t lo, const std::size_t hi) {
                     f(lo, hi, part[lo / grain]);
                   });
    std::size_t total = 0;
    for (const auto &p : part)
      total += p.size();
    std::vector<T> all;
    all.reserve(total);
    for (auto &p : part)
      all.insert(all.end(),
                 std::make_move_iterator(p.begin()),
                 std::make_move_iterator(p.end()));
    return all;
  }

  /**
   * The items (e.g. contacts) of each of @p n_rows rows (e.g. blocks or
   * pairs of blocks) in item order: items(r) is entry[start[r]] to
   * entry[start[r + 1] - 1], each entry 2 k + side for item k listed under
   * its row first(k) (side 0) or second(k) (side 1). A chunked loop over
   * the rows that adds each row's items in this order sums as a serial loop
   * over the items does, with each row written by one chunk: the same bits
   * on any number of threads.
   */
  struct ItemsOfRows
  {
    std::vector<int> start, entry;
  };

  /// ItemsOfRows of @p n_items items, @p rows_of(k) giving the pair (first,
  /// second) of item k's rows (-1: none).
  template <typename RowsOf>
  ItemsOfRows
  items_of_rows(const int         n_rows,
                const std::size_t n_items,
                const RowsOf     &rows_of)
  {
    ItemsOfRows out;
    out.start.assign(n_rows + 1, 0);
    for (std::size_t k = 0; k < n_items; ++k)
      {
        const std::pair<int, int> r = rows_of(k);
        for (const int row : {r.first, r.second})
          if (row >= 0)
            ++out.start[row + 1];
      }
    for (int r = 0; r < n_rows; ++r)
      out.start[r + 1] += out.start[r];
    out.entry.resize(out.start[n_rows]);
    std::vector<int> next(out.start.begin(), out.start.end() - 1);
    for (std::size_t k = 0; k < n_items; ++k)
      {
        const std::pair<int, int> r = rows_of(k);
        if (r.first >= 0)
          out.entry[next[r.first]++] = 2 * static_cast<int>(k);
        if (r.second >= 0)
          out.entry[next[r.second]++] = 2 * static_cast<int>(k) + 1;
      }
    return out;
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
    /// Runs the block pairs in chunks, possibly on threads (ChunkRunner).
    ChunkRunner run_chunks;
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
