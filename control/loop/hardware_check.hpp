// The hardware section resolved against the scene's models (docs/loop.md): entity, joint and
// frame names to indices, buses to indices, node ids distinct per bus, one robot per bus (its
// drives' SYNC producer), and the bus budget of drivers/ run for every bus at the robot's cycle
// rate: an over-budget configuration is refused with the budget's own message. Every failure is a
// SceneError "FILE:LINE: FIELD: message". Host-side: allocates and throws.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "loop/hardware_spec.hpp"
#include "problem/multi_robot_problem.hpp"

namespace mrqp::loop {

struct ResolvedDrive {
  int joint = -1;    ///< velocity index in the entity
  int q_index = -1;  ///< position index in the entity
  std::string joint_name;
  int bus = -1;  ///< index into ResolvedHardware::buses
  int node = 1;
  DriveMode mode = DriveMode::Csp;
  double rated_torque = 100.0;
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
  std::vector<ResolvedDrive> drives;     ///< CiA 402, in the order of the file
  std::vector<ResolvedDrive> impedance;  ///< MIT / FD joints (declared)
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
};

/// Resolves `spec` against the entities of `problem` for a loop period `dt` (s).
ResolvedHardware resolveHardware(const HardwareSpec& spec, const problem::MultiRobotProblem& problem,
                                 double dt);

}  // namespace mrqp::loop
