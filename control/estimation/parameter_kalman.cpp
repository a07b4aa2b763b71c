// Kalman filter on constant parameters (see the header for the equations).
#include "estimation/parameter_kalman.hpp"

#include <stdexcept>

namespace mrqp::estimation {

ParameterKalman::ParameterKalman(int parameters, int observations)
    : phi_(Eigen::VectorXd::Zero(parameters)),
      q_(Eigen::VectorXd::Zero(parameters)),
      innovation_(observations),
      solved_(observations),
      P_(Eigen::MatrixXd::Identity(parameters, parameters)),
      Pprior_(parameters, parameters),
      YP_(observations, parameters),
      S_(observations, observations),
      L_(parameters, observations),
      A_(parameters, parameters),
      AP_(parameters, parameters),
      LR_(parameters, observations),
      llt_(observations) {
  if (parameters <= 0 || observations <= 0)
    throw std::invalid_argument("ParameterKalman: parameter and observation counts must be positive");
}

void ParameterKalman::reset(const Eigen::Ref<const Eigen::VectorXd>& phi0,
                            const Eigen::Ref<const Eigen::MatrixXd>& P0) noexcept {
  phi_ = phi0;
  P_ = P0;
}

bool ParameterKalman::update(const Eigen::Ref<const Eigen::MatrixXd>& Y,
                             const Eigen::Ref<const Eigen::VectorXd>& mu,
                             const Eigen::Ref<const Eigen::MatrixXd>& R) noexcept {
  if (Y.rows() != S_.rows() || Y.cols() != phi_.size() || mu.size() != S_.rows() || R.rows() != S_.rows() ||
      R.cols() != S_.rows())
    return false;
  if (!Y.allFinite() || !mu.allFinite() || !R.allFinite()) return false;
  // Predict (eq. 52 with the previous a-posteriori values).
  Pprior_ = P_;
  Pprior_.diagonal() += q_;
  // Innovation covariance S = Y P⁻ Yᵀ + R.
  YP_.noalias() = Y * Pprior_;
  S_ = R;
  S_.noalias() += YP_ * Y.transpose();
  llt_.compute(S_);
  if (llt_.info() != Eigen::Success) return false;
  // Gain Lᵀ = S⁻¹ Y P⁻ (eq. 57; S and P⁻ symmetric).
  llt_.matrixL().solveInPlace(YP_);
  llt_.matrixU().solveInPlace(YP_);
  L_ = YP_.transpose();
  // Estimate (eq. 58).
  innovation_ = mu;
  innovation_.noalias() -= Y * phi_;
  solved_ = innovation_;
  llt_.matrixL().solveInPlace(solved_);
  nis_ = solved_.squaredNorm();
  phi_.noalias() += L_ * innovation_;
  // Covariance, Joseph form (eq. 59 made numerically safe).
  A_.setIdentity();
  A_.noalias() -= L_ * Y;
  AP_.noalias() = A_ * Pprior_;
  P_.noalias() = AP_ * A_.transpose();
  LR_.noalias() = L_ * R;
  P_.noalias() += LR_ * L_.transpose();
  A_ = 0.5 * (P_ + P_.transpose());
  P_ = A_;
  return true;
}

}  // namespace mrqp::estimation
