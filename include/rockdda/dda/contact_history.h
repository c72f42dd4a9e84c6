/**
 * @file
 * Which contact of the previous step a contact of this step continues: the
 * transfer rule of both DDA engines (Shi 1988, ch. 4; doc/theory/dda.md,
 * "Contacts"), written once over the key of a contact's features.
 */
#ifndef ROCKDDA_DDA_CONTACT_HISTORY_H
#define ROCKDDA_DDA_CONTACT_HISTORY_H

#include <algorithm>
#include <utility>
#include <vector>

namespace rockdda::dda
{
  /**
   * The contacts stored at the end of a step, indexed for the transfer of
   * their states to the next step's contacts. A contact is identified by
   * the key of its features (Key: block i, its vertex or edge, block j, its
   * edge or face); a vertex contact also by the vertex and the block it
   * touches (VertexKey: block i, vertex, block j). A new contact continues
   * - the stored contact with the same key (the same features);
   * - else, for a vertex contact, the first stored closed contact (in
   *   stored order) of the same vertex on the same block whose own
   *   features are no longer detected: the vertex went round a convex
   *   corner or edge of block j onto another edge or face. A vertex that
   *   still touches its old edge or face (a reflex corner of j) keeps that
   *   contact, and the new one starts from its own gap;
   * - else none (a new contact).
   * Key and VertexKey need operator<.
   */
  template <typename Key, typename VertexKey>
  class ContactHistory
  {
  public:
    /// A stored contact continued by a new one (index into the stored
    /// order; -1: none), and whether it is the same features.
    struct Match
    {
      int  index        = -1;
      bool same_feature = false;
    };

    /// Index the stored contacts: their keys, and the vertex key of each
    /// closed vertex contact (@p vertex_keys[k].first false for an open
    /// contact or one that is not a vertex contact).
    void
    store(const std::vector<Key>                        &keys,
          const std::vector<std::pair<bool, VertexKey>> &vertex_keys)
    {
      by_key.clear();
      by_vertex.clear();
      for (std::size_t k = 0; k < keys.size(); ++k)
        {
          by_key.emplace_back(keys[k], static_cast<int>(k));
          if (vertex_keys[k].first)
            by_vertex.emplace_back(vertex_keys[k].second, static_cast<int>(k));
        }
      // Sorted by key, then stored order; a key stored twice (not
      // expected) resolves to its last contact.
      std::sort(by_key.begin(), by_key.end());
      std::sort(by_vertex.begin(), by_vertex.end());
      std::vector<std::pair<Key, int>> unique;
      for (std::size_t k = 0; k < by_key.size(); ++k)
        if (k + 1 == by_key.size() || by_key[k].first < by_key[k + 1].first)
          unique.push_back(by_key[k]);
      by_key.swap(unique);
      stored_keys.assign(keys.begin(), keys.end());
    }

    /**
     * The stored contact that a contact with key @p key continues, for
     * this step's detected keys @p detected (sorted); @p vertex its vertex
     * key, nullptr if it is not a vertex contact.
     */
    Match
    find(const Key              &key,
         const VertexKey        *vertex,
         const std::vector<Key> &detected) const
    {
      Match      m;
      const auto it = std::lower_bound(by_key.begin(),
                                       by_key.end(),
                                       key,
                                       [](const auto &e, const Key &k) {
                                         return e.first < k;
                                       });
      if (it != by_key.end() && !(key < it->first))
        {
          m.index        = it->second;
          m.same_feature = true;
          return m;
        }
      if (vertex == nullptr)
        return m;
      auto v = std::lower_bound(by_vertex.begin(),
                                by_vertex.end(),
                                *vertex,
                                [](const auto &e, const VertexKey &k) {
                                  return e.first < k;
                                });
      for (; v != by_vertex.end() && !(*vertex < v->first); ++v)
        if (!std::binary_search(detected.begin(),
                                detected.end(),
                                stored_keys[v->second]))
          {
            m.index = v->second;
            return m;
          }
      return m;
    }

  private:
    std::vector<std::pair<Key, int>>       by_key;
    std::vector<std::pair<VertexKey, int>> by_vertex;
    std::vector<Key>                       stored_keys;
  };

  /**
   * What a contact of this step inherits from the stored contact it
   * continues (ContactHistory::find()), both engines: its state, normal
   * force, sliding direction, whether its joint broke and its slip rate;
   * from the same features (@p same_feature) also its shear force and,
   * through @p same_features(to, from), what belongs to the features: the
   * shear spring's anchor of a locked contact; and from the same features
   * its hold across static steps (held).
   * A vertex that went round a corner onto another edge or face keeps its
   * state but starts its spring where it touches now, carrying no shear
   * force (and no stored spring energy) from the old features.
   */
  template <typename Contact, typename SameFeatures>
  void
  continue_contact(Contact            &to,
                   const Contact      &from,
                   const bool          same_feature,
                   const SameFeatures &same_features)
  {
    to.state           = from.state;
    to.normal_force    = from.normal_force;
    to.slide_direction = from.slide_direction;
    to.broken          = from.broken;
    to.slip_rate       = from.slip_rate;
    if (same_feature)
      {
        to.shear_force = from.shear_force;
        to.held        = from.held;
        same_features(to, from);
      }
  }
} // namespace rockdda::dda

#endif
