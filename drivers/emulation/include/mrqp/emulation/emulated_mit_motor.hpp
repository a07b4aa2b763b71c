// mrqp emulation -- one MIT-mode motor's firmware (firmware_if/mit_frame.h), transport-free.
//
// Frames come in through onFrame(); each frame addressed to the motor (its id) is answered with
// one reply (identifier 0x000: id, position, velocity, torque measured through the host) after
// the response delay, as the motor controllers of that protocol do: "enter motor mode" enables
// the servo (zero gains until the first command), "exit motor mode" disables it, "zero" makes
// the current position the zero of the reported (and commanded) position, an impedance command
// sets the servo (p, v, kp, kd, t) while enabled and is only answered while disabled.
//
// Fault switches: setSilent() (no reply: the master's feedback goes missing), corruptReplies(n)
// (the next n replies one byte short), setStale() (replies repeat the last measurement: the
// encoder stopped), raiseFault() (the controller trips: leaves motor mode and stops answering
// until powerOn(), since the MIT reply has no fault field). No allocation.
#pragma once

#include <cstddef>
#include <cstdint>

#include "mrqp/emulation/joint_host.hpp"
#include "mrqp/firmware_if/mit_frame.h"

namespace mrqp::emulation {

class EmulatedMitMotor {
 public:
  struct Options {
    std::uint8_t motor_id = 1;  ///< 1..127
    std::size_t joint = 0;      ///< the host's index of this motor's joint
    mrqp_fw_mit_ranges ranges = MRQP_FW_MIT_RANGES_DEFAULT_INIT;
    TimeNs response_delay = 30000;  ///< command -> reply (30 us)
  };

  EmulatedMitMotor(JointHost& host, const Options& options) noexcept;
  EmulatedMitMotor(const EmulatedMitMotor&) = delete;
  EmulatedMitMotor& operator=(const EmulatedMitMotor&) = delete;

  /// A frame on the bus at `now`; true if it was addressed to this motor.
  bool onFrame(const mrqp_fw_frame& frame, TimeNs now) noexcept;
  /// Nothing is timed in this firmware (kept for the common device shape).
  void advance(TimeNs) noexcept {}
  TimeNs nextEvent() const noexcept { return INT64_MAX; }

  // ---- power and fault injection ----
  /// Power on again: motor mode off, zero offset cleared, fault cleared.
  void powerOn(TimeNs now) noexcept;
  void setSilent(bool silent) noexcept { silent_ = silent; }
  void corruptReplies(unsigned n) noexcept { corrupt_left_ = n; }
  void setStale(bool stale) noexcept { stale_ = stale; }
  void raiseFault(TimeNs now) noexcept;

  // ---- observation ----
  std::uint8_t motorId() const noexcept { return options_.motor_id; }
  bool enabled() const noexcept { return servo_.enabled; }
  bool faulted() const noexcept { return faulted_; }
  const ServoCommand& servo() const noexcept { return servo_; }
  unsigned frames() const noexcept { return frames_; }

 private:
  void setServo(const ServoCommand& s, TimeNs now) noexcept;

  JointHost& host_;
  Options options_;
  ServoCommand servo_{};
  JointMeasurement last_{};
  bool have_last_ = false;
  double zero_ = 0.0;
  bool silent_ = false;
  bool stale_ = false;
  bool faulted_ = false;
  unsigned corrupt_left_ = 0;
  unsigned frames_ = 0;
};

}  // namespace mrqp::emulation
