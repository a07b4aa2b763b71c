// An emulated CiA 402 drive on the plant (see plant_cia402_drive.hpp).
#include "loop/plant_cia402_drive.hpp"

#include <mrqp/firmware_if/arm_scale.h>
#include <mrqp/firmware_if/cia402.h>

#include <algorithm>
#include <cmath>

namespace mrqp::loop {

namespace {
drivers::EmulatedCia402Drive::Options driveOptions(const PlantDriveOptions& o) noexcept {
  drivers::EmulatedCia402Drive::Options d;
  d.node = o.node;
  d.response_delay = o.response_delay;
  d.profile = o.profile;
  return d;
}
}  // namespace

PlantCia402Drive::PlantCia402Drive(drivers::SimNode& node, Plant& plant, const PlantDriveOptions& options)
    : node_(node), plant_(plant), options_(options), drive_(*this, driveOptions(options)) {
  scale_.increments_per_rev = 524288u;
  scale_.rated_torque_mNm = static_cast<std::uint32_t>(std::lround(options.rated_torque * 1000.0));
  node_.setListener(this);
  engageBrake();  // power-on: the holding brake is closed until the drive is enabled
  rearm();
}

void PlantCia402Drive::engageBrake() noexcept {
  if (braked_) return;
  braked_ = true;
  ServoCommand c;
  c.position = plant_.jointPosition(options_.joint);
  c.kp = options_.brake_kp;
  c.kd = options_.brake_kd;
  c.torque_limit = options_.torque_limit;
  c.enabled = std::isfinite(c.position);
  plant_.setServo(options_.joint, c);
}

void PlantCia402Drive::rearm() noexcept {
  const drivers::TimeNs at = drive_.nextEvent();
  if (at == Drive::kNever) {
    node_.cancelTimer();
  } else {
    node_.setTimer(at);
  }
}

void PlantCia402Drive::emit(const mrqp_fw_frame& frame, drivers::TimeNs at) noexcept {
  mrqp_fw_frame f = frame;
  const bool tpdo = (f.id & 0x780u) == 0x180u || (f.id & 0x780u) == 0x280u;
  if (loss_per_mille_ > 0u) {
    rng_ = rng_ * 1664525u + 1013904223u;
    if ((rng_ >> 8) % 1000u < loss_per_mille_) {
      ++dropped_;
      return;
    }
  }
  if (corrupt_ && tpdo && f.len > 1) {
    f.len = static_cast<std::uint8_t>(f.len - 1);
  }
  (void)node_.sendAt(f, at);
}

void PlantCia402Drive::onNmtReset(bool) noexcept { node_.cancelPending(); }

PlantCia402Drive::Drive::Feedback PlantCia402Drive::onSync(const Drive& drive, bool,
                                                           drivers::TimeNs now) noexcept {
  const std::uint32_t period_us = drive.odValue(0x1006, 0);
  const double period = period_us > 0u ? static_cast<double>(period_us) * 1e-6 : 1e-3;
  const int j = options_.joint;
  ServoCommand c;
  c.kp = options_.kp;
  c.kd = options_.kd;
  c.torque_limit = options_.torque_limit;
  if (drive.state() == MRQP_FW_CIA402_OPERATION_ENABLED) {
    stopping_ = false;
    braked_ = false;
    double ff = 0.0;
    (void)mrqp_fw_arm_torque_from_permille(&scale_, drive.targetTorque(), &ff);
    if (!options_.torque_mode) {
      double target = 0.0;
      (void)mrqp_fw_arm_position_from_inc(&scale_, drive.targetPosition(), &target);
      c.position = target;
      c.velocity = have_last_target_ ? (target - last_target_) / period : 0.0;
      c.torque = ff;
      c.enabled = true;
      last_target_ = target;
      have_last_target_ = true;
    } else {
      c.kp = 0.0;
      c.kd = 0.0;
      c.torque = ff;
      c.enabled = true;
    }
  } else if (drive.state() == MRQP_FW_CIA402_QUICK_STOP_ACTIVE) {
    if (!stopping_) {
      stopping_ = true;
      stop_position_ = plant_.jointPosition(j);
    }
    c.position = stop_position_;
    c.enabled = true;
    braked_ = false;
    have_last_target_ = false;
  } else {
    have_last_target_ = false;
  }
  if (c.enabled) {
    plant_.setServo(j, c);
  } else {
    engageBrake();
  }

  const double q = encoder_broken_ ? std::nan("") : plant_.jointPosition(j);
  const double v = encoder_broken_ ? std::nan("") : plant_.jointVelocity(j);
  Drive::Feedback fb;
  if (!std::isfinite(q) || !std::isfinite(v)) {
    if (!encoder_fault_sent_) {
      encoder_fault_sent_ = true;
      drive_.raiseFault(0x7305, 0x01, now);  // incremental sensor 1 fault
    }
    return fb;
  }
  (void)mrqp_fw_arm_position_to_inc(&scale_, q, &fb.position);
  (void)mrqp_fw_arm_velocity_to_inc(&scale_, v, &fb.velocity);
  // The drive's current limiter: what it measures never exceeds its torque limit.
  const double tau = std::clamp(plant_.jointTorque(j), -options_.torque_limit, options_.torque_limit);
  (void)mrqp_fw_arm_torque_to_permille(&scale_, tau, &fb.torque);
  return fb;
}

void PlantCia402Drive::onTimer(drivers::SimNode&, drivers::TimeNs now) noexcept {
  drive_.advance(now);
  rearm();
}

void PlantCia402Drive::onReceive(drivers::SimNode&, drivers::ReceiveResult kind,
                                 const drivers::RxFrame& rx) noexcept {
  if (kind != drivers::ReceiveResult::Frame) {
    return;
  }
  (void)drive_.onFrame(rx.frame, rx.timestamp);
  rearm();
}

}  // namespace mrqp::loop
