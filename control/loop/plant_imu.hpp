// One emulated IMU on a simulated CAN FD bus, measuring the plant (docs/loop.md): the IMU
// firmware of drivers/ emulation (EmulatedImu) on a SimDeviceNode (the node's listener), with this
// class as its host: the firmware's frames go out on the node and its samples are Plant::imu at
// its frame, read on every SYNC, with the sensor's errors when set (setNoise): a constant gyro
// bias, white gyro noise and white noise on the attitude output (a rotation by a random vector),
// from a deterministic generator so that runs stay identical. Allocation-free after construction.
#pragma once

#include <mrqp/drivers/sim_bus.hpp>
#include <mrqp/emulation/emulated_imu.hpp>
#include <mrqp/emulation/sim_device_node.hpp>

#include <cstdint>

#include "loop/plant.hpp"

namespace mrqp::loop {

/// The errors of an emulated IMU (zero: a perfect one).
struct ImuNoise {
  Eigen::Vector3d gyro_bias = Eigen::Vector3d::Zero();  ///< rad/s, sensor axes
  double gyro_noise = 0.0;                              ///< rad/s, standard deviation per axis
  double attitude_noise = 0.0;                          ///< rad, standard deviation per axis
  std::uint64_t seed = 0x9E3779B97F4A7C15ull;
};

class PlantImu final : private emulation::EmulatedImu::Host {
 public:
  PlantImu(drivers::SimNode& node, Plant& plant, int frame, std::uint8_t node_id);
  PlantImu(const PlantImu&) = delete;
  PlantImu& operator=(const PlantImu&) = delete;
  virtual ~PlantImu() = default;

  emulation::EmulatedImu& firmware() noexcept { return imu_; }
  void setNoise(const ImuNoise& noise) noexcept;

 private:
  void emit(const mrqp_fw_frame& frame, drivers::TimeNs at) noexcept override;
  emulation::ImuValues imu(drivers::TimeNs now) noexcept override;
  /// A standard normal sample (xorshift64* and Box–Muller).
  double gaussian() noexcept;

  drivers::SimNode& node_;
  Plant& plant_;
  int frame_;
  ImuNoise noise_;
  std::uint64_t rng_ = 1;
  emulation::EmulatedImu imu_;
  emulation::SimDeviceNode<emulation::EmulatedImu> glue_;
};

}  // namespace mrqp::loop
