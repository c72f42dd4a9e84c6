/**
 * @file
 * Block kinematics and submatrices of 2D DDA (Shi 1988, ch. 2).
 */
#include <rockdda/dda/block_matrices.h>

#include <Eigen/Eigenvalues>

#include <algorithm>
#include <cmath>

namespace rockdda::dda
{
  double
  block_size(const geometry::Polygon &polygon)
  {
    geometry::Point mean = geometry::Point::Zero();
    for (const auto &v : polygon.vertices)
      mean += v;
    mean /= static_cast<double>(polygon.vertices.size());
    double r = 0.;
    for (const auto &v : polygon.vertices)
      r = std::max(r, (v - mean).norm());
    return 2. * r;
  }



  std::vector<char>
  clamped_blocks(const BlockSystem &system)
  {
    const std::size_t    n = system.blocks.size();
    std::vector<Matrix6> fit(n, Matrix6::Zero());
    std::vector<int>     n_points(n, 0);
    for (const auto &f : system.fixed_points)
      {
        const auto T = displacement_matrix(
          block_moments(system.blocks[f.block].polygon).centroid, f.point);
        fit[f.block] += T.transpose() * T;
        ++n_points[f.block];
      }
    std::vector<char> clamped(n, 0);
    for (std::size_t b = 0; b < n; ++b)
      {
        if (n_points[b] < 3)
          continue;
        // Rotation and strain columns (lengths) divided by the block size:
        // a dimensionless rank test.
        Vector6 scale = Vector6::Ones();
        scale.tail<4>().setConstant(1. / block_size(system.blocks[b].polygon));
        const Matrix6 A = scale.asDiagonal() * fit[b] * scale.asDiagonal();
        const Eigen::SelfAdjointEigenSolver<Matrix6> eig(A);
        clamped[b]
          = eig.eigenvalues().minCoeff() > 1e-8 * eig.eigenvalues().maxCoeff();
      }
    return clamped;
  }



  BlockMoments
  block_moments(const geometry::Polygon &polygon)
  {
    // Triangle fan from the first vertex (keeps round-off small for blocks
    // far from the origin); exact for straight edges.
    BlockMoments      m;
    const auto       &v = polygon.vertices;
    const std::size_t n = v.size();
    if (n < 3)
      return m;
    const geometry::Point o = v[0];
    double a = 0., sx = 0., sy = 0., sxx = 0., syy = 0., sxy = 0.;
    for (std::size_t k = 1; k + 1 < n; ++k)
      {
        const geometry::Point p  = v[k] - o;
        const geometry::Point q  = v[k + 1] - o;
        const double          at = 0.5 * (p.x() * q.y() - q.x() * p.y());
        a += at;
        sx += at * (p.x() + q.x()) / 3.;
        sy += at * (p.y() + q.y()) / 3.;
        sxx += at * (p.x() * p.x() + p.x() * q.x() + q.x() * q.x()) / 6.;
        syy += at * (p.y() * p.y() + p.y() * q.y() + q.y() * q.y()) / 6.;
        sxy += at
               * (2. * p.x() * p.y() + p.x() * q.y() + q.x() * p.y()
                  + 2. * q.x() * q.y())
               / 12.;
      }
    m.area = a;
    if (a == 0.)
      return m;
    const double xc = sx / a, yc = sy / a;
    m.centroid = o + geometry::Point(xc, yc);
    m.sxx      = sxx - a * xc * xc;
    m.syy      = syy - a * yc * yc;
    m.sxy      = sxy - a * xc * yc;
    return m;
  }



  Eigen::Matrix<double, 2, 6>
  displacement_matrix(const geometry::Point &centroid,
                      const geometry::Point &point)
  {
    const double                X = point.x() - centroid.x();
    const double                Y = point.y() - centroid.y();
    Eigen::Matrix<double, 2, 6> T;
    T << 1., 0., -Y, X, 0., 0.5 * Y, 0., 1., X, 0., Y, 0.5 * X;
    return T;
  }



  Matrix6
  mass_matrix(const BlockMoments &m, const double rho)
  {
    // rho * integral T^T T dA about the centroid (first moments vanish).
    const double a = m.area, xx = m.sxx, yy = m.syy, xy = m.sxy;
    Matrix6      M = Matrix6::Zero();
    M(0, 0)        = a;
    M(1, 1)        = a;
    M(2, 2)        = xx + yy;
    M(2, 3)        = -xy;
    M(2, 4)        = xy;
    M(2, 5)        = 0.5 * (xx - yy);
    M(3, 3)        = xx;
    M(3, 5)        = 0.5 * xy;
    M(4, 4)        = yy;
    M(4, 5)        = 0.5 * xy;
    M(5, 5)        = 0.25 * (xx + yy);
    for (int i = 0; i < 6; ++i)
      for (int j = 0; j < i; ++j)
        M(i, j) = M(j, i);
    return rho * M;
  }



  Eigen::Matrix3d
  elasticity_matrix(const BlockMaterial &mat)
  {
    const double    E = mat.young, nu = mat.poisson;
    Eigen::Matrix3d C = Eigen::Matrix3d::Zero();
    if (mat.plane_strain)
      {
        const double f = E / ((1. + nu) * (1. - 2. * nu));
        C << 1. - nu, nu, 0., nu, 1. - nu, 0., 0., 0., 0.5 * (1. - 2. * nu);
        C *= f;
      }
    else
      {
        const double f = E / (1. - nu * nu);
        C << 1., nu, 0., nu, 1., 0., 0., 0., 0.5 * (1. - nu);
        C *= f;
      }
    return C;
  }


  Eigen::Vector3d
  thermal_eigenstrain(const BlockMaterial &material, const double free_strain)
  {
    const double e = material.plane_strain
                       ? (1. + material.poisson) * free_strain
                       : free_strain;
    return Eigen::Vector3d(e, e, 0.);
  }



  geometry::Point
  move_point(const geometry::Point &c,
             const Vector6         &d,
             const geometry::Point &p)
  {
    const geometry::Point X = p - c;
    const geometry::Point S(X.x() + d[3] * X.x() + 0.5 * d[5] * X.y(),
                            X.y() + d[4] * X.y() + 0.5 * d[5] * X.x());
    const double          cr = std::cos(d[2]), sr = std::sin(d[2]);
    return c
           + geometry::Point(d[0] + cr * S.x() - sr * S.y(),
                             d[1] + sr * S.x() + cr * S.y());
  }
} // namespace rockdda::dda
