// An emulated IMU on the plant (see plant_imu.hpp).
#include "loop/plant_imu.hpp"

#include <cmath>

#include "loop/base_attitude_filter.hpp"

namespace mrqp::loop {

namespace {
emulation::EmulatedImu::Options imuOptions(std::uint8_t node) noexcept {
  emulation::EmulatedImu::Options o;
  o.node = node;
  return o;
}
}  // namespace

PlantImu::PlantImu(drivers::SimNode& node, Plant& plant, int frame, std::uint8_t node_id)
    : node_(node), plant_(plant), frame_(frame), imu_(*this, imuOptions(node_id)), glue_(node) {
  glue_.add(imu_);
}

void PlantImu::setNoise(const ImuNoise& noise) noexcept {
  noise_ = noise;
  rng_ = noise.seed != 0u ? noise.seed : 1u;
}

double PlantImu::gaussian() noexcept {
  auto uniform = [this]() {
    rng_ ^= rng_ >> 12;
    rng_ ^= rng_ << 25;
    rng_ ^= rng_ >> 27;
    const std::uint64_t x = rng_ * 0x2545F4914F6CDD1Dull;
    return (static_cast<double>(x >> 11) + 0.5) * 0x1.0p-53;  // (0, 1)
  };
  const double u1 = uniform(), u2 = uniform();
  return std::sqrt(-2.0 * std::log(u1)) * std::cos(6.283185307179586 * u2);
}

void PlantImu::emit(const mrqp_fw_frame& frame, drivers::TimeNs at) noexcept {
  (void)node_.sendAt(frame, at);
}

emulation::ImuValues PlantImu::imu(drivers::TimeNs) noexcept {
  ImuSample s = plant_.imu(frame_);
  if (noise_.attitude_noise > 0.0) {
    const Eigen::Vector3d n(gaussian(), gaussian(), gaussian());
    s.orientation = s.orientation * rotationExp(noise_.attitude_noise * n);
  }
  s.angular_velocity += noise_.gyro_bias;
  if (noise_.gyro_noise > 0.0) {
    s.angular_velocity += noise_.gyro_noise * Eigen::Vector3d(gaussian(), gaussian(), gaussian());
  }
  emulation::ImuValues v;
  v.orientation = {s.orientation.w(), s.orientation.x(), s.orientation.y(), s.orientation.z()};
  v.angular_velocity = {s.angular_velocity.x(), s.angular_velocity.y(), s.angular_velocity.z()};
  v.specific_force = {s.specific_force.x(), s.specific_force.y(), s.specific_force.z()};
  return v;
}

}  // namespace mrqp::loop
