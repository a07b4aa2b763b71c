// mrqp drivers -- MIT-mode hand actuators: the real-time part. See mit_hand_driver.hpp.
#include "mrqp/drivers/mit_hand_driver.hpp"

#include "driver_util.hpp"

namespace mrqp::drivers {

void MitHandDriver::requestEnable(TimeNs now) noexcept {
  quick_stop_ = false;
  for (Motor& m : motors_) {
    if (m.state.mode != MitMode::On) {
      m.state.mode = MitMode::Enabling;
      m.special_sent = false;
      m.mode_since = now;
    }
    m.sp_valid = false;
  }
}

void MitHandDriver::requestDisable(TimeNs now) noexcept {
  quick_stop_ = false;
  for (Motor& m : motors_) {
    if (m.state.mode != MitMode::Off) {
      m.state.mode = MitMode::Disabling;
      m.special_sent = false;
      m.mode_since = now;
    }
    m.sp_valid = false;
  }
}

void MitHandDriver::requestQuickStop(TimeNs) noexcept {
  quick_stop_ = true;
  for (Motor& m : motors_) {
    m.sp = mrqp_fw_mit_cmd{};
    m.sp.p = m.state.position;
    m.sp.kd = m.cfg.quick_stop_kd;
    m.sp_valid = true;
  }
}

SetpointResult MitHandDriver::setJoint(std::size_t i, const JointCommand& c) noexcept {
  if (i >= motors_.size()) {
    return SetpointResult::BadIndex;
  }
  const MitMotorConfig& cfg = motors_[i].cfg;
  mrqp_fw_mit_cmd cmd{};
  cmd.p = static_cast<float>(c.position);
  cmd.v = static_cast<float>(c.velocity);
  cmd.kp = c.stiffness < 0.0 ? cfg.default_kp : static_cast<float>(c.stiffness);
  cmd.kd = c.damping < 0.0 ? cfg.default_kd : static_cast<float>(c.damping);
  cmd.t = static_cast<float>(c.torque);
  return setCommand(i, cmd);
}

JointFeedback MitHandDriver::joint(std::size_t i) const noexcept {
  JointFeedback out;
  if (i >= motors_.size()) {
    return out;
  }
  const MitMotorState& s = motors_[i].state;
  out.position = static_cast<double>(s.position);
  out.velocity = static_cast<double>(s.velocity);
  out.torque = static_cast<double>(s.torque);
  out.valid = s.valid;
  out.fresh = s.fresh;
  out.timestamp = s.timestamp;
  return out;
}

bool MitHandDriver::allOn() const noexcept {
  for (const Motor& m : motors_) {
    if (m.state.mode != MitMode::On) {
      return false;
    }
  }
  return !motors_.empty();
}

bool MitHandDriver::allOff() const noexcept {
  for (const Motor& m : motors_) {
    if (m.state.mode != MitMode::Off) {
      return false;
    }
  }
  return !motors_.empty();
}

SetpointResult MitHandDriver::setCommand(std::size_t i, const mrqp_fw_mit_cmd& cmd) noexcept {
  if (i >= motors_.size()) {
    return SetpointResult::BadIndex;
  }
  Motor& m = motors_[i];
  if (quick_stop_) {
    return SetpointResult::Ok;  // held with damping until the next enable / disable request
  }
  if (!detail::finiteF(cmd.p) || !detail::finiteF(cmd.v) || !detail::finiteF(cmd.kp) ||
      !detail::finiteF(cmd.kd) || !detail::finiteF(cmd.t)) {
    ++m.faults.refused_setpoints;
    m.events |= fault::kSetpointRefused;
    return SetpointResult::Refused;
  }
  bool limited = false;
  m.sp = cmd;
  m.sp.p = static_cast<float>(detail::clamp(cmd.p, m.cfg.position_min, m.cfg.position_max, &limited));
  // The wire ranges: pack would saturate anyway; clamp here so that the flag is reported now.
  const mrqp_fw_mit_ranges& r = m.cfg.ranges;
  m.sp.p = static_cast<float>(detail::clamp(m.sp.p, r.p_min, r.p_max, &limited));
  m.sp.v = static_cast<float>(detail::clamp(cmd.v, r.v_min, r.v_max, &limited));
  m.sp.kp = static_cast<float>(detail::clamp(cmd.kp, r.kp_min, r.kp_max, &limited));
  m.sp.kd = static_cast<float>(detail::clamp(cmd.kd, r.kd_min, r.kd_max, &limited));
  m.sp.t = static_cast<float>(detail::clamp(cmd.t, r.t_min, r.t_max, &limited));
  m.sp_valid = true;
  if (limited) {
    ++m.faults.limited_setpoints;
    m.events |= fault::kSetpointLimited;
    return SetpointResult::Limited;
  }
  return SetpointResult::Ok;
}

const FaultReport& MitHandDriver::update(TimeNs now) noexcept {
  routers_.startCycle();
  for (std::size_t i = 0; i < motors_.size(); ++i) {
    Motor& m = motors_[i];
    std::uint32_t flags = m.events;
    m.events = 0;
    m.state.fresh = m.replied;
    if (m.sent) {
      m.faults.missed_cycles = m.replied ? 0u : m.faults.missed_cycles + 1u;
    }
    if (m.replied && m.special_sent) {
      // The reply to ENABLE / DISABLE confirms it.
      if (m.state.mode == MitMode::Enabling) {
        m.state.mode = MitMode::On;
      } else if (m.state.mode == MitMode::Disabling) {
        m.state.mode = MitMode::Off;
      }
      m.special_sent = false;
    }
    m.replied = false;
    m.sent = false;
    if (m.faults.missed_cycles >= config_.feedback_missing_cycles) {
      flags |= fault::kFeedbackMissing;
    }
    if ((m.state.mode == MitMode::Enabling || m.state.mode == MitMode::Disabling) &&
        now - m.mode_since > config_.enable_timeout) {
      flags |= fault::kTimeout;
    }
    m.faults.flags = flags;
    routers_.device(i) = m.faults;
  }
  return routers_.publish();
}

std::size_t MitHandDriver::transmit(TimeNs) noexcept {
  std::size_t count = 0;
  for (Motor& m : motors_) {
    mrqp_fw_frame f;
    mrqp_fw_pack_flags pf = MRQP_FW_PACK_OK;
    switch (m.state.mode) {
      case MitMode::Enabling:
        pf = mrqp_fw_mit_pack_special(m.cfg.motor_id, MRQP_FW_MIT_KIND_ENABLE, &f);
        break;
      case MitMode::Disabling:
        pf = mrqp_fw_mit_pack_special(m.cfg.motor_id, MRQP_FW_MIT_KIND_DISABLE, &f);
        break;
      case MitMode::On: {
        mrqp_fw_mit_cmd c{};
        if (m.sp_valid) {
          c = m.sp;
        } else {
          c.p = m.state.position;  // no setpoint yet: no stiffness, no damping, no torque
        }
        pf = mrqp_fw_mit_pack_cmd(&m.cfg.ranges, m.cfg.motor_id, &c, &f);
        break;
      }
      case MitMode::Off:
        if (!config_.poll_when_disabled) {
          continue;
        }
        {
          mrqp_fw_mit_cmd c{};
          c.p = m.state.position;
          pf = mrqp_fw_mit_pack_cmd(&m.cfg.ranges, m.cfg.motor_id, &c, &f);
        }
        break;
    }
    if (mrqp_fw_pack_failed(pf)) {
      continue;
    }
    if ((pf & MRQP_FW_PACK_SAT_MASK) != 0u && m.state.mode == MitMode::On && m.sp_valid) {
      ++m.faults.limited_setpoints;
      m.events |= fault::kSetpointLimited;
    }
    const SendResult r = routers_.router(m.cfg.bus).bus().send(f);
    if (r == SendResult::Ok) {
      ++count;
      m.sent = true;
      if (m.state.mode == MitMode::Enabling || m.state.mode == MitMode::Disabling) {
        m.special_sent = true;
      }
    } else if (r == SendResult::QueueFull) {
      ++m.faults.tx_queue_full;
      m.events |= fault::kTxQueueFull;
    }
  }
  return count;
}

Claim MitHandDriver::onFrame(const BusRouter& from, const RxFrame& rx, TimeNs now) noexcept {
  const int slot = routers_.slotOf(from);
  const mrqp_fw_frame& f = rx.frame;
  if (slot < 0 || f.id != MRQP_FW_MIT_MASTER_ID || (f.flags & MRQP_FW_FRAME_EXT) != 0u) {
    return Claim::NotMine;
  }
  // The motor id is byte 0; without it the frame cannot be attributed.
  if (f.len < 1u) {
    return Claim::Rejected;
  }
  const std::uint8_t id = f.data[0];
  const std::int16_t index = id < 128u ? buses_[static_cast<std::size_t>(slot)].id_to_motor[id] : -1;
  if (index < 0) {
    return Claim::Rejected;
  }
  Motor& m = motors_[static_cast<std::size_t>(index)];
  mrqp_fw_mit_reply reply;
  if (mrqp_fw_mit_unpack_reply(&m.cfg.ranges, &f, &reply) != MRQP_FW_OK) {
    ++m.faults.corrupt_frames;
    m.events |= fault::kCorruptFrame;
    return Claim::Rejected;
  }
  MitMotorState& s = m.state;
  s.position = reply.p;
  s.velocity = reply.v;
  s.torque = reply.t;
  s.valid = true;
  s.timestamp = detail::rxTime(rx, now);
  m.replied = true;
  // A value at the end of its wire range may be saturated; outside the limits is out of range.
  const mrqp_fw_mit_ranges& r = m.cfg.ranges;
  if (reply.p <= r.p_min || reply.p >= r.p_max || reply.v <= r.v_min || reply.v >= r.v_max ||
      reply.t <= r.t_min || reply.t >= r.t_max || reply.p < m.cfg.position_min ||
      reply.p > m.cfg.position_max) {
    ++m.faults.out_of_range;
    m.events |= fault::kOutOfRange;
  }
  return Claim::Accepted;
}

}  // namespace mrqp::drivers
