// mrqp drivers -- one face for every driver the control loop runs.
//
// The arm (CiA 402), the MIT-mode hand, the CAN FD hand boards, the F/T sensors and the IMUs all
// follow the same cycle (BusRouter::poll, update(now), setpoints, transmit(now)) and the same
// lifecycle (start, enable, safe stop, disable). Device is that lifecycle; JointDevice adds the
// joints a driver moves (one flat index over all its drives / motors / board joints), WrenchDevice
// the F/T sensors, ImuDevice the IMUs. The loop (control/loop) maps a robot's joint and frame
// names onto (device, index) once at set-up and then only calls these.
//
// Everything except declareTraffic() is real-time safe: noexcept, no allocation, no lock.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>

#include "mrqp/drivers/bus_budget.hpp"
#include "mrqp/drivers/faults.hpp"
#include "mrqp/drivers/setpoint.hpp"
#include "mrqp/drivers/time.hpp"

namespace mrqp::drivers {

/// How a joint is driven: the fields of JointCommand it uses.
enum class JointMode : std::uint8_t {
  Position = 0,  ///< position (and velocity feed-forward): CiA 402 CSP
  Torque,        ///< torque: CiA 402 CST
  Impedance      ///< position, velocity, gains and feed-forward torque: MIT mode, FD hand boards
};

/// One joint's setpoint for the next transmit().
struct JointCommand {
  double position = 0.0;    ///< rad
  double velocity = 0.0;    ///< rad/s
  double torque = 0.0;      ///< N m (the command in Torque mode, feed-forward otherwise)
  double stiffness = -1.0;  ///< N m/rad, Impedance mode; < 0: the device's configured default
  double damping = -1.0;    ///< N m s/rad, Impedance mode; < 0: the device's configured default
};

/// What the driver last received for one joint.
struct JointFeedback {
  double position = 0.0;  ///< rad
  double velocity = 0.0;  ///< rad/s
  double torque = 0.0;    ///< N m
  bool valid = false;     ///< something has been received
  bool fresh = false;     ///< received since the previous update()
  TimeNs timestamp = 0;
};

struct WrenchFeedback {
  std::array<double, 6> wrench{};  ///< fx fy fz (N), mx my mz (N m), sensor frame
  bool valid = false;
  bool fresh = false;
  TimeNs timestamp = 0;
};

struct ImuFeedback {
  std::array<double, 4> orientation{{1.0, 0.0, 0.0, 0.0}};  ///< w x y z, sensor frame in the world
  std::array<double, 3> angular_velocity{};                 ///< rad/s, sensor frame
  std::array<double, 3> specific_force{};                   ///< m/s², sensor frame
  bool valid = false;
  bool fresh = false;
  TimeNs timestamp = 0;
};

class Device {
 public:
  virtual ~Device() = default;
  /// "arm", "mit_hand", "fd_hand", "ft", "imu".
  virtual const char* kind() const noexcept = 0;

  /// Starts the boot sequence / monitoring.
  virtual void start(TimeNs now) noexcept = 0;
  /// Booted and, for actuators, every joint enabled: setpoints are being applied.
  virtual bool ready() const noexcept = 0;
  /// Actuators: power every joint (resetting faults). Sensors: nothing.
  virtual void requestEnable(TimeNs now) noexcept { (void)now; }
  /// Actuators: remove power. Sensors: nothing.
  virtual void requestDisable(TimeNs now) noexcept { (void)now; }
  /// The device's own safe stop (CiA 402 quick stop; an impedance motor holds with damping only).
  virtual void requestQuickStop(TimeNs now) noexcept { requestDisable(now); }

  /// After polling the buses: timeouts, state machines, this cycle's fault flags.
  virtual const FaultReport& update(TimeNs now) noexcept = 0;
  /// Sends this cycle's frames; returns how many were queued.
  virtual std::size_t transmit(TimeNs now) noexcept = 0;
  virtual const FaultReport& faults() const noexcept = 0;
  /// Adds this device's cyclic traffic on bus `bus` (index as given to create) to a budget.
  virtual void declareTraffic(std::size_t bus, BusBudget& budget) const = 0;

 protected:
  Device() = default;
  Device(const Device&) = default;
  Device& operator=(const Device&) = default;
};

class JointDevice : public Device {
 public:
  virtual std::size_t jointCount() const noexcept = 0;
  virtual JointMode jointMode(std::size_t joint) const noexcept = 0;
  virtual SetpointResult setJoint(std::size_t joint, const JointCommand& command) noexcept = 0;
  virtual JointFeedback joint(std::size_t joint) const noexcept = 0;
};

class WrenchDevice : public Device {
 public:
  virtual std::size_t sensorCount() const noexcept = 0;
  virtual WrenchFeedback wrench(std::size_t sensor) const noexcept = 0;
};

class ImuDevice : public Device {
 public:
  virtual std::size_t imuCount() const noexcept = 0;
  virtual ImuFeedback imu(std::size_t imu) const noexcept = 0;
};

}  // namespace mrqp::drivers
