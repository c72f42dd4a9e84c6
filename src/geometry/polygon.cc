#include <rockdda/geometry/polygon.h>

#include <algorithm>
#include <cmath>
#include <limits>

namespace rockdda::geometry
{
  double
  Polygon::signed_area() const
  {
    double            a = 0.;
    const std::size_t n = vertices.size();
    for (std::size_t i = 0; i < n; ++i)
      {
        const Point &p = vertices[i];
        const Point &q = vertices[(i + 1) % n];
        a += p.x() * q.y() - q.x() * p.y();
      }
    return 0.5 * a;
  }



  double
  Polygon::area() const
  {
    return std::abs(signed_area());
  }



  PolygonMoments
  Polygon::moments() const
  {
    // Triangle (0, p, q) with cross = p x q: integral 1 = cross/2,
    // integral x = cross (px + qx) / 6,
    // integral x^2 = cross (px^2 + px qx + qx^2) / 12,
    // integral x y = cross (2 px py + px qy + qx py + 2 qx qy) / 24.
    PolygonMoments    m;
    const std::size_t n = vertices.size();
    for (std::size_t i = 0; i < n; ++i)
      {
        const Point &p = vertices[i];
        const Point &q = vertices[(i + 1) % n];
        const double c = p.x() * q.y() - q.x() * p.y();
        m.a += c / 2.;
        m.sx += c * (p.x() + q.x()) / 6.;
        m.sy += c * (p.y() + q.y()) / 6.;
        m.sxx += c * (p.x() * p.x() + p.x() * q.x() + q.x() * q.x()) / 12.;
        m.syy += c * (p.y() * p.y() + p.y() * q.y() + q.y() * q.y()) / 12.;
        m.sxy += c
                 * (2. * p.x() * p.y() + p.x() * q.y() + q.x() * p.y()
                    + 2. * q.x() * q.y())
                 / 24.;
      }
    return m;
  }



  Point
  Polygon::centroid() const
  {
    // Shift to the first vertex to limit cancellation far from the origin.
    Polygon shifted;
    shifted.vertices.reserve(vertices.size());
    for (const Point &p : vertices)
      shifted.vertices.push_back(p - vertices.front());
    const PolygonMoments m = shifted.moments();
    return vertices.front() + Point(m.sx / m.a, m.sy / m.a);
  }



  Eigen::Vector3d
  Polygon::central_second_moments() const
  {
    const Point c = centroid();
    Polygon     shifted;
    for (const Point &p : vertices)
      shifted.vertices.push_back(p - c);
    PolygonMoments m = shifted.moments();
    if (m.a < 0.)
      {
        m.syy = -m.syy;
        m.sxx = -m.sxx;
        m.sxy = -m.sxy;
      }
    return {m.syy, m.sxx, m.sxy};
  }



  void
  Polygon::make_counter_clockwise()
  {
    if (signed_area() < 0.)
      std::reverse(vertices.begin(), vertices.end());
  }



  double
  Polygon::min_interior_angle() const
  {
    const std::size_t n     = vertices.size();
    const double      sign  = signed_area() >= 0. ? 1. : -1.;
    double            angle = 2. * M_PI;
    for (std::size_t i = 0; i < n; ++i)
      {
        const Point &a  = vertices[(i + n - 1) % n];
        const Point &b  = vertices[i];
        const Point &c  = vertices[(i + 1) % n];
        const Point  u  = a - b;
        const Point  v  = c - b;
        const double cr = sign * (v.x() * u.y() - v.y() * u.x());
        double       t  = std::atan2(cr, v.dot(u)); // angle from v to u (CCW)
        if (t < 0.)
          t += 2. * M_PI;
        angle = std::min(angle, t);
      }
    return angle;
  }



  double
  Polygon::min_width() const
  {
    const std::size_t n     = vertices.size();
    double            width = std::numeric_limits<double>::infinity();
    for (std::size_t i = 0; i < n; ++i)
      {
        const Point &a = vertices[i];
        const Point  t = vertices[(i + 1) % n] - a;
        const double l = t.norm();
        if (!(l > 0.))
          continue;
        double far = 0.;
        for (const Point &v : vertices)
          far = std::max(
            far,
            std::abs(t.x() * (v.y() - a.y()) - t.y() * (v.x() - a.x())) / l);
        width = std::min(width, far);
      }
    return n < 3 ? 0. : width;
  }



  Eigen::Vector4d
  Polygon::bounding_box() const
  {
    Eigen::Vector4d b(1e300, 1e300, -1e300, -1e300);
    for (const Point &p : vertices)
      {
        b[0] = std::min(b[0], p.x());
        b[1] = std::min(b[1], p.y());
        b[2] = std::max(b[2], p.x());
        b[3] = std::max(b[3], p.y());
      }
    return b;
  }



  namespace
  {
    double
    orient(const Point &a, const Point &b, const Point &c)
    {
      return (b.x() - a.x()) * (c.y() - a.y())
             - (b.y() - a.y()) * (c.x() - a.x());
    }

    bool
    on_segment(const Point &a, const Point &b, const Point &p)
    {
      return std::min(a.x(), b.x()) <= p.x() && p.x() <= std::max(a.x(), b.x())
             && std::min(a.y(), b.y()) <= p.y()
             && p.y() <= std::max(a.y(), b.y());
    }

    bool
    segments_intersect(const Point &a,
                       const Point &b,
                       const Point &c,
                       const Point &d)
    {
      const double d1 = orient(c, d, a), d2 = orient(c, d, b);
      const double d3 = orient(a, b, c), d4 = orient(a, b, d);
      if (((d1 > 0. && d2 < 0.) || (d1 < 0. && d2 > 0.))
          && ((d3 > 0. && d4 < 0.) || (d3 < 0. && d4 > 0.)))
        return true;
      return (d1 == 0. && on_segment(c, d, a))
             || (d2 == 0. && on_segment(c, d, b))
             || (d3 == 0. && on_segment(a, b, c))
             || (d4 == 0. && on_segment(a, b, d));
    }
  } // namespace



  bool
  Polygon::self_intersects() const
  {
    const std::size_t n = vertices.size();
    if (n < 3)
      return true;
    for (std::size_t i = 0; i < n; ++i)
      for (std::size_t j = i + 1; j < n; ++j)
        {
          if (j == i + 1 || (i == 0 && j == n - 1))
            {
              // Adjacent edges share a vertex; they overlap only if folded
              // back onto each other.
              const Point &a = vertices[i], &b = vertices[(i + 1) % n];
              const Point &c = vertices[j], &d = vertices[(j + 1) % n];
              const Point  shared = (j == i + 1) ? b : a;
              const Point  u      = ((j == i + 1) ? a : b) - shared;
              const Point  v      = ((j == i + 1) ? d : c) - shared;
              if (u.x() * v.y() - u.y() * v.x() == 0. && u.dot(v) > 0.)
                return true;
              continue;
            }
          if (segments_intersect(vertices[i],
                                 vertices[(i + 1) % n],
                                 vertices[j],
                                 vertices[(j + 1) % n]))
            return true;
        }
    return false;
  }



  bool
  Polygon::contains(const Point &p) const
  {
    bool              inside = false;
    const std::size_t n      = vertices.size();
    for (std::size_t i = 0, j = n - 1; i < n; j = i++)
      {
        const Point &a = vertices[i], &b = vertices[j];
        if ((a.y() > p.y()) != (b.y() > p.y())
            && p.x()
                 < (b.x() - a.x()) * (p.y() - a.y()) / (b.y() - a.y()) + a.x())
          inside = !inside;
      }
    return inside;
  }
} // namespace rockdda::geometry
