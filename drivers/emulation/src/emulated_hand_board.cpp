// mrqp emulation -- one hand controller board's firmware (see emulated_hand_board.hpp).
#include "mrqp/emulation/emulated_hand_board.hpp"

namespace mrqp::emulation {

EmulatedHandBoard::EmulatedHandBoard(JointHost& host, const Options& options) noexcept
    : host_(host), options_(options) {
  if (options_.joints > MRQP_FW_HAND_MAX_JOINTS) {
    options_.joints = MRQP_FW_HAND_MAX_JOINTS;
  }
}

std::uint8_t EmulatedHandBoard::status() const noexcept {
  unsigned st = 0;
  if (mode_ != MRQP_FW_HAND_MODE_DISABLED) {
    st |= MRQP_FW_HAND_STATUS_ENABLED;
  }
  if (faulted_) {
    st |= MRQP_FW_HAND_STATUS_FAULT;
  }
  if (timed_out_) {
    st |= MRQP_FW_HAND_STATUS_COMMAND_TIMEOUT;
  }
  if (crc_error_seen_) {
    st |= MRQP_FW_HAND_STATUS_CRC_ERROR_SEEN;
  }
  return static_cast<std::uint8_t>(st);
}

void EmulatedHandBoard::servoOff(TimeNs now) noexcept {
  for (std::size_t j = 0; j < options_.joints; ++j) {
    servo_[j] = ServoCommand{};
    host_.command(options_.joint + j, servo_[j], now);
  }
}

void EmulatedHandBoard::setMode(std::uint8_t mode, TimeNs now) noexcept {
  if (mode == MRQP_FW_HAND_MODE_HOLD && mode_ != MRQP_FW_HAND_MODE_HOLD) {
    for (std::size_t j = 0; j < options_.joints; ++j) {
      ServoCommand s;
      s.position = host_.measure(options_.joint + j, now).position;
      s.kp = options_.kp;
      s.kd = options_.kd;
      s.enabled = true;
      servo_[j] = s;
      host_.command(options_.joint + j, s, now);
    }
  } else if (mode == MRQP_FW_HAND_MODE_DISABLED && mode_ != MRQP_FW_HAND_MODE_DISABLED) {
    servoOff(now);
  }
  mode_ = mode;
}

void EmulatedHandBoard::powerOn(TimeNs now) noexcept {
  faulted_ = false;
  timed_out_ = false;
  crc_error_seen_ = false;
  counter_ = 0;
  seq_echo_ = 0;
  have_measured_ = false;
  mode_ = MRQP_FW_HAND_MODE_DISABLED;
  servoOff(now);
}

void EmulatedHandBoard::raiseFault(TimeNs now) noexcept {
  faulted_ = true;
  mode_ = MRQP_FW_HAND_MODE_DISABLED;
  servoOff(now);
}

TimeNs EmulatedHandBoard::nextEvent() const noexcept {
  if (options_.command_timeout <= 0 || mode_ == MRQP_FW_HAND_MODE_DISABLED ||
      mode_ == MRQP_FW_HAND_MODE_HOLD) {
    return kNever;
  }
  return last_command_ + options_.command_timeout;
}

void EmulatedHandBoard::advance(TimeNs now) noexcept {
  if (nextEvent() <= now) {
    timed_out_ = true;
    setMode(MRQP_FW_HAND_MODE_HOLD, now);
  }
}

bool EmulatedHandBoard::onFrame(const mrqp_fw_frame& f, TimeNs now) noexcept {
  if (f.id != MRQP_FW_HAND_FD_CMD_ID_BASE + options_.board || (f.flags & MRQP_FW_FRAME_EXT) != 0u) {
    return false;
  }
  mrqp_fw_hand_cmd c;
  if (mrqp_fw_hand_unpack_cmd(&options_.scale, &f, options_.board, &c) != MRQP_FW_OK ||
      static_cast<unsigned>(c.first_joint) + c.count > options_.joints) {
    crc_error_seen_ = true;
    return true;
  }
  ++commands_;
  last_command_ = now;
  timed_out_ = false;
  seq_echo_ = c.seq;
  if (faulted_ && c.mode == MRQP_FW_HAND_MODE_DISABLED) {
    faulted_ = false;
  }
  if (!faulted_) {
    setMode(c.mode, now);
    for (unsigned j = 0; j < c.count; ++j) {
      const std::size_t joint = c.first_joint + j;
      ServoCommand s;
      if (mode_ == MRQP_FW_HAND_MODE_POSITION) {
        s.position = static_cast<double>(c.joint[j].position);
        s.velocity = static_cast<double>(c.joint[j].velocity);
        s.torque = static_cast<double>(c.joint[j].torque);
        s.kp = options_.kp;
        s.kd = options_.kd;
        s.enabled = true;
      } else if (mode_ == MRQP_FW_HAND_MODE_TORQUE) {
        s.torque = static_cast<double>(c.joint[j].torque);
        s.enabled = true;
      } else {
        continue;  // HOLD keeps its servo, DISABLED has none
      }
      servo_[joint] = s;
      host_.command(options_.joint + joint, s, now);
    }
  }
  if (!stale_ || !have_measured_) {
    for (std::size_t j = 0; j < options_.joints; ++j) {
      const JointMeasurement m = host_.measure(options_.joint + j, now);
      measured_[j] = mrqp_fw_hand_joint{static_cast<float>(m.position), static_cast<float>(m.velocity),
                                        static_cast<float>(m.torque)};
    }
    have_measured_ = true;
  }
  if (silent_) {
    return true;
  }
  mrqp_fw_hand_fb fb{};
  fb.cmd_seq_echo = seq_echo_;
  fb.counter = stale_ ? counter_ : ++counter_;
  fb.mode = mode_;
  fb.status = status();
  fb.first_joint = c.first_joint;
  fb.count = c.count;
  for (unsigned j = 0; j < c.count; ++j) {
    fb.joint[j] = measured_[c.first_joint + j];
  }
  mrqp_fw_frame out;
  if (!mrqp_fw_pack_failed(mrqp_fw_hand_pack_fb(&options_.scale, options_.board, &fb, &out, nullptr))) {
    if (corrupt_left_ > 0u) {
      --corrupt_left_;
      out.data[2] ^= 0x01u;  // the counter byte: the CRC no longer matches
    }
    host_.emit(out, now + options_.response_delay);
  }
  return true;
}

}  // namespace mrqp::emulation
