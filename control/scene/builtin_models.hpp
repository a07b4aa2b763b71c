// The generated models mrqp compiles in for its own scenes: "panda" (fixed base), "jvrc1"
// (floating base), "door" (fixed base, hinge + handle). Other programs register their own.
#pragma once

#include "scene/model_registry.hpp"

namespace mrqp::scene {

/// Registers panda, jvrc1, door, shadow_hand (fixed base) and pen (floating base, docs/scenes.md "pen_click").
void addBuiltinModels(ModelRegistry& registry);

}  // namespace mrqp::scene
