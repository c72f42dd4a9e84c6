/**
 * @file
 * Contact-free time stepping of 3D DDA blocks (issue 17, first layer):
 * without contacts the blocks are decoupled and each block's 12x12 system
 * is solved directly. Shi's constant-acceleration scheme with the dynamic
 * control parameter, as the 2D engine (doc/theory/dda3d.md).
 */
#ifndef ROCKDDA_DDA3D_FREE_BLOCKS_H
#define ROCKDDA_DDA3D_FREE_BLOCKS_H

#include <rockdda/dda3d/block_matrices.h>
#include <rockdda/dda3d/local_scene.h>

#include <functional>
#include <vector>

namespace rockdda::dda3d
{
  /// Controls of the contact-free stepper.
  struct FreeStepControls
  {
    /// Time step (s), > 0.
    double dt = 1e-3;
    /// Dynamic control parameter (-): 1 fully dynamic, 0 static (the
    /// velocity is not carried into the next step).
    double dynamic = 1.;
    /// Penalty of the fixed points (N/m), > 0.
    double fixed_penalty = 1e10;
    /**
     * Ground acceleration (m/s^2, 3 components) in the seismic loading
     * mode, evaluated at the middle of each step: every block is loaded by
     * -rho V a_g (the scene is analysed in the ground's frame). Empty:
     * none.
     */
    std::function<Point(double)> ground_acceleration;
  };

  /**
   * Decoupled blocks stepped in time. Each step of length dt solves, per
   * block, (2 M / dt^2 + V C + sum p T^T T) D = (2 / dt) M (dynamic v)
   * + rho V a + loads - V sigma + sum p T^T (anchor - x), then moves the
   * vertices with the exact rotation (move_point()), sets
   * v = 2 D / dt - dynamic v, and adds and rotates the stress and strain
   * (the engine's block terms and update, block_terms() and
   * dda3d::apply_increment(): the logarithmic strain of the step).
   * With dynamic = 1 this is the constant-average-acceleration rule: a
   * constant force is integrated exactly.
   *
   * The scene is moved to a local origin (the lower corner of its
   * bounding box) on construction; positions returned here are global.
   */
  class FreeBlocks : public LocalScene
  {
  public:
    /// Validate @p system (validate_and_prepare()) and keep it.
    FreeBlocks(BlockSystem system, const FreeStepControls &controls);

    /// One step of length dt.
    void
    step();

    /**
     * Apply a prescribed increment @p d (Eq. 2.4 order) to block @p b as a
     * step would (geometry, points, stress and strain; velocity untouched).
     */
    void
    apply_increment(const std::size_t b, const Vector12 &d);


    /// The increment of block @p b in the last step.
    const Vector12 &
    last_increment(const std::size_t b) const
    {
      return increments[b];
    }

    /// Kinetic energy 1/2 v^T M v of all blocks (J).
    double
    kinetic_energy() const;

  private:
    FreeStepControls      ctrl;
    std::vector<Vector12> increments;
  };
} // namespace rockdda::dda3d

#endif
