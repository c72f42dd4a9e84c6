#include <rockdda/io/error.h>
#include <rockdda/thermal/polygon_mesh.h>

#include <algorithm>
#include <cmath>
#include <map>

namespace rockdda::thermal
{
  namespace
  {
    double
    cross(const Point2 &o, const Point2 &a, const Point2 &b)
    {
      return (a[0] - o[0]) * (b[1] - o[1]) - (a[1] - o[1]) * (b[0] - o[0]);
    }

    bool
    segments_cross(const Point2 &a,
                   const Point2 &b,
                   const Point2 &c,
                   const Point2 &d)
    {
      const double d1 = cross(a, b, c), d2 = cross(a, b, d);
      const double d3 = cross(c, d, a), d4 = cross(c, d, b);
      return ((d1 > 0 && d2 < 0) || (d1 < 0 && d2 > 0))
             && ((d3 > 0 && d4 < 0) || (d3 < 0 && d4 > 0));
    }

    /// Adds vertices, merging those within a tolerance.
    class VertexPool
    {
    public:
      VertexPool(std::vector<Point2> &vertices, const double tolerance)
          : vertices(vertices)
          , tolerance(tolerance)
      {}

      unsigned int
      add(const Point2 &p)
      {
        const auto key = std::make_pair(std::llround(p[0] / tolerance),
                                        std::llround(p[1] / tolerance));
        // Look in the neighbouring bins too (rounding at bin edges).
        for (long long dx = -1; dx <= 1; ++dx)
          for (long long dy = -1; dy <= 1; ++dy)
            {
              const auto it
                = index.find(std::make_pair(key.first + dx, key.second + dy));
              if (it != index.end())
                return it->second;
            }
        vertices.push_back(p);
        index[key] = vertices.size() - 1;
        return vertices.size() - 1;
      }

      void
      clear()
      {
        index.clear();
      }

    private:
      std::vector<Point2>                                    &vertices;
      double                                                  tolerance;
      std::map<std::pair<long long, long long>, unsigned int> index;
    };

    /// Ear clipping of a counter-clockwise simple polygon.
    std::vector<std::array<Point2, 3>>
    ear_clip(std::vector<Point2> poly, const std::string &name)
    {
      std::vector<std::array<Point2, 3>> triangles;
      std::size_t                        guard = 0;
      while (poly.size() > 3)
        {
          bool              clipped = false;
          const std::size_t n       = poly.size();
          // Prefer the ear with the best (largest) minimum angle proxy.
          std::size_t best         = n;
          double      best_quality = -1.;
          for (std::size_t i = 0; i < n; ++i)
            {
              const Point2 &a = poly[(i + n - 1) % n], &b = poly[i],
                           &c    = poly[(i + 1) % n];
              const double area2 = cross(a, b, c);
              if (area2 <= 0.)
                continue; // reflex or degenerate
              bool empty = true;
              for (std::size_t j = 0; j < n && empty; ++j)
                {
                  if (j == i || j == (i + 1) % n || j == (i + n - 1) % n)
                    continue;
                  const Point2 &p = poly[j];
                  if (cross(a, b, p) >= 0. && cross(b, c, p) >= 0.
                      && cross(c, a, p) >= 0.)
                    empty = false;
                }
              if (!empty)
                continue;
              const auto len2 = [](const Point2 &p, const Point2 &q) {
                return (p[0] - q[0]) * (p[0] - q[0])
                       + (p[1] - q[1]) * (p[1] - q[1]);
              };
              const double quality
                = area2 / std::max({len2(a, b), len2(b, c), len2(c, a)});
              if (quality > best_quality)
                {
                  best_quality = quality;
                  best         = i;
                }
            }
          if (best < n)
            {
              triangles.push_back(std::array<Point2, 3>{
                {poly[(best + n - 1) % n], poly[best], poly[(best + 1) % n]}});
              poly.erase(poly.begin() + best);
              clipped = true;
            }
          if (!clipped || ++guard > 100000)
            throw InputError("block '" + name
                             + "': the polygon could not be triangulated (is "
                               "it simple, without repeated vertices?)");
        }
      if (cross(poly[0], poly[1], poly[2]) <= 0.)
        throw InputError("block '" + name + "': degenerate polygon");
      triangles.push_back(std::array<Point2, 3>{{poly[0], poly[1], poly[2]}});
      return triangles;
    }
  } // namespace



  double
  signed_area(const std::vector<Point2> &polygon)
  {
    double a = 0.;
    for (std::size_t i = 0; i < polygon.size(); ++i)
      {
        const Point2 &p = polygon[i], &q = polygon[(i + 1) % polygon.size()];
        a += p[0] * q[1] - q[0] * p[1];
      }
    return 0.5 * a;
  }



  double
  distance_to_segment(const Point2 &p, const Point2 &a, const Point2 &b)
  {
    const double dx = b[0] - a[0], dy = b[1] - a[1];
    const double l2 = dx * dx + dy * dy;
    double       s  = 0.;
    if (l2 > 0.)
      s = std::clamp(((p[0] - a[0]) * dx + (p[1] - a[1]) * dy) / l2, 0., 1.);
    const double ex = a[0] + s * dx - p[0], ey = a[1] + s * dy - p[1];
    return std::sqrt(ex * ex + ey * ey);
  }



  CoarseMesh
  mesh_blocks(const std::vector<Block> &blocks,
              const double              cell_size,
              const bool                merge_blocks)
  {
    if (blocks.empty())
      throw InputError("heat: the geometry has no block");
    if (!(cell_size > 0.))
      throw InputError("heat: the coarse cell size must be > 0 m");
    double extent = 0.;
    for (const auto &b : blocks)
      for (const auto &v : b.vertices)
        extent = std::max({extent, std::abs(v[0]), std::abs(v[1])});
    const double tolerance = 1e-9 * std::max(extent, 1.);

    CoarseMesh mesh;
    VertexPool pool(mesh.vertices, tolerance);
    for (unsigned int bi = 0; bi < blocks.size(); ++bi)
      {
        const Block &block = blocks[bi];
        const auto   n     = block.vertices.size();
        if (n < 3)
          throw InputError("block '" + block.name
                           + "' has fewer than 3 vertices");
        if (block.edge_tags.size() != n)
          throw InputError("block '" + block.name + "' has " + std::to_string(n)
                           + " vertices but "
                           + std::to_string(block.edge_tags.size())
                           + " boundary tags (one per edge needed)");
        for (const auto &v : block.vertices)
          if (!std::isfinite(v[0]) || !std::isfinite(v[1]))
            throw InputError("block '" + block.name
                             + "' has a non-finite vertex");
        for (std::size_t i = 0; i < n; ++i)
          for (std::size_t j = i + 2; j < n; ++j)
            if (!(i == 0 && j == n - 1)
                && segments_cross(block.vertices[i],
                                  block.vertices[(i + 1) % n],
                                  block.vertices[j],
                                  block.vertices[(j + 1) % n]))
              throw InputError("block '" + block.name + "': edges "
                               + std::to_string(i + 1) + " and "
                               + std::to_string(j + 1)
                               + " intersect (the polygon must be simple)");
        std::vector<Point2> poly = block.vertices;
        const double        area = signed_area(poly);
        if (std::abs(area) < tolerance * tolerance)
          throw InputError("block '" + block.name + "' has zero area");
        if (area < 0.)
          std::reverse(poly.begin(), poly.end());
        if (!merge_blocks)
          pool.clear();

        const auto add_quad = [&](const Point2 &a,
                                  const Point2 &b,
                                  const Point2 &c,
                                  const Point2 &d) {
          mesh.quads.push_back(std::array<unsigned int, 4>{
            {pool.add(a), pool.add(b), pool.add(c), pool.add(d)}});
          mesh.quad_block.push_back(bi);
        };
        const auto mid = [](const Point2 &p, const Point2 &q) {
          return Point2{{0.5 * (p[0] + q[0]), 0.5 * (p[1] + q[1])}};
        };

        bool convex_quad = n == 4;
        for (std::size_t i = 0; i < 4 && convex_quad; ++i)
          convex_quad
            = cross(poly[i], poly[(i + 1) % 4], poly[(i + 2) % 4]) > 0.;
        if (convex_quad && blocks.size() == 1)
          {
            // Structured grid by bilinear interpolation of the corners.
            const auto len = [](const Point2 &p, const Point2 &q) {
              return std::hypot(p[0] - q[0], p[1] - q[1]);
            };
            const unsigned int nx = std::max<long>(
              1,
              std::lround(
                std::ceil(std::max(len(poly[0], poly[1]), len(poly[3], poly[2]))
                            / cell_size
                          - 1e-9)));
            const unsigned int ny = std::max<long>(
              1,
              std::lround(
                std::ceil(std::max(len(poly[0], poly[3]), len(poly[1], poly[2]))
                            / cell_size
                          - 1e-9)));
            const auto at = [&](const unsigned int i, const unsigned int j) {
              const double u = double(i) / nx, v = double(j) / ny;
              Point2       p;
              for (unsigned int d = 0; d < 2; ++d)
                p[d] = (1 - u) * (1 - v) * poly[0][d] + u * (1 - v) * poly[1][d]
                       + u * v * poly[2][d] + (1 - u) * v * poly[3][d];
              return p;
            };
            for (unsigned int j = 0; j < ny; ++j)
              for (unsigned int i = 0; i < nx; ++i)
                add_quad(at(i, j),
                         at(i + 1, j),
                         at(i + 1, j + 1),
                         at(i, j + 1));
            continue;
          }

        for (const auto &t : ear_clip(poly, block.name))
          {
            const Point2 g{{(t[0][0] + t[1][0] + t[2][0]) / 3.,
                            (t[0][1] + t[1][1] + t[2][1]) / 3.}};
            const Point2 m01 = mid(t[0], t[1]), m12 = mid(t[1], t[2]),
                         m20 = mid(t[2], t[0]);
            add_quad(t[0], m01, g, m20);
            add_quad(t[1], m12, g, m01);
            add_quad(t[2], m20, g, m12);
          }
      }
    return mesh;
  }
} // namespace rockdda::thermal
