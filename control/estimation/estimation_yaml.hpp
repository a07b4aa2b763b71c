// Reading the estimation section of a scene file (docs/estimation.md), resolved against the scene
// (entities, contacts, spring joints), its resolved hardware section (robots, F/T sensors, robot
// rates) and its plant section (the F/T noise that sets R) with the scene files' YAML checker:
// every failure a SceneError "FILE:LINE: FIELD: message" that lists what exists when a name is
// unknown. The true values that a run's summary compares with (a rigid object's mass and CoM, a
// joint's spring) come from the scene's description of the world, the plant's source. Host-side:
// allocates and throws.
#pragma once

#include <string>

#include "estimation/estimation_spec.hpp"
#include "loop/hardware_check.hpp"
#include "scene/scene_builder.hpp"
#include "scene/scene_spec.hpp"

namespace mrqp::estimation {

/// The `estimation:` section of the scene held in `text` (absent: present == false).
EstimationSpec readEstimation(const std::string& text, const std::string& file_name_for_messages,
                              const scene::SceneSpec& spec, const scene::Scene& scene,
                              const loop::ResolvedHardware& hardware);

}  // namespace mrqp::estimation
