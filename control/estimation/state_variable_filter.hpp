// A second-order low-pass state-variable filter of a vector signal (Butterworth, ζ = 1/√2):
//
//   ÿ = ω² (u − y) − 2 ζ ω ẏ,   ω = 2π f_c,
//
// discretised exactly for a zero-order-hold input at the sample period T (e^{A T} by scaling and
// squaring at construction). It gives the filtered signal y and its exact derivative ẏ: filtering
// an entity's velocity gives a filtered acceleration without differencing noisy samples, and the
// same filter applied to the positions and to the measured generalised force keeps every term of
// Y(q, q̇, q̈) φ = μ delayed alike (docs/estimation.md). Real-time: step() is noexcept and
// allocation-free; the size is fixed at construction.
#pragma once

#include <Eigen/Core>

namespace mrqp::estimation {

class StateVariableFilter {
 public:
  /// `size` signals sampled every `period` s, corner `cutoff_hz`. Throws std::invalid_argument
  /// for a size < 1, a non-positive period or a cutoff not below half the sample rate.
  StateVariableFilter(int size, double period, double cutoff_hz);

  /// Starts at rest at u (y = u, ẏ = 0).
  void reset(const Eigen::Ref<const Eigen::VectorXd>& u) noexcept;
  /// One sample: the input held over the next period. The first call after construction resets.
  void step(const Eigen::Ref<const Eigen::VectorXd>& u) noexcept;

  const Eigen::VectorXd& value() const noexcept { return y_; }
  const Eigen::VectorXd& derivative() const noexcept { return yd_; }
  /// The discrete transition: [y; ẏ]_{k+1} = A [y; ẏ]_k + B u_k (per component).
  const Eigen::Matrix2d& transition() const noexcept { return A_; }
  const Eigen::Vector2d& input() const noexcept { return B_; }

 private:
  Eigen::Matrix2d A_;
  Eigen::Vector2d B_;
  Eigen::VectorXd y_, yd_, tmp_;
  bool started_ = false;
};

}  // namespace mrqp::estimation
