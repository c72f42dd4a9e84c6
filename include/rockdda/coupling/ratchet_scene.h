/**
 * @file
 * The scene of the thermal wedging ratchet (thesis 5.4, Figs. 5-7 and 5-9):
 * a block on a bedding plane, separated from the cliff by a tension crack
 * that narrows downward and holds an infill wedge; the block and the cliff
 * are cut into bonded vertical slices near their exposed faces so that the
 * seasonal temperature front (a few skin depths) is resolved. Built once as
 * a DDA block system and as the heat solver's blocks (same polygons).
 */
#ifndef ROCKDDA_COUPLING_RATCHET_SCENE_H
#define ROCKDDA_COUPLING_RATCHET_SCENE_H

#include <rockdda/analytical/block1.h>
#include <rockdda/coupling/thermal_load.h>
#include <rockdda/dda/block_system.h>
#include <rockdda/thermal/heat_solver.h>

#include <utility>
#include <vector>

namespace rockdda::coupling
{
  /// Geometry of the ratchet scene (m, deg); x points downslope-horizontal
  /// (east), y up, the bedding plane passes through the foot of the cliff
  /// face at the origin.
  struct RatchetGeometry
  {
    /// The block's cross-section: L_B, H at the front (downslope) face and
    /// the dip eta in [0, 45) of the bedding plane (thesis Eq. 5.3). The
    /// block is exactly Block1Section::polygon(), its heel at the crack's
    /// bottom width from the cliff's foot; the union of its slices and its
    /// foot is that polygon.
    analytical::Block1Section block;
    /// Crack width at the top and at the bedding plane (m); top >= bottom
    /// > 0 (a crack that narrows downward lets the infill descend). The
    /// block's back face is vertical: the cliff's face leans (from the
    /// cliff's foot back by top - bottom width at the top).
    double crack_top_width    = 0.2;
    double crack_bottom_width = 0.02;
    /// Horizontal extent of the cliff behind the crack (m), > 0; its
    /// farthest slice is fixed.
    double cliff_width = 8.;
    /// Depth of the fixed base below the bedding plane at the toe (m).
    double base_depth = 3.;
    /// Length of the bedding plane beyond the block's toe (m).
    double toe_length = 3.;
    /// Infill wedge: present or not; depth of its top below the top of
    /// the block (m) and its height (m). Its faces lie on the crack faces.
    bool   infill           = true;
    double infill_top_depth = 6.;
    double infill_height    = 2.;
    /// Width of the infill at its top (m); 0 = the crack's width there (it
    /// touches both faces). A narrower infill lies against the cliff face
    /// and drops until it wedges; a wider one is rejected.
    double infill_width = 0.;
    /// Supply of fragments (the thesis assumes a continuous supply of
    /// detritus): when the newest fragment's top has descended this far
    /// (m) below the infill's initial top, a new fragment of the infill's
    /// height is placed at the initial position, filling the crack as it
    /// is then. 0 = no supply; otherwise at least the infill height (the
    /// new fragment must clear the last one).
    double supply_distance = 0.;
    /// Slices: within @p refinement_depth (m) of an exposed vertical face
    /// (the crack faces, the block's front) the block and the cliff are
    /// cut into @p slices bonded slices of equal width; the rest of each is
    /// one slice. 0 slices: the block is one block (the cliff one slice).
    double       refinement_depth = 2.5;
    unsigned int slices           = 4;
    /// With slices: height (m) of the block's foot, one bonded block along
    /// the bedding plane on which the slices stand (> 0), so that the
    /// block meets the bedding plane with one face, as the unsliced block
    /// does, not with one face per slice.
    double foot_height = 0.5;
  };

  /// Materials of the ratchet scene (SI).
  struct RatchetMaterials
  {
    dda::BlockMaterial rock{2600., 4e10, 0.2, true, -1};
    /// Bedding plane (the block's base): friction (deg) and the joint's
    /// normal and shear stiffness (Pa/m; 0 = rigid, penalty only).
    double bedding_friction_deg     = 41.;
    double bedding_normal_stiffness = 0.;
    double bedding_shear_stiffness  = 1e9;
    /// Crack faces against the infill: friction (deg).
    double crack_friction_deg = 41.;
  };

  /// The scene and what the ratchet driver measures on it.
  struct RatchetScene
  {
    dda::BlockSystem blocks;
    /// The same polygons for the heat solver (block and cliff slices only;
    /// the infill takes the air temperature, the fixed base none). Tags:
    /// "exposed" (top, front), "crack" (crack faces), "adiabatic" (bedding
    /// plane and the cliff's far side), "interior" (shared faces).
    std::vector<thermal::Block> heat_blocks;
    /// Per DDA block, where its temperature comes from: its heat block, the
    /// air (infill), none (the fixed base and the fixed cliff slice) or
    /// several heat blocks (the foot: one piece under each slice, so that
    /// the heat mesh is conforming without collinear vertices).
    BlockHeatMap heat_map;
    /// DDA indices of the block's slices (back to front), the cliff's
    /// slices (crack face first), the infill (-1: none) and the base.
    std::vector<int> block_slices, cliff_slices;
    int              infill = -1, base = -1;
    /// The block's heel and toe on the bedding plane, and its back-top
    /// corner (crack side): (DDA block, vertex). The heel and the back-top
    /// corner span the crack's block face; cliff_foot and cliff_top span
    /// its cliff face.
    std::pair<int, int> heel{0, 0}, toe{0, 0}, back_top{0, 0};
    std::pair<int, int> cliff_foot{0, 0}, cliff_top{0, 0};
    /// The infill's top and bottom heights at t = 0 (m, scene
    /// coordinates) and the supply distance (m; 0 = no supply).
    double infill_top = 0., infill_bottom = 0., supply_distance = 0.;
    /// Unit vector down the bedding plane.
    geometry::Point downslope;
  };

  /**
   * Build the scene. Throws InputError naming the key ('Ratchet/...') for
   * an impossible geometry: a back face lower than 10 % of the front face,
   * a crack that widens downward or has zero width at the bedding plane, a
   * cliff narrower than the crack's lean, an infill that does not fit in the
   * crack (wider than the crack, or reaching below the bedding plane), a slope
   * of 45 deg or more.
   */
  RatchetScene
  make_ratchet_scene(const RatchetGeometry  &geometry,
                     const RatchetMaterials &materials);
} // namespace rockdda::coupling

#endif
