/**
 * @file
 * Polyhedron checks and exact moments (doc/theory/dda3d.md).
 */
#include <rockdda/dda3d/polyhedron.h>
#include <rockdda/geometry/polygon.h>

#include <Eigen/Geometry>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <map>
#include <set>
#include <utility>

namespace rockdda::dda3d
{
  Point
  Polyhedron::vertex_mean() const
  {
    Point m = Point::Zero();
    for (const auto &v : vertices)
      m += v;
    return vertices.empty() ? m : Point(m / double(vertices.size()));
  }



  double
  Polyhedron::size() const
  {
    const Point m = vertex_mean();
    double      r = 0.;
    for (const auto &v : vertices)
      r = std::max(r, (v - m).norm());
    return 2. * r;
  }



  PolyhedronMoments
  Polyhedron::moments() const
  {
    // Signed tetrahedra (o, a, b, c) with o the vertex mean; coordinates
    // relative to o. For a tetrahedron with one vertex at the origin and
    // the others at a, b, c (volume V = det(a, b, c) / 6):
    //   integral x_i dV     = V (a + b + c)_i / 4,
    //   integral x_i x_j dV = V / 20 (sum_k p_k,i p_k,j
    //                                 + (sum_k p_k,i)(sum_k p_k,j))
    // with the sums over the four vertices (the origin adds nothing)
    // (Tonon 2004).
    PolyhedronMoments m;
    const Point       o  = vertex_mean();
    double            V  = 0.;
    Point             s1 = Point::Zero();
    Eigen::Matrix3d   s2 = Eigen::Matrix3d::Zero();
    for (const auto &face : faces)
      {
        if (face.size() < 3)
          continue;
        const Point a = vertices[face[0]] - o;
        for (std::size_t k = 1; k + 1 < face.size(); ++k)
          {
            const Point  b  = vertices[face[k]] - o;
            const Point  c  = vertices[face[k + 1]] - o;
            const double vt = a.dot(b.cross(c)) / 6.;
            const Point  s  = a + b + c;
            V += vt;
            s1 += vt * s / 4.;
            s2 += (vt / 20.)
                  * (a * a.transpose() + b * b.transpose() + c * c.transpose()
                     + s * s.transpose());
          }
      }
    m.volume = V;
    if (V == 0.)
      {
        m.centroid = o;
        return m;
      }
    const Point c = s1 / V;
    m.centroid    = o + c;
    m.second      = s2 - V * c * c.transpose();
    return m;
  }



  double
  Polyhedron::signed_volume() const
  {
    return moments().volume;
  }



  Point
  Polyhedron::face_normal(const std::size_t f) const
  {
    // Newell's method: exact for planar faces, a robust average otherwise.
    const auto &face = faces[f];
    Point       n    = Point::Zero();
    const Point o    = vertices[face[0]];
    for (std::size_t k = 0; k < face.size(); ++k)
      {
        const Point p = vertices[face[k]] - o;
        const Point q = vertices[face[(k + 1) % face.size()]] - o;
        n += p.cross(q);
      }
    const double l = n.norm();
    return l > 0. ? Point(n / l) : n;
  }



  double
  Polyhedron::winding_number(const Point &p) const
  {
    // Signed solid angle of each fan triangle seen from p:
    // tan(Omega / 2) = a.(b x c) / (|a||b||c| + (a.b)|c| + (b.c)|a|
    //                               + (c.a)|b|).
    const double pi    = std::acos(-1.);
    double       omega = 0.;
    for (const auto &face : faces)
      {
        if (face.size() < 3)
          continue;
        const Point  a  = vertices[face[0]] - p;
        const double la = a.norm();
        for (std::size_t k = 1; k + 1 < face.size(); ++k)
          {
            const Point  b   = vertices[face[k]] - p;
            const Point  c   = vertices[face[k + 1]] - p;
            const double lb  = b.norm();
            const double lc  = c.norm();
            const double num = a.dot(b.cross(c));
            const double den
              = la * lb * lc + a.dot(b) * lc + b.dot(c) * la + c.dot(a) * lb;
            omega += 2. * std::atan2(num, den);
          }
      }
    return omega / (4. * pi);
  }



  bool
  Polyhedron::contains(const Point &p) const
  {
    return winding_number(p) > 1e-6;
  }



  std::string
  PolyhedronDefect::describe() const
  {
    return face >= 0 ? "face " + std::to_string(face) + ": " + message
                     : message;
  }



  PolyhedronDefect
  polyhedron_defect(const Polyhedron &poly, const double planarity_tolerance)
  {
    const auto &v   = poly.vertices;
    const auto &F   = poly.faces;
    auto        bad = [](const int face, const std::string &message) {
      return PolyhedronDefect{face, message};
    };
    if (v.size() < 4)
      return bad(-1,
                 "has " + std::to_string(v.size())
                   + " vertices; a polyhedron needs at least 4");
    if (F.size() < 4)
      return bad(-1,
                 "has " + std::to_string(F.size())
                   + " faces; a closed polyhedron needs at least 4");
    for (const auto &p : v)
      if (!p.allFinite())
        return bad(-1, "has a vertex that is not a finite number");
    const double size = poly.size();
    if (!(size > 0.))
      return bad(-1, "has all its vertices at one point");
    std::vector<char> used(v.size(), 0);
    for (std::size_t f = 0; f < F.size(); ++f)
      {
        const auto &face = F[f];
        if (face.size() < 3)
          return bad(f,
                     "has " + std::to_string(face.size())
                       + " vertices; a face needs at least 3");
        std::set<int> distinct;
        for (const int k : face)
          {
            if (k < 0 || k >= int(v.size()))
              return bad(f,
                         "vertex index " + std::to_string(k)
                           + " does not exist (valid: 0-"
                           + std::to_string(v.size() - 1) + ")");
            if (!distinct.insert(k).second)
              return bad(f,
                         "vertex " + std::to_string(k)
                           + " appears twice in the face");
            used[k] = 1;
          }
      }
    for (std::size_t k = 0; k < v.size(); ++k)
      if (!used[k])
        return bad(-1, "vertex " + std::to_string(k) + " is used by no face");

    // Closed and consistently oriented: each directed edge (a, b) once and
    // its reverse (b, a) once, in another face.
    using Edge = std::pair<int, int>;
    std::map<Edge, std::vector<std::size_t>> edges;
    auto edge_of = [&](const std::size_t f, const std::size_t k) {
      return Edge{F[f][k], F[f][(k + 1) % F[f].size()]};
    };
    for (std::size_t f = 0; f < F.size(); ++f)
      for (std::size_t k = 0; k < F[f].size(); ++k)
        edges[edge_of(f, k)].push_back(f);
    auto edge_name = [](const Edge &e) {
      return "edge " + std::to_string(e.first) + "-" + std::to_string(e.second);
    };
    // A face listed clockwise meets each neighbour on an edge running the
    // same way; name the face with the largest share of such edges.
    std::vector<int> same_way(F.size(), 0);
    for (const auto &[e, faces_of] : edges)
      if (faces_of.size() > 1)
        for (const auto f : faces_of)
          ++same_way[f];
    int    worst       = -1;
    double worst_share = 0.;
    for (std::size_t f = 0; f < F.size(); ++f)
      {
        const double share = double(same_way[f]) / double(F[f].size());
        if (share > worst_share)
          {
            worst_share = share;
            worst       = int(f);
          }
      }
    if (worst >= 0)
      for (std::size_t k = 0; k < F[worst].size(); ++k)
        {
          const Edge  e        = edge_of(worst, k);
          const auto &faces_of = edges[e];
          if (faces_of.size() > 1)
            {
              const auto other
                = faces_of[0] == std::size_t(worst) ? faces_of[1] : faces_of[0];
              return bad(worst,
                         edge_name(e) + " runs the same way in face "
                           + std::to_string(other)
                           + " (this face is listed clockwise seen from "
                             "outside, or the surface is not a manifold)");
            }
        }
    for (std::size_t f = 0; f < F.size(); ++f)
      for (std::size_t k = 0; k < F[f].size(); ++k)
        {
          const Edge e   = edge_of(f, k);
          const auto rev = edges.find({e.second, e.first});
          if (rev == edges.end())
            return bad(f,
                       edge_name(e)
                         + " is used by no other face (the polyhedron is "
                           "not closed)");
          if (rev->second.size() == 1 && rev->second[0] == f)
            return bad(f, edge_name(e) + " is used twice by the same face");
        }

    // Planar faces with a non-zero area.
    for (std::size_t f = 0; f < F.size(); ++f)
      {
        const auto &face = F[f];
        Point       n    = Point::Zero();
        Point       mean = Point::Zero();
        for (std::size_t k = 0; k < face.size(); ++k)
          {
            const Point p = v[face[k]] - v[face[0]];
            const Point q = v[face[(k + 1) % face.size()]] - v[face[0]];
            n += p.cross(q);
            mean += v[face[k]];
          }
        mean /= double(face.size());
        const double area = 0.5 * n.norm();
        if (!(area > 1e-12 * size * size))
          return bad(f, "has zero area");
        n /= 2. * area;
        for (const int k : face)
          {
            const double d = std::abs((v[k] - mean).dot(n));
            if (d > planarity_tolerance * size)
              {
                char buf[200];
                std::snprintf(buf,
                              sizeof(buf),
                              "is not planar: vertex %d is %.3g m off the "
                              "face's plane (allowed %.3g m = %.3g x the "
                              "block size)",
                              k,
                              d,
                              planarity_tolerance * size,
                              planarity_tolerance);
                return bad(f, buf);
              }
          }
        // Simple: the point-in-face test of the contact detection (a
        // crossing rule in the face's plane) needs a polygon whose edges
        // do not cross; non-convex faces are fine.
        const Point       e1 = (v[face[1]] - v[face[0]]).normalized();
        const Point       e2 = n.cross(e1);
        geometry::Polygon in_plane;
        for (const int k : face)
          in_plane.vertices.emplace_back((v[k] - v[face[0]]).dot(e1),
                                         (v[k] - v[face[0]]).dot(e2));
        if (in_plane.self_intersects())
          return bad(f,
                     "is not a simple polygon: two of its edges cross or "
                     "fold back onto each other");
      }
    const double volume = poly.signed_volume();
    if (volume < 0.)
      {
        char buf[200];
        std::snprintf(buf,
                      sizeof(buf),
                      "(and every other face) is listed clockwise seen from "
                      "outside: inward normals, signed volume %.6g m^3",
                      volume);
        return bad(0, buf);
      }
    if (!(volume > 1e-12 * size * size * size))
      return bad(-1, "has zero volume");
    return {};
  }
} // namespace rockdda::dda3d
