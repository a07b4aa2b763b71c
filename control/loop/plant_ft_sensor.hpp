// One emulated wrist force/torque sensor on a simulated bus, measuring the plant (docs/loop.md):
// the sensor firmware of drivers/ emulation (EmulatedFtSensor) on a SimDeviceNode (the node's
// listener), with this class as its host: the firmware's frames go out on the node and its
// samples are Plant::sensorWrench at its frame, read on every SYNC. Fault switches are the
// firmware's own (stale samples, silence, corrupt frames). Allocation-free after construction.
#pragma once

#include <mrqp/drivers/sim_bus.hpp>
#include <mrqp/emulation/emulated_ft_sensor.hpp>
#include <mrqp/emulation/sim_device_node.hpp>

#include "loop/plant.hpp"

namespace mrqp::loop {

class PlantFtSensor final : private emulation::EmulatedFtSensor::Host {
 public:
  PlantFtSensor(drivers::SimNode& node, Plant& plant, int frame, std::uint8_t node_id);
  PlantFtSensor(const PlantFtSensor&) = delete;
  PlantFtSensor& operator=(const PlantFtSensor&) = delete;
  virtual ~PlantFtSensor() = default;

  emulation::EmulatedFtSensor& firmware() noexcept { return sensor_; }

 private:
  void emit(const mrqp_fw_frame& frame, drivers::TimeNs at) noexcept override;
  std::array<double, 6> wrench(drivers::TimeNs now) noexcept override;

  drivers::SimNode& node_;
  Plant& plant_;
  int frame_;
  emulation::EmulatedFtSensor sensor_;
  emulation::SimDeviceNode<emulation::EmulatedFtSensor> glue_;
};

}  // namespace mrqp::loop
