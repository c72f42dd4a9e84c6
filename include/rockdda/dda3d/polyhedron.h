/**
 * @file
 * A closed polyhedron (plain data: vertices and faces as vertex-index
 * loops) with its input checks and exact volume moments, the geometry of a
 * 3D DDA block (doc/theory/dda3d.md).
 */
#ifndef ROCKDDA_DDA3D_POLYHEDRON_H
#define ROCKDDA_DDA3D_POLYHEDRON_H

#include <Eigen/Core>

#include <string>
#include <vector>

namespace rockdda::dda3d
{
  /// A 3D point or vector (m).
  using Point = Eigen::Vector3d;

  /**
   * Volume (m^3), centroid (m) and central second moments (m^5)
   * S_ij = integral (x_i - c_i)(x_j - c_j) dV of a polyhedron.
   */
  struct PolyhedronMoments
  {
    double          volume   = 0.;
    Point           centroid = Point::Zero();
    Eigen::Matrix3d second   = Eigen::Matrix3d::Zero();
  };

  /**
   * A polyhedron: vertices (m) and faces, each face a loop of vertex
   * indices, counter-clockwise seen from outside (outward normal by the
   * right-hand rule); the closing edge of a loop is implicit. Convex and
   * non-convex polyhedra with planar, simple (possibly non-convex) faces.
   */
  struct Polyhedron
  {
    std::vector<Point>            vertices;
    std::vector<std::vector<int>> faces;

    /**
     * Exact volume, centroid and central second moments by the divergence
     * theorem: each face is split fan-wise into triangles (v0, vk, vk+1),
     * each triangle spans a signed tetrahedron with a local origin (the
     * vertex mean), and the tetrahedra's closed-form integrals are summed
     * (Tonon 2004, J. Math. Stat. 1(1) 8-11; equivalent to Mirtich 1996).
     * Working about the vertex mean keeps the result independent of where
     * the block sits (e.g. UTM coordinates). Signed: negative volume for
     * inward faces.
     */
    PolyhedronMoments
    moments() const;

    /// Signed volume (m^3), positive for outward faces.
    double
    signed_volume() const;

    /// Mean of the vertices (m).
    Point
    vertex_mean() const;

    /**
     * Size (m): twice the largest distance of a vertex from the vertex
     * mean (rotation invariant; every per-block tolerance derives from it).
     */
    double
    size() const;

    /// Outward unit normal of face @p f by Newell's method.
    Point
    face_normal(const std::size_t f) const;

    /**
     * Winding number of @p p (1 inside, 0 outside, the solid angle over
     * 4 pi on the boundary), from the signed solid angles of the fan
     * triangles (Van Oosterom & Strackee 1983). Valid for non-convex
     * polyhedra.
     */
    double
    winding_number(const Point &p) const;

    /// Whether @p p is inside or on the boundary (winding number > 1e-6).
    bool
    contains(const Point &p) const;
  };

  /// A defect of a polyhedron: the face concerned (-1: none) and what is
  /// wrong. Empty message: no defect.
  struct PolyhedronDefect
  {
    int         face = -1;
    std::string message;

    /// Whether there is a defect.
    explicit operator bool() const
    {
      return !message.empty();
    }

    /// "face F: MESSAGE", or the message alone.
    std::string
    describe() const;
  };

  /**
   * The first defect of @p polyhedron, if any: at least 4 vertices and 4
   * faces; every face has at least 3 distinct, valid vertex indices and a
   * non-zero area; every vertex is used; closed (every edge used exactly
   * twice, in opposite directions); each face planar (every face vertex
   * within @p planarity_tolerance x size() of the face's plane through its
   * vertex mean with Newell's normal); outward normals (signed volume
   * > 0). Faces are named by their index from 0, edges by their vertex
   * indices, e.g. face 3: "edge 2-6 is used by no other face (the
   * polyhedron is not closed)".
   */
  PolyhedronDefect
  polyhedron_defect(const Polyhedron &polyhedron,
                    const double      planarity_tolerance = 1e-6);
} // namespace rockdda::dda3d

#endif
