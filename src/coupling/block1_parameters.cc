#include <rockdda/coupling/block1_parameters.h>
#include <rockdda/io/output.h>
#include <rockdda/io/parameters.h>

#include <deal.II/base/utilities.h>

namespace rockdda::coupling
{
  std::vector<double>
  number_list(dealii::ParameterHandler &prm, const std::string &key)
  {
    std::vector<double> v;
    for (const auto &s : dealii::Utilities::split_string_list(prm.get(key)))
      v.push_back(dealii::Utilities::string_to_double(s));
    return v;
  }



  void
  declare_block1_geometry_keys(dealii::ParameterHandler &prm)
  {
    using io::DoubleInterval;
    const Block1Geometry  g;
    const Block1Materials m;
    const auto num = [](const double x) { return io::format_number(x, 12); };
    io::declare(prm,
                "Block length",
                num(g.length),
                DoubleInterval::positive(),
                "m",
                "Horizontal length L_B of Block 1's base, > 0 m.");
    io::declare(prm,
                "Block height",
                num(g.height),
                DoubleInterval::positive(),
                "m",
                "Height H of Block 1's front (downslope) face, > 0 m; the "
                "back face is H - L_B tan(slope) high (area as in thesis Eq. "
                "5.3; the ratchet model of 'compare' takes it as H).");
    io::declare(prm,
                "Slope",
                num(g.slope_deg),
                DoubleInterval::right_open(0., 45.),
                "deg",
                "Dip of the bedding plane, 0 <= slope < 45 deg.");
    io::declare(prm,
                "Friction angle",
                num(m.friction_deg),
                DoubleInterval::right_open(0., 90.),
                "deg",
                "Friction angle of the bedding plane, 0 <= phi < 90 deg "
                "(thesis: 41 deg).");
  }



  void
  parse_block1_geometry_keys(dealii::ParameterHandler &prm,
                             Block1Geometry           &geometry,
                             Block1Materials          &materials)
  {
    geometry.length        = prm.get_double("Block length");
    geometry.height        = prm.get_double("Block height");
    geometry.slope_deg     = prm.get_double("Slope");
    materials.friction_deg = prm.get_double("Friction angle");
  }



  void
  declare_block1_keys(dealii::ParameterHandler &prm, const std::string &name)
  {
    using io::DoubleInterval;
    io::declare(prm,
                "Distance",
                "1000",
                dealii::Patterns::Double(0., 1e6),
                "m",
                "Joyner-Boore distance of every event, 0 to 1e6 m (thesis: "
                "1 km, an upper bound of the displacement).");
    io::declare(prm,
                "Site amplification",
                "masada",
                dealii::Patterns::Selection("masada|none"),
                "-",
                "Topographic amplification multiplied into the target "
                "spectrum of the synthetic motions: masada (modes at 1.3, 3.8 "
                "and 6.5 Hz, cut at 10 Hz; SiteAmplification::masada()) or "
                "none.");
    declare_block1_geometry_keys(prm);
    io::declare(prm,
                "Penalty",
                "1e11",
                DoubleInterval::positive(),
                "N/m",
                "Normal contact penalty of DDA, > 0 N/m (calibrate: best "
                "100 GN/m; thesis 500 GN/m).");
    io::declare(prm,
                "Time step",
                "0.005",
                DoubleInterval::positive(),
                "s",
                "DDA time step, > 0 s (thesis and calibrate: 0.005 s).");
    io::declare(prm,
                "Threads",
                "0",
                dealii::Patterns::Integer(0, 256),
                "-",
                "DDA runs at once, 0 to 256 (0: one per core); each run's "
                "linear solver uses one thread.");
    io::declare(prm,
                "Plot",
                "true",
                dealii::Patterns::Bool(),
                "-",
                "Write " + name + ".png (scripts/plot_" + name + ".py).");
  }



  Block1Keys
  parse_block1_keys(dealii::ParameterHandler &prm)
  {
    Block1Keys k;
    parse_block1_geometry_keys(prm, k.geometry, k.materials);
    k.penalty     = prm.get_double("Penalty");
    k.dt          = prm.get_double("Time step");
    k.threads     = prm.get_integer("Threads");
    k.distance    = prm.get_double("Distance");
    k.masada_site = prm.get("Site amplification") == "masada";
    k.plot        = prm.get_bool("Plot");
    return k;
  }
} // namespace rockdda::coupling
