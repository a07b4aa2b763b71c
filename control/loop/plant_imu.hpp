// One emulated IMU on a simulated CAN FD bus, measuring the plant (docs/loop.md): the IMU
// firmware of drivers/ (EmulatedImu) as the firmware of a SimNode, sampling Plant::imu at its
// frame on every SYNC. Allocation-free after construction.
#pragma once

#include <mrqp/drivers/sim_bus.hpp>
#include <mrqp/emulation/emulated_imu.hpp>

#include "loop/plant.hpp"

namespace mrqp::loop {

class PlantImu final : public drivers::SimListener, private emulation::EmulatedImu::Host {
 public:
  PlantImu(drivers::SimNode& node, Plant& plant, int frame, std::uint8_t node_id);

  void on_receive(drivers::SimNode& node, drivers::ReceiveResult kind,
                  const drivers::RxFrame& rx) noexcept override;

  emulation::EmulatedImu& firmware() noexcept { return imu_; }

 private:
  void emit(const mrqp_fw_frame& frame, drivers::TimeNs at) noexcept override;
  emulation::ImuValues imu(drivers::TimeNs now) noexcept override;

  drivers::SimNode& node_;
  Plant& plant_;
  int frame_;
  emulation::EmulatedImu imu_;
};

}  // namespace mrqp::loop
