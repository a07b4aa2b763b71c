// The floating base's orientation from gyro and reference (see base_attitude_filter.hpp).
#include "loop/base_attitude_filter.hpp"

#include <algorithm>
#include <cmath>

namespace mrqp::loop {

Eigen::Vector3d rotationLog(const Eigen::Quaterniond& q_in) noexcept {
  Eigen::Quaterniond q = q_in.normalized();
  if (q.w() < 0.0) q.coeffs() = -q.coeffs();  // the shorter way round
  const Eigen::Vector3d u = q.vec();
  const double s = u.norm();
  if (s < 1e-12) return 2.0 * u;  // first order: angle ≈ 2 s
  const double angle = 2.0 * std::atan2(s, q.w());
  return (angle / s) * u;
}

Eigen::Quaterniond rotationExp(const Eigen::Vector3d& w) noexcept {
  const double angle = w.norm();
  if (angle < 1e-12) return Eigen::Quaterniond(1.0, 0.5 * w.x(), 0.5 * w.y(), 0.5 * w.z()).normalized();
  return Eigen::Quaterniond(Eigen::AngleAxisd(angle, w / angle));
}

void BaseAttitudeFilter::reset(const Eigen::Quaterniond& world_base) noexcept {
  q_ = world_base.normalized();
  bias_.setZero();
  rate_.setZero();
  initialised_ = true;
}

void BaseAttitudeFilter::update(const Eigen::Vector3d& gyro_base, double period,
                                const Eigen::Quaterniond& reference, bool from_contacts) noexcept {
  if (!initialised_) {
    reset(reference);
    rate_ = gyro_base;
    return;
  }
  // Predict with the gyro, then pull towards the reference of the same instant.
  const double kp = from_contacts ? gains_.kp_contacts : gains_.kp_imu;
  rate_ = gyro_base - bias_;
  const Eigen::Quaterniond predicted = (q_ * rotationExp(rate_ * period)).normalized();
  const Eigen::Vector3d e = rotationLog(predicted.conjugate() * reference);
  q_ = (predicted * rotationExp(kp * period * e)).normalized();
  if (from_contacts) {
    bias_ -= gains_.ki * period * e;
    for (int k = 0; k < 3; ++k) bias_(k) = std::clamp(bias_(k), -gains_.max_bias, gains_.max_bias);
  }
}

}  // namespace mrqp::loop
