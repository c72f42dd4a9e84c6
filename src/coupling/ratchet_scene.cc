#include <rockdda/coupling/ratchet_scene.h>
#include <rockdda/io/error.h>

#include <cmath>
#include <string>

namespace rockdda::coupling
{
  namespace
  {
    using geometry::Point;

    constexpr double pi = 3.14159265358979323846;

    /// Joint materials of the scene.
    enum Joint : int
    {
      bedding = 0,
      bonded  = 1,
      crack   = 2
    };

    /**
     * Fractions in [0, 1] of the slices of a length @p length cut at equal
     * widths within @p depth of the end at 0 (and of the end at 1 if
     * @p both_ends); the rest is one slice.
     */
    std::vector<double>
    slice_fractions(const double       length,
                    const double       depth,
                    const unsigned int n,
                    const bool         both_ends)
    {
      std::vector<double> f{0.};
      if (n == 0)
        {
          f.push_back(1.);
          return f;
        }
      const double band  = std::min(depth, both_ends ? 0.5 * length : length);
      const double width = band / n;
      for (unsigned int k = 1; k <= n; ++k)
        f.push_back(k * width / length);
      if (both_ends)
        {
          const double far = 1. - band / length;
          if (far > f.back() + 1e-9)
            f.push_back(far);
          for (unsigned int k = 1; k < n; ++k)
            f.push_back(far + k * width / length);
        }
      if (f.back() < 1. - 1e-9)
        f.push_back(1.);
      else
        f.back() = 1.;
      return f;
    }

    /// Append a DDA block with per-edge joints; returns its index.
    int
    add_block(dda::BlockSystem        &s,
              const std::vector<Point> vertices,
              const std::vector<int>   edge_joints)
    {
      dda::Block b;
      b.id               = static_cast<int>(s.blocks.size());
      b.polygon.vertices = vertices;
      b.material         = 0;
      b.joint            = bonded;
      b.edge_joints      = edge_joints;
      s.blocks.push_back(b);
      return b.id;
    }

    /// Fix block @p b at @p points (three or more, not collinear: clamped).
    void
    fix(dda::BlockSystem &s, const int b, const std::vector<Point> &points)
    {
      for (const auto &p : points)
        {
          dda::FixedPoint f;
          f.block = b;
          f.point = p;
          s.fixed_points.push_back(f);
        }
    }

    thermal::Block
    heat_block(const std::string              &name,
               const std::vector<Point>       &vertices,
               const std::vector<std::string> &tags)
    {
      thermal::Block b;
      b.name = name;
      for (const auto &v : vertices)
        b.vertices.push_back(thermal::Point2{{v[0], v[1]}});
      b.edge_tags = tags;
      return b;
    }
  } // namespace



  RatchetScene
  make_ratchet_scene(const RatchetGeometry &g, const RatchetMaterials &m)
  {
    const analytical::Block1Section &section = g.block;
    require_in_range(section.length > 0.,
                     "Ratchet/Block length",
                     section.length,
                     "> 0 m");
    require_in_range(section.height > 0.,
                     "Ratchet/Block height",
                     section.height,
                     "> 0 m");
    require_in_range(section.slope_deg >= 0. && section.slope_deg < 45.,
                     "Ratchet/Slope",
                     section.slope_deg,
                     "0 <= slope < 45 deg");
    require_in_range(g.crack_bottom_width > 0.,
                     "Ratchet/Crack bottom width",
                     g.crack_bottom_width,
                     "> 0 m (the block must not touch the cliff at the "
                     "bedding plane)");
    require_in_range(g.crack_top_width >= g.crack_bottom_width
                       && g.crack_top_width < 0.5 * section.length,
                     "Ratchet/Crack top width",
                     g.crack_top_width,
                     ">= 'Crack bottom width' (a crack that narrows "
                     "downward) and < half the block length");
    require_in_range(g.cliff_width > g.crack_top_width - g.crack_bottom_width,
                     "Ratchet/Cliff width",
                     g.cliff_width,
                     "> 'Crack top width' - 'Crack bottom width' (the lean "
                     "of the cliff's face) m");
    require_in_range(g.base_depth > 0.,
                     "Ratchet/Base depth",
                     g.base_depth,
                     "> 0 m");
    require_in_range(g.toe_length >= 0.,
                     "Ratchet/Toe length",
                     g.toe_length,
                     ">= 0 m");
    require_in_range(g.refinement_depth > 0.,
                     "Ratchet/Refinement depth",
                     g.refinement_depth,
                     "> 0 m");

    const double t  = section.tan_slope();
    const auto   yb = [&](const double x) { return -t * x; }; // bedding plane
    const double wb = g.crack_bottom_width, wt = g.crack_top_width;
    // The block is Block 1's section with its heel at the crack's bottom
    // width from the cliff's foot (the origin): back-bottom (heel),
    // front-bottom (toe), front-top, back-top. Its back face is vertical;
    // the cliff's face leans back by wt - wb over the height, from its foot
    // (0, 0) to (wb - wt, y_top), so that the crack narrows from wt at the
    // top to wb at the bedding plane.
    const std::vector<Point> corners
      = section.polygon(Point(wb, yb(wb))).vertices;
    const Point &B0 = corners[0], &F0 = corners[1], &F1 = corners[2],
                &B1    = corners[3];
    const double y_top = F1[1];
    if (!(section.back_height() > 0.1 * section.height))
      throw InputError("key 'Ratchet/Block height' = "
                       + std::to_string(section.height)
                       + " m is too low for the block length and slope: the "
                         "back face (H - L_B tan(slope)) would be shorter "
                         "than 10 % of it");
    // The cliff's face at height y (a line through (0, 0) and
    // (wb - wt, y_top)).
    const auto cliff_face
      = [&](const double y) { return (wb - wt) * y / y_top; };

    RatchetScene scene;
    scene.downslope     = section.downslope();
    dda::BlockSystem &s = scene.blocks;
    s.materials.push_back(m.rock);
    dda::JointMaterial bed;
    bed.friction_deg     = m.bedding_friction_deg;
    bed.normal_stiffness = m.bedding_normal_stiffness;
    bed.shear_stiffness  = m.bedding_shear_stiffness;
    s.joints.push_back(bed);
    // Intact rock between slices: a strength no load of the scene reaches.
    dda::JointMaterial intact;
    intact.friction_deg = 60.;
    intact.cohesion     = 1e3 * m.rock.young;
    intact.tensile      = 1e3 * m.rock.young;
    s.joints.push_back(intact);
    dda::JointMaterial cr;
    cr.friction_deg = m.crack_friction_deg;
    s.joints.push_back(cr);
    s.gravity = Point(0., -9.80665);

    // The block's slices (vertices: bottom-left, bottom-right, top-right,
    // top-left), refined near the crack face and the front face, standing
    // on the foot (if sliced).
    const auto fb
      = slice_fractions(section.length, g.refinement_depth, g.slices, true);
    const bool   foot = fb.size() > 2;
    const double hf   = foot ? g.foot_height : 0.;
    if (foot)
      require_in_range(g.foot_height > 0.
                         && g.foot_height < 0.5 * (B1[1] - B0[1]),
                       "Ratchet/Foot height",
                       g.foot_height,
                       "> 0 m and below half the back face");
    // The back face at the foot's top, and the front.
    const Point Bf = B0 + Point(0., hf);
    const Point Ff = F0 + Point(0., hf);
    for (std::size_t k = 0; k + 1 < fb.size(); ++k)
      {
        const Point p0   = Bf + fb[k] * (Ff - Bf),
                    p1   = Bf + fb[k + 1] * (Ff - Bf);
        const Point q0   = B1 + fb[k] * (F1 - B1),
                    q1   = B1 + fb[k + 1] * (F1 - B1);
        const bool first = k == 0, last = k + 2 == fb.size();
        const int  i = add_block(s,
                                {p0, p1, q1, q0},
                                {foot ? bonded : bedding,
                                 last ? bedding : bonded,
                                 bedding,
                                 first ? crack : bonded});
        scene.block_slices.push_back(i);
        scene.heat_map.index.push_back(
          static_cast<int>(scene.heat_blocks.size()));
        scene.heat_blocks.push_back(heat_block("block" + std::to_string(k),
                                               {p0, p1, q1, q0},
                                               {foot ? "interior" : "adiabatic",
                                                last ? "exposed" : "interior",
                                                "exposed",
                                                first ? "crack" : "interior"}));
        if (first)
          {
            scene.heel     = {i, 0};
            scene.back_top = {i, 3};
          }
        if (last)
          scene.toe = {i, 1};
      }
    if (foot)
      {
        const int i
          = add_block(s, {B0, F0, Ff, Bf}, {bedding, bedding, bonded, crack});
        scene.heel = {i, 0};
        scene.toe  = {i, 1};
        scene.block_slices.push_back(i);
        // For the heat solver the foot is one piece under each slice: the
        // mesh is conforming, and no polygon has collinear vertices (which
        // the heat mesher cannot split).
        scene.heat_map.index.push_back(-3);
        scene.heat_map.pieces.resize(s.blocks.size());
        for (std::size_t k = 0; k + 1 < fb.size(); ++k)
          {
            const bool first = k == 0, last = k + 2 == fb.size();
            scene.heat_map.pieces[i].push_back(
              static_cast<int>(scene.heat_blocks.size()));
            scene.heat_blocks.push_back(
              heat_block("foot" + std::to_string(k),
                         {B0 + fb[k] * (F0 - B0),
                          B0 + fb[k + 1] * (F0 - B0),
                          Bf + fb[k + 1] * (Ff - Bf),
                          Bf + fb[k] * (Ff - Bf)},
                         {"adiabatic",
                          last ? "exposed" : "interior",
                          "interior",
                          first ? "crack" : "interior"}));
          }
      }

    // The cliff's slices, from the crack face backwards; the last is fixed.
    // A slice boundary at fraction f lies at -f W on the bedding plane and
    // at (wb - wt) - f (W + wb - wt) at the top: the crack face (f = 0)
    // leans, the far side (f = 1) is vertical.
    const auto fc
      = slice_fractions(g.cliff_width, g.refinement_depth, g.slices, false);
    const double lean = wb - wt;
    for (std::size_t k = 0; k + 1 < fc.size(); ++k)
      {
        const double             xr = -fc[k] * g.cliff_width;
        const double             xl = -fc[k + 1] * g.cliff_width;
        const double             tr = lean - fc[k] * (g.cliff_width + lean);
        const double             tl = lean - fc[k + 1] * (g.cliff_width + lean);
        const std::vector<Point> v{Point(xl, yb(xl)),
                                   Point(xr, yb(xr)),
                                   Point(tr, y_top),
                                   Point(tl, y_top)};
        const bool               first = k == 0, last = k + 2 == fc.size();
        const int                i
          = add_block(s, v, {bonded, first ? crack : bonded, bonded, bonded});
        scene.cliff_slices.push_back(i);
        if (first)
          {
            scene.cliff_foot = {i, 1};
            scene.cliff_top  = {i, 2};
          }
        if (last)
          {
            fix(s, i, v);
            scene.heat_map.index.push_back(-2);
          }
        else
          scene.heat_map.index.push_back(
            static_cast<int>(scene.heat_blocks.size()));
        // The fixed slice still conducts heat: it is in the heat domain.
        scene.heat_blocks.push_back(
          heat_block("cliff" + std::to_string(k),
                     v,
                     {"adiabatic",
                      first ? "crack" : "interior",
                      "exposed",
                      last ? "adiabatic" : "interior"}));
      }

    // The infill wedge, its faces on the crack faces.
    if (g.infill)
      {
        const double ya = y_top - g.infill_top_depth;
        const double yz = ya - g.infill_height;
        require_in_range(g.infill_top_depth >= 0.
                           && g.infill_top_depth < section.height,
                         "Ratchet/Infill top depth",
                         g.infill_top_depth,
                         "0 <= depth < the block height");
        require_in_range(g.infill_height > 0. && yz > 0.,
                         "Ratchet/Infill height",
                         g.infill_height,
                         "> 0 m, and the infill must end above the bedding "
                         "plane at the cliff face (at most "
                           + std::to_string(ya) + " m high)");
        // The crack's width at height y (the block's back face is at
        // x = wb).
        const auto crack_width
          = [&](const double y) { return wb - cliff_face(y); };
        const double crack_at_top = crack_width(ya);
        double       shift        = 0.;
        if (g.infill_width > 0.)
          {
            if (g.infill_width > crack_at_top * (1. + 1e-12))
              throw InputError(
                "key 'Ratchet/Infill width' = " + std::to_string(g.infill_width)
                + " m: the infill is wider than the crack at its top ("
                + std::to_string(crack_at_top)
                + " m): it would overlap the block or the cliff");
            shift = crack_at_top - g.infill_width;
          }
        if (crack_width(yz) - shift <= 0.)
          throw InputError("key 'Ratchet/Infill width' = "
                           + std::to_string(g.infill_width)
                           + " m: the infill would taper to nothing above "
                             "its bottom; make it wider or shorter");
        // Against the cliff's face; a narrower infill leaves a gap of
        // @p shift to the block.
        const int i         = add_block(s,
                                {Point(cliff_face(yz), yz),
                                         Point(wb - shift, yz),
                                         Point(wb - shift, ya),
                                         Point(cliff_face(ya), ya)},
                                {crack, crack, crack, crack});
        s.blocks[i].joint   = crack;
        scene.infill        = i;
        scene.infill_top    = ya;
        scene.infill_bottom = yz;
        require_in_range(g.supply_distance == 0.
                           || g.supply_distance >= g.infill_height,
                         "Ratchet/Infill supply distance",
                         g.supply_distance,
                         "0 (no supply) or >= the infill height ("
                           + std::to_string(g.infill_height) + " m)");
        scene.supply_distance = g.supply_distance;
        scene.heat_map.index.push_back(-1);
      }

    // The fixed base: the bedding plane from behind the cliff to beyond
    // the toe, split in the crack (under the cliff the joint is intact).
    {
      const double             xl = -g.cliff_width, xr = F0[0] + g.toe_length;
      const double             xs = 0.5 * wb, y_low = yb(xr) - g.base_depth;
      const std::vector<Point> v{Point(xl, y_low),
                                 Point(xr, y_low),
                                 Point(xr, yb(xr)),
                                 Point(xs, yb(xs)),
                                 Point(xl, yb(xl))};
      const int                i
        = add_block(s, v, {bedding, bedding, bedding, bonded, bedding});
      scene.base = i;
      fix(s, i, {v[0], v[1], v[2]});
      scene.heat_map.index.push_back(-2);
    }
    scene.heat_map.pieces.resize(s.blocks.size());
    return scene;
  }
} // namespace rockdda::coupling
