// mrqp emulation -- one MIT-mode motor's firmware (see emulated_mit_motor.hpp).
#include "mrqp/emulation/emulated_mit_motor.hpp"

namespace mrqp::emulation {

EmulatedMitMotor::EmulatedMitMotor(JointHost& host, const Options& options) noexcept
    : host_(host), options_(options) {}

void EmulatedMitMotor::powerOn(TimeNs now) noexcept {
  faulted_ = false;
  zero_ = 0.0;
  have_last_ = false;
  setServo(ServoCommand{}, now);
}

void EmulatedMitMotor::raiseFault(TimeNs now) noexcept {
  faulted_ = true;
  setServo(ServoCommand{}, now);
}

void EmulatedMitMotor::setServo(const ServoCommand& s, TimeNs now) noexcept {
  servo_ = s;
  host_.command(options_.joint, servo_, now);
}

bool EmulatedMitMotor::onFrame(const mrqp_fw_frame& f, TimeNs now) noexcept {
  if (f.id != options_.motor_id ||
      (f.flags & (MRQP_FW_FRAME_EXT | MRQP_FW_FRAME_RTR | MRQP_FW_FRAME_FD)) != 0u) {
    return false;
  }
  const mrqp_fw_mit_kind kind = mrqp_fw_mit_classify(&f);
  if (kind == MRQP_FW_MIT_KIND_INVALID) {
    return true;  // addressed to us, not a frame of the protocol: ignored, not answered
  }
  ++frames_;
  if (faulted_) {
    return true;
  }
  switch (kind) {
    case MRQP_FW_MIT_KIND_ENABLE: {
      ServoCommand s;
      s.enabled = true;  // no gains, no torque until the first command
      setServo(s, now);
      break;
    }
    case MRQP_FW_MIT_KIND_DISABLE:
      setServo(ServoCommand{}, now);
      break;
    case MRQP_FW_MIT_KIND_ZERO:
      zero_ = host_.measure(options_.joint, now).position;
      break;
    case MRQP_FW_MIT_KIND_COMMAND: {
      mrqp_fw_mit_cmd c;
      if (servo_.enabled && mrqp_fw_mit_unpack_cmd(&options_.ranges, &f, nullptr, &c) == MRQP_FW_OK) {
        ServoCommand s;
        s.position = static_cast<double>(c.p) + zero_;
        s.velocity = static_cast<double>(c.v);
        s.torque = static_cast<double>(c.t);
        s.kp = static_cast<double>(c.kp);
        s.kd = static_cast<double>(c.kd);
        s.enabled = true;
        setServo(s, now);
      }
      break;
    }
    case MRQP_FW_MIT_KIND_INVALID:
      break;
  }
  if (!stale_ || !have_last_) {
    last_ = host_.measure(options_.joint, now);
    have_last_ = true;
  }
  if (silent_) {
    return true;
  }
  const mrqp_fw_mit_reply r{options_.motor_id, static_cast<float>(last_.position - zero_),
                            static_cast<float>(last_.velocity), static_cast<float>(last_.torque)};
  mrqp_fw_frame out;
  if (!mrqp_fw_pack_failed(mrqp_fw_mit_pack_reply(&options_.ranges, &r, &out))) {
    if (corrupt_left_ > 0u) {
      --corrupt_left_;
      out.len = static_cast<std::uint8_t>(out.len - 1u);
    }
    host_.emit(out, now + options_.response_delay);
  }
  return true;
}

}  // namespace mrqp::emulation
