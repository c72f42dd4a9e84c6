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
        box[i] += Eigen::Vector4d(-0.5 * distance,
                                  -0.5 * distance,
                                  0.5 * distance,
                                  0.5 * distance);
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
    double
    cross(const geometry::Point &a, const geometry::Point &b)
    {
      return a.x() * b.y() - a.y() * b.x();
    }

    struct Scored
    {
      ContactCandidate c;
      double           score;
      /// Coincident vertex of the edge's block (-1 if none).
      int other_vertex;
    };

    /// Candidates of the convex vertices of block a against the edges of b.
    void
    vertices_on_edges(const std::vector<geometry::Polygon> &polys,
                      const int                             a,
                      const int                             b,
                      const DetectionOptions               &opt,
                      std::vector<Scored>                  &out)
    {
      const auto     &va = polys[a].vertices;
      const auto     &vb = polys[b].vertices;
      const int       na = static_cast<int>(va.size());
      const int       nb = static_cast<int>(vb.size());
      const double    d0 = opt.search_distance;
      Eigen::Vector4d bb = polys[b].bounding_box();
      for (int k = 0; k < na; ++k)
        {
          const geometry::Point &P = va[k];
          if (P.x() < bb[0] - d0 || P.x() > bb[2] + d0 || P.y() < bb[1] - d0
              || P.y() > bb[3] + d0)
            continue;
          const geometry::Point a1  = va[(k + na - 1) % na] - P;
          const geometry::Point a2  = va[(k + 1) % na] - P;
          const double          la1 = a1.norm(), la2 = a2.norm();
          // Convex vertex: turning left from (P - prev) to (next - P).
          if (cross(-a1, a2) <= 1e-6 * la1 * la2)
            continue;
          for (int e = 0; e < nb; ++e)
            {
              const geometry::Point &Q0 = vb[e];
              const geometry::Point &Q1 = vb[(e + 1) % nb];
              const geometry::Point  E  = Q1 - Q0;
              const double           l  = E.norm();
              if (l <= 0.)
                continue;
              const geometry::Point t = E / l;
              const geometry::Point nn(t.y(), -t.x());
              const geometry::Point r   = P - Q0;
              const double          gap = nn.dot(r);
              if (gap > d0 || gap < -opt.penetration_limit)
                continue;
              const double xi_raw = t.dot(r) / l;
              // A penetrated vertex must lie over the edge.
              if (gap < 0. && (xi_raw < 0. || xi_raw > 1.))
                continue;
              // Entrance rule: the vertex's wedge must not lie behind the
              // edge.
              const double s1 = nn.dot(a1) / la1, s2 = nn.dot(a2) / la2;
              if (s1 < -opt.angle_tolerance || s2 < -opt.angle_tolerance)
                continue;
              const double ctol = std::min(opt.coincidence_tolerance, 0.05 * l);
              int          other = -1;
              double       xi    = xi_raw;
              if (xi_raw < 0. || xi_raw > 1.)
                {
                  // Beyond an end of the edge: a vertex-vertex situation.
                  // Keep the edge only if the vertex lies closer to this
                  // edge's normal than to the neighbouring edge's normal.
                  const bool             at_end = xi_raw > 1.;
                  const geometry::Point &Q      = at_end ? Q1 : Q0;
                  const geometry::Point  d      = P - Q;
                  if (d.norm() > d0)
                    continue;
                  const geometry::Point N  = at_end ? vb[(e + 2) % nb] - Q1
                                                    : Q0 - vb[(e + nb - 1) % nb];
                  const double          ln = N.norm();
                  const geometry::Point nn2(N.y() / ln, -N.x() / ln);
                  if (nn.dot(d) < nn2.dot(d) - 1e-12 * d.norm())
                    continue;
                  xi = at_end ? 1. : 0.;
                }
              if ((P - Q0).norm() < ctol)
                other = e;
              else if ((P - Q1).norm() < ctol)
                other = (e + 1) % nb;
              Scored s;
              s.c.block_i    = a;
              s.c.vertex     = k;
              s.c.block_j    = b;
              s.c.edge       = e;
              s.c.normal     = nn;
              s.c.xi         = xi;
              s.c.gap        = gap;
              s.score        = std::min(s1, s2);
              s.other_vertex = other;
              out.push_back(s);
            }
        }
    }
  } // namespace



  std::vector<ContactCandidate>
  detect_contacts(const std::vector<geometry::Polygon> &polygons,
                  const DetectionOptions               &options)
  {
    std::vector<ContactCandidate> result;
    std::vector<Scored>           local;
    for (const auto &[i, j] :
         candidate_pairs(polygons, options.search_distance))
      {
        local.clear();
        vertices_on_edges(polygons, i, j, options, local);
        vertices_on_edges(polygons, j, i, options, local);
        // Coincident vertex pairs: keep one candidate per pair of vertices.
        std::map<std::pair<int, int>, int> best; // (vertex of i, vertex of j)
        for (int c = 0; c < static_cast<int>(local.size()); ++c)
          {
            const Scored &s = local[c];
            if (s.other_vertex < 0)
              continue;
            const std::pair<int, int> key
              = s.c.block_i == i ? std::make_pair(s.c.vertex, s.other_vertex)
                                 : std::make_pair(s.other_vertex, s.c.vertex);
            auto it = best.find(key);
            if (it == best.end())
              {
                best[key] = c;
                continue;
              }
            const Scored &o = local[it->second];
            // The most open wedge wins; on a tie (within the angle
            // tolerance) the vertex of the lower block (i).
            const bool better
              = s.score > o.score + options.angle_tolerance
                || (std::abs(s.score - o.score) <= options.angle_tolerance
                    && s.c.block_i < o.c.block_i)
                || (std::abs(s.score - o.score) <= options.angle_tolerance
                    && s.c.block_i == o.c.block_i && s.c.gap > o.c.gap);
            if (better)
              it->second = c;
          }
        for (int c = 0; c < static_cast<int>(local.size()); ++c)
          {
            const Scored &s = local[c];
            if (s.other_vertex >= 0)
              {
                const std::pair<int, int> key
                  = s.c.block_i == i
                      ? std::make_pair(s.c.vertex, s.other_vertex)
                      : std::make_pair(s.other_vertex, s.c.vertex);
                if (best[key] != c)
                  continue;
              }
            result.push_back(s.c);
          }
      }
    return result;
  }
} // namespace rockdda::dda
