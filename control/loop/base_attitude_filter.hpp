// The orientation of a floating base from its IMU's gyroscope fused with a reference orientation
// (docs/loop.md, "The cycle"): an explicit complementary filter on SO(3) (Mahony, Hamel & Pflimlin,
// "Nonlinear complementary filters on the special orthogonal group", IEEE TAC 2008, eq. 32):
//
//   R̂⁻ = R̂ Exp((ω_gyro − b̂) T)         predicted with the gyro over the sample period T
//   e   = Log(R̂⁻ᵀ R_ref)                error to the reference of the same instant, base axes
//   R̂   = R̂⁻ Exp(k_p e T)               pulled towards the reference
//   b̂  ← b̂ − k_i e T                   the gyro bias, the error's integral
//
// The gyro carries the fast motion (smooth, but its bias integrates into drift); the reference
// carries the slow part (drift-free, but noisy or stepwise): the orientation of the ground
// contacts' kinematic fit while the robot stands on them, the IMU's own attitude output (with a
// lower gain) while it does not. Error dynamics ë + k_p ė + k_i e = 0 for a constant bias: with
// k_p = 10/s and k_i = k_p²/4 = 25/s² (critical damping) the error and the bias estimate settle
// within about 1 s (e(t) ∝ t e^{−5t}).
// Plain arithmetic: noexcept, allocation-free.
#pragma once

#include <Eigen/Core>
#include <Eigen/Geometry>

namespace mrqp::loop {

struct AttitudeFilterGains {
  double kp_contacts = 10.0;  ///< 1/s: pull towards the contacts' orientation
  double kp_imu = 1.0;        ///< 1/s: pull towards the IMU's attitude output (no ground contact)
  double ki = 25.0;           ///< 1/s²: gyro-bias learning (with the contacts' reference only)
  double max_bias = 0.2;      ///< rad/s: the bias estimate is clamped to this per axis
};

class BaseAttitudeFilter {
 public:
  explicit BaseAttitudeFilter(const AttitudeFilterGains& gains = AttitudeFilterGains{}) noexcept
      : gains_(gains) {}

  /// Starts from a known orientation of the base in the world (the bias estimate is cleared).
  void reset(const Eigen::Quaterniond& world_base) noexcept;
  bool initialised() const noexcept { return initialised_; }

  /// One sample: the gyro's rate in base axes (rad/s), the sample period T (s), and the reference
  /// orientation of the base in the world, from the contacts (`from_contacts`) or from the IMU.
  void update(const Eigen::Vector3d& gyro_base, double period, const Eigen::Quaterniond& reference,
              bool from_contacts) noexcept;

  const Eigen::Quaterniond& orientation() const noexcept { return q_; }
  /// The gyro's rate with the bias estimate removed (base axes): the base's angular velocity.
  const Eigen::Vector3d& rate() const noexcept { return rate_; }
  const Eigen::Vector3d& bias() const noexcept { return bias_; }

 private:
  AttitudeFilterGains gains_;
  Eigen::Quaterniond q_ = Eigen::Quaterniond::Identity();
  Eigen::Vector3d bias_ = Eigen::Vector3d::Zero();
  Eigen::Vector3d rate_ = Eigen::Vector3d::Zero();
  bool initialised_ = false;
};

/// Log of SO(3) as a rotation vector (the axis times the angle in [0, π]).
Eigen::Vector3d rotationLog(const Eigen::Quaterniond& q) noexcept;
/// Exp of SO(3): the rotation by |w| about w.
Eigen::Quaterniond rotationExp(const Eigen::Vector3d& w) noexcept;

}  // namespace mrqp::loop
