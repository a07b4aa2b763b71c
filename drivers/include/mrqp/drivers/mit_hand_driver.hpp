// mrqp drivers -- hand actuators in "MIT mode" on classic CAN (firmware_if/mit_frame.h).
//
// Every cycle each motor gets exactly one frame and answers with one reply (identifier 0x000,
// motor id in byte 0): an impedance command (p, v, kp, kd, t) when enabled, the special
// "enter motor mode" frame while enabling (repeated every cycle until the motor answers), "exit
// motor mode" while disabling (likewise), and while disabled a zero-gain command (kp = kd = t = 0:
// no torque even if the motor were enabled) so that positions are read and the motor is monitored.
// A reply missing for N cycles is a fault. The hand bus is not a CANopen bus: identifier 0x000
// is the master's reply address, so MIT motors need their own bus.
//
// Cycle: BusRouter::poll, update(now), setCommand(), transmit(now). Real-time safe after create().
//
// As a JointDevice (device.hpp) joint i is motor i, JointMode::Impedance: setJoint packs
// (position, velocity, stiffness -> kp, damping -> kd, torque -> t), a negative stiffness or
// damping taking the motor's configured default_kp / default_kd. requestQuickStop() holds every
// motor that is On with damping only (kp = 0, kd = quick_stop_kd, t = 0, v = 0) and ignores
// setpoints until the next requestEnable() or requestDisable().
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <limits>
#include <memory>
#include <string>
#include <vector>

#include "mrqp/drivers/bus_budget.hpp"
#include "mrqp/drivers/bus_router.hpp"
#include "mrqp/drivers/device.hpp"
#include "mrqp/drivers/faults.hpp"
#include "mrqp/drivers/router_attachment.hpp"
#include "mrqp/drivers/setpoint.hpp"
#include "mrqp/drivers/time.hpp"
#include "mrqp/firmware_if/mit_frame.h"

namespace mrqp::drivers {

struct MitMotorConfig {
  std::size_t bus = 0;        ///< index into the routers given to create()
  std::uint8_t motor_id = 1;  ///< 1..127
  mrqp_fw_mit_ranges ranges = MRQP_FW_MIT_RANGES_DEFAULT_INIT;
  float position_min = -std::numeric_limits<float>::infinity();  ///< rad: setpoints clamped, feedback flagged
  float position_max = std::numeric_limits<float>::infinity();
  float default_kp = 0.0f;     ///< N m/rad: JointCommand::stiffness < 0
  float default_kd = 0.0f;     ///< N m s/rad: JointCommand::damping < 0
  float quick_stop_kd = 0.0f;  ///< N m s/rad: the damping of requestQuickStop()
};

struct MitHandConfig {
  std::vector<MitMotorConfig> motors;
  std::uint32_t feedback_missing_cycles = 3;
  bool poll_when_disabled = true;  ///< zero-gain commands while disabled
  TimeNs enable_timeout = milliseconds(100);
};

/// Per-motor power mode as driven by this driver.
enum class MitMode : std::uint8_t { Off = 0, Enabling, On, Disabling };

struct MitMotorState {
  float position = 0.0f;  ///< rad
  float velocity = 0.0f;  ///< rad/s
  float torque = 0.0f;    ///< N m
  MitMode mode = MitMode::Off;
  bool valid = false;  ///< a reply has been received
  bool fresh = false;  ///< a reply arrived since the previous update()
  TimeNs timestamp = 0;
};

class MitHandDriver final : public JointDevice, public FrameHandler {
 public:
  static std::unique_ptr<MitHandDriver> create(const std::vector<BusRouter*>& buses,
                                               const MitHandConfig& config, std::string* error);
  MitHandDriver(const MitHandDriver&) = delete;
  MitHandDriver& operator=(const MitHandDriver&) = delete;

  const char* kind() const noexcept override { return "mit_hand"; }
  /// Nothing to boot: motors are polled from the first transmit().
  void start(TimeNs) noexcept override {}
  bool ready() const noexcept override { return allOn(); }
  void requestEnable(TimeNs now) noexcept override;
  void requestDisable(TimeNs now) noexcept override;
  /// Holds every motor with damping only (see above).
  void requestQuickStop(TimeNs now) noexcept override;

  const FaultReport& update(TimeNs now) noexcept override;
  /// Impedance command for the next transmit() (used while the motor is On).
  SetpointResult setCommand(std::size_t motor, const mrqp_fw_mit_cmd& cmd) noexcept;
  std::size_t transmit(TimeNs now) noexcept override;

  // JointDevice: joint i is motor i.
  std::size_t jointCount() const noexcept override { return motors_.size(); }
  JointMode jointMode(std::size_t) const noexcept override { return JointMode::Impedance; }
  SetpointResult setJoint(std::size_t joint, const JointCommand& command) noexcept override;
  JointFeedback joint(std::size_t joint) const noexcept override;
  bool quickStopped() const noexcept { return quick_stop_; }

  Claim onFrame(const BusRouter& from, const RxFrame& rx, TimeNs now) noexcept override;

  bool allOn() const noexcept;
  bool allOff() const noexcept;
  std::size_t motorCount() const noexcept { return motors_.size(); }
  const MitMotorState& motor(std::size_t i) const noexcept { return motors_[i].state; }
  const FaultReport& faults() const noexcept override { return routers_.report(); }
  void declareTraffic(std::size_t bus, BusBudget& budget) const override;

 private:
  struct Motor {
    MitMotorConfig cfg;
    MitMotorState state;
    DeviceFaults faults;
    std::uint32_t events = 0;
    mrqp_fw_mit_cmd sp{};
    bool sp_valid = false;
    bool sent = false;          ///< a frame went out at the previous transmit
    bool replied = false;       ///< a reply since the previous update
    bool special_sent = false;  ///< ENABLE / DISABLE went out; the next reply confirms it
    TimeNs mode_since = 0;
  };
  struct BusSlot {
    std::array<std::int16_t, 128> id_to_motor{};
  };
  MitHandDriver() = default;

  MitHandConfig config_;
  bool quick_stop_ = false;
  std::vector<Motor> motors_;
  std::vector<BusSlot> buses_;
  RouterAttachment routers_;
};

}  // namespace mrqp::drivers
