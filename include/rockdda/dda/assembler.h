/**
 * @file
 * Assembly of the 2D DDA equations K D = F from 6x6 block submatrices by
 * minimising the total potential energy (Shi 1988): elastic strain energy,
 * initial stress, inertia (constant-acceleration scheme), body forces,
 * point loads, fixed points and contact springs.
 */
#ifndef ROCKDDA_DDA_ASSEMBLER_H
#define ROCKDDA_DDA_ASSEMBLER_H

#include <rockdda/dda/block_matrices.h>
#include <rockdda/dda/block_system.h>
#include <rockdda/dda/contact_damping.h>
#include <rockdda/dda/contact_law.h>
#include <rockdda/dda/contact_set.h>
#include <rockdda/dda/linear_solver.h>

#include <functional>
#include <vector>

namespace rockdda::dda
{
  /// What one step's assembly needs besides the scene.
  struct StepParameters
  {
    /// Step length (s).
    double dt = 1e-3;
    /// Dynamic control in [0, 1]: the carried-over velocity is scaled by it.
    double dynamic = 1.;
    /// Kelvin-Voigt viscous time of the blocks' strain (s; StrainDamping).
    double strain_damping = 0.;
    /// Contact dashpots (ContactDamping): ratio of critical zeta (-) and
    /// step damping beta (-) of the closed contacts' springs.
    double contact_damping = 0., contact_step_damping = 0.;
    /// Body acceleration during the step (m/s^2): gravity and seismic
    /// inertial load.
    geometry::Point body_acceleration = geometry::Point::Zero();
    /// Fixed-point spring stiffness (N/m).
    double fixed_penalty = 1e12;
    /// Target positions of the fixed points at the end of the step (m).
    std::vector<geometry::Point> fixed_targets;
    ContactLaw                   law;
    /// Runs the contact kinematics and the assembly in chunks, possibly on
    /// threads (ChunkRunner).
    ChunkRunner run_chunks;
    /// Threads of run_chunks: with fewer than 2 the assembly makes one pass
    /// over the contacts instead of one per block and per pair.
    unsigned int threads = 1;
    /// Which blocks their fixed points clamp (clamped_blocks()); nullptr:
    /// none, every fixed point is a penalty spring.
    const std::vector<char> *clamped = nullptr;
  };

  /**
   * Builds the block matrix and right-hand side. prepare_step() computes
   * the state-independent part (per-block matrices, loads, contact
   * kinematics) and the pattern; assemble() adds the contact springs and
   * friction forces for the current states, filling values in place.
   */
  class Assembler
  {
  public:
    /// Compute the parts that do not depend on the contact states.
    void
    prepare_step(const BlockSystem          &system,
                 const std::vector<Contact> &contacts,
                 const StepParameters       &parameters,
                 BlockSparseMatrix          &matrix);

    /**
     * Assemble K and F for the current contact states: on threads, the
     * diagonal blocks and loads in chunks of block_grain blocks and the
     * off-diagonal blocks in chunks of pair_grain pairs
     * (StepParameters::run_chunks), each row adding its contacts in contact
     * order; otherwise in one pass over the contacts. The sums are the same,
     * bit for bit, on any number of threads. F is assembled whole; of K,
     * after the first call of a step into the same @p matrix, only the
     * block rows and pairs with a contact whose springs changed (its state
     * or its shear reference) are assembled again, each from scratch in the
     * same order, so K is bit for bit the one a whole assembly gives.
     * Returns the number of diagonal blocks assembled.
     */
    int
    assemble(const std::vector<Contact> &contacts,
             BlockSparseMatrix          &matrix,
             Eigen::VectorXd            &rhs);

    /// Contacts per chunk of the kinematics in prepare_step().
    static constexpr std::size_t contact_grain = 256;
    /// Blocks per chunk of the assembly's diagonal blocks and loads (on
    /// threads from 8 chunks on: 1,013 blocks ran as fast with 8 as with 32;
    /// benchmarks/dda-scaling, section 12).
    static constexpr std::size_t block_grain = 32;
    /// Pairs of blocks per chunk of the assembly's off-diagonal blocks.
    static constexpr std::size_t pair_grain = 64;

    /// Recompute the shear kinematics of contact @p index after its shear
    /// reference changed (a contact that locks during the iteration).
    void
    set_shear_reference(const BlockSystem &system,
                        const int          index,
                        const Contact     &contact);

    /// Kinematics of each contact (same order as the contacts), with its
    /// length and springs.
    const std::vector<ContactKinematics> &
    kinematics() const
    {
      return contact_kinematics;
    }

    /// Whether the step being assembled has contact dashpots
    /// (ContactDamping::active() for its parameters).
    bool
    damped() const
    {
      return ContactDamping(params.contact_damping,
                            params.contact_step_damping,
                            params.dt,
                            params.dynamic)
        .active();
    }

    /**
     * Face group of each contact (-1 for a corner on a face): the vertex
     * contacts between one pair of faces, whose Mohr-Coulomb strength is
     * checked on their resultant (the self-equilibrated corner forces of
     * uniformly strained blocks, e.g. from Poisson expansion, do not break
     * a joint).
     */
    const std::vector<int> &
    groups() const
    {
      return contact_group;
    }

    /// The contacts of face group g: group_members()[group_start()[g]] to
    /// group_members()[group_start()[g + 1] - 1].
    const std::vector<int> &
    group_start() const
    {
      return group_start_;
    }
    const std::vector<int> &
    group_members() const
    {
      return group_members_;
    }

    /// Moments of each block at the start of the step.
    const std::vector<BlockMoments> &
    moments() const
    {
      return block_moments_;
    }

    /// Mass matrix of each block at the start of the step.
    const std::vector<Matrix6> &
    masses() const
    {
      return mass;
    }

    /// Kinematics of a contact at the current geometry, with its shear
    /// reference @p xi_ref (length 0, the penalty springs of a rigid joint).
    ContactKinematics
    contact_kinematics_of(const BlockSystem      &system,
                          const ContactCandidate &candidate,
                          const double            xi_ref) const;

    /**
     * The contact length (m) of each of @p contacts at the current geometry
     * of @p system, by the rule of prepare_step(): a vertex contact between
     * two faces that are parallel within ~6 degrees gets an equal share of
     * the length over which they overlap, a corner on a face 0. The shares
     * of one pair of faces add up to its overlap.
     */
    static std::vector<double>
    contact_lengths(const BlockSystem          &system,
                    const std::vector<Contact> &contacts);

    /// Shear displacement (m) of contact @p index for the increments @p x.
    double
    shear_displacement(const int index, const Eigen::VectorXd &x) const;
    /// Normal gap (m) of contact @p index for the increments @p x.
    double
    gap(const int index, const Eigen::VectorXd &x) const;

  private:
    /// 1e-4 of the weight of the lighter of blocks @p block_i and
    /// @p block_j (N/m): ContactKinematics::weight_tolerance.
    double
    weight_tolerance_of(const int block_i, const int block_j) const;
    /// Force tolerance of a contact with the normal spring and round-off
    /// of @p k between blocks @p block_i and @p block_j (N/m).
    double
    force_tolerance_of(const ContactKinematics &k,
                       const int                block_i,
                       const int                block_j) const;
    /// Add contact @p ct's springs to the diagonal block @p Kb of its vertex
    /// block (@p vertex_side) or edge block.
    void
    add_to_block(const Contact           &ct,
                 const ContactKinematics &kin,
                 const bool               vertex_side,
                 Matrix6                 &Kb) const;
    /// Add contact @p ct's spring and friction loads to the load @p Fb of
    /// its vertex block (@p vertex_side) or edge block.
    void
    add_to_load(const Contact           &ct,
                const ContactKinematics &kin,
                const bool               vertex_side,
                Eigen::Ref<Vector6>      Fb) const;
    /// Add contact @p ct's springs to the off-diagonal block @p Kp of its
    /// pair.
    void
    add_to_pair(const Contact           &ct,
                const ContactKinematics &kin,
                Matrix6                 &Kp) const;
    /// Put the stiffness of contact @p c's joint (over its length) in
    /// series with the penalty springs.
    void
    set_springs(const int c, const Contact &contact);
    /// Contact @p c's dashpots for its springs (ContactDamping; the
    /// lighter free block's mass, a clamped block's infinite) and its gap
    /// and shear rates at the start of the step from the velocities of
    /// @p system's blocks.
    void
                         set_dashpots(const BlockSystem &system, const int c);
    StepParameters       params;
    std::vector<Matrix6> base_matrix, mass;
    std::vector<Vector6> base_rhs;
    std::vector<BlockMoments> block_moments_;
    /// Size (larger side of the bounding box, m) of each block.
    std::vector<double> block_size;
    /// Contact length of each contact (m): its share of the length over
    /// which the two faces overlap (0 for a corner on a face).
    std::vector<double> contact_length;
    std::vector<int>    contact_group;
    std::vector<int>    group_start_, group_members_;
    /// Blocks whose displacement is prescribed by their fixed points, and
    /// that displacement.
    std::vector<char>              clamped;
    std::vector<Vector6>           prescribed;
    std::vector<ContactKinematics> contact_kinematics;
    /// Pair index of each contact (its off-diagonal block).
    std::vector<int> contact_pair;
    /// The two blocks of each contact (vertex block, edge block; distinct:
    /// detection pairs different blocks).
    std::vector<std::pair<int, int>> contact_blocks;
    /// The contacts of each block (side 0: its vertex block, 1: its edge
    /// block) and of each pair, in contact order (items_of_rows()).
    ItemsOfRows contacts_of_block, contacts_of_pair;
    /// The pairs with a clamped block (their coupling is eliminated).
    std::vector<int> clamped_pairs;
    /// The matrix the last assemble() of this step filled (nullptr: none
    /// yet), and the state of each contact in it; a contact whose shear
    /// reference moved since is marked changed.
    const BlockSparseMatrix  *assembled_matrix = nullptr;
    std::vector<ContactState> assembled_state;
    std::vector<char>         springs_changed;
    /// Scratch of assemble(): the block rows and pairs to assemble again.
    std::vector<char>          dirty_block, dirty_pair;
    std::vector<JointMaterial> joints;
  };
} // namespace rockdda::dda

#endif
