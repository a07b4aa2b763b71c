// The hardware section of a scene file (docs/loop.md): which buses exist at which bit rates and,
// for each robot entity, which of its actuated joints are CiA 402 drives (node ids, CSP or CST),
// MIT-mode motors or FD hand boards, and which frames carry a force/torque sensor or an IMU.
// Plain data with the file line of every element; read by readHardware (hardware_yaml.hpp),
// resolved against the models by resolveHardware (hardware_check.hpp).
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "scene/scene_spec.hpp"

namespace mrqp::loop {

struct BusDecl {
  std::string name;
  std::uint32_t bitrate = 1000000;  ///< nominal (arbitration) rate, bit/s
  std::uint32_t data_bitrate = 0;   ///< > 0: a CAN FD bus with this data-phase rate
  scene::Source source;
};

enum class DriveMode : std::uint8_t { Csp = 0, Cst };

/// A group of CiA 402 drives on one bus: node ids first_node, first_node + 1, ... in joint order.
struct Cia402Group {
  std::string bus;
  DriveMode mode = DriveMode::Csp;
  int first_node = 1;
  double rated_torque = 100.0;  ///< N·m per 1000 ‰ on the wire
  std::vector<std::string> joints;
  scene::Source source;
};

/// MIT-mode motors (kind "mit": motor ids first_id, first_id + 1, ... in joint order, on a classic
/// bus of their own) or the joints of one CAN FD hand board (kind "fd": board number `board`, its
/// joints in the board's order, on a CAN FD bus).
struct ImpedanceGroup {
  std::string kind;  ///< "mit" or "fd"
  std::string bus;
  int first_id = 1;  ///< mit: the first motor id (1..127); fd: the board (0..15)
  double kp = 50.0;  ///< mit: the impedance's stiffness, N·m/rad (N/m for a prismatic joint)
  double kd = 1.0;   ///< mit: its damping, N·m·s/rad; also the damping of the quick stop
  std::vector<std::string> joints;
  scene::Source source;
};

/// A sensor on a frame: a force/torque sensor or an IMU.
struct SensorDecl {
  std::string frame;
  std::string bus;
  int node = 1;
  scene::Source source;
};

enum class SafeStop : std::uint8_t { Hold = 0, QuickStop };

struct RobotHardware {
  std::string entity;
  int divisor = 1;  ///< the robot's cycle = the loop's period × divisor
  SafeStop safe_stop = SafeStop::Hold;
  double hold_damping = 1.0;  ///< 1/s: hold decays the commanded velocity by this rate
  std::vector<Cia402Group> cia402;
  std::vector<ImpedanceGroup> impedance;
  std::vector<SensorDecl> ft_sensors;
  std::vector<SensorDecl> imus;
  scene::Source source;
};

struct HardwareSpec {
  bool present = false;               ///< the scene has a hardware section
  double heartbeat_timeout_s = 0.25;  ///< consumer time of the drives' heartbeats
  int feedback_missing_cycles = 3;    ///< robot cycles without feedback → fault
  std::vector<BusDecl> buses;
  std::vector<RobotHardware> robots;
  scene::Source source;
};

}  // namespace mrqp::loop
