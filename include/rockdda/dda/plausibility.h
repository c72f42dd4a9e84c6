/**
 * @file
 * The physical sanity check of every accepted step, both DDA engines: no
 * energy created, no contact penetrated deeper than a fraction of its
 * blocks, no block strained beyond small strain, no block faster than the
 * scene can make it (doc/theory/dda.md, "Sanity checks"). A step that fails
 * it is cut; if cutting does not help, the run stops with the diagnosis.
 */
#ifndef ROCKDDA_DDA_PLAUSIBILITY_H
#define ROCKDDA_DDA_PLAUSIBILITY_H

#include <string>
#include <vector>

namespace rockdda::dda
{
  /**
   * Limits of the sanity check: a step is cut when the energy ledger gains
   * more than energy_tolerance x the energy in play (1: the ledger is not
   * exact across lock/slide changes; a settling block at a penalty of 0.1 E
   * gains 25 % of the energy in play in one legitimate step, while a
   * blow-up creates hundreds of times it), a closed contact penetrates
   * deeper than penetration_ratio x the smaller block's size, a block
   * strains by more than strain_limit, or a block moves faster than
   * speed_factor x the fastest motion the scene can produce (free fall
   * since t = 0 plus the ground velocity plus the initial speeds).
   */
  struct PlausibilityLimits
  {
    double energy_tolerance  = 1.;
    double penetration_ratio = 0.01;
    double strain_limit      = 0.05;
    double speed_factor      = 2.;
  };

  /// What the check sees of one block.
  struct BlockPlausibility
  {
    int    id      = 0;
    double kinetic = 0., speed = 0., strain = 0., young = 0.;
  };

  /// What the check sees of one closed contact (normal force in N, or N/m
  /// in 2D; size the smaller block's, m).
  struct ContactPlausibility
  {
    int    block_i = 0, block_j = 0;
    double normal_force = 0., size = 0.;
  };

  /// The state after a trial step.
  struct PlausibilityInput
  {
    /// Time at the end of the step (s).
    double time = 0.;
    /// "J/m" in 2D, "J" in 3D.
    std::string energy_unit = "J";
    /// Whether the ledger is checked (not with prescribed ground motion,
    /// whose work it does not book), its gain over the step and the
    /// energy in play.
    bool   check_energy = false;
    double energy_gain = 0., energy_scale = 0.;
    /// The contact penalty (N/m): the numerical closure is N / penalty.
    double normal_penalty = 0.;
    /// The fastest motion the scene can produce (m/s), before
    /// PlausibilityLimits::speed_factor, and a floor added after it.
    double                           motion_bound = 0., speed_floor = 0.;
    std::vector<BlockPlausibility>   blocks;
    std::vector<ContactPlausibility> contacts;
  };

  /// The diagnosis of an impossible state, empty if the state is plausible.
  std::string
  implausible_state(const PlausibilityLimits &limits,
                    const PlausibilityInput  &input);
} // namespace rockdda::dda

#endif
