/**
 * @file
 * Checkpoint and restart of the 3D DDA engine, in the 2D engine's binary
 * format (io::BinaryWriter, dda/engine_checkpoint.cc): every quantity that
 * evolves during a run as raw doubles and integers, so that a resumed run
 * continues exactly as the uninterrupted one.
 */
#include <rockdda/dda/scene_checkpoint.h>
#include <rockdda/dda3d/engine.h>
#include <rockdda/io/binary_stream.h>
#include <rockdda/io/error.h>

#include <cmath>
#include <cstdint>

namespace rockdda::dda3d
{
  namespace
  {
    constexpr char magic[] = "rockdda DDA 3d checkpoint";
    // 3: the strain damping's dissipated energy.
    constexpr std::uint32_t format_version = 5;
    /// Bytes of one contact in the file (a larger count is a damaged file).
    constexpr std::size_t contact_bytes = 217;
    using io::BinaryReader;
    using io::BinaryWriter;
  } // namespace



  std::string
  Engine::checkpoint() const
  {
    BinaryWriter w;
    w.put_header(magic, format_version);
    w.put_fixed(origin_);
    w.put<std::uint64_t>(system.blocks.size());
    for (const Block &b : system.blocks)
      {
        w.put<std::uint64_t>(b.polyhedron.vertices.size());
        for (const auto &v : b.polyhedron.vertices)
          w.put_fixed(v);
        w.put_fixed(b.velocity);
        w.put_fixed(b.stress);
        w.put_fixed(b.strain);
        w.put_fixed(b.initial_centroid);
      }
    dda::put_scene_points(w, system);
    w.put<std::uint64_t>(stored.size());
    for (const auto &c : stored)
      {
        const auto &g = c.geometry;
        for (const int i : {int(g.type), g.i, g.a, g.j, g.b})
          w.put<std::int32_t>(i);
        for (const Point *p : {&g.p, &g.q, &g.normal})
          w.put_fixed(*p);
        w.put(g.gap);
        w.put(g.score);
        w.put<std::int32_t>(static_cast<std::int32_t>(c.state));
        w.put<std::int32_t>(static_cast<std::int32_t>(c.state_at_start));
        w.put_fixed(c.reference);
        // Flags: bit 0 broken, bit 1 has a shear reference, bit 2 held
        // (older checkpoints: 0).
        w.put<std::uint8_t>((c.broken ? 1 : 0) | (c.has_reference ? 2 : 0)
                            | (c.held ? 4 : 0));
        w.put_fixed(c.slide_direction);
        w.put(c.normal_force);
        w.put_fixed(c.shear_force);
        w.put<std::int32_t>(c.joint);
        w.put(c.area);
        w.put(c.slip_rate);
      }
    w.put(t);
    w.put(steps_.current());
    w.put<std::uint64_t>(n_steps);
    w.put<std::uint64_t>(n_cuts);
    w.put<std::uint64_t>(n_iterations);
    w.put(friction_work);
    w.put(load_work);
    w.put(contact_energy);
    w.put(damping_work);
    w.put(initial_speed_);
    w.put(ground_speed_);
    w.put(worst_strength_ratio);
    w.put<std::uint8_t>(first_detection ? 1 : 0);
    for (const int i : {stats.iterations,
                        stats.cuts,
                        stats.open,
                        stats.sliding,
                        stats.locked})
      w.put<std::int32_t>(i);
    w.put(stats.dt);
    dda::put_warm_start(w, last_solution);
    return w.bytes;
  }



  void
  Engine::restore(const std::string &bytes, const std::string &source)
  {
    BinaryReader r(bytes, source);
    r.check_header(magic, format_version);
    if (r.get_fixed<Point>() != origin_)
      throw InputError(source
                       + ": the checkpoint's scene has another local origin "
                         "(lower corner of the blocks' bounding box): it "
                         "belongs to another scene");
    // Read into a copy: the engine is untouched if the file is rejected.
    BlockSystem s = system;
    r.expect_count(s.blocks.size(), "blocks");
    for (Block &b : s.blocks)
      {
        r.expect_count(b.polyhedron.vertices.size(),
                       "vertices in block " + std::to_string(b.id));
        for (auto &v : b.polyhedron.vertices)
          v = r.get_fixed<Point>();
        r.get_fixed(b.velocity);
        r.get_fixed(b.stress);
        r.get_fixed(b.strain);
        b.initial_centroid = r.get_fixed<Point>();
      }
    dda::get_scene_points(r, s);
    std::vector<Contact> contacts(r.get_count(contact_bytes, "contacts"));
    const int            n_blocks = static_cast<int>(s.blocks.size());
    for (auto &c : contacts)
      {
        auto &g = c.geometry;
        g.type  = static_cast<ContactType>(r.get_index(1, "contact type"));
        for (int *i : {&g.i, &g.a, &g.j, &g.b})
          *i = r.get<std::int32_t>();
        for (Point *p : {&g.p, &g.q, &g.normal})
          *p = r.get_fixed<Point>();
        g.gap   = r.get<double>();
        g.score = r.get<double>();
        c.state = static_cast<ContactState>(r.get_index(2, "contact state"));
        c.state_at_start
          = static_cast<ContactState>(r.get_index(2, "contact state"));
        c.reference       = r.get_fixed<Point>();
        const auto flags  = r.get<std::uint8_t>();
        c.broken          = (flags & 1) != 0;
        c.has_reference   = (flags & 2) != 0;
        c.held            = (flags & 4) != 0;
        c.slide_direction = r.get_fixed<Point>();
        c.normal_force    = r.get<double>();
        c.shear_force     = r.get_fixed<Point>();
        c.joint           = r.get<std::int32_t>();
        c.area            = r.get<double>();
        c.slip_rate       = r.get<double>();
        if (g.i < 0 || g.i >= n_blocks || g.j < 0 || g.j >= n_blocks
            || c.joint < 0 || c.joint >= static_cast<int>(s.joints.size()))
          throw InputError(source
                           + ": the checkpoint is damaged (contact between "
                             "blocks "
                           + std::to_string(g.i) + " and " + std::to_string(g.j)
                           + ")");
      }
    const double   time       = r.get<double>();
    const double   step       = r.get<double>();
    const auto     steps      = r.get<std::uint64_t>();
    const auto     cuts       = r.get<std::uint64_t>();
    const auto     iterations = r.get<std::uint64_t>();
    const double   friction   = r.get<double>();
    const double   loads      = r.get<double>();
    const double   contact    = r.get<double>();
    const double   damped     = r.get<double>();
    const double   speed0     = r.get<double>();
    const double   ground     = r.get<double>();
    const double   strength   = r.get<double>();
    const bool     first      = r.get<std::uint8_t>() != 0;
    StepStatistics st;
    for (int *i : {&st.iterations, &st.cuts, &st.open, &st.sliding, &st.locked})
      *i = r.get<std::int32_t>();
    st.dt             = r.get<double>();
    Eigen::VectorXd x = dda::get_warm_start(r, 12 * s.blocks.size(), source);
    if (!r.at_end())
      throw InputError(source + ": the checkpoint has trailing data");
    if (!(std::isfinite(time) && step > 0. && std::isfinite(step)))
      throw InputError(source + ": the checkpoint is damaged (t = "
                       + std::to_string(time)
                       + " s, dt = " + std::to_string(step) + " s)");

    system = std::move(s);
    stored = std::move(contacts);
    t      = time;
    steps_.restore(step);
    n_steps              = steps;
    n_cuts               = cuts;
    n_iterations         = iterations;
    friction_work        = friction;
    load_work            = loads;
    contact_energy       = contact;
    damping_work         = damped;
    initial_speed_       = speed0;
    ground_speed_        = ground;
    worst_strength_ratio = strength;
    first_detection      = first;
    stats                = st;
    last_solution        = std::move(x);
  }
} // namespace rockdda::dda3d
