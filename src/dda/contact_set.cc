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
    std::vector<Contact> result(candidates.size());
    // Whether the candidates hold vertex (i, k) of block i against edge e
    // of block j: the candidates of one vertex and block are adjacent
    // (detection emits them together), so look at the neighbours of c.
    const auto present = [&](const std::size_t c, const int e) {
      const ContactCandidate &g    = candidates[c];
      const auto              same = [&](const ContactCandidate &o) {
        return o.block_i == g.block_i && o.vertex == g.vertex
               && o.block_j == g.block_j;
      };
      for (std::size_t d = c; d < candidates.size() && same(candidates[d]); ++d)
        if (candidates[d].edge == e)
          return true;
      for (std::size_t d = c; d-- > 0 && same(candidates[d]);)
        if (candidates[d].edge == e)
          return true;
      return false;
    };
    for (std::size_t c = 0; c < candidates.size(); ++c)
      {
        const ContactCandidate &g = candidates[c];
        Contact                &r = result[c];
        r.geometry                = g;
        r.xi_ref                  = g.projection;
        const Contact *found
          = find(by_edge, key(g.block_i, g.vertex, g.block_j, g.edge));
        if (found != nullptr)
          {
            const Contact &o  = *found;
            r.state           = o.state;
            r.normal_force    = o.normal_force;
            r.shear_force     = o.shear_force;
            r.slide_direction = o.slide_direction;
            r.broken          = o.broken;
            r.held            = o.held;
            r.slip_rate       = o.slip_rate;
            if (o.state == ContactState::locked)
              r.xi_ref = o.xi_ref;
          }
        else
          {
            const Contact *v
              = find(by_vertex, vertex_key(g.block_i, g.vertex, g.block_j));
            // Only if the vertex has left its previous edge (near a reflex
            // corner it touches both, each with its own state).
            if (v != nullptr && v->state != ContactState::open
                && !present(c, v->geometry.edge))
              {
                // The vertex moved onto another edge of the same block.
                const Contact &o  = *v;
                r.state           = o.state;
                r.normal_force    = o.normal_force;
                r.slide_direction = o.slide_direction;
                r.broken          = o.broken;
                r.slip_rate       = o.slip_rate;
              }
            else
              {
                // A vertex beyond the edge's end (coming round a reflex
                // corner) starts open: it closes when it crosses the edge's
                // line.
                const bool beyond = g.projection < 0. || g.projection > 1.;
                r.state           = !beyond && g.gap <= closed_gap(g)
                                      ? ContactState::locked
                                      : ContactState::open;
                r.broken          = !intact;
              }
          }
        r.state_at_start = r.state;
      }
    return result;
  }



  const Contact *
  ContactSet::find(const std::vector<std::pair<std::uint64_t, int>> &index,
                   const std::uint64_t                               k) const
  {
    const auto it
      = std::lower_bound(index.begin(), index.end(), std::make_pair(k, -1));
    return it != index.end() && it->first == k ? &stored[it->second] : nullptr;
  }



  void
  ContactSet::store(const std::vector<Contact> &contacts)
  {
    stored = contacts;
    by_edge.clear();
    by_vertex.clear();
    for (std::size_t c = 0; c < stored.size(); ++c)
      {
        const auto &g = stored[c].geometry;
        by_edge.emplace_back(key(g.block_i, g.vertex, g.block_j, g.edge),
                             static_cast<int>(c));
        by_vertex.emplace_back(vertex_key(g.block_i, g.vertex, g.block_j),
                               static_cast<int>(c));
      }
    std::sort(by_edge.begin(), by_edge.end());
    // Per vertex key, keep one entry: the first closed contact in input
    // order, else the first one.
    std::sort(by_vertex.begin(),
              by_vertex.end(),
              [this](const auto &a, const auto &b) {
                if (a.first != b.first)
                  return a.first < b.first;
                const bool ca = stored[a.second].state != ContactState::open;
                const bool cb = stored[b.second].state != ContactState::open;
                if (ca != cb)
                  return ca;
                return a.second < b.second;
              });
    by_vertex.erase(std::unique(by_vertex.begin(),
                                by_vertex.end(),
                                [](const auto &a, const auto &b) {
                                  return a.first == b.first;
                                }),
                    by_vertex.end());
    // Duplicate edge keys (not expected) keep the last contact, as before.
    for (std::size_t k = by_edge.size(); k-- > 1;)
      if (by_edge[k].first == by_edge[k - 1].first)
        by_edge[k - 1].second = by_edge[k].second;
  }
} // namespace rockdda::dda
