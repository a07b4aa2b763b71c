// mrqp emulation -- one hand controller board's firmware on CAN FD (firmware_if/hand_fd_frame.h),
// transport-free.
//
// Each valid command frame (0x120 + board) sets the mode and, for its joints, the servo: POSITION
// -> the board's PD (kp, kd of the options) on position / velocity plus the feed-forward torque,
// TORQUE -> torque only, HOLD -> the PD on the position measured when HOLD began, DISABLED -> no
// servo. It is answered after the response delay by one feedback frame (0x140 + board) of the
// same joints: the command's sequence echoed, the feedback counter + 1, mode, status, and the
// joints as the host measures them. A command that fails its CRC is dropped and sets the status
// bit CRC_ERROR_SEEN. With a command timeout, no valid command for that long drops an enabled
// board into HOLD with COMMAND_TIMEOUT set (cleared by the next command).
//
// Fault switches: setSilent() (no feedback), corruptFeedback(n) (the next n feedback frames with
// a flipped bit: CRC error at the master), setStale() (joints no longer read from the host and
// the counter stands still: the master sees a counter gap), raiseFault() (status FAULT, servo
// off, commanded modes ignored until a DISABLED command clears it). No allocation.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>

#include "mrqp/emulation/joint_host.hpp"
#include "mrqp/firmware_if/hand_fd_frame.h"

namespace mrqp::emulation {

class EmulatedHandBoard {
 public:
  static constexpr TimeNs kNever = INT64_MAX;

  struct Options {
    std::uint8_t board = 0;    ///< 0..15
    std::uint8_t joints = 20;  ///< 1..32
    std::size_t joint = 0;     ///< the host's index of joint 0 of this board
    mrqp_fw_hand_scale scale = MRQP_FW_HAND_SCALE_DEFAULT_INIT;
    double kp = 5.0;   ///< N m/rad: the board's position gain
    double kd = 0.05;  ///< N m s/rad
    TimeNs response_delay = 20000;
    TimeNs command_timeout = 0;  ///< 0: none
  };

  EmulatedHandBoard(JointHost& host, const Options& options) noexcept;
  EmulatedHandBoard(const EmulatedHandBoard&) = delete;
  EmulatedHandBoard& operator=(const EmulatedHandBoard&) = delete;

  /// A frame on the bus at `now`; true if it was a command to this board.
  bool onFrame(const mrqp_fw_frame& frame, TimeNs now) noexcept;
  /// The command timeout, when due at or before `now`.
  void advance(TimeNs now) noexcept;
  TimeNs nextEvent() const noexcept;

  // ---- power and fault injection ----
  void powerOn(TimeNs now) noexcept;
  void setSilent(bool silent) noexcept { silent_ = silent; }
  void corruptFeedback(unsigned n) noexcept { corrupt_left_ = n; }
  void setStale(bool stale) noexcept { stale_ = stale; }
  void raiseFault(TimeNs now) noexcept;

  // ---- observation ----
  std::uint8_t mode() const noexcept { return mode_; }
  std::uint8_t status() const noexcept;
  const ServoCommand& servo(std::size_t joint) const noexcept { return servo_[joint]; }
  unsigned commands() const noexcept { return commands_; }

 private:
  void setMode(std::uint8_t mode, TimeNs now) noexcept;
  void servoOff(TimeNs now) noexcept;

  JointHost& host_;
  Options options_;
  std::array<ServoCommand, MRQP_FW_HAND_MAX_JOINTS> servo_{};
  std::array<mrqp_fw_hand_joint, MRQP_FW_HAND_MAX_JOINTS> measured_{};
  std::uint16_t seq_echo_ = 0;
  std::uint8_t counter_ = 0;
  std::uint8_t mode_ = MRQP_FW_HAND_MODE_DISABLED;
  bool crc_error_seen_ = false;
  bool timed_out_ = false;
  bool faulted_ = false;
  bool silent_ = false;
  bool stale_ = false;
  bool have_measured_ = false;
  unsigned corrupt_left_ = 0;
  unsigned commands_ = 0;
  TimeNs last_command_ = 0;
};

}  // namespace mrqp::emulation
