// One emulated wrist force/torque sensor on a simulated bus, measuring the plant (docs/loop.md):
// the sensor firmware of drivers/ (EmulatedFtSensor) as the firmware of a SimNode, sampling
// Plant::sensorWrench at its frame on every SYNC. Fault switches are the firmware's own (stale
// samples, silence, corrupt frames). Allocation-free after construction.
#pragma once

#include <mrqp/drivers/sim_bus.hpp>
#include <mrqp/emulation/emulated_ft_sensor.hpp>

#include "loop/plant.hpp"

namespace mrqp::loop {

class PlantFtSensor final : public drivers::SimListener, private emulation::EmulatedFtSensor::Host {
 public:
  PlantFtSensor(drivers::SimNode& node, Plant& plant, int frame, std::uint8_t node_id);

  void on_receive(drivers::SimNode& node, drivers::ReceiveResult kind,
                  const drivers::RxFrame& rx) noexcept override;

  emulation::EmulatedFtSensor& firmware() noexcept { return sensor_; }

 private:
  void emit(const mrqp_fw_frame& frame, drivers::TimeNs at) noexcept override;
  std::array<double, 6> wrench(drivers::TimeNs now) noexcept override;

  drivers::SimNode& node_;
  Plant& plant_;
  int frame_;
  emulation::EmulatedFtSensor sensor_;
};

}  // namespace mrqp::loop
