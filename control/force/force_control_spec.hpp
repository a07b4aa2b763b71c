// The force_control section of a scene file resolved against the built scene and its hardware
// (docs/force-control.md): per end-effector the admittance's task, F/T sensor, normal, mode, user
// force and gains as indices and numbers, and the timeline's force-control events. Plain data,
// read by readForceControl (force_control_yaml.hpp), run by AdmittanceHook (admittance_hook.hpp).
#pragma once

#include <Eigen/Core>

#include <string>
#include <vector>

#include "force/admittance.hpp"
#include "force/force_mode.hpp"
#include "scene/scene_spec.hpp"

namespace mrqp::force {

struct EndEffectorSpec {
  std::string name;
  int entity = -1;        ///< the robot entity
  int task = -1;          ///< its frame_position or frame_pose task (the admittance's output)
  int sensor_robot = -1;  ///< the robot's index in the hardware section (ResolvedHardware::robots)
  int sensor = -1;        ///< the F/T sensor's index among that robot's ft_sensors
  int sensor_frame = -1;  ///< the entity frame carrying the sensor
  int divisor = 1;        ///< the robot's cycle in loop periods
  int contact = -1;       ///< the contact whose QP force is the target (switch 2 up), or −1
  int force_task = -1;    ///< the `force` task that carries fᵈ into the QP (switch 1 closed), or −1
  /// The direction in which the end-effector pushes on what it touches (unit), in the task
  /// frame's axes, or in world axes when normal_in_world.
  Eigen::Vector3d normal = Eigen::Vector3d::UnitZ();
  bool normal_in_world = false;
  ForceMode mode = ForceMode::Off;
  double force = 0.0;      ///< fᵈ along the normal, N
  bool force_set = false;  ///< fᵈ was written in the file
  AdmittanceGains gains;
  double tool_mass = 0.0;  ///< kg between the sensor and the contact (its weight is removed)
  scene::Source source;
};

/// A timeline event of the force control: a new mode and/or a new fᵈ for one end-effector.
struct ForceEvent {
  double at = 0.0;        ///< s since the first cycle
  int end_effector = -1;  ///< index into ForceControlSpec::end_effectors
  bool set_mode = false;
  ForceMode mode = ForceMode::Off;
  bool set_force = false;
  double force = 0.0;
};

struct ForceControlSpec {
  bool present = false;  ///< the scene has a force_control section
  std::vector<EndEffectorSpec> end_effectors;
  std::vector<ForceEvent> events;  ///< in time order (file order for equal times)
};

}  // namespace mrqp::force
