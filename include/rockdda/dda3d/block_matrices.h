/**
 * @file
 * Per-block kinematics and 12x12 submatrices of 3D DDA (thesis Eqs.
 * 2.4-2.7, Shi 2001): the first-order displacement field T(x), the
 * elastic, inertia, body-force, point-load, fixed-point and initial-stress
 * terms, and the finite-rotation update (doc/theory/dda3d.md).
 */
#ifndef ROCKDDA_DDA3D_BLOCK_MATRICES_H
#define ROCKDDA_DDA3D_BLOCK_MATRICES_H

#include <rockdda/dda3d/block_system.h>

namespace rockdda::dda3d
{
  /// A 3x12 displacement matrix T.
  using Matrix3x12 = Eigen::Matrix<double, 3, 12>;
  /// A 6x6 elasticity matrix.
  using Matrix6 = Eigen::Matrix<double, 6, 6>;

  /**
   * T(x) about the centroid c, exactly as thesis Eq. 2.5 (X = x - c):
   *   u = u0 - Y r1 + Z r3 + X eps_x + Y/2 gamma_xy + Z/2 gamma_zx,
   *   v = v0 + X r1 - Z r2 + Y eps_y + X/2 gamma_xy + Z/2 gamma_yz,
   *   w = w0 + Y r2 - X r3 + Z eps_z + Y/2 gamma_yz + X/2 gamma_zx.
   * r1, r2, r3 are right-handed rotations about z, x and y.
   */
  Matrix3x12
  displacement_matrix(const Point &centroid, const Point &point);

  /**
   * Consistent mass matrix rho integral T^T T dV (kg, kg m, kg m^2), exact
   * from the volume and the central second moments: with T = T0 +
   * sum_k X_k T_k (T0, T_k constant) and the first moments zero about the
   * centroid, integral T^T T = V T0^T T0 + sum_kl S_kl T_k^T T_l.
   */
  Matrix12
  mass_matrix(const PolyhedronMoments &moments, const double density);

  /// Isotropic 3D elasticity matrix (Pa) on (eps_x, eps_y, eps_z,
  /// gamma_xy, gamma_yz, gamma_zx).
  Matrix6
  elasticity_matrix(const Material &material);

  /**
   * Rotation vector (rad) of the increment @p d: (r2, r3, r1) (about x,
   * y, z).
   */
  Point
  rotation_vector(const Vector12 &d);

  /// Rotation matrix exp([w]x) of a rotation vector @p w (rad), Rodrigues.
  Eigen::Matrix3d
  rotation_matrix(const Point &w);

  /**
   * New position of a material point under the block increment @p d with
   * the rotation treated exactly: x' = c + u0 + R(w) (I + E)(x - c), E the
   * symmetric strain tensor of @p d, R the exact rotation of the rotation
   * vector w (rotation_vector()). The 3D extension of the 2D finite-
   * rotation correction (Cheng & Zhang 2000 / Shi 1988): a pure rotation
   * keeps lengths and volume to round-off.
   */
  Point
  move_point(const Point &centroid, const Vector12 &d, const Point &point);

  /**
   * Load of a body acceleration @p a (m/s^2; gravity, or minus the ground
   * acceleration in the seismic loading mode) on the block:
   * rho integral T^T a dV = rho V a on the translations (T about the
   * centroid, first moments zero).
   */
  Vector12
  body_force(const PolyhedronMoments &moments,
             const double             density,
             const Point             &a);

  /// Load of a point force @p f (N) at @p point: T(point)^T f.
  Vector12
  point_load(const Point &centroid, const Point &point, const Point &f);

  /**
   * Stiffness p T^T T of a fixed point (penalty @p p, N/m) at @p point; the
   * matching load is p T^T (anchor - point).
   */
  Matrix12
  fixed_point_stiffness(const Point &centroid,
                        const Point &point,
                        const double p);

  /**
   * Rotate a Voigt stress (@p shear_factor 1) or engineering strain
   * (@p shear_factor 0.5) with the block: R S R^T.
   */
  Vector6
  rotate_voigt(const Vector6         &v,
               const Eigen::Matrix3d &R,
               const double           shear_factor);
} // namespace rockdda::dda3d

#endif
