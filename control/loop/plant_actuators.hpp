// Emulated joint actuators of one kind on one simulated bus node, acting on the plant
// (docs/loop.md, "The emulated rig"): MIT-mode motors (emulation::EmulatedMitMotor) or CAN FD hand
// boards (emulation::EmulatedHandBoard), the firmware of drivers/ emulation, behind one
// SimDeviceNode (the node's listener: frames to every device, timers to their advance()) and one
// PlantJointHost (their joints are the plant's). add() is set-up (allocates); the rest is
// allocation-free.
#pragma once

#include <mrqp/emulation/sim_device_node.hpp>

#include <cstddef>
#include <memory>
#include <vector>

#include "loop/plant_joint_host.hpp"

namespace mrqp::loop {

template <class Device>
class PlantActuators {
 public:
  PlantActuators(drivers::SimNode& node, Plant& plant) : host_(node, plant), glue_(node) {}
  PlantActuators(const PlantActuators&) = delete;
  PlantActuators& operator=(const PlantActuators&) = delete;

  /// Set-up: one more device; `options.joint` is set to the host index of its first joint, which
  /// the caller has added to host() just before (plant handles in the device's joint order).
  Device& add(typename Device::Options options, std::size_t first_joint) {
    options.joint = first_joint;
    devices_.push_back(std::make_unique<Device>(host_, options));
    glue_.add(*devices_.back());
    return *devices_.back();
  }
  PlantJointHost& host() noexcept { return host_; }
  std::size_t size() const noexcept { return devices_.size(); }
  Device& device(std::size_t i) noexcept { return *devices_[i]; }
  /// After a device was changed from outside (a fault switch with a timed effect).
  void rearm() noexcept { glue_.rearm(); }

 private:
  PlantJointHost host_;
  emulation::SimDeviceNode<Device> glue_;
  std::vector<std::unique_ptr<Device>> devices_;
};

}  // namespace mrqp::loop
