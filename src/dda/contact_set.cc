/**
 * @file
 * Contact transfer between time steps (Shi 1988, ch. 4).
 */
#include <rockdda/dda/contact_set.h>

#include <algorithm>

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
  ContactSet::transfer(
    const std::vector<ContactCandidate>                   &candidates,
    const std::function<double(const ContactCandidate &)> &closed_gap,
    const bool                                             intact) const
  {
    std::vector<Contact>       result(candidates.size());
    std::vector<std::uint64_t> detected(candidates.size());
    for (std::size_t c = 0; c < candidates.size(); ++c)
      {
        const ContactCandidate &g = candidates[c];
        detected[c]               = key(g.block_i, g.vertex, g.block_j, g.edge);
      }
    std::sort(detected.begin(), detected.end());
    for (std::size_t c = 0; c < candidates.size(); ++c)
      {
        const ContactCandidate &g = candidates[c];
        Contact                &r = result[c];
        r.geometry                = g;
        r.xi_ref                  = g.projection;
        const std::uint64_t v     = vertex_key(g.block_i, g.vertex, g.block_j);
        const auto m = history.find(key(g.block_i, g.vertex, g.block_j, g.edge),
                                    &v,
                                    detected);
        // (continue_contact(): the rule of both engines.)
        if (m.index >= 0)
          continue_contact(r,
                           stored[m.index],
                           m.same_feature,
                           [](Contact &to, const Contact &from) {
                             if (from.state == ContactState::locked)
                               to.xi_ref = from.xi_ref;
                           });
        else
          {
            // A vertex beyond the edge's end (coming round a reflex
            // corner) starts open: it closes when it crosses the edge's
            // line.
            const bool beyond = g.projection < 0. || g.projection > 1.;
            r.state  = !beyond && g.gap <= closed_gap(g) ? ContactState::locked
                                                         : ContactState::open;
            r.broken = !intact;
          }
        r.state_at_start = r.state;
      }
    return result;
  }



  void
  ContactSet::store(const std::vector<Contact> &contacts)
  {
    stored = contacts;
    std::vector<std::uint64_t>                  keys(stored.size());
    std::vector<std::pair<bool, std::uint64_t>> vertex_keys(stored.size());
    for (std::size_t c = 0; c < stored.size(); ++c)
      {
        const auto &g  = stored[c].geometry;
        keys[c]        = key(g.block_i, g.vertex, g.block_j, g.edge);
        vertex_keys[c] = {stored[c].state != ContactState::open,
                          vertex_key(g.block_i, g.vertex, g.block_j)};
      }
    history.store(keys, vertex_keys);
  }
} // namespace rockdda::dda
