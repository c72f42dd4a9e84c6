/**
 * @file
 * The energy ledger of both DDA engines (doc/theory/dda.md and dda3d.md, the
 * energy ledger).
 */
#ifndef ROCKDDA_DDA_ENERGY_LEDGER_H
#define ROCKDDA_DDA_ENERGY_LEDGER_H

#include <cmath>

namespace rockdda::dda
{
  /**
   * The energy ledger of a DDA run, both engines (J per m thickness in 2D,
   * J in 3D). Stored: kinetic, block strain, contact springs, gravity
   * potential (relative to t = 0), the springs of the fixed points of
   * blocks that are not clamped. Flows
   * since t = 0: work dissipated by sliding friction (>= 0) and work done on
   * the blocks by point loads and the seismic inertial load. In exact
   * dynamics balance() stays at its initial value; the time integration
   * (Newmark beta = 1/2, gamma = 1) may only lower it. Not included: the
   * work of fixed points that move (displacement-mode seismic input), so
   * the balance closes only without it.
   */
  struct EnergyLedger
  {
    double kinetic = 0., strain = 0., contact = 0., potential = 0.;
    /// Springs of the fixed points of blocks that are not clamped.
    double fixed    = 0.;
    double friction = 0., load_work = 0.;
    /// Dissipated by the strain damping (StrainDamping) and the contact
    /// dashpots (ContactDamping).
    double damping = 0.;
    /// kinetic + strain + contact + potential + fixed + friction + damping
    /// - load_work.
    double
    balance() const
    {
      return kinetic + strain + contact + potential + fixed + friction + damping
             - load_work;
    }
    /// Sum of the magnitudes of the terms (J/m in 2D, J in 3D): the energy in
    /// play.
    double
    scale() const
    {
      return std::abs(kinetic) + std::abs(strain) + std::abs(contact)
             + std::abs(potential) + std::abs(fixed) + std::abs(friction)
             + std::abs(damping) + std::abs(load_work);
    }
  };
} // namespace rockdda::dda

#endif
