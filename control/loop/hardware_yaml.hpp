// Reading the hardware section of a scene file (docs/loop.md) into a HardwareSpec: structure and
// ranges only, every failure a SceneError "FILE:LINE: FIELD: message". Names of joints, frames
// and entities are checked against the models by resolveHardware (hardware_check.hpp).
// Host-side: allocates and throws.
#pragma once

#include <string>

#include "loop/hardware_spec.hpp"

namespace mrqp::loop {

/// The `hardware:` section of the scene held in `text` (absent: present == false).
HardwareSpec readHardwareString(const std::string& text, const std::string& file_name_for_messages);

/// The same for a file.
HardwareSpec readHardwareFile(const std::string& path);

/// `plant.simulator` of the scene ("ideal" or "mujoco"; "" when the scene has no plant section).
/// Only this key is read here; the MuJoCo plant reads the rest of the section.
std::string readPlantSimulatorString(const std::string& text, const std::string& file_name_for_messages);

}  // namespace mrqp::loop
