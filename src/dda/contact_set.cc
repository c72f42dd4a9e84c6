/**
 * @file
 * Contact transfer between time steps (Shi 1988, ch. 4).
 */
#include <rockdda/dda/contact_set.h>

namespace rockdda::dda
{
  std::uint64_t
  ContactSet::key(int i, int k, int j, int e)
  {
    return (static_cast<std::uint64_t>(i) << 42)
           ^ (static_cast<std::uint64_t>(k & 0x3ff) << 32)
           ^ (static_cast<std::uint64_t>(j & 0x3fffff) << 10)
           ^ static_cast<std::uint64_t>(e & 0x3ff);
  }



  std::uint64_t
  ContactSet::vertex_key(int i, int k, int j)
  {
    return key(i, k, j, 0x3ff);
  }



  std::vector<Contact>
  ContactSet::transfer(const std::vector<ContactCandidate> &candidates,
                       const double                         closed_gap) const
  {
    std::vector<Contact> result(candidates.size());
    for (std::size_t c = 0; c < candidates.size(); ++c)
      {
        const ContactCandidate &g = candidates[c];
        Contact                &r = result[c];
        r.geometry                = g;
        r.xi_ref                  = g.xi;
        auto it = stored.find(key(g.block_i, g.vertex, g.block_j, g.edge));
        if (it != stored.end())
          {
            const Contact &o  = it->second;
            r.state           = o.state;
            r.normal_force    = o.normal_force;
            r.shear_force     = o.shear_force;
            r.slide_direction = o.slide_direction;
            r.broken          = o.broken;
            if (o.state == ContactState::locked)
              r.xi_ref = o.xi_ref;
          }
        else
          {
            auto v = by_vertex.find(vertex_key(g.block_i, g.vertex, g.block_j));
            if (v != by_vertex.end() && v->second.state != ContactState::open)
              {
                // The vertex moved onto another edge of the same block.
                const Contact &o  = v->second;
                r.state           = o.state;
                r.normal_force    = o.normal_force;
                r.slide_direction = o.slide_direction;
                r.broken          = o.broken;
              }
            else
              r.state = g.gap < closed_gap ? ContactState::locked
                                           : ContactState::open;
          }
        r.state_at_start = r.state;
      }
    return result;
  }



  void
  ContactSet::store(const std::vector<Contact> &contacts)
  {
    stored.clear();
    by_vertex.clear();
    for (const Contact &c : contacts)
      {
        const auto &g                                       = c.geometry;
        stored[key(g.block_i, g.vertex, g.block_j, g.edge)] = c;
        auto &v = by_vertex[vertex_key(g.block_i, g.vertex, g.block_j)];
        if (v.state == ContactState::open)
          v = c;
      }
  }
} // namespace rockdda::dda
