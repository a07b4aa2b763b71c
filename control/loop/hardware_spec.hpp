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

/// What the arm master reads and checks at boot before configuring a drive (0 = not checked):
/// device type 0x1000 (its low 16 bits, the profile number), identity 0x1018:1..3. A drive with
/// another value is not configured: its boot fails (docs/drivers.md).
struct DriveIdentity {
  std::uint32_t device_type = 0;
  std::uint32_t vendor_id = 0;
  std::uint32_t product_code = 0;
  std::uint32_t revision = 0;
};

/// A group of CiA 402 drives on one bus: node ids first_node, first_node + 1, ... in joint order.
struct Cia402Group {
  std::string bus;
  DriveMode mode = DriveMode::Csp;
  int first_node = 1;
  double rated_torque = 100.0;  ///< N·m per 1000 ‰ on the wire
  DriveIdentity identity;       ///< checked on every drive of the group
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

/// Where the controller's joint state of a robot comes from (docs/loop.md, "The cycle"): its
/// drives' feedback (the prediction corrected by measured − sent), or its own integrated command
/// (a position-controlled robot: the encoders are checked and logged, not fed back).
enum class JointState : std::uint8_t { Measured = 0, Commanded };

struct RobotHardware {
  std::string entity;
  int divisor = 1;  ///< the robot's cycle = the loop's period × divisor
  SafeStop safe_stop = SafeStop::Hold;
  double hold_damping = 1.0;  ///< 1/s: hold decays the commanded velocity by this rate
  JointState state = JointState::Measured;
  /// true: the drives ramp to each cyclic setpoint over the robot's period and sample their
  /// feedback at the SYNC that starts the ramp, so the velocity they report is that of the previous
  /// setpoint's ramp; the measured state's velocity is corrected against it (docs/loop.md).
  bool interpolating_drives = false;
  /// > 0: the deadline of each CiA 402 drive's RPDO1 in seconds, written to 0x1400:05 (its event
  /// timer, in ms) at boot; a drive that watches it reacts when the controller's setpoints stop.
  /// 0: not written (the drive's own value stands).
  double rpdo_timeout_s = 0.0;
  scene::Source rpdo_timeout_source;
  std::vector<Cia402Group> cia402;
  std::vector<ImpedanceGroup> impedance;
  std::vector<SensorDecl> ft_sensors;
  std::vector<SensorDecl> imus;
  scene::Source source;
};

/// How the arm drives are left at the end of a run (the arm driver's safe exit): the power stage
/// stopped by quick stop or disable voltage, then the NMT state.
enum class ExitStopKind : std::uint8_t { QuickStop = 0, DisableVoltage };
enum class ExitNmtKind : std::uint8_t { PreOperational = 0, Stopped, Unchanged };
struct SafeExitSpec {
  ExitStopKind stop = ExitStopKind::QuickStop;
  ExitNmtKind nmt = ExitNmtKind::PreOperational;
};

/// The loop's recovery of recoverable drive faults (docs/loop.md, "Safety"): at most max_attempts
/// attempts of backoff_s seconds each; 0 attempts: none (every fault stops the controller).
struct RecoverySpec {
  int max_attempts = 0;
  double backoff_s = 0.5;
};

/// The controller's heartbeat on the buses of the CiA 402 drives (node 0: none), and the consumer
/// time every drive is given for it (0x1016:1).
struct ControllerHeartbeatSpec {
  int node = 0;
  double period_s = 0.1;
  double drive_timeout_s = 0.3;
  scene::Source source;
};

struct HardwareSpec {
  bool present = false;               ///< the scene has a hardware section
  double heartbeat_timeout_s = 0.25;  ///< consumer time of the drives' heartbeats
  int feedback_missing_cycles = 3;    ///< robot cycles without feedback → fault
  double frame_loss_window = 100.0;   ///< robot cycles of the frame-loss rate's average
  double frame_loss_limit = 0.02;     ///< largest rate of robot cycles without fresh feedback
  ControllerHeartbeatSpec controller_heartbeat;
  RecoverySpec recovery;
  SafeExitSpec safe_exit;
  std::vector<BusDecl> buses;
  std::vector<RobotHardware> robots;
  scene::Source source;
};

}  // namespace mrqp::loop
