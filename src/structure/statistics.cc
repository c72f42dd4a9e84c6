#include <rockdda/structure/statistics.h>

#include <algorithm>
#include <cmath>
#include <numeric>

namespace rockdda::structure
{
  double
  block_width(const Block &block, const double bedding_dip_deg)
  {
    const double a = bedding_dip_deg * M_PI / 180.;
    const Point  d(std::cos(a), std::sin(a));
    double       lo = 1e300, hi = -1e300;
    for (const Point &p : block.polygon.vertices)
      {
        lo = std::min(lo, d.dot(p));
        hi = std::max(hi, d.dot(p));
      }
    return hi - lo;
  }



  namespace
  {
    /// Parameters t in (0, 1) where segment (a, b) crosses polygon edges.
    void
    add_crossings(const Point         &a,
                  const Point         &b,
                  const Polygon       &poly,
                  std::vector<double> &ts)
    {
      const Point       r = b - a;
      const std::size_t n = poly.vertices.size();
      for (std::size_t i = 0; i < n; ++i)
        {
          const Point &p     = poly.vertices[i];
          const Point  s     = poly.vertices[(i + 1) % n] - p;
          const double denom = r.x() * s.y() - r.y() * s.x();
          if (denom == 0.)
            continue;
          const Point  q = p - a;
          const double t = (q.x() * s.y() - q.y() * s.x()) / denom;
          const double u = (q.x() * r.y() - q.y() * r.x()) / denom;
          if (t > 0. && t < 1. && u >= 0. && u <= 1.)
            ts.push_back(t);
        }
    }

    bool
    in_rock(const Point                &p,
            const Polygon              &domain,
            const std::vector<Polygon> &excavations)
    {
      if (!domain.contains(p))
        return false;
      for (const Polygon &e : excavations)
        if (e.contains(p))
          return false;
      return true;
    }

    double
    median(std::vector<double> v)
    {
      if (v.empty())
        return 0.;
      std::sort(v.begin(), v.end());
      const std::size_t n = v.size();
      return n % 2 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
    }

    double
    mean(const std::vector<double> &v)
    {
      return v.empty() ? 0.
                       : std::accumulate(v.begin(), v.end(), 0.) / v.size();
    }
  } // namespace



  std::vector<std::pair<double, double>>
  clip_to_rock(const Point                &a,
               const Point                &b,
               const Polygon              &domain,
               const std::vector<Polygon> &excavations)
  {
    std::vector<double> ts = {0., 1.};
    add_crossings(a, b, domain, ts);
    for (const Polygon &e : excavations)
      add_crossings(a, b, e, ts);
    std::sort(ts.begin(), ts.end());
    std::vector<std::pair<double, double>> pieces;
    for (std::size_t i = 0; i + 1 < ts.size(); ++i)
      {
        if (!(ts[i + 1] > ts[i]))
          continue;
        const Point m = a + 0.5 * (ts[i] + ts[i + 1]) * (b - a);
        if (!in_rock(m, domain, excavations))
          continue;
        if (!pieces.empty() && pieces.back().second == ts[i])
          pieces.back().second = ts[i + 1];
        else
          pieces.emplace_back(ts[i], ts[i + 1]);
      }
    return pieces;
  }



  StructureStatistics
  compute_statistics(const BlockSet                   &blocks,
                     const std::vector<TaggedSegment> &traces,
                     const Polygon                    &domain,
                     const std::vector<Polygon>       &excavations,
                     const double                      bedding_dip_deg,
                     const unsigned int                n_scan_lines)
  {
    StructureStatistics s;
    s.n_blocks = blocks.blocks.size();
    for (const Block &b : blocks.blocks)
      {
        s.areas.push_back(b.polygon.area());
        s.widths.push_back(block_width(b, bedding_dip_deg));
      }
    s.mean_area    = mean(s.areas);
    s.median_area  = median(s.areas);
    s.mean_width   = mean(s.widths);
    s.median_width = median(s.widths);

    s.rock_area = domain.area();
    for (const Polygon &e : excavations)
      s.rock_area -= e.area();

    double joint_length = 0., all_length = 0.;
    for (const TaggedSegment &t : traces)
      {
        double length = 0.;
        for (const auto &[t0, t1] : clip_to_rock(t.a, t.b, domain, excavations))
          length += (t1 - t0) * (t.b - t.a).norm();
        all_length += length;
        if (t.tag.kind == EdgeKind::joint)
          joint_length += length;
      }
    s.p21_joints = joint_length / s.rock_area;
    s.p21_all    = all_length / s.rock_area;

    // P10: crossings of each trace with each scan line, inside the rock.
    const Eigen::Vector4d box = domain.bounding_box();
    for (const bool horizontal : {true, false})
      {
        double       line_length = 0.;
        unsigned int crossings   = 0;
        for (unsigned int i = 0; i < n_scan_lines; ++i)
          {
            const double f = (i + 0.5) / n_scan_lines;
            Point        a, b;
            if (horizontal)
              {
                const double y = box[1] + f * (box[3] - box[1]);
                a              = Point(box[0] - 1., y);
                b              = Point(box[2] + 1., y);
              }
            else
              {
                const double x = box[0] + f * (box[2] - box[0]);
                a              = Point(x, box[1] - 1.);
                b              = Point(x, box[3] + 1.);
              }
            for (const auto &[t0, t1] : clip_to_rock(a, b, domain, excavations))
              line_length += (t1 - t0) * (b - a).norm();
            const Point r = b - a;
            for (const TaggedSegment &t : traces)
              {
                const Point  s2    = t.b - t.a;
                const double denom = r.x() * s2.y() - r.y() * s2.x();
                if (denom == 0.)
                  continue;
                const Point  q = t.a - a;
                const double u = (q.x() * r.y() - q.y() * r.x()) / denom;
                const double v = (q.x() * s2.y() - q.y() * s2.x()) / denom;
                if (u < 0. || u > 1. || v < 0. || v > 1.)
                  continue;
                if (in_rock(a + v * r, domain, excavations))
                  ++crossings;
              }
          }
        (horizontal ? s.p10_horizontal : s.p10_vertical)
          = line_length > 0. ? crossings / line_length : 0.;
      }
    return s;
  }
} // namespace rockdda::structure
