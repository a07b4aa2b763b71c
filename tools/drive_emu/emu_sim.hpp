// DriveEmulator on a SimNode (tests): the node's listener and timer drive the emulator.
#pragma once

#include <mrqp/drivers/sim_bus.hpp>

#include <algorithm>

#include "drive_emu.hpp"

namespace mrqp::drive_emu {

class SimDriveEmulator final : public mrqp::drivers::SimListener, private FrameSink {
 public:
  SimDriveEmulator(mrqp::drivers::SimNode& node, const EmuConfig& config) : node_(node), emu_(config, *this) {
    node_.setListener(this);
    rearm();
  }
  void onReceive(mrqp::drivers::SimNode&, mrqp::drivers::ReceiveResult kind,
                 const mrqp::drivers::RxFrame& rx) noexcept override {
    if (kind != mrqp::drivers::ReceiveResult::Frame) {
      return;
    }
    emu_.advance(rx.timestamp);
    emu_.onFrame(rx.frame, rx.timestamp);
    rearm();
  }
  void onTimer(mrqp::drivers::SimNode&, TimeNs now) noexcept override {
    emu_.advance(now);
    rearm();
  }
  DriveEmulator& emulator() noexcept { return emu_; }

 private:
  void emit(const mrqp_fw_frame& frame, TimeNs) noexcept override { (void)node_.send(frame); }
  void rearm() noexcept { node_.setTimer(std::max(emu_.nextEvent(), node_.bus().now())); }

  mrqp::drivers::SimNode& node_;
  DriveEmulator emu_;
};

}  // namespace mrqp::drive_emu
