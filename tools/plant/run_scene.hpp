// The scene of a run, loaded as mrqp-run and mrqp-plant both need it (docs/loop.md): the file's
// text with the --set overrides applied, the model registry, the scene spec and the built scene
// (the controller's problem), its hardware section (required) resolved against the models at the
// scene's period, and the plant — `--plant` when given, else the scene's plant.simulator, else
// ideal. Host-side: allocates and throws (scene::SceneError "FILE:LINE: FIELD: message" for the
// scene, std::runtime_error otherwise).
#pragma once

#include <memory>
#include <string>
#include <vector>

#include "loop/hardware_check.hpp"
#include "loop/plant.hpp"
#include "scene/model_registry.hpp"
#include "scene/scene_builder.hpp"
#include "scene/scene_spec.hpp"

namespace mrqp::run {

struct RunScene {
  std::string file;  ///< the scene file (for messages)
  std::string text;  ///< its text with the overrides applied
  scene::ModelRegistry models;
  scene::SceneSpec spec;
  scene::Scene scene;
  loop::ResolvedHardware hardware;
  std::unique_ptr<loop::Plant> plant;
};

/// Loads `file` with the overrides `sets` ("KEY=VALUE", in order) and the plant `plant_kind`
/// ("ideal", "mujoco", or "" for the scene's choice). Not movable (the plant refers to the rest):
/// returned by pointer.
std::unique_ptr<RunScene> loadRunScene(const std::string& file, const std::vector<std::string>& sets,
                                       const std::string& plant_kind);

}  // namespace mrqp::run
