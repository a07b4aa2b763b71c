// A fake CiA 402 drive (see fake_cia402_drive.hpp).
#include "fake_cia402_drive.hpp"

namespace drvtest {

using mrqp::drivers::ReceiveResult;

namespace {
mrqp::emulation::EmulatedCia402Drive::Options driveOptions(const FakeDriveOptions& o) noexcept {
  mrqp::emulation::EmulatedCia402Drive::Options d;
  d.node = o.node;
  d.boot_delay = o.boot_delay;
  d.response_delay = o.response_delay;
  d.profile = o.profile;
  return d;
}
}  // namespace

FakeCia402Drive::FakeCia402Drive(SimNode& node, const FakeDriveOptions& options)
    : node_(node), drive_(*this, driveOptions(options)), position_(options.initial_position) {
  node_.setListener(this);
  rearm();  // power-on: the boot-up message after the boot delay
}

void FakeCia402Drive::rearm() noexcept {
  const TimeNs at = drive_.nextEvent();
  if (at == Drive::kNever) {
    node_.cancelTimer();
  } else {
    node_.setTimer(at);
  }
}

void FakeCia402Drive::emit(const mrqp_fw_frame& frame, TimeNs at) noexcept { (void)node_.sendAt(frame, at); }

void FakeCia402Drive::onNmtReset(bool) noexcept {
  node_.cancelPending();  // the controller is reset with the node: queued answers are lost
}

FakeCia402Drive::Drive::Feedback FakeCia402Drive::onSync(const Drive& drive, bool, TimeNs) noexcept {
  const std::int32_t before = position_;
  if (drive.state() == MRQP_FW_CIA402_OPERATION_ENABLED) {
    if (drive.mode() == MRQP_FW_MODE_CSP) {
      position_ = drive.targetPosition();
      torque_ = 0;
    } else {
      torque_ = drive.targetTorque();
    }
  } else {
    torque_ = 0;
  }
  const std::uint32_t period_us = drive.odValue(0x1006, 0);
  velocity_ = period_us > 0u ? static_cast<std::int32_t>(static_cast<std::int64_t>(position_ - before) *
                                                         1000000 / static_cast<std::int64_t>(period_us))
                             : 0;
  Drive::Feedback fb;
  fb.position = position_;
  fb.velocity = velocity_;
  fb.torque = torque_;
  return fb;
}

void FakeCia402Drive::power(bool on) noexcept {
  powered_ = on;
  node_.setConnected(on);
  if (on) {
    drive_.powerOn(node_.bus().now());
    rearm();
  }
}

void FakeCia402Drive::injectFault(std::uint16_t code, std::uint8_t error_register) noexcept {
  drive_.raiseFault(code, error_register, node_.bus().now());
}

void FakeCia402Drive::onTimer(SimNode&, TimeNs now) noexcept {
  drive_.advance(now);
  rearm();
}

void FakeCia402Drive::onTransmitted(SimNode&, const mrqp_fw_frame&, TimeNs) noexcept {}

void FakeCia402Drive::onReceive(SimNode&, ReceiveResult kind, const RxFrame& rx) noexcept {
  if (kind != ReceiveResult::Frame || !powered_) {
    return;
  }
  (void)drive_.onFrame(rx.frame, rx.timestamp);
  rearm();
}

}  // namespace drvtest
