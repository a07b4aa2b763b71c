// The second-order state-variable filter (see state_variable_filter.hpp).
#include "estimation/state_variable_filter.hpp"

#include <Eigen/LU>

#include <cmath>
#include <stdexcept>

namespace mrqp::estimation {

namespace {

/// e^{M} of a 2 × 2 matrix: scaling and squaring with a Taylor series.
Eigen::Matrix2d expm2(const Eigen::Matrix2d& M) {
  int squarings = 0;
  double norm = M.cwiseAbs().rowwise().sum().maxCoeff();
  while (norm > 0.125) {
    norm *= 0.5;
    ++squarings;
  }
  const Eigen::Matrix2d S = M / std::ldexp(1.0, squarings);
  Eigen::Matrix2d term = Eigen::Matrix2d::Identity(), sum = Eigen::Matrix2d::Identity();
  for (int k = 1; k <= 16; ++k) {
    term = term * S / static_cast<double>(k);
    sum += term;
  }
  for (int i = 0; i < squarings; ++i) sum = sum * sum;
  return sum;
}

}  // namespace

StateVariableFilter::StateVariableFilter(int size, double period, double cutoff_hz) {
  if (size < 1) throw std::invalid_argument("state-variable filter: size must be at least 1");
  if (!(period > 0.0) || !std::isfinite(period))
    throw std::invalid_argument("state-variable filter: the period must be positive");
  if (!(cutoff_hz > 0.0) || !(cutoff_hz < 0.5 / period))
    throw std::invalid_argument(
        "state-variable filter: the cutoff must lie between 0 and half the sample rate");
  const double w = 2.0 * M_PI * cutoff_hz;
  const double zeta = std::sqrt(0.5);
  Eigen::Matrix2d Ac;
  Ac << 0.0, 1.0, -w * w, -2.0 * zeta * w;
  const Eigen::Vector2d Bc(0.0, w * w);
  A_ = expm2(Ac * period);
  B_ = Ac.inverse() * (A_ - Eigen::Matrix2d::Identity()) * Bc;  // ∫₀ᵀ e^{A s} ds B
  y_ = Eigen::VectorXd::Zero(size);
  yd_ = Eigen::VectorXd::Zero(size);
  tmp_ = Eigen::VectorXd::Zero(size);
}

void StateVariableFilter::reset(const Eigen::Ref<const Eigen::VectorXd>& u) noexcept {
  y_ = u;
  yd_.setZero();
  started_ = true;
}

void StateVariableFilter::step(const Eigen::Ref<const Eigen::VectorXd>& u) noexcept {
  if (!started_) {
    reset(u);
    return;
  }
  tmp_ = A_(0, 0) * y_ + A_(0, 1) * yd_ + B_(0) * u;
  yd_ = A_(1, 0) * y_ + A_(1, 1) * yd_ + B_(1) * u;
  y_ = tmp_;
}

}  // namespace mrqp::estimation
