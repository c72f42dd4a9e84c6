// Cutting-time benchmark of the exact block cutter: two Shi & Goodman joint
// sets at constant density (L = 5 m, b = 2 m, s = 1 m, DR = 0.5, dips 30
// and 120 deg) in a square domain sized for N segments, N = 1k ... 100k.
// Usage: structure_cutting_time OUTPUT_DIR [max_segments]
// Writes OUTPUT_DIR/results.csv (segments, blocks, vertices, seconds).
#include <rockdda/io/output.h>
#include <rockdda/structure/block_cutter.h>
#include <rockdda/structure/generators.h>

#include <chrono>
#include <cmath>
#include <iostream>
#include <string>

using namespace rockdda::structure;

int
main(int argc, char **argv)
{
  if (argc < 2)
    {
      std::cerr << "usage: structure_cutting_time OUTPUT_DIR [max_segments]\n";
      return 2;
    }
  const double           max_n = argc > 2 ? std::stod(argv[2]) : 1e5;
  rockdda::io::CsvWriter out;
  out.record(
    {"segments", "blocks", "vertices", "domain_side_m", "generate_s", "cut_s"});
  for (const double target : {1e3, 3e3, 1e4, 3e4, 1e5, 3e5})
    {
      if (target > max_n)
        break;
      // Segments per set ~ (W / s) (W / (L + b)): W^2 / 7 each.
      // Sets at 30 and 120 deg cover the box projected on their axes, 1.37 W
      // wide each way: (1.37 W)^2 / 7 segments per set.
      const double W = std::sqrt(3.5 * target) / 1.366;
      Polygon      domain;
      domain.vertices = {Point(0, 0), Point(W, 0), Point(W, W), Point(0, W)};
      const auto                 t0 = std::chrono::steady_clock::now();
      Random                     random(1);
      std::vector<TaggedSegment> segments;
      for (int set = 0; set < 2; ++set)
        {
          JointSetParameters p;
          p.dip          = set == 0 ? 30. : 120.;
          p.mean_length  = 5.;
          p.mean_bridge  = 2.;
          p.mean_spacing = 1.;
          const auto s
            = generate_joint_set(p, set, domain.bounding_box(), random);
          segments.insert(segments.end(), s.begin(), s.end());
        }
      const auto     t1     = std::chrono::steady_clock::now();
      const BlockSet blocks = cut_blocks(domain, {}, segments);
      const auto     t2     = std::chrono::steady_clock::now();
      const double   gen    = std::chrono::duration<double>(t1 - t0).count();
      const double   cut    = std::chrono::duration<double>(t2 - t1).count();
      out.number(segments.size()).number(blocks.blocks.size());
      out.number(blocks.vertices.size()).number(W).number(gen).number(cut);
      out.end_record();
      // Rewritten after every size (atomically), so that an interrupted
      // study keeps the sizes done.
      rockdda::io::OutputDirectory(argv[1]).write("results.csv", out.text());
      std::cout << segments.size() << " segments: " << blocks.blocks.size()
                << " blocks, cut in " << cut << " s" << std::endl;
    }
  return 0;
}
