/**
 * @file
 * Checkpoint and restart of the DDA engine: every quantity that evolves
 * during a run, written as raw doubles and integers so that a resumed run
 * continues exactly as the uninterrupted one.
 */
#include <rockdda/dda/engine.h>
#include <rockdda/dda/scene_checkpoint.h>
#include <rockdda/io/binary_stream.h>
#include <rockdda/io/error.h>

#include <cmath>
#include <cstdint>
#include <limits>

namespace rockdda::dda
{
  namespace
  {
    constexpr char magic[] = "rockdda DDA checkpoint";
    // 8: the strain damping's dissipated energy.
    constexpr std::uint32_t format_version = 8;
    using io::BinaryReader;
    using io::BinaryWriter;

  } // namespace



  std::string
  DdaSystem::checkpoint() const
  {
    BinaryWriter w;
    w.put_header(magic, format_version);
    w.put<std::uint64_t>(scene.blocks.size());
    w.put<std::uint64_t>(n_scene_blocks);
    for (std::size_t k = 0; k < scene.blocks.size(); ++k)
      {
        const Block &b = scene.blocks[k];
        if (k >= n_scene_blocks)
          {
            // An added block: its definition and its size at insertion.
            w.put<std::int32_t>(b.id);
            w.put<std::int32_t>(b.material);
            w.put<std::int32_t>(b.joint);
            w.put<std::uint64_t>(b.edge_joints.size());
            for (const int j : b.edge_joints)
              w.put<std::int32_t>(j);
            w.put(block_size[k]);
          }
        w.put<std::uint64_t>(b.polygon.vertices.size());
        for (const auto &v : b.polygon.vertices)
          w.put_fixed(v);
        w.put_fixed(b.velocity);
        w.put_fixed(b.stress);
        w.put_fixed(b.strain);
        w.put_fixed(b.eigenstrain);
        w.put_fixed(b.applied_eigenstrain);
        w.put_fixed(b.initial_centroid);
        w.put(b.rotation);
      }
    dda::put_scene_points(w, scene);
    w.put<std::uint64_t>(current_contacts.size());
    for (const auto &c : current_contacts)
      {
        const auto &g = c.geometry;
        for (const int i : {g.block_i, g.vertex, g.block_j, g.edge})
          w.put<std::int32_t>(i);
        w.put_fixed(g.normal);
        w.put(g.xi);
        w.put(g.gap);
        w.put<std::int32_t>(static_cast<std::int32_t>(c.state));
        w.put<std::int32_t>(static_cast<std::int32_t>(c.state_at_start));
        w.put(c.xi_ref);
        w.put(c.normal_force);
        w.put(c.shear_force);
        w.put<std::int32_t>(c.slide_direction);
        // Flags: bit 0 broken, bit 1 held (older checkpoints: 0).
        w.put<std::uint8_t>((c.broken ? 1 : 0) | (c.held ? 2 : 0));
        w.put<std::int32_t>(c.joint);
        w.put(c.slip_rate);
      }
    w.put(t);
    w.put(step_control.current());
    w.put<std::uint64_t>(n_steps);
    w.put<std::uint64_t>(n_cuts);
    w.put<std::uint64_t>(n_iterations);
    w.put<std::uint64_t>(n_solves);
    w.put<std::uint64_t>(n_solver_iterations);
    put_warm_start(w, last_solution);
    w.put(friction_work);
    w.put(load_work);
    w.put(damping_work);
    w.put<std::uint8_t>(first_detection ? 1 : 0);
    w.put(worst_strength_ratio);
    return w.bytes;
  }



  void
  DdaSystem::restore(const std::string &bytes, const std::string &source)
  {
    BinaryReader r(bytes, source);
    r.check_header(magic, format_version);
    // Read into a copy: the engine is untouched if the file is rejected.
    BlockSystem s       = scene;
    const auto  n_total = r.get<std::uint64_t>();
    r.expect_count(n_scene_blocks, "blocks in the scene");
    // Blocks added after the checkpoint's own (add_block) cannot be undone.
    if (n_total < s.blocks.size() || n_total > bytes.size() / 64)
      throw InputError(source + ": the checkpoint has "
                       + std::to_string(n_total) + " blocks; this run has "
                       + std::to_string(s.blocks.size()));
    s.blocks.resize(n_total);
    std::vector<double> sizes(block_size.begin(),
                              block_size.begin() + n_scene_blocks);
    for (std::size_t k = 0; k < s.blocks.size(); ++k)
      {
        Block &b = s.blocks[k];
        if (k >= n_scene_blocks)
          {
            b.id         = r.get<std::int32_t>();
            b.material   = r.get<std::int32_t>();
            b.joint      = r.get<std::int32_t>();
            const auto n = r.get<std::uint64_t>();
            if (n > 1000000 || b.material < 0
                || b.material >= static_cast<int>(s.materials.size())
                || b.joint < 0 || b.joint >= static_cast<int>(s.joints.size()))
              throw InputError(source
                               + ": the checkpoint is damaged (added block "
                               + std::to_string(b.id) + ")");
            b.edge_joints.resize(n);
            for (auto &j : b.edge_joints)
              {
                j = r.get<std::int32_t>();
                if (j < 0 || j >= static_cast<int>(s.joints.size()))
                  throw InputError(source
                                   + ": the checkpoint is damaged (added block "
                                   + std::to_string(b.id) + ")");
              }
            sizes.push_back(r.get<double>());
            const auto n_vertices = r.get<std::uint64_t>();
            if (n_vertices < 3 || n_vertices > 1000000)
              throw InputError(source
                               + ": the checkpoint is damaged (added block "
                               + std::to_string(b.id) + ")");
            b.polygon.vertices.resize(n_vertices);
          }
        else
          r.expect_count(b.polygon.vertices.size(),
                         "vertices in block " + std::to_string(b.id));
        for (auto &v : b.polygon.vertices)
          v = r.get_fixed<geometry::Point>();
        r.get_fixed(b.velocity);
        r.get_fixed(b.stress);
        r.get_fixed(b.strain);
        r.get_fixed(b.eigenstrain);
        r.get_fixed(b.applied_eigenstrain);
        b.initial_centroid = r.get_fixed<geometry::Point>();
        b.rotation         = r.get<double>();
      }
    dda::get_scene_points(r, s);
    // Each contact takes 97 bytes: a larger count is a damaged file.
    const auto           n_contacts = r.get_count(97, "contacts");
    std::vector<Contact> contacts(n_contacts);
    for (auto &c : contacts)
      {
        auto &g      = c.geometry;
        g.block_i    = r.get<std::int32_t>();
        g.vertex     = r.get<std::int32_t>();
        g.block_j    = r.get<std::int32_t>();
        g.edge       = r.get<std::int32_t>();
        g.normal     = r.get_fixed<geometry::Point>();
        g.xi         = r.get<double>();
        g.projection = g.xi;
        g.gap        = r.get<double>();
        c.state = static_cast<ContactState>(r.get_index(2, "contact state"));
        c.state_at_start
          = static_cast<ContactState>(r.get_index(2, "contact state"));
        c.xi_ref           = r.get<double>();
        c.normal_force     = r.get<double>();
        c.shear_force      = r.get<double>();
        c.slide_direction  = r.get<std::int32_t>();
        const auto flags   = r.get<std::uint8_t>();
        c.broken           = (flags & 1) != 0;
        c.held             = (flags & 2) != 0;
        c.joint            = r.get<std::int32_t>();
        c.slip_rate        = r.get<double>();
        const int n_blocks = static_cast<int>(s.blocks.size());
        if (g.block_i < 0 || g.block_i >= n_blocks || g.block_j < 0
            || g.block_j >= n_blocks || c.joint < 0
            || c.joint >= static_cast<int>(s.joints.size()))
          throw InputError(source
                           + ": the checkpoint is damaged (contact "
                             "between blocks "
                           + std::to_string(g.block_i) + " and "
                           + std::to_string(g.block_j) + ")");
      }
    const double        time              = r.get<double>();
    const double        step              = r.get<double>();
    const std::uint64_t steps             = r.get<std::uint64_t>();
    const std::uint64_t cuts              = r.get<std::uint64_t>();
    const std::uint64_t iterations        = r.get<std::uint64_t>();
    const std::uint64_t solves            = r.get<std::uint64_t>();
    const std::uint64_t solver_iterations = r.get<std::uint64_t>();
    Eigen::VectorXd     x = get_warm_start(r, 6 * s.blocks.size(), source);
    const double        friction = r.get<double>();
    const double        loads    = r.get<double>();
    const double        damped   = r.get<double>();
    const bool          first    = r.get<std::uint8_t>() != 0;
    const double        strength = r.get<double>();
    if (!r.at_end())
      throw InputError(source + ": the checkpoint has trailing data");
    if (!(std::isfinite(time) && step > 0.))
      throw InputError(source + ": the checkpoint is damaged (t = "
                       + std::to_string(time)
                       + " s, dt = " + std::to_string(step) + " s)");

    scene      = std::move(s);
    block_size = std::move(sizes);
    allowed_step.resize(block_size.size());
    for (std::size_t k = n_scene_blocks; k < block_size.size(); ++k)
      allowed_step[k] = allowed_displacement_for(block_size[k]);
    clamped_block.resize(block_size.size(), 0);
    current_contacts = std::move(contacts);
    contact_set.store(current_contacts);
    t = time;
    step_control.restore(step);
    n_steps              = steps;
    n_cuts               = cuts;
    n_iterations         = iterations;
    n_solves             = solves;
    n_solver_iterations  = solver_iterations;
    last_solution        = std::move(x);
    friction_work        = friction;
    load_work            = loads;
    damping_work         = damped;
    first_detection      = first;
    worst_strength_ratio = strength;
    accepted_balance     = std::numeric_limits<double>::quiet_NaN();
  }
} // namespace rockdda::dda
