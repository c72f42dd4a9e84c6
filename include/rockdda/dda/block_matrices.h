/**
 * @file
 * Per-block kinematics and 6x6 submatrices of 2D DDA (Shi 1988): the
 * first-order displacement field T(x, y), exact polygon moments, mass and
 * elastic matrices, and the finite-rotation geometry update.
 */
#ifndef ROCKDDA_DDA_BLOCK_MATRICES_H
#define ROCKDDA_DDA_BLOCK_MATRICES_H

#include <rockdda/dda/block_system.h>

#include <vector>

namespace rockdda::dda
{
  /**
   * Area (m^2), centroid (m) and central second moments (m^4):
   * sxx = integral (x - xc)^2, syy = integral (y - yc)^2,
   * sxy = integral (x - xc)(y - yc), by exact triangle-fan integration.
   */
  struct BlockMoments
  {
    double          area     = 0.;
    geometry::Point centroid = geometry::Point::Zero();
    double          sxx = 0., syy = 0., sxy = 0.;
  };

  /// Exact moments of a polygon (signed area for clockwise input).
  BlockMoments
  block_moments(const geometry::Polygon &polygon);

  /**
   * Size of a block (m): twice the largest distance of a vertex from the
   * centroid of its vertices. Unlike a bounding box it does not change
   * when the scene is rotated; every per-block scale (allowed step,
   * tolerances) derives from it.
   */
  double
  block_size(const geometry::Polygon &polygon);

  /**
   * Which blocks of @p system their fixed points clamp: three or more
   * points that are not collinear (the smallest eigenvalue of
   * sum T^T T, with the rotation and strain columns divided by the block
   * size, above 1e-8 of the largest). A clamped block's displacement is
   * prescribed instead of held by penalty springs.
   */
  std::vector<char>
  clamped_blocks(const BlockSystem &system);

  /**
   * T(x, y) about the centroid c: u = T D with
   * T = [[1, 0, -(y-yc), x-xc, 0, (y-yc)/2], [0, 1, x-xc, 0, y-yc, (x-xc)/2]].
   */
  Eigen::Matrix<double, 2, 6>
  displacement_matrix(const geometry::Point &centroid,
                      const geometry::Point &point);

  /// Consistent mass matrix rho * integral T^T T dA (kg, kg m, kg m^2).
  Matrix6
  mass_matrix(const BlockMoments &moments, const double density);

  /// Elasticity matrix (Pa) of the material (plane stress or plane strain),
  /// acting on (eps_x, eps_y, gamma_xy).
  Eigen::Matrix3d
  elasticity_matrix(const BlockMaterial &material);

  /**
   * In-plane eigenstrain (eps_x, eps_y, gamma_xy) of an isotropic free
   * expansion @p free_strain = alpha (T - T_ref) (-): (1 + nu) alpha dT in
   * plane strain (the out-of-plane strain is held at zero, so the block
   * expands more in its plane), alpha dT in plane stress.
   */
  Eigen::Vector3d
  thermal_eigenstrain(const BlockMaterial &material, const double free_strain);

  /**
   * New position of a material point under the block increment @p d with
   * the rotation treated exactly: x' = c + (u0, v0) + R(r0) (I + E)(x - c),
   * E = [[eps_x, gamma/2], [gamma/2, eps_y]]. A pure rotation keeps lengths
   * and area exactly.
   */
  geometry::Point
  move_point(const geometry::Point &centroid,
             const Vector6         &d,
             const geometry::Point &point);
} // namespace rockdda::dda

#endif
