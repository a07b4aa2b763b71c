// The plant as the world of emulated joint actuators (MIT-mode motors, CAN FD hand boards) on one
// simulated bus node (docs/loop.md, "The emulated rig"): the JointHost of drivers/ emulation whose
// frames go out on the node, whose joints are joints of the plant (host index i is the i-th handle
// given) and whose servo commands become Plant::setServo with the joint's torque limit. The
// devices themselves and their SimNode listener are PlantActuators (plant_actuators.hpp).
// Allocation-free after construction.
#pragma once

#include <mrqp/drivers/sim_bus.hpp>
#include <mrqp/emulation/joint_host.hpp>

#include <cstddef>
#include <vector>

#include "loop/plant.hpp"

namespace mrqp::loop {

class PlantJointHost final : public emulation::JointHost {
 public:
  PlantJointHost(drivers::SimNode& node, Plant& plant) : node_(node), plant_(plant) {}
  PlantJointHost(const PlantJointHost&) = delete;
  PlantJointHost& operator=(const PlantJointHost&) = delete;
  virtual ~PlantJointHost() = default;

  /// Set-up: one more joint (plant handle, torque limit in N·m); returns its host index.
  std::size_t addJoint(int plant_joint, double torque_limit);
  std::size_t jointCount() const noexcept { return joints_.size(); }

  void emit(const mrqp_fw_frame& frame, emulation::TimeNs at) noexcept override;
  emulation::JointMeasurement measure(std::size_t joint, emulation::TimeNs now) noexcept override;
  void command(std::size_t joint, const emulation::ServoCommand& servo,
               emulation::TimeNs now) noexcept override;

 private:
  struct Joint {
    int handle = -1;
    double torque_limit = 1e9;
  };
  drivers::SimNode& node_;
  Plant& plant_;
  std::vector<Joint> joints_;
};

}  // namespace mrqp::loop
