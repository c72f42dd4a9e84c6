/**
 * @file
 * A simple polygon (plain data) with its exact area, centroid and second
 * moments, shared by block cutting and the DDA engine.
 */
#ifndef ROCKDDA_GEOMETRY_POLYGON_H
#define ROCKDDA_GEOMETRY_POLYGON_H

#include <Eigen/Core>

#include <vector>

namespace rockdda::geometry
{
  /// A 2D point or vector (m).
  using Point = Eigen::Vector2d;

  /**
   * Area moments of a polygon about the origin (triangle-fan integration,
   * exact for straight edges): a = integral 1, sx = integral x,
   * sy = integral y, sxx = integral x^2, syy = integral y^2,
   * sxy = integral x y. Units m^2, m^3, m^4.
   */
  struct PolygonMoments
  {
    double a = 0., sx = 0., sy = 0., sxx = 0., syy = 0., sxy = 0.;
  };

  /**
   * A simple polygon: vertices (m) in counter-clockwise order, the closing
   * edge from the last vertex back to the first is implicit. No vertex is
   * repeated.
   */
  struct Polygon
  {
    std::vector<Point> vertices;

    /// Signed area (m^2): positive for counter-clockwise vertices.
    double
    signed_area() const;

    /// Area (m^2), always >= 0.
    double
    area() const;

    /// Centroid (m). Requires a non-zero area.
    Point
    centroid() const;

    /**
     * Moments about the origin by triangle-fan integration from the origin
     * (each edge (p, q) contributes the triangle (0, p, q), signed). For a
     * counter-clockwise polygon all moments come out with their physical
     * sign.
     */
    PolygonMoments
    moments() const;

    /**
     * Second moments about the centroid (m^4): Ixx = integral (y - yc)^2,
     * Iyy = integral (x - xc)^2, Ixy = integral (x - xc)(y - yc).
     */
    Eigen::Vector3d
    central_second_moments() const;

    /// Reverse the vertex order if it is clockwise.
    void
    make_counter_clockwise();

    /// Smallest interior angle (rad) of the polygon, in (0, 2 pi).
    double
    min_interior_angle() const;

    /**
     * Smallest width (m): the minimum over the edges of the largest distance
     * of a vertex from the edge's line. For a convex polygon this is the
     * minimum caliper width (the narrowest slot it passes through); for a
     * non-convex one it is an upper bound of it.
     */
    double
    min_width() const;

    /// Bounding box as (xmin, ymin, xmax, ymax) (m).
    Eigen::Vector4d
    bounding_box() const;

    /// Whether two non-adjacent edges intersect (O(n^2); for input checks).
    bool
    self_intersects() const;

    /// Whether @p p is strictly inside (crossing rule; boundary undefined).
    bool
    contains(const Point &p) const;
  };
} // namespace rockdda::geometry

#endif
