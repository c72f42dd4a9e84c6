/**
 * @file
 * The parameter keys that the analyses running Block 1 in DDA share
 * ('earthquakes', 'compare'): the block's geometry and friction, and DDA's
 * penalty, time step and concurrent runs, declared and read in the current
 * subsection of a ParameterHandler.
 */
#ifndef ROCKDDA_COUPLING_BLOCK1_PARAMETERS_H
#define ROCKDDA_COUPLING_BLOCK1_PARAMETERS_H

#include <rockdda/coupling/block1_seismic.h>

#include <deal.II/base/parameter_handler.h>

#include <string>
#include <vector>

namespace rockdda::coupling
{
  /// The numbers of the comma-separated list key @p key (its pattern has
  /// checked them).
  std::vector<double>
  number_list(dealii::ParameterHandler &prm, const std::string &key);

  /**
   * Declare 'Block length', 'Block height', 'Slope' and 'Friction angle'
   * (Block1Geometry and Block1Materials defaults) in the current
   * subsection ('calibrate', and declare_block1_keys()).
   */
  void
  declare_block1_geometry_keys(dealii::ParameterHandler &prm);

  /// Read the keys of declare_block1_geometry_keys() into @p geometry and
  /// @p materials (other members unchanged).
  void
  parse_block1_geometry_keys(dealii::ParameterHandler &prm,
                             Block1Geometry           &geometry,
                             Block1Materials          &materials);

  /**
   * Declare 'Distance' and 'Site amplification' of the events, 'Block
   * length', 'Block height', 'Slope', 'Friction angle' (Block1Geometry and
   * Block1Materials defaults), 'Penalty', 'Time step', 'Threads' (the
   * calibrated 100 GN/m and 0.005 s; 0 threads = one per core) and 'Plot'
   * (write @p name.png with scripts/plot_@p name.py) in the current
   * subsection.
   */
  void
  declare_block1_keys(dealii::ParameterHandler &prm, const std::string &name);

  /// What declare_block1_keys() declared, read from the current subsection.
  struct Block1Keys
  {
    Block1Geometry  geometry;
    Block1Materials materials;
    double          penalty = 1e11, dt = 0.005;
    unsigned int    threads = 0;
    /// Joyner-Boore distance of the events (m); Masada site or none.
    double distance    = 1e3;
    bool   masada_site = true;
    bool   plot        = true;
  };

  /// Read the keys of declare_block1_keys() from the current subsection.
  Block1Keys
  parse_block1_keys(dealii::ParameterHandler &prm);
} // namespace rockdda::coupling

#endif
