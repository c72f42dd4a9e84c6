/**
 * @file
 * Checks of a DDA scene, and the exact integral of a ground motion record.
 */
#include <rockdda/dda/block_matrices.h>
#include <rockdda/dda/block_system.h>
#include <rockdda/dda/contact_detection.h>
#include <rockdda/io/error.h>
#include <rockdda/io/output.h>

#include <algorithm>
#include <cmath>
#include <limits>

namespace rockdda::dda
{
  namespace
  {
    std::string
    block_name(const Block &b)
    {
      return "block " + std::to_string(b.id);
    }

    double
    distance_to_boundary(const geometry::Polygon &poly,
                         const geometry::Point   &p)
    {
      double            best = std::numeric_limits<double>::max();
      const std::size_t n    = poly.vertices.size();
      for (std::size_t k = 0; k < n; ++k)
        {
          const geometry::Point a  = poly.vertices[k];
          const geometry::Point b  = poly.vertices[(k + 1) % n];
          const geometry::Point e  = b - a;
          const double          l2 = e.squaredNorm();
          double                t  = l2 > 0. ? (p - a).dot(e) / l2 : 0.;
          t                        = std::clamp(t, 0., 1.);
          best                     = std::min(best, (a + t * e - p).norm());
        }
      return best;
    }
    /**
     * Check one block of @p system (vertices, area, materials, edge joints)
     * and prepare it: a clockwise polygon is reversed (with a warning), the
     * initial centroid set.
     */
    void
    prepare_block(const BlockSystem        &system,
                  Block                    &b,
                  std::vector<std::string> &warnings)
    {
      const int         n_mat = static_cast<int>(system.materials.size());
      const std::string name  = block_name(b);
      auto             &v     = b.polygon.vertices;
      if (v.size() < 3)
        throw InputError(name + ": a block needs at least 3 vertices, it has "
                         + std::to_string(v.size()));
      for (const auto &p : v)
        if (!std::isfinite(p.x()) || !std::isfinite(p.y()))
          throw InputError(name + ": a vertex coordinate is not finite");
      if (b.material < 0 || b.material >= n_mat)
        throw InputError(name + ": has no material (material index "
                         + std::to_string(b.material) + "; "
                         + std::to_string(n_mat) + " materials defined)");
      const BlockMaterial &m = system.materials[b.material];
      if (!(m.density > 0.) || !std::isfinite(m.density))
        throw InputError(name + ": its material has density "
                         + io::format_number(m.density)
                         + " kg/m^3; valid: density > 0");
      if (!(m.young > 0.) || !std::isfinite(m.young))
        throw InputError(name + ": its material has Young's modulus "
                         + io::format_number(m.young) + " Pa; valid: E > 0");
      if (!(m.poisson >= 0. && m.poisson < 0.5))
        throw InputError(name + ": its material has Poisson's ratio "
                         + io::format_number(m.poisson)
                         + "; valid: 0 <= nu < 0.5");
      if (b.joint < 0 || b.joint >= static_cast<int>(system.joints.size()))
        throw InputError(name + ": has no joint material (index "
                         + std::to_string(b.joint) + ")");
      if (b.polygon.self_intersects())
        throw InputError(name + ": the polygon is self-intersecting");
      const Eigen::Vector4d box  = b.polygon.bounding_box();
      const double          size = std::max(box[2] - box[0], box[3] - box[1]);
      const double          area = b.polygon.signed_area();
      if (!(std::abs(area) > 1e-12 * size * size))
        throw InputError(name + ": zero area (degenerate polygon)");
      if (!b.edge_joints.empty()
          && b.edge_joints.size() != b.polygon.vertices.size())
        throw InputError(name + ": has " + std::to_string(b.edge_joints.size())
                         + " edge joint materials for "
                         + std::to_string(b.polygon.vertices.size())
                         + " edges");
      for (const int j : b.edge_joints)
        if (j < 0 || j >= static_cast<int>(system.joints.size()))
          throw InputError(name + ": an edge has no joint material (index "
                           + std::to_string(j) + ")");
      if (area < 0.)
        {
          // Reversed, edge k (v_k -> v_k+1) becomes edge n-2-k (mod n).
          if (!b.edge_joints.empty())
            {
              const int        n = static_cast<int>(b.edge_joints.size());
              std::vector<int> e(n);
              for (int k = 0; k < n; ++k)
                e[((n - 2 - k) % n + n) % n] = b.edge_joints[k];
              b.edge_joints = e;
            }
          std::reverse(v.begin(), v.end());
          warnings.push_back(name
                             + ": vertices were clockwise; reversed to "
                               "counter-clockwise");
        }
      b.initial_centroid = block_moments(b.polygon).centroid;
    }

    /// Throws InputError if a vertex of block @p a, or its centroid
    /// @p centroid, lies deeper than @p tolerance inside block @p c
    /// (coordinates relative to @p origin, which messages add back).
    void
    check_overlap(const Block           &a,
                  const geometry::Point &centroid,
                  const Block           &c,
                  const geometry::Point &origin,
                  const double           tolerance)
    {
      const auto                  &poly   = c.polygon;
      std::vector<geometry::Point> probes = a.polygon.vertices;
      probes.push_back(centroid);
      for (const auto &p : probes)
        if (poly.contains(p) && distance_to_boundary(poly, p) > tolerance)
          throw InputError(
            block_name(a) + " overlaps " + block_name(c) + " at t = 0 (point ("
            + io::format_number(origin.x() + p.x(), 8) + ", "
            + io::format_number(origin.y() + p.y(), 8) + ") m lies "
            + io::format_number(distance_to_boundary(poly, p), 4)
            + " m inside it)");
    }
  } // namespace



  void
  validate_and_prepare(BlockSystem              &system,
                       std::vector<std::string> &warnings,
                       const double              overlap_fraction)
  {
    for (auto &b : system.blocks)
      prepare_block(system, b, warnings);
    for (const auto &j : system.joints)
      if (!(j.friction_deg >= 0. && j.friction_deg < 90.) || !(j.cohesion >= 0.)
          || !(j.tensile >= 0.))
        throw InputError(
          "joint material: friction angle " + io::format_number(j.friction_deg)
          + " deg, cohesion " + io::format_number(j.cohesion)
          + " Pa, tensile strength " + io::format_number(j.tensile)
          + " Pa; valid: 0 <= phi < 90 deg, c >= 0, T >= 0");
    for (const auto &j : system.joints)
      if (const std::string e = friction_law_error(j); !e.empty())
        throw InputError("joint material: " + e);

    // Overlap at t = 0: a vertex (or the centroid) of one block deeper than
    // the tolerance inside another.
    std::vector<geometry::Polygon> polys;
    polys.reserve(system.blocks.size());
    for (const auto &b : system.blocks)
      polys.push_back(b.polygon);
    std::vector<double> sizes;
    for (const auto &p : polys)
      {
        sizes.push_back(block_size(p));
      }
    for (const auto &[i, j] : candidate_pairs(polys, 0.))
      {
        const double tolerance
          = overlap_fraction * std::min(sizes[i], sizes[j]);
        const Block &a = system.blocks[i], &b = system.blocks[j];
        check_overlap(a, a.initial_centroid, b, system.origin, tolerance);
        check_overlap(b, b.initial_centroid, a, system.origin, tolerance);
      }

    const int n_blocks    = static_cast<int>(system.blocks.size());
    auto      check_block = [&](const int b, const std::string &what) {
      if (b < 0 || b >= n_blocks)
        throw InputError(what + " refers to block index " + std::to_string(b)
                         + ", but there are " + std::to_string(n_blocks)
                         + " blocks");
    };
    // A point must lie in its block (on its boundary within 1e-6 of the
    // block's size).
    auto check_inside
      = [&](const int b, const geometry::Point &p, const std::string &what) {
          check_block(b, what);
          const auto &poly = system.blocks[b].polygon;
          if (!p.allFinite()
              || (!poly.contains(p)
                  && distance_to_boundary(poly, p) > 1e-6 * sizes[b]))
            throw InputError(
              what + " at (" + io::format_number(system.origin.x() + p.x(), 8)
              + ", " + io::format_number(system.origin.y() + p.y(), 8)
              + ") m lies outside " + block_name(system.blocks[b]) + " ("
              + io::format_number(distance_to_boundary(poly, p), 4)
              + " m from it); valid: inside the block or on its boundary");
        };
    for (auto &f : system.fixed_points)
      {
        check_inside(f.block, f.point, "a fixed point");
        f.anchor = f.point;
      }
    for (const auto &l : system.load_points)
      check_inside(l.block, l.point, "a load point");
    for (auto &m : system.measurement_points)
      {
        check_inside(m.block, m.point, "a measurement point");
        m.initial = m.point;
      }
  }



  void
  validate_added_block(const BlockSystem        &system,
                       Block                    &block,
                       std::vector<std::string> &warnings,
                       const double              overlap_fraction)
  {
    prepare_block(system, block, warnings);
    // The overlap test against the blocks as they are (only the new
    // block's pairs: the others may touch within their contact springs'
    // penetration).
    const double size = block_size(block.polygon);
    const auto   box  = block.polygon.bounding_box();
    for (const auto &other : system.blocks)
      {
        const auto o = other.polygon.bounding_box();
        if (o[0] > box[2] || o[2] < box[0] || o[1] > box[3] || o[3] < box[1])
          continue;
        const double tolerance
          = overlap_fraction * std::min(size, block_size(other.polygon));
        check_overlap(
          block, block.initial_centroid, other, system.origin, tolerance);
        check_overlap(other,
                      block_moments(other.polygon).centroid,
                      block,
                      system.origin,
                      tolerance);
      }
  }



  GroundMotionIntegral::GroundMotionIntegral(const seismic::Record &record,
                                             const double           g,
                                             const double           start)
      : dt(record.dt)
      , t0(start)
  {
    const std::size_t n = record.acceleration.size();
    a.resize(n);
    v.assign(n, 0.);
    u.assign(n, 0.);
    for (std::size_t k = 0; k < n; ++k)
      a[k] = g * record.acceleration[k];
    for (std::size_t k = 0; k + 1 < n; ++k)
      {
        v[k + 1] = v[k] + 0.5 * (a[k] + a[k + 1]) * dt;
        u[k + 1] = u[k] + v[k] * dt + (2. * a[k] + a[k + 1]) * dt * dt / 6.;
      }
  }



  double
  GroundMotionIntegral::acceleration(const double time) const
  {
    const double t = time - t0;
    if (a.empty() || t < 0. || dt <= 0.)
      return 0.;
    const double      s = t / dt;
    const std::size_t k = static_cast<std::size_t>(s);
    if (k + 1 >= a.size())
      return k + 1 == a.size() && s - k < 1e-9 ? a.back() : 0.;
    const double f = s - k;
    return (1. - f) * a[k] + f * a[k + 1];
  }



  double
  GroundMotionIntegral::displacement(const double time) const
  {
    const double t = time - t0;
    if (a.empty() || t <= 0. || dt <= 0.)
      return 0.;
    const std::size_t k = static_cast<std::size_t>(t / dt);
    if (k + 1 >= a.size())
      return u.back() + v.back() * (t - dt * (a.size() - 1));
    const double tau = t - k * dt;
    return u[k] + v[k] * tau + 0.5 * a[k] * tau * tau
           + (a[k + 1] - a[k]) * tau * tau * tau / (6. * dt);
  }


  double
  GroundMotionIntegral::peak_velocity() const
  {
    double m = 0.;
    for (const double x : v)
      m = std::max(m, std::abs(x));
    return m;
  }
} // namespace rockdda::dda
