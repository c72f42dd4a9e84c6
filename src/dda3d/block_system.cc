/**
 * @file
 * Scene checks of 3D DDA.
 */
#include <rockdda/dda3d/block_system.h>
#include <rockdda/dda3d/contact_detection.h>
#include <rockdda/io/error.h>
#include <rockdda/io/output.h>

#include <Eigen/Geometry>

#include <algorithm>
#include <cmath>
#include <limits>

namespace rockdda::dda3d
{
  namespace
  {
    /// Whether every vertex of @p p lies on the inner side of every face's
    /// plane (within @p tolerance, m).
    bool
    is_convex(const Polyhedron &p, const double tolerance)
    {
      for (std::size_t f = 0; f < p.faces.size(); ++f)
        {
          const Point  n = p.face_normal(f);
          const double h = n.dot(p.vertices[p.faces[f][0]]);
          for (const auto &v : p.vertices)
            if (n.dot(v) - h > tolerance)
              return false;
        }
      return true;
    }

    /// The point of @p a deepest inside @p b (a vertex of @p a or its
    /// centroid @p centroid) and a lower bound of its depth (the distance
    /// to the nearest face plane of @p b); depth < 0 if none is inside.
    std::pair<Point, double>
    deepest_vertex(const Polyhedron &a,
                   const Point      &centroid,
                   const Polyhedron &b)
    {
      std::pair<Point, double> best(Point::Zero(), -1.);
      std::vector<Point>       probes = a.vertices;
      probes.push_back(centroid);
      for (const auto &x : probes)
        {
          if (!b.contains(x))
            continue;
          double d = std::numeric_limits<double>::infinity();
          for (std::size_t f = 0; f < b.faces.size(); ++f)
            d = std::min(
              d, std::abs(b.face_normal(f).dot(x - b.vertices[b.faces[f][0]])));
          if (d > best.second)
            best = {x, d};
        }
      return best;
    }
  } // namespace



  OverlapDepth
  overlap_depth(const Polyhedron &a, const Polyhedron &b)
  {
    const double tol = 1e-9 * std::max(a.size(), b.size());
    OverlapDepth r;
    if (is_convex(a, tol) && is_convex(b, tol))
      {
        // Separating axes of two convex polyhedra: the face normals of
        // either and the cross products of an edge of each. The overlap
        // along an axis is that of the two projections; the depth is the
        // least over the axes (<= 0: separated or touching).
        std::vector<Point> axes;
        for (const Polyhedron *p : {&a, &b})
          for (std::size_t f = 0; f < p->faces.size(); ++f)
            axes.push_back(p->face_normal(f));
        const auto ea = polyhedron_edges(a), eb = polyhedron_edges(b);
        for (const auto &u : ea.v)
          for (const auto &v : eb.v)
            {
              const Point du = a.vertices[u[1]] - a.vertices[u[0]];
              const Point dv = b.vertices[v[1]] - b.vertices[v[0]];
              const Point n  = du.cross(dv);
              if (n.norm() > 1e-6 * du.norm() * dv.norm())
                axes.push_back(n.normalized());
            }
        r.depth = std::numeric_limits<double>::infinity();
        for (const auto &n : axes)
          {
            double lo_a = std::numeric_limits<double>::infinity(), hi_a = -lo_a;
            double lo_b = lo_a, hi_b = hi_a;
            for (const auto &v : a.vertices)
              {
                lo_a = std::min(lo_a, n.dot(v));
                hi_a = std::max(hi_a, n.dot(v));
              }
            for (const auto &v : b.vertices)
              {
                lo_b = std::min(lo_b, n.dot(v));
                hi_b = std::max(hi_b, n.dot(v));
              }
            const double d = std::min(hi_a, hi_b) - std::max(lo_a, lo_b);
            if (d < r.depth)
              {
                r.depth = d;
                r.axis  = n;
              }
          }
        // A point of the overlap for the message: the deepest vertex of
        // either inside the other, else the mean of the vertices inside.
        const auto pa = deepest_vertex(a, a.vertex_mean(), b);
        const auto pb = deepest_vertex(b, b.vertex_mean(), a);
        r.point       = pa.second >= pb.second ? pa.first : pb.first;
        if (pa.second < 0. && pb.second < 0.)
          r.point = 0.5 * (a.vertex_mean() + b.vertex_mean());
        return r;
      }
    // Non-convex: a vertex or centroid of one inside the other, deeper than
    // its distance to the nearest face plane (a lower bound of the depth).
    const auto  pa = deepest_vertex(a, a.moments().centroid, b);
    const auto  pb = deepest_vertex(b, b.moments().centroid, a);
    const auto &p  = pa.second >= pb.second ? pa : pb;
    r.depth        = p.second;
    r.point        = p.first;
    return r;
  }



  void
  check_overlaps(const BlockSystem &system,
                 const double       overlap_fraction,
                 const Point       &origin)
  {
    const std::size_t        n = system.blocks.size();
    std::vector<BoundingBox> boxes(n);
    for (std::size_t b = 0; b < n; ++b)
      boxes[b] = bounding_box(system.blocks[b].polyhedron);
    for (const auto &[i, j] : broad_phase(boxes))
      {
        const Polyhedron &a = system.blocks[i].polyhedron,
                         &b = system.blocks[j].polyhedron;
        const double tolerance
          = overlap_fraction * std::min(a.size(), b.size());
        const OverlapDepth o = overlap_depth(a, b);
        if (o.depth > tolerance)
          {
            const Point x = origin + o.point;
            throw InputError(
              "block " + std::to_string(system.blocks[i].id)
              + " overlaps block " + std::to_string(system.blocks[j].id)
              + " at t = 0 by " + io::format_number(o.depth, 4) + " m (near ("
              + io::format_number(x.x(), 8) + ", " + io::format_number(x.y(), 8)
              + ", " + io::format_number(x.z(), 8) + ") m; allowed "
              + io::format_number(tolerance, 3)
              + " m = " + io::format_number(overlap_fraction, 3)
              + " x the smaller block's size)");
          }
      }
  }



  void
  validate_and_prepare(BlockSystem &system)
  {
    for (std::size_t m = 0; m < system.materials.size(); ++m)
      {
        const Material   &mat = system.materials[m];
        const std::string name
          = "material " + std::to_string(mat.id >= 0 ? mat.id : int(m));
        if (!(mat.density > 0.) || !std::isfinite(mat.density))
          throw InputError(name + ": density " + std::to_string(mat.density)
                           + " kg/m^3; valid: > 0");
        if (!(mat.young > 0.) || !std::isfinite(mat.young))
          throw InputError(name + ": Young's modulus "
                           + std::to_string(mat.young) + " Pa; valid: > 0");
        if (!(mat.poisson >= 0. && mat.poisson < 0.5))
          throw InputError(name + ": Poisson's ratio "
                           + std::to_string(mat.poisson)
                           + "; valid: 0 <= nu < 0.5");
      }
    for (std::size_t k = 0; k < system.joints.size(); ++k)
      {
        const auto       &j    = system.joints[k];
        const std::string name = "joint material " + std::to_string(k);
        if (!(j.friction_deg >= 0. && j.friction_deg < 90.))
          throw InputError(name + ": friction angle "
                           + std::to_string(j.friction_deg)
                           + " deg; valid: 0 <= phi < 90");
        if (!(j.cohesion >= 0.) || !(j.tensile >= 0.)
            || !(j.normal_stiffness >= 0.) || !(j.shear_stiffness >= 0.))
          throw InputError(name
                           + ": cohesion, tensile strength and "
                             "stiffnesses must be >= 0");
        if (const std::string e = dda::friction_law_error(j); !e.empty())
          throw InputError(name + ": " + e);
      }
    for (auto &b : system.blocks)
      {
        const std::string name = "block " + std::to_string(b.id);
        if (b.material < 0 || b.material >= int(system.materials.size()))
          throw InputError(name + ": has no material");
        if (!system.joints.empty()
            && (b.joint < 0 || b.joint >= int(system.joints.size())))
          throw InputError(name + ": joint material index "
                           + std::to_string(b.joint) + " does not exist");
        const auto defect = polyhedron_defect(b.polyhedron);
        if (defect)
          throw InputError(name + (defect.face >= 0 ? ", " : ": ")
                           + defect.describe());
        b.initial_centroid = b.polyhedron.moments().centroid;
      }
    auto check_point = [&](const int block, const Point &p, const char *what) {
      if (block < 0 || block >= int(system.blocks.size()))
        throw InputError(std::string(what) + " point on block index "
                         + std::to_string(block) + ", which does not exist");
      if (!system.blocks[block].polyhedron.contains(p))
        throw InputError("block " + std::to_string(system.blocks[block].id)
                         + ": " + what + " point (" + std::to_string(p.x())
                         + ", " + std::to_string(p.y()) + ", "
                         + std::to_string(p.z()) + ") is outside the block");
    };
    for (auto &f : system.fixed_points)
      {
        check_point(f.block, f.point, "fixed");
        f.anchor = f.point;
      }
    for (const auto &l : system.load_points)
      check_point(l.block, l.point, "load");
    for (auto &m : system.measurement_points)
      {
        check_point(m.block, m.point, "measurement");
        m.initial = m.point;
      }
  }
} // namespace rockdda::dda3d
