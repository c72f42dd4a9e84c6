#include <rockdda/io/error.h>
#include <rockdda/io/output.h>
#include <rockdda/io/parameters.h>
#include <rockdda/io/text.h>
#include <rockdda/structure/structure_model.h>

#include <cmath>
#include <sstream>

namespace rockdda::structure
{
  namespace
  {
    std::string
    set_section(const unsigned int i)
    {
      return "Joint set " + std::to_string(i + 1);
    }

    bool
    blank(const std::string &s)
    {
      return s.find_first_not_of(" \t") == std::string::npos;
    }
  } // namespace



  Polygon
  parse_polygon(const std::string &text, const std::string &where)
  {
    Polygon p;
    for (const std::string &vertex : io::split_fields(text, ';'))
      {
        if (blank(vertex))
          continue;
        const auto  xy = io::split_fields(vertex, ',');
        double      x = 0., y = 0.;
        std::size_t used_x = 0, used_y = 0;
        try
          {
            if (xy.size() != 2)
              throw std::invalid_argument("");
            x = std::stod(xy[0], &used_x);
            y = std::stod(xy[1], &used_y);
          }
        catch (const std::exception &)
          {
            throw InputError(where + ": vertex '" + vertex
                             + "' is not 'x, y' (two numbers in m; vertices "
                               "separated by ';')");
          }
        if (!blank(xy[0].substr(used_x)) || !blank(xy[1].substr(used_y))
            || !std::isfinite(x) || !std::isfinite(y))
          throw InputError(where + ": vertex '" + vertex
                           + "' is not 'x, y' (two finite numbers in m)");
        p.vertices.emplace_back(x, y);
      }
    if (p.vertices.size() < 3)
      throw InputError(where
                       + ": a polygon needs at least 3 vertices 'x, y; "
                         "x, y; x, y' (m), got "
                       + std::to_string(p.vertices.size()));
    if (p.self_intersects())
      throw InputError(where
                       + ": the polygon intersects itself (or repeats a "
                         "vertex); give a simple polygon");
    if (!(p.area() > 0.))
      throw InputError(where + ": the polygon has zero area");
    p.make_counter_clockwise();
    return p;
  }



  void
  declare_structure_parameters(dealii::ParameterHandler &prm)
  {
    using namespace dealii::Patterns;
    if (prm.subsection_path_exists({"Structure"}))
      return;
    prm.enter_subsection("Structure");
    io::declare(prm,
                "Domain",
                "0, 0; 60, 0; 60, 40; 0, 40",
                Anything(),
                "m",
                "The rock domain: a simple polygon 'x1, y1; x2, y2; ...' "
                "(either orientation; x horizontal, y up).");
    io::declare(prm,
                "Excavations",
                "",
                Anything(),
                "m",
                "Openings removed from the rock: simple polygons inside the "
                "domain, 'x1, y1; x2, y2; ...', several separated by '|'. "
                "Empty for none.");
    io::declare(prm,
                "Random seed",
                "1",
                Integer(0),
                "-",
                "Seed of the random stream of every generator; the same "
                "seed gives the same network. 0 draws a seed from the clock "
                "and records it in the output parameters.prm.");
    prm.enter_subsection("Bedding");
    io::declare(prm,
                "Enabled",
                "true",
                Bool(),
                "-",
                "Generate through-going bedding planes (a mechanically "
                "layered rock mass).");
    io::declare(prm,
                "Dip",
                "0",
                Double(-90., 90.),
                "deg",
                "Apparent dip of the bedding in the section, counter-"
                "clockwise from +x.");
    io::declare(prm,
                "Thickness log10 mean",
                "0",
                Double(-3., 3.),
                "log10(m)",
                "log10 of the arithmetic mean (m) of the untruncated "
                "lognormal bed thickness law (thesis: 0, i.e. 1 m).");
    io::declare(prm,
                "Thickness log10 deviation",
                "-0.2",
                Double(-6., 3.),
                "log10(m)",
                "log10 of the arithmetic standard deviation (m) of the "
                "untruncated lognormal law (thesis: -0.2, i.e. 0.631 m).");
    io::declare(prm,
                "Minimum thickness",
                "0.7",
                io::DoubleInterval::positive(),
                "m",
                "Beds thinner than this are drawn again (truncated law). "
                "Must be > 0 and not exceed the domain's extent across the "
                "beds.");
    io::declare(prm,
                "Confined joints",
                "true",
                Bool(),
                "-",
                "Generate joints confined to each bed with median spacing "
                "thickness / FSI (joint set index 0 in the output tags).");
    io::declare(prm,
                "Fracture spacing index",
                "1.3",
                io::DoubleInterval::positive(),
                "-",
                "FSI = bed thickness / median joint spacing (Gross 1993; "
                "thesis 1.3). Must be > 0.");
    io::declare(prm,
                "Joint dip",
                "90",
                Double(-180., 180.),
                "deg",
                "Apparent dip of the confined joints, counter-clockwise from "
                "+x; must differ from the bedding dip by >= 5 deg.");
    io::declare(prm,
                "Joint spacing log deviation",
                "0.25",
                Double(0., 2.),
                "-",
                "Standard deviation of ln(spacing) of the confined joints "
                "(lognormal spacings with median thickness / FSI); 0 gives "
                "regular spacing. In [0, 2].");
    io::declare(prm,
                "Joint model",
                "2d",
                Selection("2d|3d"),
                "-",
                "'2d': confined joints placed along each bed by a renewal "
                "process (lognormal spacings); '3d': rectangular fractures "
                "normal to the bedding, spanning their bed, Poisson centres "
                "in the bed plane, cut by a vertical trace plane (FRACMAN-"
                "like, thesis Sec. 3.2). Both give median spacing thickness "
                "/ FSI along the section.");
    io::declare(prm,
                "Fracture length",
                "5",
                io::DoubleInterval::positive(),
                "m",
                "3d: mean horizontal length of the fractures (uniform in "
                "[0.5, 1.5] x this). Must be > 0.");
    io::declare(prm,
                "Fracture strike",
                "90",
                Double(-360., 360.),
                "deg",
                "3d: mean strike of the fractures, counter-clockwise from "
                "the section's x axis in plan view (90: normal to the "
                "section).");
    io::declare(prm,
                "Strike spread",
                "0",
                Double(0., 90.),
                "deg",
                "3d: strikes are uniform in mean +- this.");
    io::declare(prm,
                "Section azimuth",
                "0",
                Double(-360., 360.),
                "deg",
                "3d: azimuth of the vertical trace plane in plan view, from "
                "the same axis as the strike.");
    prm.leave_subsection();
    for (unsigned int i = 0; i < max_joint_sets; ++i)
      {
        prm.enter_subsection(set_section(i));
        io::declare(prm,
                    "Enabled",
                    "false",
                    Bool(),
                    "-",
                    "Generate this Shi & Goodman (1989) statistical joint "
                    "set.");
        io::declare(prm,
                    "Dip",
                    "90",
                    Double(-180., 180.),
                    "deg",
                    "Apparent dip of the traces in the section, counter-"
                    "clockwise from +x.");
        io::declare(prm,
                    "Mean length",
                    "5",
                    io::DoubleInterval::positive(),
                    "m",
                    "Mean trace length L. Must be > 0.");
        io::declare(prm,
                    "Mean bridge",
                    "1",
                    Double(0.),
                    "m",
                    "Mean rock bridge b between traces on a line. Must be "
                    ">= 0.");
        io::declare(prm,
                    "Mean spacing",
                    "0.54",
                    io::DoubleInterval::positive(),
                    "m",
                    "Mean spacing s between trace lines. Must be > 0.");
        io::declare(prm,
                    "Degree of randomness",
                    "0.5",
                    Double(0., 1.),
                    "-",
                    "DR in [0, 1]: L, b and s are each uniform in "
                    "[mean (1 - DR), mean (1 + DR)].");
        prm.leave_subsection();
      }
    prm.enter_subsection("Cutting");
    io::declare(prm,
                "Sliver area",
                "1e-4",
                Double(0.),
                "m^2",
                "Blocks smaller than this are slivers (0: no area test). "
                "Must be >= 0.");
    io::declare(prm,
                "Sliver width",
                "0",
                Double(0.),
                "m",
                "Blocks narrower than this are slivers (0: no width test): "
                "the smallest width over the block's edge directions (for a "
                "convex block its minimum caliper width). A 5 cm strip cut "
                "off at a domain edge is the typical case. Must be >= 0.");
    io::declare(prm,
                "Sliver angle",
                "2",
                io::DoubleInterval::right_open(0., 60.),
                "deg",
                "Blocks with an interior angle below this are slivers "
                "(0: no angle test). In [0, 60).");
    io::declare(prm,
                "Merge slivers",
                "true",
                Bool(),
                "-",
                "Merge each sliver into the neighbour across its longest "
                "shared boundary (drop it if it has none); false only "
                "reports them.");
    io::declare(prm,
                "Remove T-junction vertices",
                "true",
                Bool(),
                "-",
                "Remove every vertex where a block's boundary goes straight "
                "on (true), or keep those where another block's edge meets "
                "(false: conforming blocks).");
    prm.leave_subsection();
    prm.leave_subsection();
  }



  StructureModel
  parse_structure(dealii::ParameterHandler &prm, const std::string &prm_file)
  {
    StructureModel m;
    prm.enter_subsection("Structure");
    const std::string where = prm_file + ": key 'Structure/";
    m.domain = parse_polygon(prm.get("Domain"), where + "Domain'");
    int k    = 0;
    for (const std::string &text :
         io::split_fields(prm.get("Excavations"), '|'))
      {
        if (blank(text))
          continue;
        m.excavations.push_back(parse_polygon(text,
                                              where + "Excavations' (polygon "
                                                + std::to_string(++k) + ")"));
        for (const Point &p : m.excavations.back().vertices)
          if (!m.domain.contains(p))
            {
              // contains() is strict; accept points on the boundary.
              bool        on_boundary = false;
              const auto &v           = m.domain.vertices;
              for (std::size_t i = 0; i < v.size(); ++i)
                {
                  const Point a = v[i], b = v[(i + 1) % v.size()];
                  const Point ab = b - a, ap = p - a;
                  if (std::abs(ab.x() * ap.y() - ab.y() * ap.x())
                        <= 1e-12 * ab.squaredNorm()
                      && ap.dot(ab) >= 0. && ap.dot(ab) <= ab.squaredNorm())
                    on_boundary = true;
                }
              if (!on_boundary)
                {
                  std::ostringstream s;
                  s << where << "Excavations': polygon " << k << " has vertex ("
                    << p.x() << ", " << p.y()
                    << ") m outside the domain; excavations must lie "
                       "inside 'Structure/Domain'";
                  throw InputError(s.str());
                }
            }
      }
    long seed = prm.get_integer("Random seed");
    if (seed == 0)
      {
        seed = 1 + std::random_device()() % 2147483646;
        prm.set("Random seed", seed); // recorded in parameters.prm
      }
    m.seed = seed;

    prm.enter_subsection("Bedding");
    m.layered                = prm.get_bool("Enabled");
    m.layers.bedding_dip     = prm.get_double("Dip");
    m.layers.log10_mean      = prm.get_double("Thickness log10 mean");
    m.layers.log10_deviation = prm.get_double("Thickness log10 deviation");
    m.layers.min_thickness   = prm.get_double("Minimum thickness");
    m.layers.confined_joints = prm.get_bool("Confined joints");
    m.layers.fsi             = prm.get_double("Fracture spacing index");
    m.layers.joint_dip       = prm.get_double("Joint dip");
    m.layers.spacing_log_deviation
      = prm.get_double("Joint spacing log deviation");
    m.layers.three_d         = prm.get("Joint model") == "3d";
    m.layers.fracture_length = prm.get_double("Fracture length");
    m.layers.fracture_strike = prm.get_double("Fracture strike");
    m.layers.strike_spread   = prm.get_double("Strike spread");
    m.layers.section_azimuth = prm.get_double("Section azimuth");
    prm.leave_subsection();
    if (m.layered)
      {
        io::with_parameter_file(prm_file, [&]() {
          m.layers.check("section 'Structure/Bedding'");
        });
        const double a = m.layers.bedding_dip * M_PI / 180.;
        const Point  n(-std::sin(a), std::cos(a));
        double       lo = 1e300, hi = -1e300;
        for (const Point &p : m.domain.vertices)
          {
            lo = std::min(lo, n.dot(p));
            hi = std::max(hi, n.dot(p));
          }
        io::require(m.layers.min_thickness <= hi - lo,
                    prm_file,
                    "Structure/Bedding/Minimum thickness",
                    m.layers.min_thickness,
                    "0 < minimum thickness <= " + io::format_number(hi - lo, 6)
                      + " m (the domain's extent across the beds)");
      }

    for (unsigned int i = 0; i < max_joint_sets; ++i)
      {
        prm.enter_subsection(set_section(i));
        if (prm.get_bool("Enabled"))
          {
            JointSetParameters s;
            s.dip                  = prm.get_double("Dip");
            s.mean_length          = prm.get_double("Mean length");
            s.mean_bridge          = prm.get_double("Mean bridge");
            s.mean_spacing         = prm.get_double("Mean spacing");
            s.degree_of_randomness = prm.get_double("Degree of randomness");
            io::with_parameter_file(prm_file, [&]() {
              s.check("section 'Structure/" + set_section(i) + "'");
            });
            m.joint_sets.push_back(s);
          }
        prm.leave_subsection();
      }

    prm.enter_subsection("Cutting");
    m.cut.sliver_area          = prm.get_double("Sliver area");
    m.cut.sliver_width         = prm.get_double("Sliver width");
    const double angle         = prm.get_double("Sliver angle");
    m.cut.merge_slivers        = prm.get_bool("Merge slivers");
    m.cut.remove_all_collinear = prm.get_bool("Remove T-junction vertices");
    prm.leave_subsection();
    io::require(m.cut.sliver_area >= 0.,
                prm_file,
                "Structure/Cutting/Sliver area",
                m.cut.sliver_area,
                ">= 0 m^2");
    io::require(m.cut.sliver_width >= 0.,
                prm_file,
                "Structure/Cutting/Sliver width",
                m.cut.sliver_width,
                ">= 0 m");
    io::require(angle >= 0. && angle < 60.,
                prm_file,
                "Structure/Cutting/Sliver angle",
                angle,
                "0 <= angle < 60 deg");
    m.cut.sliver_angle = angle * M_PI / 180.;
    prm.leave_subsection();
    return m;
  }



  TraceNetwork
  generate_traces(const StructureModel &model)
  {
    TraceNetwork net;
    Random       random(model.seed);
    const auto   box = model.domain.bounding_box();
    int          set = 0;
    if (model.layered)
      {
        net.layers = generate_layered(model.layers, set, box, random);
        net.traces = net.layers.bedding;
        net.traces.insert(net.traces.end(),
                          net.layers.joints.begin(),
                          net.layers.joints.end());
        if (model.layers.confined_joints)
          ++set;
      }
    for (const JointSetParameters &s : model.joint_sets)
      {
        const auto t = generate_joint_set(s, set++, box, random);
        net.traces.insert(net.traces.end(), t.begin(), t.end());
      }
    return net;
  }



  BlockSet
  build_blocks(const StructureModel &model, const TraceNetwork &traces)
  {
    return cut_blocks(model.domain,
                      model.excavations,
                      traces.traces,
                      model.cut);
  }
} // namespace rockdda::structure
