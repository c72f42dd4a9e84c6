/**
 * @file
 * The analysis types of the analytical subsystem (sliding blocks, yield
 * acceleration, rate-and-state friction, back-analysis, the analytical
 * thermal ratchet) as the driver sees
 * them, and the shared "Friction" parameter section.
 */
#ifndef ROCKDDA_ANALYTICAL_ANALYSES_H
#define ROCKDDA_ANALYTICAL_ANALYSES_H

#include <rockdda/analytical/friction.h>
#include <rockdda/io/analysis.h>

#include <memory>
#include <vector>

namespace rockdda::analytical
{
  /// The analyses of this subsystem, for io::all_analyses().
  std::vector<std::unique_ptr<io::Analysis>>
  make_analyses();

  namespace internal
  {
    /// Factories of the individual analyses (one source file each).
    std::unique_ptr<io::Analysis>
    make_newmark_analysis();
    std::unique_ptr<io::Analysis>
    make_sliding3d_analysis();
    std::unique_ptr<io::Analysis>
    make_yield_analysis();
    std::unique_ptr<io::Analysis>
    make_rate_state_analysis();
    std::unique_ptr<io::Analysis>
    make_back_analysis();
    std::unique_ptr<io::Analysis>
    make_ratchet_analytical_analysis();
  } // namespace internal

  /// Declare the shared "Friction" section (once; later calls do nothing).
  void
  declare_friction_parameters(dealii::ParameterHandler &prm);

  /**
   * Read the "Friction" section's rate dependence into a law whose reference
   * coefficient is tan(@p phi_deg). Throws InputError naming @p prm_file and
   * the key for out-of-range values (phi must be in [0, 90) deg).
   */
  FrictionLaw
  parse_friction(dealii::ParameterHandler &prm,
                 const std::string        &prm_file,
                 const double              phi_deg,
                 const std::string        &phi_key);
} // namespace rockdda::analytical

#endif
