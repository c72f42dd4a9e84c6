/**
 * @file
 * Generators of polyhedral blocks.
 */
#include <rockdda/analytical/sliding3d.h>
#include <rockdda/dda3d/generators.h>
#include <rockdda/io/error.h>

#include <Eigen/Geometry>

#include <algorithm>
#include <cmath>

namespace rockdda::dda3d
{
  Polyhedron
  make_box(const Point &lo, const Point &hi)
  {
    Polyhedron p;
    for (int k = 0; k < 8; ++k)
      p.vertices.emplace_back(k & 1 ? hi.x() : lo.x(),
                              k & 2 ? hi.y() : lo.y(),
                              k & 4 ? hi.z() : lo.z());
    // Counter-clockwise seen from outside.
    p.faces = {{0, 2, 3, 1},
               {4, 5, 7, 6},
               {0, 1, 5, 4},
               {2, 6, 7, 3},
               {0, 4, 6, 2},
               {1, 3, 7, 5}};
    return p;
  }



  Polyhedron
  make_prism(const geometry::Polygon &base_in, const double z0, const double z1)
  {
    geometry::Polygon base = base_in;
    base.make_counter_clockwise();
    const int  n = int(base.vertices.size());
    Polyhedron p;
    for (const double z : {z0, z1})
      for (const auto &v : base.vertices)
        p.vertices.emplace_back(v.x(), v.y(), z);
    std::vector<int> bottom, top;
    for (int k = 0; k < n; ++k)
      {
        bottom.push_back(n - 1 - k); // clockwise from above = outward down
        top.push_back(n + k);
      }
    p.faces.push_back(bottom);
    p.faces.push_back(top);
    for (int k = 0; k < n; ++k)
      {
        const int l = (k + 1) % n;
        p.faces.push_back({k, l, n + l, n + k});
      }
    return p;
  }



  Polyhedron
  make_tetrahedron(const Point &a,
                   const Point &b,
                   const Point &c,
                   const Point &d)
  {
    Polyhedron p;
    p.vertices = {a, b, c, d};
    p.faces    = {{0, 2, 1}, {0, 1, 3}, {1, 2, 3}, {0, 3, 2}};
    if ((b - a).dot((c - a).cross(d - a)) < 0.)
      for (auto &f : p.faces)
        std::reverse(f.begin(), f.end());
    return p;
  }



  HalfSpace
  half_space_from_dip(const double dip_deg,
                      const double dip_direction_deg,
                      const Point &point,
                      const bool   above)
  {
    const Point n = analytical::plane_normal(dip_deg, dip_direction_deg);
    HalfSpace   h;
    h.normal = above ? Point(-n) : n;
    h.offset = h.normal.dot(point);
    return h;
  }



  Polyhedron
  clip_convex(const Polyhedron &convex, const std::vector<HalfSpace> &cuts)
  {
    // Work on a polygon soup (faces as coordinate loops, counter-clockwise
    // from outside); index it at the end.
    std::vector<std::vector<Point>> faces;
    for (const auto &f : convex.faces)
      {
        faces.emplace_back();
        for (const int k : f)
          faces.back().push_back(convex.vertices[k]);
      }
    const double size = convex.size();
    const double tol  = 1e-9 * size;
    for (const auto &h : cuts)
      {
        const double                    ln = h.normal.norm();
        const Point                     n  = h.normal / ln;
        const double                    d  = h.offset / ln;
        std::vector<std::vector<Point>> kept;
        std::vector<Point>              cap;
        for (const auto &face : faces)
          {
            std::vector<Point> out;
            const std::size_t  m = face.size();
            for (std::size_t k = 0; k < m; ++k)
              {
                const Point &p  = face[k];
                const Point &q  = face[(k + 1) % m];
                const double sp = n.dot(p) - d, sq = n.dot(q) - d;
                if (sp <= tol)
                  out.push_back(p);
                if (sp <= tol && std::abs(sp) <= tol)
                  cap.push_back(p);
                if ((sp < -tol && sq > tol) || (sp > tol && sq < -tol))
                  {
                    const Point x = p + (sp / (sp - sq)) * (q - p);
                    out.push_back(x);
                    cap.push_back(x);
                  }
              }
            if (out.size() >= 3)
              kept.push_back(out);
          }
        // The cap: the points on the plane, ordered counter-clockwise seen
        // from +n (outside).
        std::vector<Point> unique;
        for (const auto &p : cap)
          if (std::none_of(unique.begin(), unique.end(), [&](const Point &q) {
                return (p - q).norm() <= tol;
              }))
            unique.push_back(p);
        if (unique.size() >= 3)
          {
            Point mean = Point::Zero();
            for (const auto &p : unique)
              mean += p;
            mean /= double(unique.size());
            const Point u
              = (std::abs(n.x()) < 0.9 ? Point::UnitX() : Point::UnitY())
                  .cross(n)
                  .normalized();
            const Point w = n.cross(u);
            std::sort(unique.begin(),
                      unique.end(),
                      [&](const Point &a, const Point &b) {
                        return std::atan2((a - mean).dot(w), (a - mean).dot(u))
                               < std::atan2((b - mean).dot(w),
                                            (b - mean).dot(u));
                      });
            kept.push_back(unique);
          }
        faces = kept;
      }
    // Index the soup, merging coincident vertices and dropping repeated
    // consecutive ones.
    Polyhedron result;
    for (const auto &face : faces)
      {
        std::vector<int> f;
        for (const auto &p : face)
          {
            int k = -1;
            for (std::size_t j = 0; j < result.vertices.size(); ++j)
              if ((result.vertices[j] - p).norm() <= tol)
                {
                  k = int(j);
                  break;
                }
            if (k < 0)
              {
                k = int(result.vertices.size());
                result.vertices.push_back(p);
              }
            if (f.empty() || (f.back() != k && f.front() != k))
              f.push_back(k);
          }
        if (f.size() >= 3)
          result.faces.push_back(f);
      }
    if (result.faces.size() < 4 || !(result.signed_volume() > 0.))
      throw InputError("clip_convex: the half-spaces leave no block");
    return result;
  }



  namespace
  {
    /// Where the joints' line of intersection of a tetrahedral wedge
    /// daylights: in the slope face at depth @p height below the crest,
    /// down the slope's dip line.
    Point
    wedge_toe(const double slope_dip_deg,
              const double slope_dip_direction_deg,
              const double height,
              const Point &crest)
    {
      const double deg = std::acos(-1.) / 180.;
      const double b = slope_dip_deg * deg, a = slope_dip_direction_deg * deg;
      const Point  down(std::cos(b) * std::sin(a),
                       std::cos(b) * std::cos(a),
                       -std::sin(b));
      return crest + (height / std::sin(b)) * down;
    }
  } // namespace



  Polyhedron
  make_tetrahedral_wedge(const WedgePlanes &p,
                         const double       height,
                         const Point       &crest)
  {
    if (!(height > 0.))
      throw InputError("tetrahedral wedge: height " + std::to_string(height)
                       + " m; valid: > 0");
    const Point toe
      = wedge_toe(p.slope_dip_deg, p.slope_dip_direction_deg, height, crest);
    const double                 L   = 200. * height;
    const Point                  big = Point::Constant(L);
    Polyhedron                   box = make_box(crest - big, crest + big);
    const std::vector<HalfSpace> cuts
      = {{Point::UnitZ(), crest.z()},
         half_space_from_dip(p.slope_dip_deg, p.slope_dip_direction_deg, crest),
         half_space_from_dip(
           p.joint1_dip_deg, p.joint1_dip_direction_deg, toe, true),
         half_space_from_dip(
           p.joint2_dip_deg, p.joint2_dip_direction_deg, toe, true)};
    Polyhedron wedge = clip_convex(box, cuts);
    if (wedge.vertices.size() != 4)
      throw InputError(
        "tetrahedral wedge: the joints' line of intersection does not "
        "daylight in the slope face (no tetrahedron within "
        + std::to_string(L) + " m of the crest)");
    return wedge;
  }



  WedgeInTrough
  make_wedge_in_trough(const WedgePlanes &planes,
                       const double       height,
                       const double       margin,
                       const Point       &crest)
  {
    if (!(margin > 0.))
      throw InputError("wedge in trough: margin " + std::to_string(margin)
                       + " m; valid: > 0");
    WedgeInTrough out;
    out.wedge = make_tetrahedral_wedge(planes, height, crest);
    out.toe   = wedge_toe(planes.slope_dip_deg,
                        planes.slope_dip_direction_deg,
                        height,
                        crest);
    Point lo = out.wedge.vertices.front(), hi = lo;
    for (const auto &v : out.wedge.vertices)
      {
        lo = lo.cwiseMin(v);
        hi = hi.cwiseMax(v);
      }
    const Polyhedron box = make_box(lo - Point(margin, margin, 2. * margin),
                                    hi + Point::Constant(margin));
    const HalfSpace  below1
      = half_space_from_dip(planes.joint1_dip_deg,
                            planes.joint1_dip_direction_deg,
                            out.toe);
    const HalfSpace below2
      = half_space_from_dip(planes.joint2_dip_deg,
                            planes.joint2_dip_direction_deg,
                            out.toe);
    // Trough block 1 where joint 1 is the lower plane: n1 . x <= n2 . x.
    const Point split = (below1.normal - below2.normal).normalized();
    out.trough[0]     = clip_convex(box, {below1, {split, split.dot(out.toe)}});
    out.trough[1] = clip_convex(box, {below2, {-split, -split.dot(out.toe)}});
    return out;
  }



  BlockSystem
  wedge_in_trough_scene(const WedgeInTrough      &w,
                        const Material           &material,
                        const dda::JointMaterial &joint)
  {
    BlockSystem s;
    s.materials = {material};
    s.joints    = {joint};
    for (const Polyhedron *p : {&w.trough[0], &w.trough[1], &w.wedge})
      {
        Block b;
        b.id         = int(s.blocks.size()) + 1;
        b.material   = 0;
        b.polyhedron = *p;
        s.blocks.push_back(b);
      }
    for (const int b : {0, 1})
      for (const Point &v : s.blocks[b].polyhedron.vertices)
        s.fixed_points.push_back({b, v, Point::Zero()});
    s.measurement_points.push_back(
      {2, w.wedge.moments().centroid, Point::Zero()});
    return s;
  }
} // namespace rockdda::dda3d
