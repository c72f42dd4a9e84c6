/**
 * @file
 * The logarithmic (Hencky) strain of a step's stretch, shared by the 2D and
 * 3D engines' stress update (doc/theory/dda.md, "Strain update").
 */
#ifndef ROCKDDA_DDA_LOGARITHMIC_STRAIN_H
#define ROCKDDA_DDA_LOGARITHMIC_STRAIN_H

#include <Eigen/Core>
#include <Eigen/Eigenvalues>

#include <cmath>

namespace rockdda::dda
{
  /**
   * log(I + E) for a symmetric strain increment E (dim x dim, tensor shear
   * components): the logarithmic strain of the stretch I + E by which a
   * step moves a block's points (Shi's first-order update), computed as
   * V diag(log1p(lambda)) V^T so that a zero increment is exactly zero.
   * The stress adds these, so it is a function of the block's shape: the
   * product of a cycle's stretches is I exactly when the sum of their
   * logarithms is zero (for increments with common principal axes). Added
   * as E itself, a cycle of increments d_k summing to zero left the stress
   * at zero with the shape shrunk by sum d_k^2 / 2 (Hencky 1928; Xiao,
   * Bruhns & Meyers 1997 on the logarithmic strain).
   */
  template <int dim>
  Eigen::Matrix<double, dim, dim>
  logarithmic_strain_increment(const Eigen::Matrix<double, dim, dim> &E)
  {
    if (E.isZero(0.))
      return Eigen::Matrix<double, dim, dim>::Zero();
    Eigen::SelfAdjointEigenSolver<Eigen::Matrix<double, dim, dim>> es;
    es.computeDirect(E);
    const Eigen::Matrix<double, dim, 1> g = es.eigenvalues().unaryExpr(
      [](const double l) { return std::log1p(l); });
    return es.eigenvectors() * g.asDiagonal() * es.eigenvectors().transpose();
  }
} // namespace rockdda::dda

#endif
