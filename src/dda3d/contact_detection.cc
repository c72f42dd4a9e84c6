/**
 * @file
 * Broad and narrow phase of 3D DDA contact detection (Shi 2001; Jiang &
 * Yeung 2004; Beyabanaki et al. 2008).
 */
#include <rockdda/dda3d/contact_detection.h>
#include <rockdda/geometry/polygon.h>

#include <Eigen/Geometry>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <map>
#include <tuple>
#include <utility>

namespace rockdda::dda3d
{
  BoundingBox
  bounding_box(const Polyhedron &p, const double margin)
  {
    BoundingBox b;
    b.lo = Point::Constant(std::numeric_limits<double>::infinity());
    b.hi = -b.lo;
    for (const auto &v : p.vertices)
      {
        b.lo = b.lo.cwiseMin(v);
        b.hi = b.hi.cwiseMax(v);
      }
    b.lo.array() -= margin;
    b.hi.array() += margin;
    return b;
  }



  std::vector<std::pair<int, int>>
  broad_phase(const std::vector<BoundingBox> &boxes)
  {
    const int                        n = static_cast<int>(boxes.size());
    std::vector<std::pair<int, int>> pairs;
    if (n < 2)
      return pairs;
    // Cell: the median of the boxes' largest extents, enlarged so that no
    // box spans more than about 4 cells per axis (a few huge blocks, e.g.
    // a base, must not fill the grid).
    std::vector<double> extent(n);
    double              largest = 0.;
    Point lo = Point::Constant(std::numeric_limits<double>::infinity());
    for (int b = 0; b < n; ++b)
      {
        extent[b] = (boxes[b].hi - boxes[b].lo).maxCoeff();
        largest   = std::max(largest, extent[b]);
        lo        = lo.cwiseMin(boxes[b].lo);
      }
    std::vector<double> sorted = extent;
    std::nth_element(sorted.begin(), sorted.begin() + n / 2, sorted.end());
    double cell = std::max(sorted[n / 2], largest / 4.);
    if (!(cell > 0.))
      cell = 1.;
    auto index = [&](const double x, const int k) {
      return static_cast<std::int64_t>(std::floor((x - lo[k]) / cell));
    };
    // (cell key, box) for every cell a box overlaps, sorted by cell.
    std::vector<std::pair<std::uint64_t, int>> entries;
    auto key = [](std::int64_t x, std::int64_t y, std::int64_t z) {
      return (std::uint64_t(x) << 42) | (std::uint64_t(y) << 21)
             | std::uint64_t(z);
    };
    for (int b = 0; b < n; ++b)
      {
        const std::int64_t x0 = index(boxes[b].lo.x(), 0),
                           x1 = index(boxes[b].hi.x(), 0);
        const std::int64_t y0 = index(boxes[b].lo.y(), 1),
                           y1 = index(boxes[b].hi.y(), 1);
        const std::int64_t z0 = index(boxes[b].lo.z(), 2),
                           z1 = index(boxes[b].hi.z(), 2);
        for (std::int64_t x = x0; x <= x1; ++x)
          for (std::int64_t y = y0; y <= y1; ++y)
            for (std::int64_t z = z0; z <= z1; ++z)
              entries.emplace_back(key(x, y, z), b);
      }
    std::sort(entries.begin(), entries.end());
    for (std::size_t s = 0; s < entries.size();)
      {
        std::size_t e = s;
        while (e < entries.size() && entries[e].first == entries[s].first)
          ++e;
        for (std::size_t u = s; u < e; ++u)
          for (std::size_t w = u + 1; w < e; ++w)
            {
              const int   i = entries[u].second, j = entries[w].second;
              const auto &A = boxes[i], &B = boxes[j];
              const Point ilo = A.lo.cwiseMax(B.lo), ihi = A.hi.cwiseMin(B.hi);
              if ((ilo.array() > ihi.array()).any())
                continue;
              // Report the pair only in the cell of the intersection's
              // lower corner.
              if (key(index(ilo.x(), 0), index(ilo.y(), 1), index(ilo.z(), 2))
                  != entries[s].first)
                continue;
              pairs.emplace_back(std::min(i, j), std::max(i, j));
            }
        s = e;
      }
    std::sort(pairs.begin(), pairs.end());
    return pairs;
  }



  namespace
  {
    /// Angle (rad, in [0, 2 pi)) by which @p x lies from the unit vector
    /// @p start, turning towards the unit vector @p towards (perpendicular
    /// to start); x is projected on their plane.
    double
    turn_angle(const Point &x, const Point &start, const Point &towards)
    {
      const double a = std::atan2(x.dot(towards), x.dot(start));
      return a < 0. ? a + 2. * std::acos(-1.) : a;
    }
  } // namespace



  PolyhedronEdges
  polyhedron_edges(const Polyhedron &p)
  {
    const double                       pi = std::acos(-1.);
    std::map<std::pair<int, int>, int> index;
    PolyhedronEdges                    e;
    e.face_edges.resize(p.faces.size());
    for (int f = 0; f < int(p.faces.size()); ++f)
      {
        const auto &loop = p.faces[f];
        for (std::size_t k = 0; k < loop.size(); ++k)
          {
            const int  a = loop[k], b = loop[(k + 1) % loop.size()];
            const auto edge = std::minmax(a, b);
            auto       it   = index.find(edge);
            if (it == index.end())
              {
                it = index.emplace(edge, int(e.v.size())).first;
                e.v.push_back({{edge.first, edge.second}});
                e.face.push_back({{-1, -1}});
              }
            e.face[it->second][a < b ? 0 : 1] = f;
            e.face_edges[f].push_back(it->second);
          }
      }
    // Dihedral angle: from the direction into face 0 (perpendicular to the
    // edge), turning into the solid (against face 0's normal), to the
    // direction into face 1.
    std::vector<Point> normals(p.faces.size());
    for (std::size_t f = 0; f < p.faces.size(); ++f)
      normals[f] = p.face_normal(f);
    const std::size_t ne = e.v.size();
    e.dihedral.resize(ne);
    e.edge_convexity.resize(ne);
    std::vector<int> n_reflex(p.vertices.size(), 0),
      n_edges(p.vertices.size(), 0);
    for (std::size_t k = 0; k < ne; ++k)
      {
        const Point d
          = (p.vertices[e.v[k][1]] - p.vertices[e.v[k][0]]).normalized();
        const Point &m0 = normals[e.face[k][0]], &m1 = normals[e.face[k][1]];
        const Point  w0 = m0.cross(d), w1 = m1.cross(-d);
        double       a = turn_angle(w1, w0, -m0);
        if (a == 0.)
          a = 2. * pi;
        e.dihedral[k]       = a;
        e.edge_convexity[k] = a > pi + flat_angle   ? Convexity::reflex
                              : a < pi - flat_angle ? Convexity::convex
                                                    : Convexity::flat;
        for (const int v : e.v[k])
          {
            ++n_edges[v];
            n_reflex[v] += e.edge_convexity[k] == Convexity::reflex;
          }
        if (e.edge_convexity[k] == Convexity::reflex)
          e.convex = false;
      }
    e.vertex_convexity.resize(p.vertices.size());
    for (std::size_t v = 0; v < p.vertices.size(); ++v)
      e.vertex_convexity[v] = n_reflex[v] == 0            ? Convexity::convex
                              : n_reflex[v] == n_edges[v] ? Convexity::reflex
                                                          : Convexity::saddle;
    return e;
  }



  FaceLocation
  locate_on_face(const Polyhedron &p,
                 const std::size_t f,
                 const Point      &normal,
                 const Point      &x)
  {
    // In-plane coordinates about the face's first vertex.
    const auto  &loop     = p.faces[f];
    const Point &o        = p.vertices[loop[0]];
    const Point  e1       = (p.vertices[loop[1]] - o).normalized();
    const Point  e2       = normal.cross(e1);
    auto         in_plane = [&](const Point &y) {
      return geometry::Point((y - o).dot(e1), (y - o).dot(e2));
    };
    thread_local geometry::Polygon polygon;
    polygon.vertices.resize(loop.size());
    for (std::size_t k = 0; k < loop.size(); ++k)
      polygon.vertices[k] = in_plane(p.vertices[loop[k]]);
    const geometry::Point q = in_plane(x);
    FaceLocation          out;
    out.inside   = polygon.contains(q);
    out.distance = std::numeric_limits<double>::infinity();
    for (std::size_t k = 0; k < loop.size(); ++k)
      {
        const geometry::Point &a = polygon.vertices[k],
                              &b = polygon.vertices[(k + 1) % loop.size()];
        const geometry::Point ab = b - a;
        const double          t
          = std::clamp((q - a).dot(ab) / std::max(ab.squaredNorm(), 1e-300),
                       0.,
                       1.);
        const double dist = (q - a - t * ab).norm();
        if (dist < out.distance)
          {
            out.distance = dist;
            out.edge     = int(k);
          }
      }
    return out;
  }



  namespace
  {
    /// Per-face data of a polyhedron for the narrow phase.
    struct FaceData
    {
      Point normal, point;
    };

    std::vector<FaceData>
    face_data(const Polyhedron &p)
    {
      std::vector<FaceData> out(p.faces.size());
      for (std::size_t f = 0; f < p.faces.size(); ++f)
        {
          const auto &loop = p.faces[f];
          auto       &d    = out[f];
          d.normal         = p.face_normal(f);
          d.point          = Point::Zero();
          for (const int v : loop)
            d.point += p.vertices[v];
          d.point /= double(loop.size());
        }
      return out;
    }

    /**
     * A planar arc of unit directions: from @p start turning towards
     * @p towards (unit, perpendicular to start) by @p angle (rad, in
     * (0, 2 pi)) to @p end.
     */
    struct Arc
    {
      Point  start, towards, end;
      double angle = 0.;
    };

    /// Minimum of n . d over the directions d of an arc, and whether it
    /// is attained inside the arc (0 at the start, 1 at the end, 2 inside).
    std::pair<double, int>
    arc_minimum(const Arc &arc, const Point &n)
    {
      const double x = n.dot(arc.start), y = n.dot(arc.towards);
      if (std::hypot(x, y) > 0.)
        {
          // The direction of the arc's plane closest to -n.
          const double t = turn_angle(-n, arc.start, arc.towards);
          if (t > 0. && t < arc.angle)
            return {-std::hypot(x, y), 2};
        }
      const double e = n.dot(arc.end);
      return x <= e ? std::make_pair(x, 0) : std::make_pair(e, 1);
    }

    /// The solid's wedge about each edge: the arc from the direction into
    /// face 0 to the direction into face 1 through the solid (longer than
    /// pi at a reflex edge).
    std::vector<Arc>
    edge_wedges(const Polyhedron            &p,
                const PolyhedronEdges       &e,
                const std::vector<FaceData> &faces)
    {
      std::vector<Arc> out(e.v.size());
      for (std::size_t k = 0; k < e.v.size(); ++k)
        {
          const Point d
            = (p.vertices[e.v[k][1]] - p.vertices[e.v[k][0]]).normalized();
          out[k].start   = faces[e.face[k][0]].normal.cross(d);
          out[k].towards = -faces[e.face[k][0]].normal;
          out[k].end     = faces[e.face[k][1]].normal.cross(-d);
          out[k].angle   = e.dihedral[k];
        }
      return out;
    }

    /// Whether the direction @p t (perpendicular to edge k) points into
    /// the solid's wedge about the edge.
    bool
    in_wedge(const Arc &wedge, const Point &t)
    {
      const double a = turn_angle(t, wedge.start, wedge.towards);
      return a > 0. && a < wedge.angle;
    }

    /**
     * The tangent cone of a polyhedron at a vertex: one sector per face
     * corner at the vertex (the face's directions between its two edges
     * there, turning about the face's normal from the next vertex of the
     * loop to the previous one; longer than pi at a reflex corner of a
     * non-convex face), with the face's normal and the edges that bound
     * it.
     */
    struct ConeSector
    {
      Arc   arc;
      Point normal;
      /// Edges along arc.start and arc.end.
      int start_edge = -1, end_edge = -1;
    };

    std::vector<std::vector<ConeSector>>
    vertex_cones(const Polyhedron            &p,
                 const PolyhedronEdges       &e,
                 const std::vector<FaceData> &faces)
    {
      const double                         pi = std::acos(-1.);
      std::vector<std::vector<ConeSector>> out(p.vertices.size());
      for (std::size_t f = 0; f < p.faces.size(); ++f)
        {
          const auto       &loop = p.faces[f];
          const std::size_t n    = loop.size();
          for (std::size_t k = 0; k < n; ++k)
            {
              const Point &v    = p.vertices[loop[k]];
              const Point  next = (p.vertices[loop[(k + 1) % n]] - v),
                          prev  = (p.vertices[loop[(k + n - 1) % n]] - v);
              ConeSector s;
              s.normal      = faces[f].normal;
              s.arc.start   = next.normalized();
              s.arc.towards = s.normal.cross(s.arc.start);
              s.arc.end     = prev.normalized();
              double a      = turn_angle(s.arc.end, s.arc.start, s.arc.towards);
              if (a == 0.)
                a = 2. * pi;
              s.arc.angle  = a;
              s.start_edge = e.face_edges[f][k];
              s.end_edge   = e.face_edges[f][(k + n - 1) % n];
              out[loop[k]].push_back(s);
            }
        }
      return out;
    }

    /**
     * Entrance score of a vertex with tangent cone @p cone on a plane of
     * unit normal @p n: the minimum of n . d over the unit directions d
     * into the solid at the vertex (>= 0 when the solid lies locally on the
     * outer side of the plane). Exact for any cone, convex or not: the
     * minimum over the cone's boundary (its face sectors, which include
     * the edges) unless -n points into the cone (-1). That is decided at
     * the boundary direction closest to -n, where the great circle towards
     * -n leaves the boundary: inside a sector, along the inward side of its
     * face (n . normal > 0); at an edge, into the edge's wedge.
     */
    double
    cone_score(const std::vector<ConeSector> &cone,
               const std::vector<Arc>        &wedges,
               const Point                   &n)
    {
      double            best  = std::numeric_limits<double>::infinity();
      const ConeSector *at    = nullptr;
      int               where = 0;
      for (const auto &s : cone)
        {
          const auto [value, w] = arc_minimum(s.arc, n);
          if (value < best)
            {
              best  = value;
              at    = &s;
              where = w;
            }
        }
      if (!at)
        return best;
      bool inside;
      if (where == 2)
        inside = n.dot(at->normal) > 0.;
      else
        {
          const Point r = where == 0 ? at->arc.start : at->arc.end;
          const Point t = -(n - n.dot(r) * r);
          inside
            = t.squaredNorm() > 1e-24
              && in_wedge(wedges[where == 0 ? at->start_edge : at->end_edge],
                          t);
        }
      return inside ? -1. : best;
    }

    /// Entrance score of an edge with wedge @p wedge on a plane through it
    /// of unit normal @p n (the minimum of n . d over the wedge).
    double
    wedge_score(const Arc &wedge, const Point &n)
    {
      return arc_minimum(wedge, n).first;
    }

    /// A vertex-face contact with the vertex it coincides with (-1: none).
    struct VertexFace
    {
      ContactCandidate c;
      int              partner = -1;
    };

    /// The face of @p e across reflex edge @p edge from face @p f.
    int
    across(const PolyhedronEdges &e, const int edge, const int f)
    {
      return e.face[edge][0] == f ? e.face[edge][1] : e.face[edge][0];
    }

    /// Whether faces @p f and @p g of @p e meet at a reflex edge.
    bool
    reflex_neighbours(const PolyhedronEdges &e, const int f, const int g)
    {
      for (const int k : e.face_edges[f])
        if (e.edge_convexity[k] == Convexity::reflex && across(e, k, f) == g)
          return true;
      return false;
    }

    /// One block of a pair with its derived data.
    struct Side
    {
      const Polyhedron                    &p;
      const PolyhedronEdges               &e;
      int                                  id;
      std::vector<FaceData>                faces;
      std::vector<Arc>                     wedges;
      std::vector<std::vector<ConeSector>> cones;
      BoundingBox                          box;

      Side(const Polyhedron      &p_,
           const PolyhedronEdges &e_,
           const int              id_,
           const double           d)
          : p(p_)
          , e(e_)
          , id(id_)
          , faces(face_data(p_))
          , wedges(edge_wedges(p_, e_, faces))
          , cones(vertex_cones(p_, e_, faces))
          , box(bounding_box(p_, d))
      {}
    };

    /**
     * Vertices of @p A against faces of @p B (doc/theory/dda3d.md,
     * "Contacts"). A face is a candidate of vertex P when |gap| <= d and
     * P's projection lies in the face (within c of it), or, beyond the
     * face's boundary, within d of a reflex edge of the face (P coming
     * round the concave corner onto the face).
     */
    void
    vertices_on_faces(const Side              &A,
                      const Side              &B,
                      const double             d,
                      const double             c,
                      const double             sin_e,
                      std::vector<VertexFace> &out)
    {
      const Polyhedron &a = A.p, &b = B.p;
      struct Candidate
      {
        ContactCandidate c;
        bool             on_face = true;
      };
      std::vector<Candidate> found;
      std::vector<double>    gaps(b.faces.size());
      for (int k = 0; k < int(a.vertices.size()); ++k)
        {
          const Point &P = a.vertices[k];
          if (((P.array() < B.box.lo.array()) || (P.array() > B.box.hi.array()))
                .any())
            continue;
          double gmax = -std::numeric_limits<double>::infinity();
          for (std::size_t f = 0; f < b.faces.size(); ++f)
            {
              gaps[f] = B.faces[f].normal.dot(P - B.faces[f].point);
              gmax    = std::max(gmax, gaps[f]);
            }
          // Outside a convex block by more than d: nothing to touch.
          if (B.e.convex && gmax > d)
            continue;
          found.clear();
          for (int f = 0; f < int(b.faces.size()); ++f)
            {
              const auto  &F = B.faces[f];
              const double g = gaps[f];
              if (g < -d || g > d)
                continue;
              const FaceLocation loc     = locate_on_face(b, f, F.normal, P);
              const bool         on_face = loc.inside || loc.distance <= c;
              bool               round   = false;
              if (!on_face && loc.distance <= d)
                {
                  // Beyond a reflex edge of the face, within d of it.
                  const auto &loop = b.faces[f];
                  for (std::size_t m = 0; m < loop.size() && !round; ++m)
                    {
                      const int edge = B.e.face_edges[f][m];
                      if (B.e.edge_convexity[edge] != Convexity::reflex)
                        continue;
                      const Point &x0 = b.vertices[loop[m]],
                                  &x1 = b.vertices[loop[(m + 1) % loop.size()]];
                      const Point  u  = x1 - x0;
                      const double t
                        = std::clamp((P - x0).dot(u) / u.squaredNorm(), 0., 1.);
                      round = (P - x0 - t * u).norm() <= d;
                    }
                }
              if (!on_face && !round)
                continue;
              Candidate cc;
              cc.on_face  = on_face;
              cc.c.type   = ContactType::vertex_face;
              cc.c.i      = A.id;
              cc.c.j      = B.id;
              cc.c.a      = k;
              cc.c.b      = f;
              cc.c.p      = P;
              cc.c.q      = P - g * F.normal;
              cc.c.normal = F.normal;
              cc.c.gap    = g;
              cc.c.score  = cone_score(A.cones[k], A.wedges, F.normal);
              found.push_back(cc);
            }
          if (found.empty())
            continue;
          // Inside the other block, and not on its surface: penetrated.
          bool on_surface = false;
          for (const auto &cc : found)
            on_surface = on_surface || (cc.on_face && std::abs(cc.c.gap) <= c);
          const bool inside
            = B.e.convex ? gmax < 0. : b.winding_number(P) > 0.5;
          std::vector<ContactCandidate> keep;
          if (!inside || on_surface)
            {
              // Outside or on the surface: every face it enters and is not
              // behind. A face whose plane it is behind by more than the
              // coincidence tolerance is not touched (the vertex is on or
              // outside another face; a spring there would push it out
              // through that face by the depth): a column 1 mm wide standing
              // on a base 4.5 mm wide had its corners on the base's top face
              // 0.5 mm behind its side faces, within the contact distance of
              // the column's 1 m size, and the step never converged. Both
              // faces at a reflex edge that it enters (a vertex in a
              // concave corner) are kept.
              for (const auto &cc : found)
                if (cc.c.score >= -sin_e && cc.c.gap >= -c)
                  keep.push_back(cc.c);
            }
          else
            {
              // Penetrated: of the faces it is behind and projects onto,
              // the entered one of shortest exit, else the one of shortest
              // exit (a face of a non-convex block whose plane it is in
              // front of is no exit); only if it projects onto none (in a
              // concave corner, beyond both faces' common edge), the faces
              // it reaches round a reflex edge.
              const Candidate *best = nullptr;
              for (const bool on_face : {true, false})
                {
                  for (const bool entered : {true, false})
                    {
                      for (const auto &cc : found)
                        if (cc.on_face == on_face && cc.c.gap <= 0.
                            && (!entered || cc.c.score >= -sin_e)
                            && (!best || cc.c.gap > best->c.gap))
                          best = &cc;
                      if (best)
                        break;
                    }
                  if (best)
                    break;
                }
              if (!best)
                continue;
              keep.push_back(best->c);
              // At a reflex edge of that face within reach: the face across
              // it too, penetrated (if entered) or still open (the vertex
              // closes on it when it crosses its plane). The vertex in a
              // concave corner keeps both load-carrying contacts.
              for (const auto &cc : found)
                if (&cc != best && reflex_neighbours(B.e, best->c.b, cc.c.b)
                    && (cc.c.gap >= 0. || cc.c.score >= -sin_e))
                  keep.push_back(cc.c);
            }
          // The vertex of b that P coincides with, if any.
          int partner = -1;
          for (int v = 0; v < int(b.vertices.size()); ++v)
            if ((b.vertices[v] - P).norm() <= c)
              {
                partner = v;
                break;
              }
          for (const auto &cc : keep)
            out.push_back({cc, partner});
        }
    }
  } // namespace



  void
  narrow_phase(const Polyhedron              &a,
               const PolyhedronEdges         &a_edges,
               const int                      ia,
               const Polyhedron              &b,
               const PolyhedronEdges         &b_edges,
               const int                      ib,
               const DetectionTolerances     &tol,
               std::vector<ContactCandidate> &out)
  {
    const double d     = tol.distance_factor * std::max(a.size(), b.size());
    const double c     = tol.coincidence_factor * std::min(a.size(), b.size());
    const double sin_e = std::sin(tol.entrance_angle);
    const Side   A(a, a_edges, ia, d), B(b, b_edges, ib, d);

    // Vertex-face, both ways; then one contact per pair of coincident
    // vertices (vertex-vertex).
    std::vector<VertexFace> vf;
    vertices_on_faces(A, B, d, c, sin_e, vf);
    const std::size_t n_ab = vf.size();
    vertices_on_faces(B, A, d, c, sin_e, vf);
    // Key of a coincident pair: (vertex of a, vertex of b).
    auto vv_key = [&](const std::size_t k) {
      return k < n_ab ? std::make_pair(vf[k].c.a, vf[k].partner)
                      : std::make_pair(vf[k].partner, vf[k].c.a);
    };
    std::map<std::pair<int, int>, std::size_t> best;
    for (std::size_t k = 0; k < vf.size(); ++k)
      {
        if (vf[k].partner < 0)
          continue;
        const auto key = vv_key(k);
        auto       it  = best.find(key);
        if (it == best.end())
          {
            best.emplace(key, k);
            continue;
          }
        const auto &o = vf[it->second].c, &n = vf[k].c;
        bool        better;
        if (n.score > o.score + 0.01)
          better = true;
        else if (o.score > n.score + 0.01)
          better = false;
        else if (n.i != o.i)
          better = n.i < o.i;
        else
          better = n.score > o.score || (n.score == o.score && n.gap > o.gap);
        if (better)
          it->second = k;
      }
    for (std::size_t k = 0; k < vf.size(); ++k)
      {
        bool kept = vf[k].partner < 0;
        if (!kept)
          {
            // The chosen contact of the pair, and the same vertex on the
            // faces across a reflex edge from the chosen face (a vertex in
            // a concave corner keeps both load-carrying contacts).
            const std::size_t chosen = best[vv_key(k)];
            const auto       &x = vf[chosen].c, &y = vf[k].c;
            kept = chosen == k
                   || (x.i == y.i && x.a == y.a
                       && reflex_neighbours(x.i == ia ? b_edges : a_edges,
                                            x.b,
                                            y.b));
          }
        if (kept)
          out.push_back(vf[k].c);
      }

    // Edge-edge: the contact plane must separate the two edges' wedges
    // (each wedge scored over its real extent, so that a reflex edge,
    // whose wedge is wider than pi, is entered by nothing).
    const double sin_par = std::sin(tol.parallel_angle);
    for (int ea = 0; ea < int(a_edges.v.size()); ++ea)
      {
        const Point &P1 = a.vertices[a_edges.v[ea][0]],
                    &P2 = a.vertices[a_edges.v[ea][1]];
        BoundingBox ebox;
        ebox.lo = P1.cwiseMin(P2);
        ebox.hi = P1.cwiseMax(P2);
        if (((ebox.hi.array() < B.box.lo.array())
             || (ebox.lo.array() > B.box.hi.array()))
              .any())
          continue;
        const Point  u  = P2 - P1;
        const double lu = u.norm();
        for (int eb = 0; eb < int(b_edges.v.size()); ++eb)
          {
            const Point &Q1 = b.vertices[b_edges.v[eb][0]],
                        &Q2 = b.vertices[b_edges.v[eb][1]];
            const Point  v  = Q2 - Q1;
            const double lv = v.norm();
            const Point  w  = u.cross(v);
            const double lw = w.norm();
            if (lw <= sin_par * lu * lv)
              continue;
            const Point  r  = P1 - Q1;
            const double uu = u.dot(u), uv = u.dot(v), vv = v.dot(v);
            const double ur = u.dot(r), vr = v.dot(r);
            const double den = uu * vv - uv * uv;
            const double sp  = (uv * vr - vv * ur) / den;
            const double tq  = (uu * vr - uv * ur) / den;
            if (sp * lu <= c || (1. - sp) * lu <= c || tq * lv <= c
                || (1. - tq) * lv <= c)
              continue;
            const Point p = P1 + sp * u, q = Q1 + tq * v;
            Point       n = w / lw;
            // Orientation: the sign whose plane separates the two edges'
            // wedges best.
            auto score_of = [&](const Point &nn) {
              return std::min(wedge_score(A.wedges[ea], nn),
                              wedge_score(B.wedges[eb], -nn));
            };
            double score = score_of(n);
            if (const double other = score_of(-n); other > score)
              {
                n     = -n;
                score = other;
              }
            if (score < -sin_e)
              continue;
            const double g = n.dot(p - q);
            if (g < -d || g > d)
              continue;
            ContactCandidate cc;
            cc.type   = ContactType::edge_edge;
            cc.i      = ia;
            cc.j      = ib;
            cc.a      = ea;
            cc.b      = eb;
            cc.p      = p;
            cc.q      = q;
            cc.normal = n;
            cc.gap    = g;
            cc.score  = score;
            out.push_back(cc);
          }
      }
  }



  std::vector<ContactCandidate>
  detect_contacts(const std::vector<const Polyhedron *> &blocks,
                  const DetectionTolerances             &tol,
                  const dda::ChunkRunner                &run_chunks,
                  std::vector<PolyhedronEdges>          *edges_out)
  {
    const std::size_t        n = blocks.size();
    std::vector<BoundingBox> boxes(n);
    for (std::size_t b = 0; b < n; ++b)
      boxes[b]
        = bounding_box(*blocks[b], tol.distance_factor * blocks[b]->size());
    const auto        pairs = broad_phase(boxes);
    std::vector<char> have(n, 0);
    for (const auto &[i, j] : pairs)
      have[i] = have[j] = 1;
    std::vector<PolyhedronEdges> edges(n);
    dda::for_each_chunk(run_chunks,
                        n,
                        32,
                        [&](const std::size_t lo, const std::size_t hi) {
                          for (std::size_t b = lo; b < hi; ++b)
                            if (have[b])
                              edges[b] = polyhedron_edges(*blocks[b]);
                        });
    // The pairs in chunks, each with its own output, joined in order.
    auto out = dda::joined_chunks<ContactCandidate>(
      run_chunks,
      pairs.size(),
      32,
      [&](const std::size_t              lo,
          const std::size_t              hi,
          std::vector<ContactCandidate> &chunk) {
        for (std::size_t k = lo; k < hi; ++k)
          {
            const auto [i, j] = pairs[k];
            narrow_phase(
              *blocks[i], edges[i], i, *blocks[j], edges[j], j, tol, chunk);
          }
      });
    std::sort(out.begin(), out.end(), [](const auto &x, const auto &y) {
      return std::make_tuple(x.i, x.j, int(x.type), x.a, x.b)
             < std::make_tuple(y.i, y.j, int(y.type), y.a, y.b);
    });
    if (edges_out != nullptr)
      *edges_out = std::move(edges);
    return out;
  }
} // namespace rockdda::dda3d
