// Reading the force_control section of a scene file (docs/force-control.md) and the force-control
// events of its timeline, resolved against the built scene (tasks, contacts) and its resolved
// hardware section (robots, F/T sensors, robot rates) with the scene files' YAML checker: every
// failure a SceneError "FILE:LINE: FIELD: message" that lists what exists when a name is unknown.
// Host-side: allocates and throws.
#pragma once

#include <string>

#include "force/force_control_spec.hpp"
#include "loop/hardware_check.hpp"
#include "scene/scene_builder.hpp"

namespace mrqp::force {

/// The `force_control:` section of the scene held in `text` (absent: present == false) and the
/// timeline items that name `force_control`. `dt`: the loop period (s); each end-effector's
/// filter runs at 1 / (dt × its robot's divisor).
ForceControlSpec readForceControl(const std::string& text, const std::string& file_name_for_messages,
                                  const scene::Scene& scene, const loop::ResolvedHardware& hardware,
                                  double dt);

}  // namespace mrqp::force
