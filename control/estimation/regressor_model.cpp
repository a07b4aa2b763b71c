// The free rigid body's regressor model (see the header).
#include "estimation/regressor_model.hpp"

#include <Eigen/Geometry>

#include "estimation/rigid_body_regressor.hpp"

namespace mrqp::estimation {

void FreeBodyRegressorModel::linkRegressor(const Eigen::Ref<const Eigen::VectorXd>& q,
                                           const Eigen::Ref<const Eigen::VectorXd>& v,
                                           const Eigen::Ref<const Eigen::VectorXd>& a,
                                           Eigen::Ref<Eigen::MatrixXd> Y) noexcept {
  const Eigen::Quaterniond orientation(q(3), q(4), q(5), q(6));
  const Eigen::Matrix3d R = orientation.normalized().toRotationMatrix();
  Vector6d acc = a.head<6>();
  acc.tail<3>() -= R.transpose() * gravity_;
  BodyRegressor Yb;
  rigidBodyRegressor(v.head<6>(), acc, Yb);
  Y = Yb;
}

}  // namespace mrqp::estimation
