/**
 * @file
 * Kelvin-Voigt damping of a block's strain in Shi's time integration,
 * written once for the 2D and the 3D engine (doc/theory/dda3d.md, "Strain
 * damping").
 */
#ifndef ROCKDDA_DDA_STRAIN_DAMPING_H
#define ROCKDDA_DDA_STRAIN_DAMPING_H

#include <Eigen/Dense>

namespace rockdda::dda
{
  /**
   * Kelvin-Voigt strain damping of a block: the stress sigma = C (eps + eta
   * d eps / dt), eta the viscous time (s). A strain mode of angular
   * frequency omega gets the damping ratio eta omega / 2; a rigid motion
   * (translation, rotation, sliding) has no strain rate and is not damped.
   * In a step of length h the rate is the step's mean, the strain
   * increment d over h: the viscous stress C (eta / h) d adds
   * (eta / h) V C to the block's strain stiffness and dissipates
   * (eta / h) V d . C d >= 0 (J), which the energy ledger books. Only in
   * dynamic steps: a static step (dynamic control 0) has no rate.
   */
  class StrainDamping
  {
  public:
    /// @p eta viscous time (s, >= 0), @p h the step (s), @p dynamic the
    /// dynamic control parameter of the step (-).
    StrainDamping(const double eta, const double h, const double dynamic)
        : factor_(dynamic > 0. && eta > 0. ? eta / h : 0.)
    {}

    /// Whether the step is damped.
    bool
    active() const
    {
      return factor_ > 0.;
    }

    /// eta / h (-): the factor of the block's elastic strain stiffness V C
    /// added to its matrix.
    double
    factor() const
    {
      return factor_;
    }

    /// The energy (J) dissipated in the step by a block of elastic strain
    /// stiffness @p VC (V C, N m) whose strain grew by @p d.
    template <typename Matrix, typename Vector>
    double
    dissipation(const Matrix &VC, const Vector &d) const
    {
      return factor_ * d.dot(VC * d);
    }

  private:
    double factor_;
  };
} // namespace rockdda::dda

#endif
