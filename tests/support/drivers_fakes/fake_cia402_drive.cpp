// A fake CiA 402 drive (see fake_cia402_drive.hpp).
#include "fake_cia402_drive.hpp"

namespace drvtest {

using mrqp::drivers::ReceiveResult;

namespace {
mrqp::emulation::EmulatedCia402Drive::Options drive_options(const FakeDriveOptions& o) noexcept {
  mrqp::emulation::EmulatedCia402Drive::Options d;
  d.node = o.node;
  d.boot_delay = o.boot_delay;
  d.response_delay = o.response_delay;
  d.profile = o.profile;
  return d;
}
}  // namespace

FakeCia402Drive::FakeCia402Drive(SimNode& node, const FakeDriveOptions& options)
    : node_(node), drive_(*this, drive_options(options)), position_(options.initial_position) {
  node_.set_listener(this);
  rearm();  // power-on: the boot-up message after the boot delay
}

void FakeCia402Drive::rearm() noexcept {
  const TimeNs at = drive_.next_event();
  if (at == Drive::kNever) {
    node_.cancel_timer();
  } else {
    node_.set_timer(at);
  }
}

void FakeCia402Drive::emit(const mrqp_fw_frame& frame, TimeNs at) noexcept { (void)node_.send_at(frame, at); }

void FakeCia402Drive::on_nmt_reset(bool) noexcept {
  node_.cancel_pending();  // the controller is reset with the node: queued answers are lost
}

FakeCia402Drive::Drive::Feedback FakeCia402Drive::on_sync(const Drive& drive, bool, TimeNs) noexcept {
  const std::int32_t before = position_;
  if (drive.state() == MRQP_FW_CIA402_OPERATION_ENABLED) {
    if (drive.mode() == MRQP_FW_MODE_CSP) {
      position_ = drive.target_position();
      torque_ = 0;
    } else {
      torque_ = drive.target_torque();
    }
  } else {
    torque_ = 0;
  }
  const std::uint32_t period_us = drive.od_value(0x1006, 0);
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
  node_.set_connected(on);
  if (on) {
    drive_.power_on(node_.bus().now());
    rearm();
  }
}

void FakeCia402Drive::inject_fault(std::uint16_t code, std::uint8_t error_register) noexcept {
  drive_.raise_fault(code, error_register, node_.bus().now());
}

void FakeCia402Drive::on_timer(SimNode&, TimeNs now) noexcept {
  drive_.advance(now);
  rearm();
}

void FakeCia402Drive::on_transmitted(SimNode&, const mrqp_fw_frame&, TimeNs) noexcept {}

void FakeCia402Drive::on_receive(SimNode&, ReceiveResult kind, const RxFrame& rx) noexcept {
  if (kind != ReceiveResult::Frame || !powered_) {
    return;
  }
  (void)drive_.on_frame(rx.frame, rx.timestamp);
  rearm();
}

}  // namespace drvtest
