// The hardware section resolved against the scene's models (docs/loop.md): entity, joint and
// frame names to indices, buses to indices, node ids distinct per bus, one robot per bus (its
// drives' SYNC producer), MIT motors alone on a classic bus (their replies use identifier 0x000,
// CANopen's NMT), hand boards and IMUs on CAN FD buses, and the bus budget of drivers/ run for every bus at the robot's cycle
// rate: an over-budget configuration is refused with the budget's own message. Every failure is a
// SceneError "FILE:LINE: FIELD: message". Host-side: allocates and throws.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "loop/hardware_spec.hpp"
#include "problem/multi_robot_problem.hpp"

namespace mrqp::drivers {
struct ArmConfig;
struct ArmDriveConfig;
}  // namespace mrqp::drivers

namespace mrqp::loop {

/// What drives a joint: a CiA 402 drive, an MIT-mode motor, a joint of a CAN FD hand board.
enum class ActuatorKind : std::uint8_t { Cia402 = 0, Mit, FdBoard };

struct ResolvedDrive {
  int joint = -1;    ///< velocity index in the entity
  int q_index = -1;  ///< position index in the entity
  std::string joint_name;
  int bus = -1;  ///< index into ResolvedHardware::buses
  int node = 1;  ///< CiA 402: node id; MIT: motor id; FD: board number
  DriveMode mode = DriveMode::Csp;
  double rated_torque = 100.0;
  DriveIdentity identity;  ///< CiA 402: checked at boot (0 = not checked)
  ActuatorKind kind = ActuatorKind::Cia402;
  int group = -1;    ///< MIT / FD: the group of the hardware section (an fd group is one board)
  double kp = -1.0;  ///< MIT: the impedance's stiffness
  double kd = -1.0;  ///< MIT: its damping
};

struct ResolvedSensor {
  int frame = -1;
  std::string frame_name;
  int bus = -1;
  int node = 1;
};

struct ResolvedRobot {
  int entity = -1;
  std::string name;
  int divisor = 1;
  SafeStop safe_stop = SafeStop::Hold;
  double hold_damping = 1.0;
  JointState state = JointState::Measured;
  bool interpolating_drives = false;  ///< RobotHardware::interpolating_drives
  double rpdo_timeout_s = 0.0;           ///< > 0: written to the CiA 402 drives' 0x1400:05
  std::vector<ResolvedDrive> drives;     ///< CiA 402, in the order of the file
  std::vector<ResolvedDrive> impedance;  ///< MIT motors and FD board joints, in the order of the file
  std::vector<ResolvedSensor> ft_sensors;
  std::vector<ResolvedSensor> imus;
};

struct ResolvedBus {
  BusDecl decl;
  int robot = -1;  ///< index into robots
  double cycle_hz = 0.0;
  double utilisation_worst = 0.0;
  std::string report;  ///< the budget's start-up report
};

struct ResolvedHardware {
  std::vector<ResolvedBus> buses;
  std::vector<ResolvedRobot> robots;
  double heartbeat_timeout_s = 0.25;
  int feedback_missing_cycles = 3;
  double frame_loss_window = 100.0;
  double frame_loss_limit = 0.02;
  ControllerHeartbeatSpec controller_heartbeat;
  RecoverySpec recovery;
  SafeExitSpec safe_exit;
};

/// The hardware section's controller heartbeat (master node, its period, the drives' consumer
/// time) and safe exit in an arm driver's configuration, and `robot`'s RPDO timeout (0x1400:05)
/// when given; recovery stays the loop's decision (RecoveryPolicy::Manual).
void applySafetyConfig(drivers::ArmConfig& config, const ResolvedHardware& hw,
                       const ResolvedRobot* robot = nullptr);

/// The identity a CiA 402 drive is checked against at boot, in its arm driver's configuration.
void applyDriveIdentity(drivers::ArmDriveConfig& config, const ResolvedDrive& drive);

/// Resolves `spec` against the entities of `problem` for a loop period `dt` (s).
ResolvedHardware resolveHardware(const HardwareSpec& spec, const problem::MultiRobotProblem& problem,
                                 double dt);

}  // namespace mrqp::loop
