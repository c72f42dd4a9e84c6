/**
 * @file
 * The fields of a DDA snapshot, gathered once for every output format.
 */
#include <rockdda/dda/snapshot.h>

#include <algorithm>

namespace rockdda::dda
{
  namespace
  {
    std::vector<double>
    planar_vectors(const std::vector<geometry::Point> &v)
    {
      std::vector<double> out;
      out.reserve(3 * v.size());
      for (const auto &p : v)
        out.insert(out.end(), {p.x(), p.y(), 0.});
      return out;
    }
  } // namespace



  Snapshot
  blocks_snapshot(const DdaSystem &dda)
  {
    const auto                  &scene  = dda.system();
    const auto                  &blocks = scene.blocks;
    const std::size_t            n      = blocks.size();
    const geometry::Point        o      = scene.origin;
    Snapshot                     out;
    std::vector<std::int32_t>    id(n), material(n);
    std::vector<geometry::Point> displacement(n), velocity(n);
    std::vector<double>          rotation(n), stress;
    stress.reserve(6 * n);
    out.offsets.reserve(n);
    for (std::size_t i = 0; i < n; ++i)
      {
        const Block &b = blocks[i];
        for (const auto &v : b.polygon.vertices)
          out.xyz.insert(out.xyz.end(), {o.x() + v.x(), o.y() + v.y(), 0.});
        out.offsets.push_back(static_cast<std::int64_t>(out.xyz.size() / 3));
        id[i] = b.id;
        const int user_material
          = b.material >= 0
                && b.material < static_cast<int>(scene.materials.size())
                && scene.materials[b.material].id >= 0
              ? scene.materials[b.material].id
              : b.material;
        material[i]     = user_material;
        displacement[i] = dda.centroid_displacement(static_cast<int>(i));
        velocity[i]     = geometry::Point(b.velocity[0], b.velocity[1]);
        rotation[i]     = b.rotation;
        stress.insert(stress.end(),
                      {b.stress[0], b.stress[1], 0., b.stress[2], 0., 0.});
      }
    out.description
      = "rockdda dda blocks (one polygon cell per block; points in m).\n"
        "Cell data: block_id (block file id), material (block file "
        "material id),\n"
        "displacement (m) and velocity (m/s) of the centroid, rotation "
        "(rad),\n"
        "stress (Pa, tension positive; symmetric tensor XX YY ZZ XY YZ "
        "XZ,\n"
        "the out-of-plane components written as 0).\n";
    out.fields.push_back(integer_field("block_id", std::move(id)));
    out.fields.push_back(integer_field("material", std::move(material)));
    out.fields.push_back(
      real_field("displacement", 3, planar_vectors(displacement)));
    out.fields.push_back(real_field("velocity", 3, planar_vectors(velocity)));
    out.fields.push_back(real_field("rotation", 1, std::move(rotation)));
    out.fields.push_back(real_field("stress", 6, std::move(stress)));
    out.fields.back().component_names = {"XX", "YY", "ZZ", "XY", "YZ", "XZ"};
    out.scalars                       = "material";
    out.vectors                       = "displacement";
    out.tensors                       = "stress";
    return out;
  }



  Snapshot
  contacts_snapshot(const DdaSystem &dda)
  {
    const auto                  &contacts = dda.contacts();
    const auto                  &scene    = dda.system();
    const auto                  &blocks   = scene.blocks;
    const geometry::Point        o        = scene.origin;
    const std::size_t            n        = contacts.size();
    Snapshot                     out;
    std::vector<double>          gap(n), slip(n), fn(n), fs(n);
    std::vector<std::int32_t>    state(n), vertex_block(n), edge_block(n);
    std::vector<geometry::Point> normal(n);
    out.lines = true;
    out.offsets.resize(n);
    for (std::size_t c = 0; c < n; ++c)
      {
        // The contact's vertex and edge in the current geometry (the
        // contact records hold the detection at the start of the step).
        const auto           &g  = contacts[c].geometry;
        const auto           &vi = blocks[g.block_i].polygon.vertices;
        const auto           &vj = blocks[g.block_j].polygon.vertices;
        const geometry::Point P  = vi[g.vertex];
        const geometry::Point Q0 = vj[g.edge];
        const geometry::Point E  = vj[(g.edge + 1) % vj.size()] - Q0;
        const double          l  = E.norm();
        const geometry::Point t  = E / l;
        const geometry::Point nn(t.y(), -t.x()); // out of block j
        const double          xi = std::clamp(t.dot(P - Q0) / l, 0., 1.);
        const geometry::Point P0 = Q0 + xi * E;
        out.xyz.insert(out.xyz.end(),
                       {o.x() + P.x(),
                        o.y() + P.y(),
                        0.,
                        o.x() + P0.x(),
                        o.y() + P0.y(),
                        0.});
        out.offsets[c]  = static_cast<std::int64_t>(2 * (c + 1));
        state[c]        = static_cast<std::int32_t>(contacts[c].state);
        vertex_block[c] = blocks[g.block_i].id;
        edge_block[c]   = blocks[g.block_j].id;
        gap[c]          = nn.dot(P - Q0);
        slip[c]         = contacts[c].state == ContactState::open
                            ? 0.
                            : t.dot(P - (Q0 + contacts[c].xi_ref * E));
        fn[c]           = contacts[c].normal_force;
        fs[c]           = contacts[c].shear_force;
        normal[c]       = nn;
      }
    out.description
      = "rockdda dda contacts (one line cell per contact, from the "
        "vertex to its\n"
        "projection on the edge; points in m). Cell data:\n"
        "state: 0 open, 1 sliding, 2 locked;\n"
        "vertex_block, edge_block: block file ids of the block whose "
        "vertex\n"
        "touches and of the block whose edge is touched;\n"
        "normal_gap (m, negative = penetration);\n"
        "shear_slip (m, along the edge from the shear reference: "
        "locked, the\n"
        "elastic shear displacement; sliding, the slip of the last "
        "step; open, 0);\n"
        "normal_force (N/m, compression positive), "
        "shear_force (N/m), normal (outward unit normal of the edge).\n";
    out.fields.push_back(integer_field("state", std::move(state)));
    out.fields.push_back(
      integer_field("vertex_block", std::move(vertex_block)));
    out.fields.push_back(integer_field("edge_block", std::move(edge_block)));
    out.fields.push_back(real_field("normal_gap", 1, std::move(gap)));
    out.fields.push_back(real_field("shear_slip", 1, std::move(slip)));
    out.fields.push_back(real_field("normal_force", 1, std::move(fn)));
    out.fields.push_back(real_field("shear_force", 1, std::move(fs)));
    out.fields.push_back(real_field("normal", 3, planar_vectors(normal)));
    out.scalars = "state";
    out.vectors = "normal";
    return out;
  }
} // namespace rockdda::dda
