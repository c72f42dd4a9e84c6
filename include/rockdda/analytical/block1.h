/**
 * @file
 * The cross-section of Masada Block 1 (thesis 5.2.2 and 5.4.1, Fig. 5-9,
 * Table 5-2), one definition for every model of the block: the analytical
 * thermal ratchet (Eqs. 5.3-5.5), the coupled ratchet scene, the seismic
 * calibration, the earthquake runs and the thermal-versus-seismic
 * comparison. doc/theory/block1.md explains the choice of the faces.
 */
#ifndef ROCKDDA_ANALYTICAL_BLOCK1_H
#define ROCKDDA_ANALYTICAL_BLOCK1_H

#include <rockdda/geometry/polygon.h>

#include <string>

namespace rockdda::analytical
{
  /**
   * Block 1's cross-section: a quadrilateral with a base of horizontal
   * length L_B on a bedding plane dipping eta, vertical back (upslope, the
   * tension crack) and front (downslope) faces, and a horizontal top. H is
   * the height of the front face, so the back face is H - L_B tan(eta) high
   * and the area is L_B (H - L_B tan(eta) / 2), the cross-section of thesis
   * Eq. 5.3. x is horizontal and points downslope, y up.
   */
  struct Block1Section
  {
    /// Horizontal length L_B of the base (m), > 0 (thesis: about 7 m).
    double length = 7.;
    /// Height H of the front (downslope) face (m), > 0 (thesis: 15 m).
    double height = 15.;
    /// Dip eta of the bedding plane (deg), in [0, 90) (thesis: 19 deg).
    double slope_deg = 19.;

    /// tan(eta).
    double
    tan_slope() const;

    /// Height of the back face (m): H - L_B tan(eta); the scenes need it
    /// > 0, Eq. 5.3 only needs a positive area.
    double
    back_height() const;

    /// Area (m^2 per m of width), thesis Eq. 5.3: L_B (H - L_B tan(eta) / 2).
    double
    area() const;

    /**
     * The polygon, counter-clockwise: heel (back-bottom) at @p heel, toe
     * (front-bottom) @p heel + (L_B, -L_B tan(eta)), front-top (the toe +
     * (0, H)) and back-top (@p heel + (0, H - L_B tan(eta))).
     */
    geometry::Polygon
    polygon(const geometry::Point &heel = geometry::Point(0., 0.)) const;

    /// Unit vector down the bedding plane: (cos(eta), -sin(eta)).
    geometry::Point
    downslope() const;
  };

  /// The default of Block1Section's member @p member as parameter text
  /// (12 significant digits): the one default of the 'Block length',
  /// 'Block height' and 'Slope' keys of every analysis of Block 1.
  std::string
  block1_default(double Block1Section::*member);
} // namespace rockdda::analytical

#endif
