#include <rockdda/io/error.h>
#include <rockdda/structure/generators.h>

#include <algorithm>
#include <cmath>
#include <sstream>

namespace rockdda::structure
{
  namespace
  {
    // Own uniform and normal draws (not std:: distributions, whose output
    // differs between standard libraries), so a seed gives the same network
    // everywhere.
    double
    uniform01(Random &r)
    {
      return (r() >> 11) * 0x1.0p-53;
    }

    double
    normal(Random &r)
    {
      double u = uniform01(r);
      while (u <= 0.)
        u = uniform01(r);
      const double v = uniform01(r);
      return std::sqrt(-2. * std::log(u)) * std::cos(2. * M_PI * v);
    }

    double
    draw_uniform_dr(const double mean, const double dr, Random &r)
    {
      return mean * (1. + dr * (2. * uniform01(r) - 1.));
    }

    void
    fail(const std::string &where, const std::string &what)
    {
      throw InputError(where + ": " + what);
    }

    Point
    direction(const double deg)
    {
      const double a = deg * M_PI / 180.;
      return Point(std::cos(a), std::sin(a));
    }

    /// Extent of the box corners projected on @p axis: (min, max).
    std::pair<double, double>
    extent(const Eigen::Vector4d &box, const Point &axis)
    {
      double lo = 1e300, hi = -1e300;
      for (const double x : {box[0], box[2]})
        for (const double y : {box[1], box[3]})
          {
            const double p = axis.dot(Point(x, y));
            lo             = std::min(lo, p);
            hi             = std::max(hi, p);
          }
      return {lo, hi};
    }

    /// Mean of |sin(strike - azimuth + x)| for x uniform in +- spread.
    double
    mean_abs_sin(const LayeredParameters &p)
    {
      const double a0 = (p.fracture_strike - p.section_azimuth) * M_PI / 180.;
      const double sp = p.strike_spread * M_PI / 180.;
      double       m  = 0.;
      for (int i = 0; i < 256; ++i)
        m += std::abs(std::sin(a0 + sp * (2. * (i + 0.5) / 256. - 1.)));
      return m / 256.;
    }

    std::string
    number(const double x)
    {
      std::ostringstream s;
      s << x;
      return s.str();
    }
  } // namespace



  void
  JointSetParameters::check(const std::string &where) const
  {
    if (!(mean_length > 0.))
      fail(where, "mean length " + number(mean_length) + " m must be > 0 m");
    if (!(mean_bridge >= 0.))
      fail(where, "mean bridge " + number(mean_bridge) + " m must be >= 0 m");
    if (!(mean_spacing > 0.))
      fail(where, "mean spacing " + number(mean_spacing) + " m must be > 0 m");
    if (!(degree_of_randomness >= 0. && degree_of_randomness <= 1.))
      fail(where,
           "degree of randomness " + number(degree_of_randomness)
             + " must be in [0, 1]");
    if (!(std::isfinite(dip)))
      fail(where, "dip must be finite (deg)");
  }



  std::vector<TaggedSegment>
  generate_joint_set(const JointSetParameters              &set,
                     const int                              set_index,
                     const Eigen::Vector4d                 &box,
                     Random                                &random,
                     std::vector<std::vector<std::size_t>> *lines)
  {
    set.check("joint set " + std::to_string(set_index + 1));
    const Point d = direction(set.dip);
    const Point n(-d.y(), d.x());
    const auto [u0, u1] = extent(box, d);
    const auto [v0, v1] = extent(box, n);
    const double dr     = set.degree_of_randomness;
    auto L = [&] { return draw_uniform_dr(set.mean_length, dr, random); };
    auto b = [&] { return draw_uniform_dr(set.mean_bridge, dr, random); };
    auto s = [&] { return draw_uniform_dr(set.mean_spacing, dr, random); };

    std::vector<TaggedSegment> out;
    const EdgeTag              tag{EdgeKind::joint, set_index};
    for (double v = v0 - uniform01(random) * s(); v <= v1; v += s())
      {
        std::vector<std::size_t> line;
        double u = u0 - uniform01(random) * (set.mean_length + set.mean_bridge);
        while (u <= u1)
          {
            const double length = L();
            if (u + length >= u0)
              {
                line.push_back(out.size());
                out.push_back({v * n + u * d, v * n + (u + length) * d, tag});
              }
            u += length + b();
          }
        if (lines)
          lines->push_back(std::move(line));
      }
    return out;
  }



  void
  LayeredParameters::check(const std::string &where) const
  {
    if (!(min_thickness > 0.))
      fail(where,
           "minimum bed thickness " + number(min_thickness)
             + " m must be > 0 m");
    if (!std::isfinite(log10_mean) || !std::isfinite(log10_deviation)
        || log10_mean > 6. || log10_deviation > 6.)
      fail(where,
           "log10 mean and deviation of the bed thickness must be "
           "finite and <= 6 log10(m)");
    if (confined_joints)
      {
        if (!(fsi > 0.))
          fail(where, "fracture spacing index " + number(fsi) + " must be > 0");
        if (!(spacing_log_deviation >= 0. && spacing_log_deviation <= 2.))
          fail(where,
               "joint spacing log deviation " + number(spacing_log_deviation)
                 + " must be in [0, 2]");
        if (three_d)
          {
            if (!(fracture_length > 0.))
              fail(where,
                   "fracture length " + number(fracture_length)
                     + " m must be > 0 m");
            if (!(strike_spread >= 0. && strike_spread <= 90.))
              fail(where,
                   "strike spread " + number(strike_spread)
                     + " deg must be in [0, 90] deg");
            if (!(mean_abs_sin(*this) >= 0.05))
              fail(where,
                   "the fractures (strike " + number(fracture_strike)
                     + " deg) are (nearly) parallel to the trace plane "
                       "(azimuth "
                     + number(section_azimuth)
                     + " deg): they leave almost no traces");
          }
        const double angle
          = std::abs(std::sin((joint_dip - bedding_dip) * M_PI / 180.));
        if (!(angle >= std::sin(5. * M_PI / 180.)))
          fail(where,
               "joint dip " + number(joint_dip)
                 + " deg must differ from the bedding dip "
                 + number(bedding_dip) + " deg by at least 5 deg");
      }
  }



  std::pair<double, double>
  LayeredParameters::log_parameters() const
  {
    const double m      = std::pow(10., log10_mean);
    const double dev    = std::pow(10., log10_deviation);
    const double sigma2 = std::log(1. + dev * dev / (m * m));
    return {std::log(m) - 0.5 * sigma2, std::sqrt(sigma2)};
  }



  double
  draw_thickness(const LayeredParameters &p, Random &random)
  {
    const auto [mu, sigma] = p.log_parameters();
    // Rejection gives the truncated law exactly; give up if the minimum is
    // so far in the tail that rejection would not end.
    for (int attempt = 0; attempt < 100000; ++attempt)
      {
        const double t = std::exp(mu + sigma * normal(random));
        if (t >= p.min_thickness)
          return t;
      }
    throw InputError("layered network: the minimum bed thickness "
                     + number(p.min_thickness)
                     + " m lies too far in the tail of the thickness law "
                       "(acceptance below 1e-5)");
  }



  std::vector<double>
  section_crossings(const LayeredParameters &p,
                    const double             thickness,
                    const double             a_min,
                    const double             a_max,
                    Random                  &random)
  {
    const double l_max = 1.5 * p.fracture_length;
    const double rate  = p.fsi * std::log(2.) / thickness; // on the section
    const double lambda
      = rate / (p.fracture_length * mean_abs_sin(p)); // per m^2 of bed
    const double        band = l_max;                 // c in [-band/2, band/2]
    std::vector<double> out;
    // Centres: a Poisson process in [a_min - l_max, a_max + l_max] x band,
    // generated along a with exponential gaps.
    double a = a_min - l_max;
    for (;;)
      {
        double u = uniform01(random);
        while (u <= 0.)
          u = uniform01(random);
        a += -std::log(u) / (lambda * band);
        if (a > a_max + l_max)
          break;
        const double c     = band * (uniform01(random) - 0.5);
        const double l     = p.fracture_length * (0.5 + uniform01(random));
        const double theta = (p.fracture_strike - p.section_azimuth
                              + p.strike_spread * (2. * uniform01(random) - 1.))
                             * M_PI / 180.;
        const double s = std::sin(theta);
        if (s == 0. || std::abs(c) > 0.5 * l * std::abs(s))
          continue;
        const double cross = a - c * std::cos(theta) / s;
        if (cross >= a_min && cross <= a_max)
          out.push_back(cross);
      }
    std::sort(out.begin(), out.end());
    return out;
  }



  LayeredNetwork
  generate_layered(const LayeredParameters &p,
                   const int                joint_set,
                   const Eigen::Vector4d   &box,
                   Random                  &random)
  {
    p.check("layered network");
    const Point d = direction(p.bedding_dip);
    const Point n(-d.y(), d.x());
    const auto [u0, u1] = extent(box, d);
    const auto [v0, v1] = extent(box, n);
    if (p.min_thickness > v1 - v0)
      fail("layered network",
           "minimum bed thickness " + number(p.min_thickness)
             + " m exceeds the domain's extent across the beds ("
             + number(v1 - v0) + " m)");

    LayeredNetwork net;
    double         t = draw_thickness(p, random);
    double         v = v0 - uniform01(random) * t;
    for (;;)
      {
        net.bedding_offsets.push_back(v);
        if (v >= v1)
          break;
        net.thicknesses.push_back(t);
        v += t;
        t = draw_thickness(p, random);
      }
    const double margin = 1.;
    for (const double off : net.bedding_offsets)
      if (off > v0 && off < v1)
        net.bedding.push_back({off * n + (u0 - margin) * d,
                               off * n + (u1 + margin) * d,
                               {EdgeKind::bedding, 0}});
    net.joint_positions.resize(net.thicknesses.size());
    if (!p.confined_joints)
      return net;

    const Point   j   = direction(p.joint_dip);
    const double  jn  = j.dot(n); // > sin(5 deg) in magnitude
    const double  cot = std::abs(j.dot(d) / jn);
    const EdgeTag tag{EdgeKind::joint, joint_set};
    for (std::size_t k = 0; k < net.thicknesses.size(); ++k)
      {
        const double thick   = net.thicknesses[k];
        const double median  = thick / p.fsi;
        auto         spacing = [&] {
          return median * std::exp(p.spacing_log_deviation * normal(random));
        };
        const double lo    = net.bedding_offsets[k];
        const double reach = thick * cot; // horizontal reach across the bed
        std::vector<double> &positions = net.joint_positions[k];
        if (p.three_d)
          positions
            = section_crossings(p, thick, u0 - reach, u1 + reach, random);
        else
          for (double u = u0 - reach - uniform01(random) * spacing();
               u <= u1 + reach;
               u += spacing())
            positions.push_back(u);
        for (const double u : positions)
          {
            const Point  base   = lo * n + u * d;
            const double lambda = thick / jn;
            const double eps    = 1e-6;
            net.joints.push_back(
              {base - eps * lambda * j, base + (1. + eps) * lambda * j, tag});
          }
      }
    return net;
  }
} // namespace rockdda::structure
