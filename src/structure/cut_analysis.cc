/**
 * @file
 * Analysis type "cut": generate the rock structure of the "Structure"
 * section, cut it into blocks and write the block file, VTU, structure
 * statistics and quick-look plots.
 */
#include <rockdda/io/error.h>
#include <rockdda/io/parameters.h>
#include <rockdda/io/plot.h>
#include <rockdda/structure/analyses.h>
#include <rockdda/structure/block_output.h>
#include <rockdda/structure/statistics.h>
#include <rockdda/structure/structure_model.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <sstream>

namespace rockdda::structure
{
  namespace
  {
    /// Histogram of @p values in @p bins equal bins over [0, max].
    io::Table
    histogram(const std::vector<double> &values,
              const unsigned int         bins,
              const std::string         &name,
              const std::string         &unit)
    {
      io::Table t;
      t.add_column(name + "_from", unit);
      t.add_column(name + "_to", unit);
      t.add_column("blocks", "-");
      t.add_column("fraction", "-");
      const double top
        = values.empty() ? 1. : *std::max_element(values.begin(), values.end());
      std::vector<double> count(bins, 0.);
      for (const double v : values)
        count[std::min<std::size_t>(bins - 1, std::size_t(v / top * bins))]
          += 1.;
      for (unsigned int i = 0; i < bins; ++i)
        t.add_row({top * i / bins,
                   top * (i + 1) / bins,
                   count[i],
                   values.empty() ? 0. : count[i] / values.size()});
      return t;
    }

    /// The "cut" analysis.
    class CutAnalysis : public io::Analysis
    {
    public:
      std::string
      name() const override
      {
        return "cut";
      }

      std::string
      description() const override
      {
        return "generate joint traces / a layered network and cut them into "
               "blocks (block file, VTU, structure statistics)";
      }

      void
      declare_parameters(dealii::ParameterHandler &prm) const override
      {
        using namespace dealii::Patterns;
        declare_structure_parameters(prm);
        prm.enter_subsection("Cut");
        io::declare(prm,
                    "Histogram bins",
                    "20",
                    Integer(1, 1000),
                    "-",
                    "Number of bins of the block width and area histograms.");
        io::declare(prm,
                    "Scan lines",
                    "10",
                    Integer(1, 10000),
                    "-",
                    "Number of horizontal and of vertical scan lines for "
                    "P10.");
        io::declare(prm,
                    "Plots",
                    "true",
                    Bool(),
                    "-",
                    "Draw blocks.png and histograms.png with "
                    "scripts/plot_structure.py (/usr/bin/python3 and "
                    "matplotlib); skipped with a note if unavailable.");
        io::declare(prm,
                    "Write traces",
                    "true",
                    Bool(),
                    "-",
                    "Write the generated traces to traces.csv.");
        io::declare(prm,
                    "Fixed blocks",
                    "none",
                    Selection("none|bottom|sides|bottom-and-sides"),
                    "-",
                    "Blocks written as fixed ('fixed-block') in blocks.dda: "
                    "those with an edge on the domain boundary facing down "
                    "(bottom: outward normal within 45 deg of -y), sideways "
                    "(sides: within 45 deg of +-x), or both; plus those in "
                    "'Fixed region'.");
        io::declare(prm,
                    "Fixed region",
                    "",
                    Anything(),
                    "m",
                    "Optional polygon 'x, y; x, y; x, y' (m): blocks whose "
                    "centroid lies inside it are fixed too. Empty: none.");
        io::declare(prm,
                    "Write DDA parameter file",
                    "true",
                    Bool(),
                    "-",
                    "Write dda.prm beside blocks.dda: a 'dda' run of the cut "
                    "blocks (dynamic, 1 s, automatic penalty) that runs as "
                    "it stands: 'rockdda OUTPUT/dda.prm'.");
        io::declare(prm,
                    "DDA end time",
                    "1",
                    io::DoubleInterval::positive(),
                    "s",
                    "End time written to dda.prm. Must be > 0.");
        prm.leave_subsection();
      }

      void
      parse_parameters(dealii::ParameterHandler &prm,
                       const std::string        &prm_file) override
      {
        model = parse_structure(prm, prm_file);
        prm.enter_subsection("Cut");
        bins                    = prm.get_integer("Histogram bins");
        scan_lines              = prm.get_integer("Scan lines");
        plots                   = prm.get_bool("Plots");
        write_traces            = prm.get_bool("Write traces");
        const std::string fixed = prm.get("Fixed blocks");
        fix_bottom = fixed == "bottom" || fixed == "bottom-and-sides";
        fix_sides  = fixed == "sides" || fixed == "bottom-and-sides";
        const std::string region = prm.get("Fixed region");
        fixed_region             = {};
        if (region.find_first_not_of(" \t") != std::string::npos)
          fixed_region
            = parse_polygon(region, prm_file + ": key 'Cut/Fixed region'");
        write_dda_prm = prm.get_bool("Write DDA parameter file");
        dda_end_time  = prm.get_double("DDA end time");
        prm.leave_subsection();
      }

      void
      run(io::RunContext &context) override
      {
        auto &log = context.log;
        log.line("random seed " + std::to_string(model.seed));
        const TraceNetwork net = generate_traces(model);
        log.line("generated " + std::to_string(net.traces.size()) + " traces ("
                 + std::to_string(net.layers.bedding.size())
                 + " bedding planes, "
                 + std::to_string(net.layers.thicknesses.size()) + " beds)");

        const auto     start    = std::chrono::steady_clock::now();
        const BlockSet blocks   = build_blocks(model, net);
        const double   cut_time = std::chrono::duration<double>(
                                  std::chrono::steady_clock::now() - start)
                                  .count();
        const double area_sum = blocks.total_block_area()
                                + blocks.excavated_area + blocks.dropped_area;
        const double area_error
          = std::abs(area_sum - blocks.domain_area) / blocks.domain_area;
        log.line("cut " + std::to_string(blocks.blocks.size()) + " blocks in "
                 + io::format_number(cut_time, 3) + " s; "
                 + std::to_string(blocks.n_dangling_edges)
                 + " dangling edges removed, "
                 + std::to_string(blocks.n_holes_split) + " holes split, "
                 + std::to_string(blocks.n_slivers_merged) + " slivers merged, "
                 + std::to_string(blocks.n_slivers_dropped) + " dropped, "
                 + std::to_string(blocks.n_slivers_remaining)
                 + " remaining (tests failed: area "
                 + std::to_string(blocks.n_slivers_by_area) + ", width "
                 + std::to_string(blocks.n_slivers_by_width) + ", angle "
                 + std::to_string(blocks.n_slivers_by_angle)
                 + "); area balance error " + io::format_number(area_error, 3));
        if (blocks.blocks.empty())
          log.line("WARNING: no blocks (is everything excavated?)");

        const double dip = model.layered ? model.layers.bedding_dip : 0.;
        const StructureStatistics s = compute_statistics(
          blocks, net.traces, model.domain, model.excavations, dip, scan_lines);

        // Thin blocks that no sliver test caught: flagged, not changed.
        {
          const double median = s.median_width;
          unsigned int thin   = 0;
          std::string  names;
          for (std::size_t i = 0; i < s.widths.size(); ++i)
            {
              const double w = blocks.blocks[i].polygon.min_width();
              if (w < 0.2 * median)
                {
                  if (++thin <= 5)
                    names += " " + std::to_string(i) + " ("
                             + io::format_number(w, 3) + " m)";
                }
            }
          if (thin > 0)
            log.line("WARNING: " + std::to_string(thin)
                     + " blocks are narrower than 0.2 x the median block "
                       "width "
                     + io::format_number(median, 3) + " m:" + names
                     + (thin > 5 ? " ..." : "")
                     + "; set 'Structure/Cutting/Sliver width' to merge "
                       "them into a neighbour");
        }

        // Files.
        const std::vector<std::size_t> fixed
          = boundary_blocks(blocks, fix_bottom, fix_sides, fixed_region);
        if (fix_bottom || fix_sides || !fixed_region.vertices.empty())
          log.line("fixed " + std::to_string(fixed.size()) + " blocks");
        context.output.write("blocks.txt", block_file_text(blocks));
        context.output.write("blocks.dda", dda_block_file_text(blocks, fixed));
        if (write_dda_prm)
          context.output.write("dda.prm", dda_parameter_file(fixed.size()));
        context.output.write("blocks.vtu", blocks_vtu(blocks, dip));
        context.output.write("edges.vtu", edges_vtu(blocks));
        io::Table per_block;
        per_block.add_column("block", "-");
        per_block.add_column("area", "m^2");
        per_block.add_column("width", "m");
        per_block.add_column("centroid_x", "m");
        per_block.add_column("centroid_y", "m");
        per_block.add_column("vertices", "-");
        per_block.add_column("min_angle", "deg");
        for (std::size_t i = 0; i < blocks.blocks.size(); ++i)
          {
            const Polygon &p = blocks.blocks[i].polygon;
            const Point    c = p.centroid();
            per_block.add_row({double(i),
                               s.areas[i],
                               s.widths[i],
                               c.x(),
                               c.y(),
                               double(p.vertices.size()),
                               p.min_interior_angle() * 180. / M_PI});
          }
        context.output.write("statistics.csv", per_block.csv());
        context.output.write("width_histogram.csv",
                             histogram(s.widths, bins, "width", "m").csv());
        context.output.write("area_histogram.csv",
                             histogram(s.areas, bins, "area", "m^2").csv());
        if (model.layered)
          {
            io::Table beds;
            beds.add_column("bed", "-");
            beds.add_column("bottom", "m");
            beds.add_column("thickness", "m");
            for (std::size_t k = 0; k < net.layers.thicknesses.size(); ++k)
              beds.add_row({double(k),
                            net.layers.bedding_offsets[k],
                            net.layers.thicknesses[k]});
            context.output.write("beds.csv", beds.csv());
          }
        if (write_traces)
          {
            io::Table t;
            t.add_column("x0", "m");
            t.add_column("y0", "m");
            t.add_column("x1", "m");
            t.add_column("y1", "m");
            t.add_column("kind", "-");
            t.add_column("set", "-");
            for (const TaggedSegment &g : net.traces)
              t.add_row({g.a.x(),
                         g.a.y(),
                         g.b.x(),
                         g.b.y(),
                         double(int(g.tag.kind)),
                         double(g.tag.set)});
            context.output.write("traces.csv", t.csv());
          }

        auto &sum = context.summary;
        sum.add("random_seed", double(model.seed), "-");
        sum.add("traces", double(net.traces.size()), "-");
        sum.add("beds", double(net.layers.thicknesses.size()), "-");
        sum.add("blocks", double(blocks.blocks.size()), "-");
        sum.add("domain_area", blocks.domain_area, "m^2");
        sum.add("block_area", blocks.total_block_area(), "m^2");
        sum.add("excavated_area", blocks.excavated_area, "m^2");
        sum.add("dropped_area", blocks.dropped_area, "m^2");
        sum.add("area_balance_error", area_error, "-");
        sum.add("mean_block_area", s.mean_area, "m^2");
        sum.add("median_block_area", s.median_area, "m^2");
        sum.add("mean_block_width", s.mean_width, "m");
        sum.add("median_block_width", s.median_width, "m");
        sum.add("p21_joints", s.p21_joints, "1/m");
        sum.add("p21_all", s.p21_all, "1/m");
        sum.add("p10_horizontal", s.p10_horizontal, "1/m");
        sum.add("p10_vertical", s.p10_vertical, "1/m");
        sum.add("dangling_edges", blocks.n_dangling_edges, "-");
        sum.add("holes_split", blocks.n_holes_split, "-");
        sum.add("slivers_merged", blocks.n_slivers_merged, "-");
        sum.add("slivers_dropped", blocks.n_slivers_dropped, "-");
        sum.add("slivers_remaining", blocks.n_slivers_remaining, "-");
        sum.add("slivers_by_area", blocks.n_slivers_by_area, "-");
        sum.add("slivers_by_width", blocks.n_slivers_by_width, "-");
        sum.add("slivers_by_angle", blocks.n_slivers_by_angle, "-");
        sum.add("fixed_blocks", double(fixed.size()), "-");
        sum.add("degenerate_dropped", blocks.n_degenerate_dropped, "-");
        sum.add("cut_time", cut_time, "s");

        if (plots)
          io::run_plot_script(context.output,
                              log,
                              "plot_structure.py",
                              {"blocks.png", "histograms.png"});
      }

    private:
      /// A 'dda' parameter file for blocks.dda in the same folder.
      std::string
      dda_parameter_file(const std::size_t n_fixed) const
      {
        std::ostringstream s;
        s << "# Written by 'rockdda cut': a dynamic DDA run of the cut "
             "blocks in\n# blocks.dda (same folder). Run: rockdda dda.prm\n"
          << "# Materials and joints are in blocks.dda; " << n_fixed
          << " blocks are fixed there\n# (Cut/Fixed blocks, Cut/Fixed "
             "region). Every key: rockdda --print-parameters.\n"
          << "set Analysis type    = dda\n"
          << "set Output directory = output-dda\n"
          << "subsection DDA\n"
          << "  set Block file      = blocks.dda\n"
          << "  set End time        = " << dda_end_time << "\n"
          << "  set Time step       = 0.001\n"
          << "  set Dynamic control = 1\n"
          << "  set Contact penalty = auto\n"
          << "  set Output interval = " << dda_end_time / 10. << "\n"
          << "end\n";
        return s.str();
      }

      StructureModel model;
      unsigned int   bins = 20, scan_lines = 10;
      bool           plots = true, write_traces = true;
      bool           fix_bottom = false, fix_sides = false;
      Polygon        fixed_region;
      bool           write_dda_prm = true;
      double         dda_end_time  = 1.;
    };
  } // namespace



  std::vector<std::unique_ptr<io::Analysis>>
  make_analyses()
  {
    std::vector<std::unique_ptr<io::Analysis>> list;
    list.push_back(std::make_unique<CutAnalysis>());
    return list;
  }
} // namespace rockdda::structure
