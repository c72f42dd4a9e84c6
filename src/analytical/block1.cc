#include <rockdda/analytical/block1.h>
#include <rockdda/io/output.h>

#include <cmath>

namespace rockdda::analytical
{
  namespace
  {
    constexpr double pi = 3.14159265358979323846;

    /// eta in radians, as slope * pi / 180 (the seismic scene's arithmetic
    /// before the section was shared, so that its runs are unchanged to the
    /// last bit).
    double
    radians(const double degrees)
    {
      return degrees * pi / 180.;
    }
  } // namespace



  double
  Block1Section::tan_slope() const
  {
    return std::tan(radians(slope_deg));
  }



  double
  Block1Section::back_height() const
  {
    return height - length * tan_slope();
  }



  double
  Block1Section::area() const
  {
    return length * (height - 0.5 * length * tan_slope());
  }



  geometry::Polygon
  Block1Section::polygon(const geometry::Point &heel) const
  {
    const geometry::Point toe
      = heel + geometry::Point(length, -length * tan_slope());
    geometry::Polygon p;
    p.vertices = {heel,
                  toe,
                  toe + geometry::Point(0., height),
                  heel + geometry::Point(0., back_height())};
    return p;
  }



  geometry::Point
  Block1Section::downslope() const
  {
    return geometry::Point(std::cos(radians(slope_deg)),
                           -std::sin(radians(slope_deg)));
  }



  std::string
  block1_default(double Block1Section::*member)
  {
    return io::format_number(Block1Section().*member, 12);
  }
} // namespace rockdda::analytical
