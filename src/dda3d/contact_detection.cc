/**
 * @file
 * Broad and narrow phase of 3D DDA contact detection (Shi 2001; Jiang &
 * Yeung 2004; Beyabanaki et al. 2008).
 */
#include <rockdda/dda3d/contact_detection.h>

#include <Eigen/Geometry>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <map>
#include <tuple>

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



  PolyhedronEdges
  polyhedron_edges(const Polyhedron &p)
  {
    std::map<std::pair<int, int>, int> index;
    PolyhedronEdges                    e;
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
          }
      }
    return e;
  }



  namespace
  {
    /// Per-face data of a polyhedron for the narrow phase.
    struct FaceData
    {
      Point              normal, point;
      std::vector<Point> edge_normals; // in-plane, outward, unit
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
          for (std::size_t k = 0; k < loop.size(); ++k)
            {
              const Point e
                = p.vertices[loop[(k + 1) % loop.size()]] - p.vertices[loop[k]];
              d.edge_normals.push_back(e.cross(d.normal).normalized());
            }
        }
      return out;
    }

    /// Unit directions from each vertex along its edges.
    std::vector<std::vector<Point>>
    vertex_directions(const Polyhedron &p, const PolyhedronEdges &e)
    {
      std::vector<std::vector<Point>> out(p.vertices.size());
      for (const auto &v : e.v)
        {
          const Point d = (p.vertices[v[1]] - p.vertices[v[0]]).normalized();
          out[v[0]].push_back(d);
          out[v[1]].push_back(-d);
        }
      return out;
    }

    /// Unit directions into the two faces of each edge, perpendicular to
    /// it (the face's normal cross the edge as the face traverses it).
    std::vector<std::array<Point, 2>>
    edge_wings(const Polyhedron            &p,
               const PolyhedronEdges       &e,
               const std::vector<FaceData> &faces)
    {
      std::vector<std::array<Point, 2>> out(e.v.size());
      for (std::size_t k = 0; k < e.v.size(); ++k)
        {
          const Point d
            = (p.vertices[e.v[k][1]] - p.vertices[e.v[k][0]]).normalized();
          out[k][0] = faces[e.face[k][0]].normal.cross(d);
          out[k][1] = faces[e.face[k][1]].normal.cross(-d);
        }
      return out;
    }

    /// A vertex-face contact with the vertex it coincides with (-1: none).
    struct VertexFace
    {
      ContactCandidate c;
      int              partner = -1;
    };

    /// Vertices of @p a against faces of @p b.
    void
    vertices_on_faces(const Polyhedron                      &a,
                      const std::vector<std::vector<Point>> &a_dirs,
                      const int                              ia,
                      const Polyhedron                      &b,
                      const std::vector<FaceData>           &b_faces,
                      const int                              ib,
                      const BoundingBox                     &b_box,
                      const double                           d,
                      const double                           c,
                      const double                           sin_e,
                      std::vector<VertexFace>               &out)
    {
      for (int k = 0; k < int(a.vertices.size()); ++k)
        {
          const Point &P = a.vertices[k];
          if (((P.array() < b_box.lo.array()) || (P.array() > b_box.hi.array()))
                .any())
            continue;
          double gmax = -std::numeric_limits<double>::infinity();
          for (const auto &f : b_faces)
            gmax = std::max(gmax, f.normal.dot(P - f.point));
          if (gmax > d)
            continue;
          std::vector<ContactCandidate> found;
          for (int f = 0; f < int(b_faces.size()); ++f)
            {
              const auto  &F = b_faces[f];
              const double g = F.normal.dot(P - F.point);
              if (g < -d || g > d)
                continue;
              bool        inside = true;
              const auto &loop   = b.faces[f];
              for (std::size_t m = 0; m < loop.size() && inside; ++m)
                inside = F.edge_normals[m].dot(P - b.vertices[loop[m]]) <= c;
              if (!inside)
                continue;
              double score = 1.;
              for (const auto &dir : a_dirs[k])
                score = std::min(score, F.normal.dot(dir));
              ContactCandidate cc;
              cc.type   = ContactType::vertex_face;
              cc.i      = ia;
              cc.j      = ib;
              cc.a      = k;
              cc.b      = f;
              cc.p      = P;
              cc.q      = P - g * F.normal;
              cc.normal = F.normal;
              cc.gap    = g;
              cc.score  = score;
              found.push_back(cc);
            }
          if (found.empty())
            continue;
          std::vector<ContactCandidate> keep;
          if (gmax >= -c)
            {
              // Outside or on the surface: every face it enters and is not
              // behind. A face whose plane it is behind by more than the
              // coincidence tolerance is not touched (the vertex is on or
              // outside another face; a spring there would push it out
              // through that face by the depth): a column 1 mm wide standing
              // on a base 4.5 mm wide had its corners on the base's top face
              // 0.5 mm behind its side faces, within the contact distance of
              // the column's 1 m size, and the step never converged.
              for (const auto &cc : found)
                if (cc.score >= -sin_e && cc.gap >= -c)
                  keep.push_back(cc);
            }
          else
            {
              // Penetrated: the entered face of shortest exit, else the
              // face of shortest exit.
              const ContactCandidate *best = nullptr;
              for (const auto &cc : found)
                if (cc.score >= -sin_e && (!best || cc.gap > best->gap))
                  best = &cc;
              if (!best)
                for (const auto &cc : found)
                  if (!best || cc.gap > best->gap)
                    best = &cc;
              keep.push_back(*best);
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
    const auto   a_faces = face_data(a), b_faces = face_data(b);
    const auto   a_dirs     = vertex_directions(a, a_edges),
               b_dirs       = vertex_directions(b, b_edges);
    const BoundingBox a_box = bounding_box(a, d), b_box = bounding_box(b, d);

    // Vertex-face, both ways; then one contact per pair of coincident
    // vertices (vertex-vertex).
    std::vector<VertexFace> vf;
    vertices_on_faces(a, a_dirs, ia, b, b_faces, ib, b_box, d, c, sin_e, vf);
    const std::size_t n_ab = vf.size();
    vertices_on_faces(b, b_dirs, ib, a, a_faces, ia, a_box, d, c, sin_e, vf);
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
      if (vf[k].partner < 0 || best[vv_key(k)] == k)
        out.push_back(vf[k].c);

    // Edge-edge.
    const auto a_wings   = edge_wings(a, a_edges, a_faces),
               b_wings   = edge_wings(b, b_edges, b_faces);
    const double sin_par = std::sin(tol.parallel_angle);
    for (int ea = 0; ea < int(a_edges.v.size()); ++ea)
      {
        const Point &P1 = a.vertices[a_edges.v[ea][0]],
                    &P2 = a.vertices[a_edges.v[ea][1]];
        BoundingBox ebox;
        ebox.lo = P1.cwiseMin(P2);
        ebox.hi = P1.cwiseMax(P2);
        if (((ebox.hi.array() < b_box.lo.array())
             || (ebox.lo.array() > b_box.hi.array()))
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
            // faces best.
            auto score_of = [&](const Point &nn) {
              return std::min({nn.dot(a_wings[ea][0]),
                               nn.dot(a_wings[ea][1]),
                               -nn.dot(b_wings[eb][0]),
                               -nn.dot(b_wings[eb][1])});
            };
            double score = score_of(n);
            if (score_of(-n) > score)
              {
                n     = -n;
                score = score_of(n);
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
                  const DetectionTolerances             &tol)
  {
    const std::size_t        n = blocks.size();
    std::vector<BoundingBox> boxes(n);
    for (std::size_t b = 0; b < n; ++b)
      boxes[b]
        = bounding_box(*blocks[b], tol.distance_factor * blocks[b]->size());
    const auto                    pairs = broad_phase(boxes);
    std::vector<PolyhedronEdges>  edges(n);
    std::vector<char>             have(n, 0);
    std::vector<ContactCandidate> out;
    for (const auto &[i, j] : pairs)
      {
        for (const int b : {i, j})
          if (!have[b])
            {
              edges[b] = polyhedron_edges(*blocks[b]);
              have[b]  = 1;
            }
        narrow_phase(
          *blocks[i], edges[i], i, *blocks[j], edges[j], j, tol, out);
      }
    std::sort(out.begin(), out.end(), [](const auto &x, const auto &y) {
      return std::make_tuple(x.i, x.j, int(x.type), x.a, x.b)
             < std::make_tuple(y.i, y.j, int(y.type), y.a, y.b);
    });
    return out;
  }
} // namespace rockdda::dda3d
