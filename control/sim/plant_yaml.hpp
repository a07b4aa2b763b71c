// Reading the `plant:` section of a scene file (docs/mujoco.md) into a PlantSpec, with the scene
// reader's checks: every failure throws scene::SceneError "FILE:LINE: FIELD: message".
// Host-side: allocates and throws.
#pragma once

#include <string>

#include "sim/plant_spec.hpp"

namespace YAML {
class Node;
}

namespace mrqp::scene {
class Reader;
}

namespace mrqp::sim {

/// The section at `node` (field path "plant"); nullptr: no section (an ideal plant).
PlantSpec readPlantSection(const scene::Reader& reader, const YAML::Node* node);

/// The plant section of the scene file at `path` (the rest of the file is left to
/// scene::loadSceneFile).
PlantSpec loadPlantSpec(const std::string& path);

/// The same for a scene held in memory.
PlantSpec loadPlantSpecString(const std::string& text, const std::string& file_name_for_messages);

}  // namespace mrqp::sim
