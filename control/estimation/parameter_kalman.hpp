// The discrete Kalman filter of paper 1, eq. 52–59, on constant parameters observed linearly:
//   φ_k = φ_{k−1} + w_k,  w ~ N(0, Q)        (52)
//   μ_k = Y_k φ_k + v_k,   v ~ N(0, R)        (53)
// Predict:  φ⁻_k = φ_{k−1},  P⁻_k = P_{k−1} + Q
// Update:   L = P⁻ Yᵀ (Y P⁻ Yᵀ + R)⁻¹,  φ_k = φ⁻ + L (μ − Y φ⁻),
//           P_k = (1 − L Y) P⁻ (1 − L Y)ᵀ + L R Lᵀ   (Joseph form, then symmetrised)
// This is the standard recursion from the previous a-posteriori values; the paper's eq. 55–56
// write the previous a-priori ones, which would discard every update. The Joseph form keeps P
// symmetric positive semi-definite under rounding where eq. 59's (1 − L Y) P⁻ does not.
//
// Sizes (p parameters, m observations) are fixed at construction; update() is allocation-free.
#pragma once

#include <Eigen/Cholesky>
#include <Eigen/Core>

namespace mrqp::estimation {

class ParameterKalman {
 public:
  ParameterKalman(int parameters, int observations);

  int parameterCount() const noexcept { return static_cast<int>(phi_.size()); }
  int observationCount() const noexcept { return static_cast<int>(S_.rows()); }

  /// Initial estimate and covariance (P0 symmetric positive definite).
  void reset(const Eigen::Ref<const Eigen::VectorXd>& phi0,
             const Eigen::Ref<const Eigen::MatrixXd>& P0) noexcept;
  /// Diagonal of Q (process noise per parameter and update).
  void setProcessNoise(const Eigen::Ref<const Eigen::VectorXd>& q_diagonal) noexcept { q_ = q_diagonal; }

  /// One predict + update with observation matrix Y (m × p), observation μ (m) and its
  /// covariance R (m × m, symmetric positive definite). Returns false, leaving the state as it
  /// was, when an input is not finite or the innovation covariance is not positive definite.
  bool update(const Eigen::Ref<const Eigen::MatrixXd>& Y, const Eigen::Ref<const Eigen::VectorXd>& mu,
              const Eigen::Ref<const Eigen::MatrixXd>& R) noexcept;

  /// Replaces the estimate (after a projection onto a constraint set); the covariance is kept.
  void setEstimate(const Eigen::Ref<const Eigen::VectorXd>& phi) noexcept { phi_ = phi; }

  const Eigen::VectorXd& estimate() const noexcept { return phi_; }
  const Eigen::MatrixXd& covariance() const noexcept { return P_; }
  /// Normalised innovation squared of the last accepted update (χ² with m degrees of freedom when
  /// the filter is consistent).
  double lastNis() const noexcept { return nis_; }

 private:
  Eigen::VectorXd phi_, q_, innovation_, solved_;
  Eigen::MatrixXd P_, Pprior_, YP_, S_, L_, A_, AP_, LR_;
  Eigen::LLT<Eigen::MatrixXd> llt_;
  double nis_ = 0.0;
};

}  // namespace mrqp::estimation
