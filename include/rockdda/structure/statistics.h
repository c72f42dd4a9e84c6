/**
 * @file
 * Structure statistics of a cut block system: block count, area and width
 * distributions, joint intensity P21 and P10 along scan lines.
 */
#ifndef ROCKDDA_STRUCTURE_STATISTICS_H
#define ROCKDDA_STRUCTURE_STATISTICS_H

#include <rockdda/structure/block_set.h>

#include <vector>

namespace rockdda::structure
{
  /**
   * Block width as used for layered rock (thesis Figs. 3-5 and 3-6): the
   * extent (m) of the block along the bedding direction (dip @p
   * bedding_dip_deg, counter-clockwise from +x), i.e. the length of the
   * beam segment a block forms within its layer.
   */
  double
  block_width(const Block &block, const double bedding_dip_deg);

  /**
   * The part of segment (a, b) inside the rock: inside @p domain and outside
   * every excavation. Returns the pieces as parameter intervals [t0, t1] of
   * a + t (b - a), t in [0, 1].
   */
  std::vector<std::pair<double, double>>
  clip_to_rock(const Point                &a,
               const Point                &b,
               const Polygon              &domain,
               const std::vector<Polygon> &excavations);

  /// The structure statistics of one block system.
  struct StructureStatistics
  {
    std::size_t         n_blocks = 0;
    std::vector<double> areas;                              ///< per block, m^2
    std::vector<double> widths;                             ///< per block, m
    double              mean_area = 0., median_area = 0.;   ///< m^2
    double              mean_width = 0., median_width = 0.; ///< m
    double              rock_area = 0.; ///< domain minus excavations, m^2
    double p21_joints = 0.; ///< joint trace length per rock area, 1/m
    double p21_all    = 0.; ///< all traces incl. bedding, 1/m
    double p10_horizontal
      = 0.;                   ///< traces crossed per m of horizontal scan line
    double p10_vertical = 0.; ///< traces crossed per m of vertical scan line
  };

  /**
   * Statistics of @p blocks cut from @p traces (joints and bedding) in
   * @p domain minus @p excavations. P21 counts the traces' length inside the
   * rock. P10 uses @p n_scan_lines evenly spaced horizontal and as many
   * vertical scan lines across the domain's bounding box, counting trace
   * crossings inside the rock per metre of scan line inside the rock.
   */
  StructureStatistics
  compute_statistics(const BlockSet                   &blocks,
                     const std::vector<TaggedSegment> &traces,
                     const Polygon                    &domain,
                     const std::vector<Polygon>       &excavations,
                     const double                      bedding_dip_deg,
                     const unsigned int                n_scan_lines);
} // namespace rockdda::structure

#endif
