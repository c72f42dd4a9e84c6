/**
 * @file
 * The per-block terms of a DDA step, its velocity update and the block
 * energies, written once for both engines over the block's unknowns: 6 in
 * 2D (u, v, r, eps_x, eps_y, gamma_xy), 12 in 3D (u, v, w, three
 * rotations, six strains). Shi 1988, ch. 2 and 5; Shi 2001; thesis Eqs.
 * 2.4-2.7; doc/theory/dda.md and dda3d.md.
 */
#ifndef ROCKDDA_DDA_BLOCK_STEP_TERMS_H
#define ROCKDDA_DDA_BLOCK_STEP_TERMS_H

#include <Eigen/Cholesky>
#include <Eigen/Core>

namespace rockdda::dda
{
  /**
   * The inertia, elasticity, initial stress and body force of one block in
   * a step of length @p h (s), Shi's constant-acceleration scheme with the
   * dynamic control @p dynamic (-):
   *   K = 2 M / h^2 + elastic_factor V C   (C on the strain unknowns),
   *   F = (2 / h) M (dynamic v) - V sigma + rho V a   (a on the
   *       translations),
   * M the block's mass matrix, V its area (2D, m^2 per m) or volume (3D,
   * m^3), C its elasticity (Pa), sigma its stress (Pa), v its velocity,
   * rho its density (kg/m^3) and a the body acceleration (m/s^2: gravity
   * less a loading-mode ground acceleration). @p elastic_factor is 1 plus
   * the strain damping's factor (StrainDamping). The block's unknowns end
   * with its n_strain strains and begin with its dim translations.
   */
  template <int n_dofs, int n_strain, int dim>
  void
  block_step_terms(const Eigen::Matrix<double, n_dofs, n_dofs>     &M,
                   const Eigen::Matrix<double, n_strain, n_strain> &C,
                   const double                                     measure,
                   const double                                     density,
                   const Eigen::Matrix<double, n_strain, 1>        &stress,
                   const Eigen::Matrix<double, n_dofs, 1>          &velocity,
                   const double                                     dynamic,
                   const double                                     h,
                   const double                           elastic_factor,
                   const Eigen::Matrix<double, dim, 1>   &acceleration,
                   Eigen::Matrix<double, n_dofs, n_dofs> &K,
                   Eigen::Matrix<double, n_dofs, 1>      &F)
  {
    constexpr int s = n_dofs - n_strain;
    K               = (2. / (h * h)) * M;
    K.template block<n_strain, n_strain>(s, s) += elastic_factor * measure * C;
    F = (2. / h) * (M * (dynamic * velocity));
    F.template segment<n_strain>(s) -= measure * stress;
    F.template head<dim>() += density * measure * acceleration;
  }

  /**
   * A block's velocity at the end of a step of length @p h (s) with
   * increments @p d, from its velocity @p v at the start carried with the
   * dynamic control @p dynamic: v' = 2 d / h - dynamic v (Shi's
   * constant-acceleration scheme, Newmark beta = 1/2, gamma = 1).
   */
  template <typename Vector>
  Vector
  end_of_step_velocity(const Vector &d,
                       const Vector &v,
                       const double  h,
                       const double  dynamic)
  {
    return (2. / h) * d - dynamic * v;
  }

  /**
   * @name A block's energies in the ledger (EnergyLedger)
   * J per m thickness in 2D, J in 3D.
   */
  /// @{
  /// Kinetic energy v . M v / 2 of velocity @p v and mass matrix @p M.
  template <typename Vector, typename Matrix>
  double
  kinetic_energy_of(const Vector &v, const Matrix &M)
  {
    return 0.5 * v.dot(M * v);
  }

  /// Strain energy V sigma . C^-1 sigma / 2 of a block of area or volume
  /// @p measure, stress @p sigma (Pa) and elasticity @p C (Pa).
  template <typename Stress, typename Elasticity>
  double
  strain_energy_of(const double      measure,
                   const Stress     &sigma,
                   const Elasticity &C)
  {
    return 0.5 * measure * sigma.dot(C.ldlt().solve(sigma));
  }

  /// Gravity potential -rho V g . (c - c0) of a block of density @p rho
  /// (kg/m^3) and area or volume @p measure whose centroid moved by
  /// @p moved (m) since t = 0.
  template <typename Point>
  double
  gravity_potential_of(const double rho,
                       const double measure,
                       const Point &gravity,
                       const Point &moved)
  {
    return -(rho * measure * gravity.dot(moved));
  }
  /// @}
} // namespace rockdda::dda

#endif
