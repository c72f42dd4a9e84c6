/**
 * @file
 * Broad phase (uniform grid) and narrow phase (vertex-edge with Shi's
 * entrance rule, vertex-vertex by the most open wedge) of 2D DDA contact
 * detection (Shi 1988, ch. 4).
 */
#include <rockdda/dda/contact_detection.h>

#include <algorithm>
#include <cmath>
#include <map>
#include <tuple>

namespace rockdda::dda
{
  std::vector<std::pair<int, int>>
  candidate_pairs(const std::vector<geometry::Polygon> &polygons,
                  const double                          distance)
  {
    return candidate_pairs(polygons,
                           std::vector<double>(polygons.size(),
                                               0.5 * distance));
  }



  std::vector<std::pair<int, int>>
  candidate_pairs(const std::vector<geometry::Polygon> &polygons,
                  const std::vector<double>            &grow)
  {
    const int                        n = static_cast<int>(polygons.size());
    std::vector<std::pair<int, int>> result;
    if (n < 2)
      return result;
    std::vector<Eigen::Vector4d> box(n);
    std::vector<double>          extent(n);
    Eigen::Vector4d              all(1e300, 1e300, -1e300, -1e300);
    for (int i = 0; i < n; ++i)
      {
        box[i] = polygons[i].bounding_box();
        box[i] += Eigen::Vector4d(-grow[i], -grow[i], grow[i], grow[i]);
        extent[i] = std::max(box[i][2] - box[i][0], box[i][3] - box[i][1]);
        all[0]    = std::min(all[0], box[i][0]);
        all[1]    = std::min(all[1], box[i][1]);
        all[2]    = std::max(all[2], box[i][2]);
        all[3]    = std::max(all[3], box[i][3]);
      }
    // Cell size: the median block extent, enlarged if that would give more
    // than about 4 cells per block.
    std::vector<double> sorted = extent;
    std::nth_element(sorted.begin(), sorted.begin() + n / 2, sorted.end());
    const double W = std::max(all[2] - all[0], 1e-300);
    const double H = std::max(all[3] - all[1], 1e-300);
    double       h = std::max(sorted[n / 2], 1e-300);
    while ((W / h + 1.) * (H / h + 1.) > 4. * n + 16.)
      h *= 1.5;
    const int nx     = static_cast<int>(W / h) + 1;
    const int ny     = static_cast<int>(H / h) + 1;
    auto      cell_x = [&](double x) {
      return std::clamp(static_cast<int>((x - all[0]) / h), 0, nx - 1);
    };
    auto cell_y = [&](double y) {
      return std::clamp(static_cast<int>((y - all[1]) / h), 0, ny - 1);
    };
    // Bucket the boxes (counting sort into a CSR layout).
    std::vector<int> start(static_cast<std::size_t>(nx) * ny + 1, 0);
    for (int i = 0; i < n; ++i)
      for (int cy = cell_y(box[i][1]); cy <= cell_y(box[i][3]); ++cy)
        for (int cx = cell_x(box[i][0]); cx <= cell_x(box[i][2]); ++cx)
          ++start[static_cast<std::size_t>(cy) * nx + cx + 1];
    for (std::size_t c = 1; c < start.size(); ++c)
      start[c] += start[c - 1];
    std::vector<int> fill(start.begin(), start.end() - 1);
    std::vector<int> members(start.back());
    for (int i = 0; i < n; ++i)
      for (int cy = cell_y(box[i][1]); cy <= cell_y(box[i][3]); ++cy)
        for (int cx = cell_x(box[i][0]); cx <= cell_x(box[i][2]); ++cx)
          members[fill[static_cast<std::size_t>(cy) * nx + cx]++] = i;
    // A pair is reported only by the cell holding the lower-left corner of
    // the intersection of its boxes, so each pair appears once.
    for (int cy = 0; cy < ny; ++cy)
      for (int cx = 0; cx < nx; ++cx)
        {
          const std::size_t c = static_cast<std::size_t>(cy) * nx + cx;
          for (int a = start[c]; a < start[c + 1]; ++a)
            for (int b = a + 1; b < start[c + 1]; ++b)
              {
                const int   i = members[a], j = members[b];
                const auto &p = box[i], &q = box[j];
                if (p[0] > q[2] || q[0] > p[2] || p[1] > q[3] || q[1] > p[3])
                  continue;
                if (cell_x(std::max(p[0], q[0])) != cx
                    || cell_y(std::max(p[1], q[1])) != cy)
                  continue;
                result.emplace_back(std::min(i, j), std::max(i, j));
              }
        }
    std::sort(result.begin(), result.end());
    return result;
  }



  namespace
  {
    using geometry::Point;

    double
    cross(const Point &a, const Point &b)
    {
      return a.x() * b.y() - a.y() * b.x();
    }

    /// A vertex with its two edges (vectors from the vertex to its
    /// neighbours).
    struct Corner
    {
      Point P, a1, a2;
      bool  convex = false;
      /// A right turn by more than flat_angle: a straight boundary with a
      /// vertex on it (collinear edges, within round-off or the strain of
      /// the block) is neither convex nor reflex. A vertex on one of two
      /// collinear edges passes onto the other by contact transfer; a
      /// 'coming round the corner' candidate on the other edge would put a
      /// second spring on the same vertex.
      bool reflex = false;
      /// Unit vectors along a1 and a2, and the lengths of a1 and a2.
      Point  u1, u2;
      double l1 = 0., l2 = 0.;
      /// The edge that starts here: unit tangent, outward unit normal,
      /// length.
      Point  t, n;
      double l = 0.;
    };

    /// Turn (rad) below which a corner is flat for the reflex-corner rules:
    /// far above round-off and the elastic strain of rock (1e-6 to 1e-4 rad
    /// of a block's corner angle come from strain of that size), far below
    /// any kink of a real boundary.
    constexpr double flat_angle = 1e-3;

    Corner
    corner(const geometry::Polygon &poly, const int k)
    {
      const auto &v = poly.vertices;
      const int   n = static_cast<int>(v.size());
      Corner      c;
      c.P             = v[k];
      c.a1            = v[(k + n - 1) % n] - c.P;
      c.a2            = v[(k + 1) % n] - c.P;
      const double l1 = c.a1.norm(), l2 = c.a2.norm();
      // A left turn: any interior angle below 180 degrees, however sharp
      // (the vertices of slivers are contact vertices too).
      c.convex = cross(-c.a1, c.a2) > 1e-14 * l1 * l2;
      c.reflex = cross(-c.a1, c.a2) < -flat_angle * l1 * l2;
      c.u1     = c.a1 / l1;
      c.u2     = c.a2 / l2;
      c.l1     = l1;
      c.l2     = l2;
      c.l      = l2;
      c.t      = c.u2;
      c.n      = Point(c.t.y(), -c.t.x());
      return c;
    }

    /// Entrance score of a vertex against an edge with outward unit normal
    /// @p n: min over the vertex's edges of n . a / |a|; >= 0 when its wedge
    /// lies on the outer side of the edge's line.
    double
    entrance_score(const Corner &c, const Point &n)
    {
      return std::min(n.dot(c.u1), n.dot(c.u2));
    }

    /// Vertex @p k (at @p P) of block @p a against edge @p e of block @p b,
    /// which starts at corner @p E.
    ContactCandidate
    vertex_edge(const Point  &P,
                const int     a,
                const int     k,
                const int     b,
                const int     e,
                const Corner &E)
    {
      const Point      r = P - E.P;
      ContactCandidate c;
      c.block_i    = a;
      c.vertex     = k;
      c.block_j    = b;
      c.edge       = e;
      c.normal     = E.n;
      c.gap        = E.n.dot(r);
      c.projection = E.t.dot(r) / E.l;
      c.xi         = std::clamp(c.projection, 0., 1.);
      return c;
    }

    /// Narrow phase of one pair of blocks.
    class PairDetector
    {
    public:
      PairDetector(const std::vector<geometry::Polygon> &polys,
                   const std::vector<Corner>            &all_corners,
                   const std::vector<int>               &offset,
                   const std::vector<Eigen::Vector4d>   &boxes,
                   const DetectionOptions               &opt,
                   const int                             i,
                   const int                             j,
                   std::vector<bool> (&consumed)[2],
                   std::vector<ContactCandidate> &out)
          : polys(polys)
          , boxes(boxes)
          , opt(opt)
          , i(i)
          , j(j)
          , d(opt.pair_distance(i, j))
          , dv(opt.vertex_distance(i, j))
          , consumed(consumed)
          , out(out)
      {
        corners[0] = all_corners.data() + offset[i];
        corners[1] = all_corners.data() + offset[j];
        count[0]   = offset[i + 1] - offset[i];
        count[1]   = offset[j + 1] - offset[j];
      }

      void
      run()
      {
        const std::size_t first = out.size();
        consumed[0].assign(count[0], false);
        consumed[1].assign(count[1], false);
        find_vertex_vertex();
        vertices_on_edges(0);
        vertices_on_edges(1);
        // One candidate per (vertex, edge).
        std::sort(out.begin() + first,
                  out.end(),
                  [](const ContactCandidate &x, const ContactCandidate &y) {
                    return std::tie(x.block_i, x.vertex, x.block_j, x.edge)
                           < std::tie(y.block_i, y.vertex, y.block_j, y.edge);
                  });
        out.erase(
          std::unique(out.begin() + first,
                      out.end(),
                      [](const ContactCandidate &x, const ContactCandidate &y) {
                        return x.block_i == y.block_i && x.vertex == y.vertex
                               && x.block_j == y.block_j && x.edge == y.edge;
                      }),
          out.end());
      }

    private:
      int
      block(const int side) const
      {
        return side == 0 ? i : j;
      }

      Point
      predicted(const int side, const int k) const
      {
        const int b = block(side);
        return opt.predicted.empty() || opt.predicted[b].empty()
                 ? Point::Zero()
                 : opt.predicted[b][k];
      }

      /// Whether P lies beyond both edges of the convex corner Q (in the
      /// region where Q itself is the nearest point of its block).
      static bool
      beyond_corner(const Point &P, const Corner &Q)
      {
        const Point d = P - Q.P;
        return Q.a1.dot(d) <= 0. && Q.a2.dot(d) <= 0.;
      }

      void
      find_vertex_vertex()
      {
        // Both tests below need dist <= max(coincidence_fraction, 1) * dv:
        // farther pairs are skipped on the squared distance (with a margin
        // far above round-off, so that no pair the tests accept is lost).
        const double reach = std::max(opt.coincidence_fraction, 1.) * dv;
        const double skip2 = (1. + 1e-9) * reach * reach;
        for (int k = 0; k < count[0]; ++k)
          for (int m = 0; m < count[1]; ++m)
            {
              const Corner &P = corners[0][k], &Q = corners[1][m];
              if (!P.convex || !Q.convex || (P.P - Q.P).squaredNorm() > skip2)
                continue;
              const double dist     = (P.P - Q.P).norm();
              const double shortest = std::min({P.l1, P.l2, Q.l1, Q.l2});
              const double ctol
                = std::min(opt.coincidence_fraction * dv, 0.05 * shortest);
              const bool coincident = dist <= ctol;
              // Approaching vertices: within the vertex reach, and closer
              // than half the shortest edge at either corner (a vertex
              // farther than that is nearer to another feature: the far
              // corner of a slender block is not a contact).
              const double local = 0.5 * shortest;
              if (coincident
                  || (dist <= std::min(dv, local)
                      && (beyond_corner(P.P, Q) || beyond_corner(Q.P, P))))
                {
                  resolve_vertex_vertex(static_cast<int>(k),
                                        static_cast<int>(m));
                  if (coincident)
                    consumed[0][k] = consumed[1][m] = true;
                }
            }
      }

      /**
       * Shi's rule for two convex vertices in contact: of the four
       * entrances (each vertex across either edge of the other), those
       * whose entering wedge lies outside the edge are admissible; the one
       * with the largest predicted separation at the end of the step, i.e.
       * the shortest penetration path, is the contact.
       */
      void
      resolve_vertex_vertex(const int k, const int m)
      {
        struct Option
        {
          ContactCandidate c;
          double           score, separation;
        };
        Option    options[4];
        int       n_options = 0;
        const int nk[2]
          = {static_cast<int>(count[0]), static_cast<int>(count[1])};
        for (int side = 0; side < 2; ++side)
          {
            // Vertex v of 'side' entering an edge at vertex w of 'other'.
            const int     other = 1 - side;
            const int     v = side == 0 ? k : m, w = side == 0 ? m : k;
            const Corner &X  = corners[side][v];
            const Point   dX = X.P + predicted(side, v);
            const Point   dW = corners[other][w].P + predicted(other, w);
            for (const int e : {(w + nk[other] - 1) % nk[other], w})
              {
                Option o;
                o.c = vertex_edge(
                  X.P, block(side), v, block(other), e, corners[other][e]);
                o.score              = entrance_score(X, o.c.normal);
                o.separation         = o.c.normal.dot(dX - dW);
                options[n_options++] = o;
              }
          }
        // Ties: flush corners give two admissible entrances that describe
        // the same contact, whose separations and wedge openness differ by
        // the blocks' relative rotation; they go to the lower block so
        // that round-off cannot switch the contact from step to step.
        const double  tie_length = 1e-6 * dv, tie_angle = 1e-2;
        const Option *best = nullptr;
        for (int q = 0; q < n_options; ++q)
          {
            const Option &o = options[q];
            if (best == nullptr)
              {
                best = &o;
                continue;
              }
            const bool ok      = o.score >= -tie_angle,
                       best_ok = best->score >= -tie_angle;
            bool better;
            if (ok != best_ok)
              better = ok;
            else if (!ok)
              better = o.score > best->score;
            else if (std::abs(o.separation - best->separation) > tie_length)
              better = o.separation > best->separation;
            else if (std::abs(o.score - best->score) > tie_angle)
              better = o.score > best->score;
            else
              better = o.c.block_i < best->c.block_i;
            if (better)
              best = &o;
          }
        out.push_back(best->c);
      }

      /// Convex vertices of 'side' against the edges of the other block.
      void
      vertices_on_edges(const int side)
      {
        const int                a = block(side), b = block(1 - side);
        const geometry::Polygon &pb = polys[b];
        const int                nb = static_cast<int>(pb.vertices.size());
        const Eigen::Vector4d   &bb = boxes[b];
        for (int k = 0; k < static_cast<int>(count[side]); ++k)
          {
            const Corner &P = corners[side][k];
            if (!P.convex || consumed[side][k] || P.P.x() < bb[0] - d
                || P.P.x() > bb[2] + d || P.P.y() < bb[1] - d
                || P.P.y() > bb[3] + d)
              continue;
            // (Outside the box: outside the block.)
            const bool in_box = P.P.x() >= bb[0] && P.P.x() <= bb[2]
                                && P.P.y() >= bb[1] && P.P.y() <= bb[3];
            // A vertex on the boundary (within round-off of an edge) is
            // not inside, whatever contains() says: otherwise, where an
            // edge next to it fails the entrance rule, a far edge would be
            // taken as its exit, at a depth of the block's width (slices
            // standing side by side on a foot).
            const auto on_boundary = [&]() {
              const Corner *cb = corners[1 - side];
              for (int e = 0; e < nb; ++e)
                {
                  const Point  r  = P.P - cb[e].P;
                  const double xr = cb[e].t.dot(r) / cb[e].l;
                  if (xr >= -1e-12 && xr <= 1. + 1e-12
                      && std::abs(cb[e].n.dot(r)) <= 1e-9 * d)
                    return true;
                }
              return false;
            };
            if (!in_box || !pb.contains(P.P) || on_boundary())
              {
                // Outside: every edge the vertex projects onto within the
                // search distance (both edges of a reflex corner).
                const Corner *cb = corners[1 - side];
                for (int e = 0; e < nb; ++e)
                  {
                    const Corner &E   = cb[e];
                    const Point   r   = P.P - E.P;
                    const double  gap = E.n.dot(r);
                    if (gap > d || gap < -1e-9 * d)
                      continue;
                    const double xr = E.t.dot(r) / E.l;
                    // Beyond an end at a reflex corner: the vertex comes
                    // round the corner onto this edge; an open candidate
                    // from now on, so that it closes when it crosses the
                    // edge's line instead of being found already inside.
                    const Corner &F = cb[(e + 1) % nb];
                    const bool    round_corner
                      = (xr < 0. && E.reflex && r.squaredNorm() <= d * d)
                        || (xr > 1. && F.reflex
                            && (P.P - F.P).squaredNorm() <= d * d);
                    if ((xr >= 0. && xr <= 1.) || round_corner)
                      out.push_back(vertex_edge(P.P, a, k, b, e, E));
                  }
                continue;
              }
            // Penetrated: the admissible edge of shortest exit, and the
            // other edge of a reflex corner next to it.
            const double min_score = -std::sin(opt.entrance_angle);
            int          best = -1, fallback = -1;
            double       best_depth = 1e300, fallback_depth = 1e300;
            thread_local std::vector<ContactCandidate> c;
            thread_local std::vector<char>             ok;
            c.resize(nb);
            ok.assign(nb, 0);
            for (int e = 0; e < nb; ++e)
              {
                const Corner &E  = corners[1 - side][e];
                c[e]             = vertex_edge(P.P, a, k, b, e, E);
                const double xr  = E.t.dot(P.P - E.P) / E.l;
                const double dep = -c[e].gap;
                // (A vertex on the boundary may be found inside or outside by
                // round-off.)
                if (dep < -1e-9 * d || dep > d || xr < -1e-12
                    || xr > 1. + 1e-12)
                  continue;
                if (dep < fallback_depth)
                  {
                    fallback_depth = dep;
                    fallback       = e;
                  }
                if (entrance_score(P, c[e].normal) < min_score)
                  continue;
                ok[e] = 1;
                if (dep < best_depth)
                  {
                    best_depth = dep;
                    best       = e;
                  }
              }
            if (best < 0)
              best = fallback;
            if (best < 0)
              continue;
            out.push_back(c[best]);
            // At a reflex corner at either end of the chosen edge, within
            // reach: the other edge of the corner too, penetrated (if
            // admissible) or still open (the vertex coming round the
            // corner closes on it when it crosses its line).
            for (const int end : {(best + 1) % nb, best})
              {
                const int     other = end == best ? (best + nb - 1) % nb : end;
                const Corner &R     = corners[1 - side][end];
                if (!R.reflex || (P.P - R.P).norm() > d || c[other].gap > d
                    || c[other].gap < -d || (c[other].gap < 0. && !ok[other]))
                  continue;
                out.push_back(c[other]);
              }
          }
      }

      const std::vector<geometry::Polygon> &polys;
      const std::vector<Eigen::Vector4d>   &boxes;
      const DetectionOptions               &opt;
      const int                             i, j;
      const double                          d, dv;
      std::vector<bool> (&consumed)[2];
      std::vector<ContactCandidate> &out;
      const Corner                  *corners[2];
      int                            count[2];
    };
  } // namespace



  std::vector<ContactCandidate>
  detect_contacts(const std::vector<geometry::Polygon> &polygons,
                  const DetectionOptions               &options)
  {
    std::vector<double> grow(polygons.size(), 0.5 * options.search_distance);
    if (!options.reach.empty())
      grow = options.reach;
    // Corners (one array, offsets per block) and boxes once per detection;
    // scratch reused by all pairs.
    std::vector<int> offset(polygons.size() + 1, 0);
    for (std::size_t b = 0; b < polygons.size(); ++b)
      offset[b + 1] = offset[b] + static_cast<int>(polygons[b].vertices.size());
    std::vector<Corner>          corners;
    std::vector<Eigen::Vector4d> boxes;
    corners.reserve(offset.back());
    boxes.reserve(polygons.size());
    for (std::size_t b = 0; b < polygons.size(); ++b)
      {
        for (int k = 0; k < offset[b + 1] - offset[b]; ++k)
          corners.push_back(corner(polygons[b], k));
        boxes.push_back(polygons[b].bounding_box());
      }
    // The pairs in chunks (in order), each with its own output and
    // scratch, joined in order: the same list on any number of threads.
    const auto pairs = candidate_pairs(polygons, grow);
    return joined_chunks<ContactCandidate>(
      options.run_chunks,
      pairs.size(),
      128,
      [&](const std::size_t              lo,
          const std::size_t              hi,
          std::vector<ContactCandidate> &out) {
        std::vector<bool> consumed[2];
        out.reserve(3 * (hi - lo));
        for (std::size_t k = lo; k < hi; ++k)
          PairDetector(polygons,
                       corners,
                       offset,
                       boxes,
                       options,
                       pairs[k].first,
                       pairs[k].second,
                       consumed,
                       out)
            .run();
      });
  }
} // namespace rockdda::dda
