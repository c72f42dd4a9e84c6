/**
 * @file
 * A 3D DDA scene held in coordinates relative to a local origin, with the
 * time and the positions a stepper reports (shared by FreeBlocks and
 * Engine).
 */
#ifndef ROCKDDA_DDA3D_LOCAL_SCENE_H
#define ROCKDDA_DDA3D_LOCAL_SCENE_H

#include <rockdda/dda3d/block_system.h>

#include <cstddef>

namespace rockdda::dda3d
{
  /**
   * A block system moved to a local origin, the lower corner of its
   * bounding box, on construction: a scene far from the origin (UTM) then
   * computes with coordinates of the scene's own size. The subtraction is
   * exact (Sterbenz: the coordinates are within a factor 2 of the
   * corner's). Positions returned here are global. Not validated here:
   * the stepper that derives from it validates the moved scene.
   */
  class LocalScene
  {
  public:
    /// Keep @p system, moved to its local origin.
    explicit LocalScene(BlockSystem system);

    /// Time (s).
    double
    time() const
    {
      return t;
    }

    /// The scene in local coordinates (add origin() for global ones).
    const BlockSystem &
    scene() const
    {
      return system;
    }

    /// The local origin (m).
    const Point &
    origin() const
    {
      return origin_;
    }

    /// Global position of the centroid of block @p b (m).
    Point
    centroid(const std::size_t b) const;

    /// Displacement of the centroid of block @p b since t = 0 (m).
    Point
    displacement(const std::size_t b) const;

    /// Global position of measurement point @p m (m).
    Point
    measurement_point(const std::size_t m) const;

  protected:
    BlockSystem system;
    Point       origin_ = Point::Zero();
    double      t       = 0.;
  };
} // namespace rockdda::dda3d

#endif
