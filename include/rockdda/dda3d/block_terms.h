/**
 * @file
 * The per-block terms of a 3D DDA step and the update of a block by its
 * increment, shared by the engine with contacts and the contact-free
 * stepper (thesis Eqs. 2.4-2.7; Shi 2001; doc/theory/dda3d.md).
 */
#ifndef ROCKDDA_DDA3D_BLOCK_TERMS_H
#define ROCKDDA_DDA3D_BLOCK_TERMS_H

#include <rockdda/dda3d/block_matrices.h>

#include <vector>

namespace rockdda::dda3d
{
  /**
   * The terms of each block in a step of length h (s), Shi's
   * constant-acceleration scheme with the dynamic control:
   *   K_b = 2 M / h^2 + elastic_factor V C + sum p T^T T (fixed points),
   *   F_b = (2 / h) M (dynamic v) + rho V g + external_b - V sigma
   *         + sum p T^T (anchor + u_g - x),
   * external_b the seismic inertial force -rho V a_g and the point loads
   * (the forces whose work the energy ledger books as load work).
   */
  struct BlockTerms
  {
    std::vector<PolyhedronMoments> moments;
    std::vector<Matrix12>          K;
    std::vector<Vector12>          F, external;
  };

  /**
   * BlockTerms of @p system for a step of length @p h (s) with dynamic
   * control @p dynamic (-), the elasticity scaled by @p elastic_factor (1
   * + the strain damping's factor, dda::StrainDamping), the ground
   * acceleration @p a_ground (m/s^2, loading mode; zero: none), the
   * ground displacement @p u_ground the fixed points' anchors follow (m)
   * and the fixed points' penalty @p fixed_penalty (N/m).
   */
  BlockTerms
  block_terms(const BlockSystem &system,
              double             h,
              double             dynamic,
              double             elastic_factor,
              const Point       &a_ground,
              const Point       &u_ground,
              double             fixed_penalty);

  /**
   * Move block @p b of @p system, whose centroid is @p centroid (before
   * the move), by its increment @p d (Eq. 2.4 order):
   * its vertices and its fixed, load and measurement points with the
   * exact rotation (move_point()), and its stress and strain by the
   * logarithmic strain of the step's stretch (dda/logarithmic_strain.h),
   * rotated with the block. The velocity is not changed.
   */
  void
  apply_increment(BlockSystem    &system,
                  std::size_t     b,
                  const Point    &centroid,
                  const Vector12 &d);
} // namespace rockdda::dda3d

#endif
