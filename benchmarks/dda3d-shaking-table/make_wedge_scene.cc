/**
 * @file
 * Write the block file of a tetrahedral wedge in its clamped V-shaped
 * trough (dda3d::make_wedge_in_trough(), doc/block-file-format-dda3d.md):
 * the thesis's shaking-table wedge by default (joints 51.4/065.8 and
 * 51.4/295.2, Bakun-Mazor 2011 Sec. 4.6; Table 4-1's E = 200 GPa,
 * nu = 0.25, rho = 1700 kg/m^3), with a measurement point at the wedge's
 * centroid.
 *
 *   make_wedge_scene OUT.blocks [phi_deg [height_m [slope_dip slope_dd
 *                    [j1_dip j1_dd j2_dip j2_dd [margin_m]]]]]
 *
 * Defaults: phi = 26.76 deg (the angle that makes 0.14 g critical, as the
 * thesis chose its friction angle), height 0.1 m below a slope face
 * 80/000.5 (the wedge is about 0.2 m long, as the 13 x 20 cm model), a
 * trough 0.3 m longer than the wedge on every side: the wedge stays on it
 * for the whole 0.17 m of the 20 s record. (The trough was once only the
 * height, 0.1 m, longer: from about 16 s the wedge's toe ran off its end,
 * and at dt = 1 ms it jammed on the trough's end edges.)
 */
#include <rockdda/dda3d/block_file.h>
#include <rockdda/dda3d/generators.h>
#include <rockdda/io/error.h>

#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <iostream>
#include <string>

using namespace rockdda;
using namespace rockdda::dda3d;

int
main(int argc, char **argv)
{
  if (argc < 2)
    {
      std::cerr << "usage: make_wedge_scene OUT.blocks [phi_deg [height_m "
                   "[slope_dip slope_dd [j1_dip j1_dd j2_dip j2_dd "
                   "[margin_m]]]]]\n";
      return 2;
    }
  auto arg = [&](const int k, const double fallback) {
    return argc > k ? std::atof(argv[k]) : fallback;
  };
  const double phi = arg(2, 26.76), height = arg(3, 0.1);
  const double slope_dip = arg(4, 80.), slope_dd = arg(5, 0.5);
  const double j1 = arg(6, 51.4), d1 = arg(7, 65.8), j2 = arg(8, 51.4),
               d2 = arg(9, 295.2), margin = arg(10, 0.3);
  try
    {
      const WedgeInTrough w
        = make_wedge_in_trough({j1, d1, j2, d2, slope_dip, slope_dd},
                               height,
                               margin);
      dda::JointMaterial joint;
      joint.friction_deg = phi;
      const BlockSystem s
        = wedge_in_trough_scene(w, {1700., 2e11, 0.25, 1}, joint);
      std::ofstream out(argv[1]);
      char          head[512];
      std::snprintf(head,
                    sizeof(head),
                    "# Wedge on joints %g/%05.1f and %g/%05.1f (phi = %g "
                    "deg), height %g m below a slope face %g/%05.1f, in "
                    "its clamped trough (blocks 1, 2); written by "
                    "benchmarks/dda3d-shaking-table/make_wedge_scene\n",
                    j1,
                    d1,
                    j2,
                    d2,
                    phi,
                    height,
                    slope_dip,
                    slope_dd);
      out << head << block_text(s);
      if (!out)
        throw InputError(std::string("cannot write '") + argv[1] + "'");
    }
  catch (const std::exception &e)
    {
      std::cerr << "make_wedge_scene: " << e.what() << '\n';
      return 1;
    }
  return 0;
}
