// mrqp drivers -- hand controller boards on CAN FD: the real-time part. See fd_hand_driver.hpp.
#include "mrqp/drivers/fd_hand_driver.hpp"

#include "driver_util.hpp"

namespace mrqp::drivers {

void FdHandDriver::requestEnable(TimeNs now) noexcept {
  for (Board& b : boards_) {
    b.mode_requested = config_.enabled_mode;
    b.mode_since = now;
    b.sp_valid = 0;
    b.state.enabled = false;
  }
}

void FdHandDriver::requestDisable(TimeNs now) noexcept {
  for (Board& b : boards_) {
    b.mode_requested = MRQP_FW_HAND_MODE_DISABLED;
    b.mode_since = now;
    b.sp_valid = 0;
    b.state.enabled = false;
  }
}

void FdHandDriver::requestQuickStop(TimeNs now) noexcept {
  for (Board& b : boards_) {
    b.mode_requested = MRQP_FW_HAND_MODE_HOLD;
    b.mode_since = now;
    b.sp_valid = 0;
    b.state.enabled = false;
  }
}

bool FdHandDriver::locate(std::size_t flat, std::size_t* board, std::size_t* joint) const noexcept {
  for (std::size_t i = 0; i < boards_.size(); ++i) {
    const std::size_t n = boards_[i].cfg.joints;
    if (flat < n) {
      *board = i;
      *joint = flat;
      return true;
    }
    flat -= n;
  }
  return false;
}

JointMode FdHandDriver::jointMode(std::size_t) const noexcept {
  return config_.enabled_mode == MRQP_FW_HAND_MODE_TORQUE ? JointMode::Torque : JointMode::Position;
}

SetpointResult FdHandDriver::setJoint(std::size_t flat, const JointCommand& c) noexcept {
  std::size_t board = 0;
  std::size_t j = 0;
  if (!locate(flat, &board, &j)) {
    return SetpointResult::BadIndex;
  }
  // A double outside float's range becomes an infinite float, refused like any non-finite value.
  return setJoint(board, j, static_cast<float>(c.position), static_cast<float>(c.velocity),
                  static_cast<float>(c.torque));
}

JointFeedback FdHandDriver::joint(std::size_t flat) const noexcept {
  JointFeedback out;
  std::size_t board = 0;
  std::size_t j = 0;
  if (!locate(flat, &board, &j)) {
    return out;
  }
  const Board& b = boards_[board];
  out.position = static_cast<double>(b.joints[j].position);
  out.velocity = static_cast<double>(b.joints[j].velocity);
  out.torque = static_cast<double>(b.joints[j].torque);
  out.valid = b.state.valid;
  out.fresh = b.state.fresh;
  out.timestamp = b.state.timestamp;
  return out;
}

bool FdHandDriver::allEnabled() const noexcept {
  for (const Board& b : boards_) {
    if (!b.state.enabled) {
      return false;
    }
  }
  return !boards_.empty();
}

SetpointResult FdHandDriver::setJoint(std::size_t board, std::size_t joint, float position, float velocity,
                                      float torque) noexcept {
  if (board >= boards_.size() || joint >= boards_[board].cfg.joints) {
    return SetpointResult::BadIndex;
  }
  Board& b = boards_[board];
  if (!detail::finiteF(position) || !detail::finiteF(velocity) || !detail::finiteF(torque)) {
    ++b.faults.refused_setpoints;
    b.events |= fault::kSetpointRefused;
    return SetpointResult::Refused;
  }
  // The wire range of each field: +/-(2^(bits-1) - 1) LSB.
  const mrqp_fw_hand_scale& s = b.cfg.scale;
  const double pmax = 32767.0 * static_cast<double>(s.position_lsb);
  const double vmax = 2047.0 * static_cast<double>(s.velocity_lsb);
  const double tmax = 2047.0 * static_cast<double>(s.torque_lsb);
  bool limited = false;
  HandJointState& sp = b.sp[joint];
  sp.position = static_cast<float>(detail::clamp(position, -pmax, pmax, &limited));
  sp.velocity = static_cast<float>(detail::clamp(velocity, -vmax, vmax, &limited));
  sp.torque = static_cast<float>(detail::clamp(torque, -tmax, tmax, &limited));
  b.sp_valid |= 1u << joint;
  if (limited) {
    ++b.faults.limited_setpoints;
    b.events |= fault::kSetpointLimited;
    return SetpointResult::Limited;
  }
  return SetpointResult::Ok;
}

const FaultReport& FdHandDriver::update(TimeNs now) noexcept {
  routers_.startCycle();
  for (std::size_t i = 0; i < boards_.size(); ++i) {
    Board& b = boards_[i];
    std::uint32_t flags = b.events;
    b.events = 0;
    const std::uint32_t all = (1u << b.chunks) - 1u;
    const bool complete = (b.chunks_seen & all) == all;
    b.state.fresh = complete;
    if (complete) {
      b.state.valid = true;
    }
    if (b.sent) {
      b.faults.missed_cycles = complete ? 0u : b.faults.missed_cycles + 1u;
    }
    b.chunks_seen = 0;
    b.sent = false;
    if (b.faults.missed_cycles >= config_.feedback_missing_cycles) {
      flags |= fault::kFeedbackMissing;
    }
    if (b.state.valid) {
      const std::uint8_t st = b.state.status;
      if ((st & MRQP_FW_HAND_STATUS_FAULT) != 0u) {
        flags |= fault::kDeviceFault;
      }
      if ((st & (MRQP_FW_HAND_STATUS_OVER_TEMPERATURE | MRQP_FW_HAND_STATUS_CRC_ERROR_SEEN)) != 0u) {
        flags |= fault::kDeviceWarning;
      }
      if ((st & MRQP_FW_HAND_STATUS_LIMIT) != 0u) {
        flags |= fault::kOutOfRange;
      }
      if ((st & MRQP_FW_HAND_STATUS_COMMAND_TIMEOUT) != 0u) {
        flags |= fault::kStateMismatch;
      }
      const std::uint16_t lag = static_cast<std::uint16_t>(b.state.seq - b.state.seq_echo);
      if (lag > config_.max_seq_lag) {
        flags |= fault::kStateMismatch;
      }
      const bool confirmed =
          b.state.mode == b.mode_requested &&
          (b.mode_requested == MRQP_FW_HAND_MODE_DISABLED || (st & MRQP_FW_HAND_STATUS_ENABLED) != 0u);
      if (b.mode_requested != MRQP_FW_HAND_MODE_DISABLED) {
        if (confirmed) {
          b.state.enabled = true;
        } else if (b.state.enabled) {
          flags |= fault::kStateMismatch;  // it was enabled and left the mode on its own
        }
      }
      if (!confirmed && !b.state.enabled && now - b.mode_since > config_.enable_timeout) {
        flags |= fault::kTimeout;
      }
    }
    b.faults.flags = flags;
    routers_.device(i) = b.faults;
  }
  return routers_.publish();
}

std::size_t FdHandDriver::transmit(TimeNs) noexcept {
  std::size_t count = 0;
  for (Board& b : boards_) {
    ++b.state.seq;
    bool any = false;
    for (std::uint32_t k = 0; k < b.chunks; ++k) {
      mrqp_fw_hand_cmd cmd{};
      cmd.seq = b.state.seq;
      cmd.mode = b.mode_requested;
      const std::uint32_t first = k * MRQP_FW_HAND_FD_MAX_JOINTS;
      const std::uint32_t left = b.cfg.joints - first;
      cmd.first_joint = static_cast<std::uint8_t>(first);
      cmd.count =
          static_cast<std::uint8_t>(left > MRQP_FW_HAND_FD_MAX_JOINTS ? MRQP_FW_HAND_FD_MAX_JOINTS : left);
      for (std::uint32_t j = 0; j < cmd.count; ++j) {
        const std::uint32_t joint = first + j;
        if (b.state.enabled && (b.sp_valid & (1u << joint)) != 0u) {
          cmd.joint[j].position = b.sp[joint].position;
          cmd.joint[j].velocity = b.sp[joint].velocity;
          cmd.joint[j].torque = b.sp[joint].torque;
        } else {
          cmd.joint[j].position = b.joints[joint].position;  // hold, no velocity, no torque
        }
      }
      mrqp_fw_frame f;
      std::uint32_t saturated = 0;
      const mrqp_fw_pack_flags pf = mrqp_fw_hand_pack_cmd(&b.cfg.scale, b.cfg.board, &cmd, &f, &saturated);
      if (mrqp_fw_pack_failed(pf)) {
        continue;
      }
      if ((pf & MRQP_FW_PACK_SAT_MASK) != 0u) {
        ++b.faults.limited_setpoints;
        b.events |= fault::kSetpointLimited;
      }
      const SendResult r = routers_.router(b.cfg.bus).bus().send(f);
      if (r == SendResult::Ok) {
        ++count;
        any = true;
      } else if (r == SendResult::QueueFull) {
        ++b.faults.tx_queue_full;
        b.events |= fault::kTxQueueFull;
      }
    }
    b.sent = any;
  }
  return count;
}

Claim FdHandDriver::onFrame(const BusRouter& from, const RxFrame& rx, TimeNs now) noexcept {
  const int slot = routers_.slotOf(from);
  const mrqp_fw_frame& f = rx.frame;
  if (slot < 0 || (f.flags & MRQP_FW_FRAME_EXT) != 0u || f.id < MRQP_FW_HAND_FD_FB_ID_BASE ||
      f.id > MRQP_FW_HAND_FD_FB_ID_BASE + MRQP_FW_HAND_BOARD_MAX) {
    return Claim::NotMine;
  }
  const std::uint32_t board = f.id - MRQP_FW_HAND_FD_FB_ID_BASE;
  const std::int16_t index = buses_[static_cast<std::size_t>(slot)].board_to_index[board];
  if (index < 0) {
    return Claim::NotMine;
  }
  Board& b = boards_[static_cast<std::size_t>(index)];
  mrqp_fw_hand_fb fb;
  if (mrqp_fw_hand_unpack_fb(&b.cfg.scale, &f, board, &fb) != MRQP_FW_OK ||
      static_cast<std::uint32_t>(fb.first_joint) + fb.count > b.cfg.joints) {
    ++b.faults.corrupt_frames;
    b.events |= fault::kCorruptFrame;
    return Claim::Rejected;
  }
  HandBoardState& s = b.state;
  if (b.counter_valid) {
    const std::uint8_t expected = static_cast<std::uint8_t>(s.counter + 1u);
    if (fb.counter != expected) {
      b.faults.lost_samples += static_cast<std::uint8_t>(fb.counter - expected);
      b.events |= fault::kSampleLost;
    }
  }
  b.counter_valid = true;
  s.counter = fb.counter;
  s.seq_echo = fb.cmd_seq_echo;
  s.mode = fb.mode;
  s.status = fb.status;
  s.timestamp = detail::rxTime(rx, now);
  for (std::uint32_t j = 0; j < fb.count; ++j) {
    HandJointState& js = b.joints[fb.first_joint + j];
    js.position = fb.joint[j].position;
    js.velocity = fb.joint[j].velocity;
    js.torque = fb.joint[j].torque;
  }
  if (fb.first_joint % MRQP_FW_HAND_FD_MAX_JOINTS == 0u) {
    b.chunks_seen |= 1u << (fb.first_joint / MRQP_FW_HAND_FD_MAX_JOINTS);
  }
  return Claim::Accepted;
}

}  // namespace mrqp::drivers
