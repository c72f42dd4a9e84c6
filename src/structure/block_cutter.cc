// Exact block cutting with a CGAL arrangement. All CGAL headers stay in this
// file: exact arrangements compile slowly.
#include <rockdda/io/error.h>
#include <rockdda/structure/block_cutter.h>

#include <CGAL/Arr_curve_data_traits_2.h>
#include <CGAL/Arr_extended_dcel.h>
#include <CGAL/Arr_segment_traits_2.h>
#include <CGAL/Arrangement_2.h>
#include <CGAL/Exact_predicates_exact_constructions_kernel.h>
#include <CGAL/Polygon_2_algorithms.h>

#include <algorithm>
#include <cmath>
#include <map>
#include <set>
#include <sstream>

namespace rockdda::structure
{
  std::string
  to_string(const EdgeKind kind)
  {
    switch (kind)
      {
        case EdgeKind::boundary:
          return "boundary";
        case EdgeKind::bedding:
          return "bedding";
        case EdgeKind::joint:
          return "joint";
        case EdgeKind::excavation:
          return "excavation";
        case EdgeKind::split:
          return "split";
      }
    return "unknown";
  }



  double
  BlockSet::total_block_area() const
  {
    double a = 0.;
    for (const Block &b : blocks)
      a += b.polygon.area();
    return a;
  }



  namespace
  {
    using Kernel    = CGAL::Exact_predicates_exact_constructions_kernel;
    using KPoint    = Kernel::Point_2;
    using KSegment  = Kernel::Segment_2;
    using SegTraits = CGAL::Arr_segment_traits_2<Kernel>;
    /// Where inputs overlap, the edge keeps the smallest tag code.
    struct MinCode
    {
      int
      operator()(const int a, const int b) const
      {
        return std::min(a, b);
      }
    };
    // A single int per curve (not a list as with the consolidated traits):
    // fewer allocations in the sweep.
    using Traits = CGAL::Arr_curve_data_traits_2<SegTraits, int, MinCode>;
    using Curve  = Traits::Curve_2;
    // Vertex data: output index (-1 none); face data: FaceClass.
    using Dcel        = CGAL::Arr_extended_dcel<Traits, long, int, int>;
    using Arrangement = CGAL::Arrangement_2<Traits, Dcel>;
    using Halfedge    = Arrangement::Halfedge_handle;
    using Face        = Arrangement::Face_handle;
    using Vertex      = Arrangement::Vertex_handle;
    using Ccb         = Arrangement::Ccb_halfedge_circulator;

    // Tag codes: the smallest code wins where inputs overlap.
    constexpr int code_base = 1000000;

    int
    rank(const EdgeKind k)
    {
      switch (k)
        {
          case EdgeKind::boundary:
            return 0;
          case EdgeKind::excavation:
            return 1;
          case EdgeKind::bedding:
            return 2;
          case EdgeKind::joint:
            return 3;
          case EdgeKind::split:
            return 4;
        }
      return 5;
    }

    int
    encode(const EdgeTag &t)
    {
      return rank(t.kind) * code_base + t.set;
    }

    EdgeTag
    decode(const int code)
    {
      static const EdgeKind kinds[] = {EdgeKind::boundary,
                                       EdgeKind::excavation,
                                       EdgeKind::bedding,
                                       EdgeKind::joint,
                                       EdgeKind::split};
      return {kinds[code / code_base], code % code_base};
    }

    int
    edge_code(const Halfedge &h)
    {
      return h->curve().data();
    }

    enum FaceClass : int
    {
      outside   = 0,
      excavated = 1,
      block     = 2
    };

    KPoint
    to_exact(const Point &p)
    {
      return KPoint(p.x(), p.y());
    }

    Point
    to_point(const KPoint &p)
    {
      return Point(CGAL::to_double(p.x()), CGAL::to_double(p.y()));
    }

    /// A polygon as exact points, counter-clockwise.
    std::vector<KPoint>
    exact_ccw(const Polygon &p)
    {
      std::vector<KPoint> v;
      for (const Point &q : p.vertices)
        v.push_back(to_exact(q));
      if (CGAL::orientation_2(v.begin(), v.end(), Kernel()) == CGAL::CLOCKWISE)
        std::reverse(v.begin(), v.end());
      return v;
    }

    /**
     * Whether the face to the left of @p h lies inside polygon @p poly (CCW):
     * by the midpoint of h, or, if that is on the polygon's boundary, by the
     * direction of h relative to the polygon edge it lies on.
     */
    bool
    face_inside(const std::vector<KPoint> &poly, const Halfedge &h)
    {
      const KPoint &s = h->source()->point();
      const KPoint &t = h->target()->point();
      const KPoint  m = CGAL::midpoint(s, t);
      switch (CGAL::bounded_side_2(poly.begin(), poly.end(), m, Kernel()))
        {
          case CGAL::ON_BOUNDED_SIDE:
            return true;
          case CGAL::ON_UNBOUNDED_SIDE:
            return false;
          default:
            break;
        }
      const std::size_t n = poly.size();
      for (std::size_t i = 0; i < n; ++i)
        {
          const KPoint &a = poly[i];
          const KPoint &b = poly[(i + 1) % n];
          if (CGAL::collinear(a, b, m)
              && CGAL::collinear_are_ordered_along_line(a, m, b))
            return (t - s) * (b - a) > 0;
        }
      return false;
    }

    /// Double-precision outer boundary of a face (for sliver tests).
    Polygon
    outer_polygon(const Face &f)
    {
      Polygon p;
      Ccb     c = f->outer_ccb(), e = c;
      do
        p.vertices.push_back(to_point(c->source()->point()));
      while (++c != e);
      return p;
    }

    double
    face_area(const Face &f)
    {
      double a = outer_polygon(f).area();
      for (auto h = f->inner_ccbs_begin(); h != f->inner_ccbs_end(); ++h)
        {
          Polygon p;
          Ccb     c = *h, e = c;
          do
            p.vertices.push_back(to_point(c->source()->point()));
          while (++c != e);
          a -= p.area();
        }
      return a;
    }

    class Cutter
    {
    public:
      Cutter(const Polygon              &domain,
             const std::vector<Polygon> &excavations,
             const CutOptions           &options)
          : domain(exact_ccw(domain))
          , options(options)
      {
        for (const Polygon &e : excavations)
          this->excavations.push_back(exact_ccw(e));
      }

      Arrangement arr;

      /// Remove every edge with the same face on both sides.
      unsigned int
      remove_dangling()
      {
        std::vector<Halfedge> doomed;
        for (auto e = arr.edges_begin(); e != arr.edges_end(); ++e)
          if (e->face() == e->twin()->face())
            doomed.push_back(e);
        for (Halfedge &h : doomed)
          arr.remove_edge(h);
        return doomed.size();
      }

      FaceClass
      classify(const Face &f) const
      {
        if (f->is_unbounded())
          return outside;
        const Halfedge h = f->outer_ccb();
        if (!face_inside(domain, h))
          return outside;
        for (const auto &e : excavations)
          if (face_inside(e, h))
            return excavated;
        return block;
      }

      void
      classify_all()
      {
        for (auto f = arr.faces_begin(); f != arr.faces_end(); ++f)
          f->set_data(classify(f));
      }

      bool
      is_sliver(const Polygon &p) const
      {
        return (options.sliver_area > 0. && p.area() < options.sliver_area)
               || (options.sliver_width > 0.
                   && p.min_width() < options.sliver_width)
               || (options.sliver_angle > 0.
                   && p.min_interior_angle() < options.sliver_angle);
      }

      /// Add the tests that @p p fails to the counters of @p result.
      void
      count_sliver(const Polygon &p, BlockSet &result) const
      {
        result.n_slivers_by_area
          += options.sliver_area > 0. && p.area() < options.sliver_area;
        result.n_slivers_by_width
          += options.sliver_width > 0. && p.min_width() < options.sliver_width;
        result.n_slivers_by_angle
          += options.sliver_angle > 0.
             && p.min_interior_angle() < options.sliver_angle;
      }

      /// Merge each sliver into its neighbour with the longest shared
      /// boundary. Returns the number merged; counts the tests each merged
      /// sliver failed in @p result.
      unsigned int
      merge_slivers(BlockSet &result)
      {
        std::map<const void *, Halfedge> doomed;
        unsigned int                     merged = 0;
        for (auto f = arr.faces_begin(); f != arr.faces_end(); ++f)
          {
            if (f->data() != block || !is_sliver(outer_polygon(f)))
              continue;
            std::map<const void *, std::pair<Face, double>> shared;
            Ccb c = f->outer_ccb(), e = c;
            do
              {
                const Face g = c->twin()->face();
                if (g != Face(f) && g->data() == block)
                  shared.try_emplace(&*g, g, 0.).first->second.second
                    += (to_point(c->target()->point())
                        - to_point(c->source()->point()))
                         .norm();
            } while (++c != e);
            if (shared.empty())
              continue;
            Face   best;
            double longest = -1.;
            for (const auto &[key, gl] : shared)
              if (gl.second > longest)
                {
                  longest = gl.second;
                  best    = gl.first;
                }
            do
              if (c->twin()->face() == best)
                {
                  Halfedge    h = c;
                  const void *a = &*h, *b = &*h->twin();
                  doomed[std::min(a, b)] = h;
                }
            while (++c != e);
            ++merged;
            count_sliver(outer_polygon(f), result);
          }
        for (auto &[key, h] : doomed)
          arr.remove_edge(h);
        return merged;
      }

      /// The boundary point nearest to @p v along the vertical ray up
      /// (@p up) or down from it, over the halfedges of face @p f.
      KPoint
      vertical_hit(const Face &f, const KPoint &v, const bool up) const
      {
        bool       found = false;
        Kernel::FT best  = 0;
        auto       test  = [&](const Halfedge &h) {
          const KPoint &s = h->source()->point();
          const KPoint &t = h->target()->point();
          Kernel::FT    y;
          if (s.x() == t.x())
            {
              if (s.x() != v.x())
                return;
              y = up ? CGAL::min(s.y(), t.y()) : CGAL::max(s.y(), t.y());
            }
          else
            {
              if (CGAL::min(s.x(), t.x()) > v.x()
                  || CGAL::max(s.x(), t.x()) < v.x())
                return;
              y = s.y() + (t.y() - s.y()) * (v.x() - s.x()) / (t.x() - s.x());
            }
          if (up ? !(y > v.y()) : !(y < v.y()))
            return;
          if (!found || (up ? y < best : y > best))
            {
              best  = y;
              found = true;
            }
        };
        {
          Ccb c = f->outer_ccb(), e = c;
          do
            test(c);
          while (++c != e);
        }
        for (auto hole = f->inner_ccbs_begin(); hole != f->inner_ccbs_end();
             ++hole)
          {
            Ccb c = *hole, e = c;
            do
              test(c);
            while (++c != e);
          }
        if (!found)
          throw std::logic_error("block cutting: vertical ray from a hole "
                                 "hit nothing");
        return KPoint(v.x(), best);
      }

      /// Split every block face with holes by vertical cuts. Returns the
      /// number of holes removed.
      unsigned int
      split_holes()
      {
        unsigned int split = 0;
        for (int pass = 0; pass < 8; ++pass)
          {
            std::vector<Curve> cuts;
            for (auto f = arr.faces_begin(); f != arr.faces_end(); ++f)
              {
                if (f->is_unbounded() || classify(f) != block)
                  continue;
                for (auto hole = f->inner_ccbs_begin();
                     hole != f->inner_ccbs_end();
                     ++hole)
                  {
                    Ccb    c = *hole, e = c;
                    KPoint lo = c->source()->point(), hi = lo;
                    do
                      {
                        const KPoint &p = c->source()->point();
                        if (CGAL::compare_xy(p, lo) == CGAL::SMALLER)
                          lo = p;
                        if (CGAL::compare_xy(p, hi) == CGAL::LARGER)
                          hi = p;
                    } while (++c != e);
                    const int code = encode({EdgeKind::split, 0});
                    cuts.emplace_back(KSegment(lo, vertical_hit(f, lo, false)),
                                      code);
                    cuts.emplace_back(KSegment(hi, vertical_hit(f, hi, true)),
                                      code);
                    ++split;
                  }
              }
            if (cuts.empty())
              break;
            CGAL::insert(arr, cuts.begin(), cuts.end());
          }
        return split;
      }

      std::vector<KPoint>              domain;
      std::vector<std::vector<KPoint>> excavations;
      CutOptions                       options;
    };
  } // namespace



  BlockSet
  cut_blocks(const Polygon                    &domain_polygon,
             const std::vector<Polygon>       &excavations,
             const std::vector<TaggedSegment> &segments,
             const CutOptions                 &options)
  {
    if (domain_polygon.vertices.size() < 3 || !(domain_polygon.area() > 0.)
        || domain_polygon.self_intersects())
      throw InputError("block cutting: the domain polygon must be simple "
                       "(no self-intersection) with at least 3 vertices and "
                       "a positive area");
    Cutter cutter(domain_polygon, excavations, options);
    for (std::size_t k = 0; k < excavations.size(); ++k)
      {
        const Polygon &e = excavations[k];
        if (e.vertices.size() < 3 || !(e.area() > 0.) || e.self_intersects())
          throw InputError("block cutting: excavation " + std::to_string(k)
                           + " must be a simple polygon with a positive area");
        for (const Point &p : e.vertices)
          if (CGAL::bounded_side_2(cutter.domain.begin(),
                                   cutter.domain.end(),
                                   to_exact(p),
                                   Kernel())
              == CGAL::ON_UNBOUNDED_SIDE)
            {
              std::ostringstream s;
              s << "block cutting: excavation " << k << " has vertex (" << p.x()
                << ", " << p.y()
                << ") m outside the domain; every excavation must lie inside "
                   "the domain";
              throw InputError(s.str());
            }
      }

    BlockSet result;
    result.domain_area   = domain_polygon.area();
    result.n_segments_in = segments.size();

    // 1. Everything into the arrangement at once (sweep line).
    std::vector<Curve> curves;
    curves.reserve(segments.size() + domain_polygon.vertices.size());
    auto add_ring = [&](const std::vector<KPoint> &ring, const EdgeTag tag) {
      for (std::size_t i = 0; i < ring.size(); ++i)
        curves.emplace_back(KSegment(ring[i], ring[(i + 1) % ring.size()]),
                            encode(tag));
    };
    add_ring(cutter.domain, {EdgeKind::boundary, 0});
    for (std::size_t k = 0; k < cutter.excavations.size(); ++k)
      add_ring(cutter.excavations[k], {EdgeKind::excavation, int(k)});
    for (const TaggedSegment &s : segments)
      {
        if (!std::isfinite(s.a.x()) || !std::isfinite(s.a.y())
            || !std::isfinite(s.b.x()) || !std::isfinite(s.b.y()))
          throw InputError("block cutting: a segment has a non-finite "
                           "coordinate");
        if (s.a == s.b)
          continue;
        curves.emplace_back(KSegment(to_exact(s.a), to_exact(s.b)),
                            encode(s.tag));
      }
    Arrangement &arr = cutter.arr;
    CGAL::insert(arr, curves.begin(), curves.end());

    // 2. Tree cutting, 3. slivers, 4. holes.
    result.n_dangling_edges = cutter.remove_dangling();
    cutter.classify_all();
    if (options.merge_slivers
        && (options.sliver_area > 0. || options.sliver_width > 0.
            || options.sliver_angle > 0.))
      {
        result.n_slivers_merged = cutter.merge_slivers(result);
        result.n_dangling_edges += cutter.remove_dangling();
      }
    result.n_holes_split = cutter.split_holes();
    cutter.classify_all();

    // 5. Blocks in double precision, shared vertices once.
    for (auto v = arr.vertices_begin(); v != arr.vertices_end(); ++v)
      v->set_data(-1);
    std::map<std::pair<double, double>, std::size_t> by_coordinates;
    for (auto f = arr.faces_begin(); f != arr.faces_end(); ++f)
      {
        if (f->data() == excavated)
          result.excavated_area += face_area(f);
        if (f->data() != block)
          continue;
        // Boundary vertices with the tag of the edge leaving each.
        std::vector<Vertex> vs;
        std::vector<int>    codes;
        Ccb                 c = f->outer_ccb(), e = c;
        do
          {
            vs.push_back(c->source());
            codes.push_back(edge_code(c));
        } while (++c != e);
        // Drop vertices where the boundary goes straight on with one tag.
        const std::size_t n = vs.size();
        std::vector<bool> keep(n, true);
        for (std::size_t i = 0; i < n; ++i)
          {
            const std::size_t prev = (i + n - 1) % n, next = (i + 1) % n;
            if (codes[prev] != codes[i])
              continue;
            if (!options.remove_all_collinear && vs[i]->degree() != 2)
              continue;
            const KPoint &a = vs[prev]->point(), &b = vs[i]->point(),
                         &d = vs[next]->point();
            if (CGAL::orientation(a, b, d) == CGAL::COLLINEAR)
              keep[i] = false;
          }
        Block blk;
        for (std::size_t i = 0; i < n; ++i)
          if (keep[i])
            {
              Vertex &v = vs[i];
              if (v->data() < 0)
                {
                  // Distinct exact vertices may round to one double point:
                  // they become one vertex.
                  const Point p = to_point(v->point());
                  const auto  it
                    = by_coordinates
                        .try_emplace({p.x(), p.y()}, result.vertices.size())
                        .first;
                  if (it->second == result.vertices.size())
                    result.vertices.push_back(p);
                  v->set_data(it->second);
                }
              blk.vertex_ids.push_back(v->data());
              blk.edge_tags.push_back(decode(codes[i]));
            }
        // Edges of zero length after rounding disappear.
        for (bool changed = true; changed && blk.vertex_ids.size() > 1;)
          {
            changed = false;
            for (std::size_t i = 0; i < blk.vertex_ids.size(); ++i)
              if (blk.vertex_ids[i]
                  == blk.vertex_ids[(i + 1) % blk.vertex_ids.size()])
                {
                  blk.vertex_ids.erase(blk.vertex_ids.begin() + i);
                  blk.edge_tags.erase(blk.edge_tags.begin() + i);
                  changed = true;
                  break;
                }
          }
        for (const std::size_t id : blk.vertex_ids)
          blk.polygon.vertices.push_back(result.vertices[id]);
        if (blk.vertex_ids.size() < 3 || !(blk.polygon.signed_area() > 0.))
          {
            // Below the resolution of double: its exact area is ~1e-30 m^2.
            ++result.n_degenerate_dropped;
            continue;
          }
        // Sliver with no block neighbour: drop.
        if (cutter.is_sliver(blk.polygon))
          {
            cutter.count_sliver(blk.polygon, result);
            bool has_neighbour = false;
            do
              has_neighbour |= (c->twin()->face()->data() == block
                                && c->twin()->face() != Face(f));
            while (++c != e);
            if (options.merge_slivers && !has_neighbour)
              {
                result.dropped_area += blk.polygon.area();
                ++result.n_slivers_dropped;
                continue;
              }
            ++result.n_slivers_remaining;
          }
        result.blocks.push_back(std::move(blk));
      }
    return result;
  }
} // namespace rockdda::structure
