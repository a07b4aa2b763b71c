// Rigid-body regressor: each column is the Newton–Euler wrench of one unit parameter, built from
// the spatial inertia (so the map is linear in φ by construction).
#include "estimation/rigid_body_regressor.hpp"

#include <Eigen/Geometry>

namespace mrqp::estimation {
namespace {

Eigen::Matrix3d skew(const Eigen::Vector3d& x) noexcept {
  Eigen::Matrix3d s;
  s << 0.0, -x.z(), x.y(), x.z(), 0.0, -x.x(), -x.y(), x.x(), 0.0;
  return s;
}

/// v ×* f for spatial force f (angular; linear).
Vector6d crossForce(const Vector6d& v, const Vector6d& f) noexcept {
  const Eigen::Vector3d w = v.head<3>();
  const Eigen::Vector3d vl = v.tail<3>();
  Vector6d out;
  out.head<3>() = w.cross(f.head<3>()) + vl.cross(f.tail<3>());
  out.tail<3>() = w.cross(f.tail<3>());
  return out;
}

}  // namespace

Matrix6d spatialInertiaOf(const InertialVector& phi) noexcept {
  Eigen::Matrix3d I;
  I << phi(4), phi(5), phi(7), phi(5), phi(6), phi(8), phi(7), phi(8), phi(9);
  const Eigen::Matrix3d hx = skew(phi.segment<3>(1));
  Matrix6d out;
  out.topLeftCorner<3, 3>() = I;
  out.topRightCorner<3, 3>() = hx;
  out.bottomLeftCorner<3, 3>() = hx.transpose();
  out.bottomRightCorner<3, 3>() = phi(0) * Eigen::Matrix3d::Identity();
  return out;
}

void rigidBodyRegressor(const Vector6d& v, const Vector6d& a, BodyRegressor& Y) noexcept {
  for (int k = 0; k < 10; ++k) {
    const Matrix6d I6 = spatialInertiaOf(InertialVector::Unit(k));
    Y.col(k) = I6 * a + crossForce(v, I6 * v);
  }
}

}  // namespace mrqp::estimation
