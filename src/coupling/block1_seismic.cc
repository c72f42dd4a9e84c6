#include <rockdda/analytical/newmark.h>
#include <rockdda/coupling/block1_seismic.h>
#include <rockdda/io/error.h>

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <stdexcept>

namespace rockdda::coupling
{
  namespace
  {
    using geometry::Point;

    constexpr double pi = 3.14159265358979323846;

    /// Cut a record after @p duration (s) (one sample beyond it kept).
    seismic::Record
    cut(const seismic::Record &record, const double duration)
    {
      seismic::Record   r = record;
      const std::size_t n
        = static_cast<std::size_t>(std::ceil(duration / record.dt - 1e-9)) + 1;
      if (r.acceleration.size() > n)
        r.acceleration.resize(n);
      return r;
    }
  } // namespace



  Block1Scene
  make_block1_seismic_scene(const Block1Geometry  &g,
                            const Block1Materials &m,
                            const std::string     &section)
  {
    require_in_range(g.length > 0.,
                     section + "/Block length",
                     g.length,
                     "> 0 m");
    require_in_range(g.height > 0.,
                     section + "/Block height",
                     g.height,
                     "> 0 m");
    require_in_range(g.slope_deg >= 0. && g.slope_deg < 45.,
                     section + "/Slope",
                     g.slope_deg,
                     "0 <= slope < 45 deg");
    require_in_range(g.toe_length > 0.,
                     section + "/Toe length",
                     g.toe_length,
                     "> 0 m");
    require_in_range(g.heel_length > 0.,
                     section + "/Heel length",
                     g.heel_length,
                     "> 0 m");
    require_in_range(g.base_depth > 0.,
                     section + "/Base depth",
                     g.base_depth,
                     "> 0 m");
    require_in_range(m.friction_deg >= 0. && m.friction_deg < 90.,
                     section + "/Friction angle",
                     m.friction_deg,
                     "0 <= friction < 90 deg");

    const double t  = g.tan_slope();
    const auto   yb = [&](const double x) { return -t * x; };
    if (!(g.back_height() > 0.1 * g.height))
      throw InputError("key '" + section
                       + "/Block height' = " + std::to_string(g.height)
                       + " m is too low for the block length and slope: the "
                         "back face would be shorter than 10 % of it");

    Block1Scene scene;
    scene.downslope     = g.downslope();
    dda::BlockSystem &s = scene.blocks;
    s.materials.push_back(m.rock);
    dda::JointMaterial bedding;
    bedding.friction_deg = m.friction_deg;
    s.joints.push_back(bedding);
    s.gravity = Point(0., -9.80665);

    // The fixed base: the bedding plane from behind the heel to beyond the
    // toe.
    const double xl = -g.heel_length, xr = g.length + g.toe_length;
    const double y_low = yb(xr) - g.base_depth;
    {
      dda::Block b;
      b.id               = 0;
      b.material         = 0;
      b.polygon.vertices = {Point(xl, y_low),
                            Point(xr, y_low),
                            Point(xr, yb(xr)),
                            Point(xl, yb(xl))};
      s.blocks.push_back(b);
      for (int k = 0; k < 3; ++k)
        {
          dda::FixedPoint f;
          f.block = 0;
          f.point = b.polygon.vertices[k];
          s.fixed_points.push_back(f);
        }
    }
    // The block: heel (at the origin), toe, front-top, back-top.
    {
      dda::Block b;
      b.id       = 1;
      b.material = 0;
      b.polygon  = g.polygon();
      s.blocks.push_back(b);
      dda::MeasurementPoint p;
      p.block = 1;
      // Just inside the block above the middle of its base.
      p.point = Point(0.5 * g.length, yb(0.5 * g.length) + 1e-3 * g.height);
      s.measurement_points.push_back(p);
    }
    scene.base       = 0;
    scene.block      = 1;
    scene.base_point = 0;
    return scene;
  }



  double
  block1_slip(const dda::DdaSystem &dda, const Block1Scene &scene)
  {
    const auto &p = dda.system().measurement_points[scene.base_point];
    return ((p.point - p.initial) - dda.centroid_displacement(scene.base))
      .dot(scene.downslope);
  }



  Block1Run
  run_block1_dda(const Block1Geometry    &geometry,
                 const Block1Materials   &materials,
                 const seismic::Record   &record,
                 const Block1RunControls &o,
                 const double             duration)
  {
    require_in_range(o.penalty > 0., o.penalty_key, o.penalty, "> 0 N/m");
    require_in_range(o.dt > 0., o.time_step_key, o.dt, "> 0 s");
    const auto start   = std::chrono::steady_clock::now();
    const auto elapsed = [&]() {
      return std::chrono::duration<double>(std::chrono::steady_clock::now()
                                           - start)
        .count();
    };

    Block1Scene scene
      = make_block1_seismic_scene(geometry, materials, o.section);
    scene.blocks.seismic.mode   = o.mode;
    scene.blocks.seismic.record = cut(record, duration + 2. * o.dt);
    scene.blocks.seismic.g      = 9.80665;

    dda::Controls c;
    c.time_step          = o.dt;
    c.dynamic            = 1.;
    c.law.normal_penalty = o.penalty;
    c.solver.threads     = 1;
    c.max_steps
      = static_cast<unsigned long>(o.max_steps_per_dt * duration / o.dt) + 1000;

    dda::DdaSystem d(scene.blocks, c);
    d.settle(o.settle_steps);
    Block1Run r;
    // run_until stops within 1e-9 dt of its end: test the end with a
    // margin above that, or a run that stops just short loops for ever.
    while (d.time() < duration - 1e-3 * o.dt)
      {
        d.run_until(std::min(duration, d.time() + o.dt));
        r.max_rotation
          = std::max(r.max_rotation,
                     std::abs(d.system().blocks[scene.block].rotation));
        if (o.wall_time_limit > 0. && elapsed() > o.wall_time_limit)
          throw std::runtime_error(
            "wall-time limit: " + std::to_string(o.wall_time_limit)
            + " s reached at t = " + std::to_string(d.time()) + " s");
        if (o.stop && o.stop())
          {
            r.stopped = true;
            break;
          }
      }
    r.slip      = block1_slip(d, scene);
    r.steps     = d.n_steps;
    r.cuts      = d.n_cuts;
    r.wall_time = elapsed();
    return r;
  }



  double
  block1_analytical_slip(const Block1Geometry  &geometry,
                         const Block1Materials &materials,
                         const seismic::Record &record,
                         const double           duration,
                         const double           time_step)
  {
    analytical::NewmarkOptions o;
    o.direction   = analytical::NewmarkOptions::Direction::two_way;
    o.yield_model = analytical::NewmarkOptions::YieldModel::plane;
    o.dip_deg     = geometry.slope_deg;
    o.friction  = analytical::FrictionLaw::coulomb_deg(materials.friction_deg);
    o.time_step = time_step;
    o.g         = 9.80665;
    // The block lags behind the ground: a ground acceleration towards +x
    // (downslope) is an inertial load upslope.
    seismic::Record input = cut(record, duration);
    for (auto &a : input.acceleration)
      a = -a;
    return analytical::newmark_sliding(input, o).final_displacement;
  }



  double
  block1_yield_acceleration(const Block1Geometry  &geometry,
                            const Block1Materials &materials)
  {
    return std::tan((materials.friction_deg - geometry.slope_deg) * pi / 180.);
  }



  double
  block1_rocking_acceleration(const Block1Geometry &g)
  {
    // The block's polygon as make_block1_seismic_scene() builds it.
    const geometry::Polygon poly = g.polygon();
    const auto             &p    = poly.vertices;
    const Point             c    = poly.centroid();
    return (p[1][0] - c[0]) / (c[1] - p[1][1]);
  }



  seismic::Record
  sinusoid_record(const double amplitude,
                  const double frequency,
                  const double duration,
                  const double dt)
  {
    seismic::Record r;
    r.name       = "sinusoid";
    r.dt         = dt;
    const auto n = static_cast<std::size_t>(std::ceil(duration / dt - 1e-9));
    for (std::size_t k = 0; k <= n; ++k)
      r.acceleration.push_back(amplitude
                               * std::sin(2. * pi * frequency * k * dt));
    return r;
  }
} // namespace rockdda::coupling
