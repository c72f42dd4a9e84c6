/**
 * @file
 * Block kinematics and submatrices of 3D DDA (thesis Eqs. 2.4-2.7).
 */
#include <rockdda/dda3d/block_matrices.h>

#include <Eigen/Geometry>

#include <array>
#include <cmath>

namespace rockdda::dda3d
{
  namespace
  {
    /**
     * T = T0 + sum_k X_k Tk[k]: the constant part and the coefficient of
     * each coordinate of thesis Eq. 2.5.
     */
    struct LinearT
    {
      Matrix3x12                T0 = Matrix3x12::Zero();
      std::array<Matrix3x12, 3> Tk;
      LinearT()
      {
        T0.block<3, 3>(0, 0).setIdentity();
        for (auto &t : Tk)
          t.setZero();
        // Coefficients of X (Tk[0]), Y (Tk[1]), Z (Tk[2]); columns
        // 3 r1, 4 r2, 5 r3, 6-8 eps, 9 gamma_xy, 10 gamma_yz, 11 gamma_zx.
        auto &X = Tk[0], &Y = Tk[1], &Z = Tk[2];
        Y(0, 3)  = -1.;
        X(1, 3)  = 1.;
        Z(1, 4)  = -1.;
        Y(2, 4)  = 1.;
        Z(0, 5)  = 1.;
        X(2, 5)  = -1.;
        X(0, 6)  = 1.;
        Y(1, 7)  = 1.;
        Z(2, 8)  = 1.;
        Y(0, 9)  = 0.5;
        X(1, 9)  = 0.5;
        Z(1, 10) = 0.5;
        Y(2, 10) = 0.5;
        Z(0, 11) = 0.5;
        X(2, 11) = 0.5;
      }
    };

    const LinearT &
    linear_t()
    {
      static const LinearT t;
      return t;
    }
  } // namespace



  Matrix3x12
  displacement_matrix(const Point &centroid, const Point &point)
  {
    const auto &t = linear_t();
    const Point X = point - centroid;
    return t.T0 + X.x() * t.Tk[0] + X.y() * t.Tk[1] + X.z() * t.Tk[2];
  }



  Matrix12
  mass_matrix(const PolyhedronMoments &m, const double rho)
  {
    const auto &t = linear_t();
    Matrix12    M = m.volume * t.T0.transpose() * t.T0;
    for (int k = 0; k < 3; ++k)
      for (int l = 0; l < 3; ++l)
        M += m.second(k, l) * t.Tk[k].transpose() * t.Tk[l];
    return rho * M;
  }



  Matrix6
  elasticity_matrix(const Material &mat)
  {
    const double E = mat.young, nu = mat.poisson;
    const double lambda = E * nu / ((1. + nu) * (1. - 2. * nu));
    const double mu     = E / (2. * (1. + nu));
    Matrix6      C      = Matrix6::Zero();
    C.block<3, 3>(0, 0).setConstant(lambda);
    for (int i = 0; i < 3; ++i)
      {
        C(i, i) += 2. * mu;
        C(3 + i, 3 + i) = mu;
      }
    return C;
  }



  Point
  rotation_vector(const Vector12 &d)
  {
    return Point(d[4], d[5], d[3]);
  }



  Eigen::Matrix3d
  rotation_matrix(const Point &w)
  {
    const double angle = w.norm();
    if (angle == 0.)
      return Eigen::Matrix3d::Identity();
    return Eigen::AngleAxisd(angle, w / angle).toRotationMatrix();
  }



  Point
  move_point(const Point &c, const Vector12 &d, const Point &p)
  {
    const Point     X = p - c;
    Eigen::Matrix3d E;
    E << d[6], 0.5 * d[9], 0.5 * d[11], 0.5 * d[9], d[7], 0.5 * d[10],
      0.5 * d[11], 0.5 * d[10], d[8];
    const Point S = X + E * X;
    return c + d.head<3>() + rotation_matrix(rotation_vector(d)) * S;
  }



  Vector12
  body_force(const PolyhedronMoments &m, const double rho, const Point &a)
  {
    Vector12 F  = Vector12::Zero();
    F.head<3>() = rho * m.volume * a;
    return F;
  }



  Vector12
  point_load(const Point &centroid, const Point &point, const Point &f)
  {
    return displacement_matrix(centroid, point).transpose() * f;
  }



  Matrix12
  fixed_point_stiffness(const Point &centroid,
                        const Point &point,
                        const double p)
  {
    const Matrix3x12 T = displacement_matrix(centroid, point);
    return p * T.transpose() * T;
  }



  Vector6
  rotate_voigt(const Vector6 &v, const Eigen::Matrix3d &R, const double f)
  {
    Eigen::Matrix3d S;
    S << v[0], f * v[3], f * v[5], f * v[3], v[1], f * v[4], f * v[5], f * v[4],
      v[2];
    const Eigen::Matrix3d Sr = R * S * R.transpose();
    Vector6               out;
    out << Sr(0, 0), Sr(1, 1), Sr(2, 2), Sr(0, 1) / f, Sr(1, 2) / f,
      Sr(0, 2) / f;
    return out;
  }
} // namespace rockdda::dda3d
