// The robot I/O map (docs/loop.md): for every robot entity with hardware, its drivers and each of
// its driven joints and sensors as (device, index) with its place in the entity's q and v, built
// once at set-up from the hardware section (makeRobotIo); the cycle reads and writes through it
// without any name lookup.
#pragma once

#include <mrqp/drivers/bus_router.hpp>
#include <mrqp/drivers/device.hpp>

#include <array>
#include <memory>
#include <string>
#include <vector>

#include "loop/hardware_check.hpp"
#include "loop/hardware_spec.hpp"

namespace mrqp::loop {

/// What a joint's command carries: a position (CiA 402 CSP: the drive derives the velocity from
/// successive targets), a torque (CST), or an impedance (MIT-mode motors and CAN FD hand boards:
/// position, velocity and the QP's τ as feed-forward, the device's own gains).
enum class JointKind : std::uint8_t { Position = 0, Torque, Impedance };

struct JointIo {
  drivers::JointDevice* device = nullptr;
  std::size_t index = 0;  ///< joint index within the device
  int v_index = -1;       ///< in the entity's v
  int q_index = -1;       ///< in the entity's q
  JointKind kind = JointKind::Position;
  bool torque = false;  ///< a torque-commanded joint (CST)
  std::string name;     ///< "ENTITY.JOINT" (logs, set-up only)
};

/// A force/torque sensor or an IMU of a robot.
struct SensorIo {
  drivers::Device* device = nullptr;
  std::size_t index = 0;    ///< sensor index within the device
  int frame = -1;           ///< entity frame
  std::string name;         ///< "ENTITY.FRAME"
  std::uint32_t stale = 0;  ///< consecutive robot cycles without a fresh sample
};

struct RobotIo {
  int entity = -1;
  std::string name;
  int divisor = 1;
  SafeStop safe_stop = SafeStop::Hold;
  double hold_damping = 1.0;
  std::vector<std::unique_ptr<drivers::Device>> devices;  ///< owned drivers
  std::vector<drivers::BusRouter*> routers;               ///< the buses this robot's devices use
  std::vector<JointIo> joints;
  std::vector<SensorIo> ft_sensors;
  std::vector<SensorIo> imus;
  std::vector<std::array<double, 6>> wrench;  ///< last F/T sample per sensor (sensor frame)
  std::vector<drivers::ImuFeedback> imu;      ///< last IMU sample per IMU
  // Per-joint cycle storage (sized at set-up).
  std::vector<double> q_cmd, v_cmd, tau_cmd;
  std::vector<double> q_meas, v_meas;
  std::vector<double> q_sent, v_sent;  ///< the last setpoint sent, as the drive reports it
  std::vector<double> v_sent_before;   ///< v_sent of the setpoint sent before it
  std::vector<std::uint32_t> stale;    ///< consecutive robot cycles without fresh feedback
  std::vector<double> miss_rate;       ///< averaged rate of robot cycles without fresh feedback
  double tracking_error_max = 0.0;     ///< |measured − commanded|, rad
};

/// Builds robot `robot` of the hardware section: its drivers on its buses (`routers[b]` is bus b
/// of the hardware section) — one ArmDriver for its CiA 402 drives, one MitHandDriver for its MIT
/// motors, one FdHandDriver for its hand boards, one FtSensorDriver and one ImuDriver for its
/// sensors (a SYNC of their own on a bus without drives) — and each joint and sensor as (device,
/// index), joints in that order. Set-up: allocates, throws std::runtime_error naming the robot.
RobotIo makeRobotIo(const ResolvedHardware& hw, std::size_t robot, const problem::Entity& entity,
                    const std::vector<drivers::BusRouter*>& routers, double dt);

}  // namespace mrqp::loop
