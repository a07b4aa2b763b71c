// The noise and bias of the plant section (docs/mujoco.md) applied to what a sensor reads: the
// emulated firmware passes the plant's true value through here. Gaussian noise from one seeded
// generator per object (deterministic runs), constant bias. Real-time: noexcept, allocation-free.
#pragma once

#include <cstdint>
#include <random>

#include "loop/plant.hpp"
#include "sim/plant_spec.hpp"

namespace mrqp::sim {

class SensorNoise {
 public:
  SensorNoise(const SensorNoiseSpec& spec, std::uint64_t seed) : spec_(spec), rng_(seed) {}

  double jointPosition(double q) noexcept { return apply(spec_.joint_position, q); }
  double jointVelocity(double v) noexcept { return apply(spec_.joint_velocity, v); }
  double jointTorque(double t) noexcept { return apply(spec_.joint_torque, t); }
  /// (force; torque) of an F/T sensor.
  loop::Vector6d wrench(const loop::Vector6d& w) noexcept {
    loop::Vector6d out;
    for (int i = 0; i < 3; ++i) {
      out(i) = apply(spec_.force, w(i));
      out(i + 3) = apply(spec_.torque, w(i + 3));
    }
    return out;
  }
  /// Gyro and accelerometer; the orientation is passed through.
  loop::ImuSample imu(const loop::ImuSample& s) noexcept {
    loop::ImuSample out = s;
    for (int i = 0; i < 3; ++i) {
      out.angular_velocity(i) = apply(spec_.gyro, s.angular_velocity(i));
      out.specific_force(i) = apply(spec_.accelerometer, s.specific_force(i));
    }
    return out;
  }

 private:
  double apply(const NoiseSpec& n, double x) noexcept {
    return n.stddev > 0.0 ? x + n.bias + n.stddev * normal_(rng_) : x + n.bias;
  }

  SensorNoiseSpec spec_;
  std::mt19937_64 rng_;
  std::normal_distribution<double> normal_{0.0, 1.0};
};

}  // namespace mrqp::sim
