// The drive side of the CiA 402 arm protocol for a set of node ids (see drive_emu.hpp): one
// EmulatedCia402Drive per node with a joint model behind it, frames out through the FrameSink
// with drop / corruption injection.
#include "drive_emu.hpp"

#include <algorithm>

namespace mrqp::drive_emu {

using mrqp::emulation::EmulatedCia402Drive;

/// One node: the emulated drive and its joint.
struct DriveEmulator::Drive final : private EmulatedCia402Drive::Host {
  Drive(DriveEmulator& owner, const EmuNode& node, TimeNs boot_delay,
        const mrqp::emulation::VendorProfile& profile) noexcept
      : emu(owner), cfg(node), drive(*this, options(node, boot_delay, profile)) {
    q = cfg.joint.initial_position;
    target_position = q;
    drive.stopHeartbeatAt(cfg.faults.heartbeat_stop_at);
  }

  static EmulatedCia402Drive::Options options(const EmuNode& node, TimeNs boot_delay,
                                              const mrqp::emulation::VendorProfile& profile) noexcept {
    EmulatedCia402Drive::Options o;
    o.node = node.node;
    o.boot_delay = boot_delay;
    o.response_delay = 0;
    o.profile = profile;
    return o;
  }

  void emit(const mrqp_fw_frame& frame, TimeNs at) noexcept override { emu.send(frame, at); }

  void onNmtReset(bool application) noexcept override {
    if (application) {
      target_position = q;
    }
  }

  EmulatedCia402Drive::Feedback onSync(const EmulatedCia402Drive& d, bool new_targets,
                                       TimeNs) noexcept override {
    if (new_targets) {
      double v = 0.0;
      if (mrqp_fw_arm_position_from_inc(&cfg.scale, d.targetPosition(), &v) == MRQP_FW_CONV_OK) {
        target_position = v;
      }
      if (mrqp_fw_arm_torque_from_permille(&cfg.scale, d.targetTorque(), &v) == MRQP_FW_CONV_OK) {
        target_torque = v;
      }
    }
    if (d.state() != MRQP_FW_CIA402_OPERATION_ENABLED) {
      target_position = q;  // follow the actual position while disabled
    }
    EmulatedCia402Drive::Feedback fb;
    (void)mrqp_fw_arm_position_to_inc(&cfg.scale, q, &fb.position);
    (void)mrqp_fw_arm_velocity_to_inc(&cfg.scale, qd, &fb.velocity);
    (void)mrqp_fw_arm_torque_to_permille(&cfg.scale, tau, &fb.torque);
    return fb;
  }

  DriveEmulator& emu;
  EmuNode cfg;
  EmulatedCia402Drive drive;
  bool emcy_done = false;
  double target_position = 0.0;  ///< rad
  double target_torque = 0.0;    ///< N m
  double q = 0.0;
  double qd = 0.0;
  double tau = 0.0;
  TimeNs now = 0;
};

DriveEmulator::DriveEmulator(const EmuConfig& config, FrameSink& sink) : cfg_(config), sink_(sink) {
  rng_ = 0x9E3779B97F4A7C15ull ^ config.seed;
  drives_.reserve(config.nodes.size());
  for (const EmuNode& node : config.nodes) {
    drives_.push_back(std::make_unique<Drive>(*this, node, config.boot_delay, config.profile));  // power-on
  }
}

double DriveEmulator::rand01() noexcept {
  rng_ ^= rng_ << 13;
  rng_ ^= rng_ >> 7;
  rng_ ^= rng_ << 17;
  return static_cast<double>(rng_ >> 11) * (1.0 / 9007199254740992.0);
}

void DriveEmulator::send(const mrqp_fw_frame& f, TimeNs now) noexcept {
  if (cfg_.drop_fraction > 0.0 && rand01() < cfg_.drop_fraction) {
    ++stats_.dropped;
    return;
  }
  if (cfg_.corrupt_fraction > 0.0 && rand01() < cfg_.corrupt_fraction) {
    mrqp_fw_frame c = f;
    c.len = 1;  // truncated: fails to decode at the master
    ++stats_.corrupted;
    ++stats_.sent;
    sink_.emit(c, now);
    return;
  }
  ++stats_.sent;
  sink_.emit(f, now);
}

DriveEmulator::~DriveEmulator() = default;
std::size_t DriveEmulator::size() const noexcept { return drives_.size(); }
double DriveEmulator::position(std::size_t i) const noexcept { return drives_[i]->q; }
mrqp_fw_cia402_state DriveEmulator::state(std::size_t i) const noexcept { return drives_[i]->drive.state(); }
mrqp_fw_nmt_state DriveEmulator::nmt(std::size_t i) const noexcept { return drives_[i]->drive.nmt(); }
unsigned DriveEmulator::commErrors(std::size_t i) const noexcept { return drives_[i]->drive.commErrors(); }

TimeNs DriveEmulator::nextEvent() const noexcept {
  TimeNs t = next_step_;
  for (const auto& d : drives_) {
    t = std::min(t, d->drive.nextEvent());
    if (!d->emcy_done) {
      t = std::min(t, d->cfg.faults.emcy_at);
    }
  }
  return t;
}

void DriveEmulator::step(Drive& d, double dt) noexcept {
  const JointModel& j = d.cfg.joint;
  double tau = 0.0;
  if (d.drive.state() == MRQP_FW_CIA402_OPERATION_ENABLED) {
    if (d.drive.mode() == MRQP_FW_MODE_CSP) {
      tau = j.kp * (d.target_position - d.q) - j.kd * d.qd;
    } else {
      tau = d.target_torque;
    }
  }
  tau = std::clamp(tau, -j.torque_limit, j.torque_limit);
  if (d.now >= d.cfg.faults.saturate_at) {
    tau = j.torque_limit;
  }
  d.tau = tau;
  const double qdd = (tau - j.damping * d.qd) / j.inertia;
  d.qd += qdd * dt;  // semi-implicit Euler
  d.q += d.qd * dt;
}

void DriveEmulator::advance(TimeNs now) noexcept {
  while (nextEvent() <= now) {
    const TimeNs t = nextEvent();
    for (auto& p : drives_) {
      Drive& d = *p;
      d.now = t;
      d.drive.advance(t);  // boot-up message, heartbeat
      if (!d.emcy_done && d.cfg.faults.emcy_at <= t) {
        d.emcy_done = true;
        d.drive.raiseFault(d.cfg.faults.emcy_code, 0x03, t);
      }
    }
    if (next_step_ <= t) {
      const double dt = static_cast<double>(cfg_.step) * 1e-9;
      for (auto& d : drives_) {
        step(*d, dt);
      }
      next_step_ += cfg_.step;
    }
  }
}

void DriveEmulator::onFrame(const mrqp_fw_frame& f, TimeNs now) noexcept {
  for (auto& d : drives_) {
    d->now = now;
    if (d->drive.onFrame(f, now) == EmulatedCia402Drive::Received::Rpdo) {
      ++stats_.rpdos;
    }
  }
  if (f.id == MRQP_FW_COB_SYNC) {
    ++stats_.syncs;
  }
}

}  // namespace mrqp::drive_emu
