// mrqp emulation -- what an emulated actuator (MIT-mode motor, hand board) exchanges with the
// world around it: its frames go out, the plant's joint state comes in, the servo it was
// commanded goes out to the plant.
//
// One JointHost may serve many devices: each device is configured with the index of its first
// joint in the host's numbering (Options::joint), so a robot's plant can implement one host for
// all its motors and boards. Every call is made from the device's onFrame() / advance().
#pragma once

#include <cstddef>

#include "mrqp/drivers/time.hpp"
#include "mrqp/firmware_if/frame.h"

namespace mrqp::emulation {

using drivers::TimeNs;

/// The joint as the device's encoders and current sensing see it.
struct JointMeasurement {
  double position = 0.0;  ///< rad
  double velocity = 0.0;  ///< rad/s
  double torque = 0.0;    ///< N m
};

/// The servo the device applies to its joint: torque = kp (position - q) + kd (velocity - q̇) +
/// torque when enabled, no torque (free) when not.
struct ServoCommand {
  double position = 0.0;  ///< rad
  double velocity = 0.0;  ///< rad/s
  double torque = 0.0;    ///< N m, feed-forward
  double kp = 0.0;        ///< N m/rad
  double kd = 0.0;        ///< N m s/rad
  bool enabled = false;
};

class JointHost {
 public:
  /// A frame of the device, ready for the bus at `at`.
  virtual void emit(const mrqp_fw_frame& frame, TimeNs at) noexcept = 0;
  /// The state of joint `joint` now.
  virtual JointMeasurement measure(std::size_t joint, TimeNs now) noexcept = 0;
  /// The servo of joint `joint` from now on (called when it changes and on every command).
  virtual void command(std::size_t joint, const ServoCommand& servo, TimeNs now) noexcept = 0;

 protected:
  ~JointHost() = default;
};

}  // namespace mrqp::emulation
