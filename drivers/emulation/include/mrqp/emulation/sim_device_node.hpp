// mrqp emulation -- emulated device firmware on a SimBus node.
//
// A SimDeviceNode is the SimListener of one SimNode: every frame the node receives goes to each
// device added (onFrame(frame, reception time)), and the node's timer runs their advance() at
// the earliest nextEvent(). Devices of one type share a node (several MIT motors behind one
// controller); put devices of different types on nodes of their own. The device's host sends its
// frames with SimNode::sendAt(frame, at). add() is set-up (allocates); the rest is real-time safe.
#pragma once

#include <algorithm>
#include <cstdint>
#include <vector>

#include "mrqp/drivers/sim_bus.hpp"

namespace mrqp::emulation {

template <class Device>
class SimDeviceNode final : public drivers::SimListener {
 public:
  explicit SimDeviceNode(drivers::SimNode& node) : node_(node) { node_.setListener(this); }
  SimDeviceNode(const SimDeviceNode&) = delete;
  SimDeviceNode& operator=(const SimDeviceNode&) = delete;

  /// Set-up: one more device behind this node.
  void add(Device& device) {
    devices_.push_back(&device);
    rearm();
  }
  drivers::SimNode& node() noexcept { return node_; }
  /// After a device was changed from outside (powerOn(), a fault switch with a timed effect).
  void rearm() noexcept {
    drivers::TimeNs t = INT64_MAX;
    for (Device* d : devices_) {
      t = std::min(t, d->nextEvent());
    }
    if (t == INT64_MAX) {
      node_.cancelTimer();
    } else {
      node_.setTimer(t);
    }
  }

  void onReceive(drivers::SimNode&, drivers::ReceiveResult kind,
                 const drivers::RxFrame& rx) noexcept override {
    if (kind != drivers::ReceiveResult::Frame) {
      return;
    }
    for (Device* d : devices_) {
      (void)d->onFrame(rx.frame, rx.timestamp);
    }
    rearm();
  }
  void onTimer(drivers::SimNode&, drivers::TimeNs now) noexcept override {
    for (Device* d : devices_) {
      d->advance(now);
    }
    rearm();
  }

 private:
  drivers::SimNode& node_;
  std::vector<Device*> devices_;
};

}  // namespace mrqp::emulation
