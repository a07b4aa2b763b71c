// Small scenes of the MuJoCo plant tests, built from YAML text with the scene and plant readers.
#pragma once

#include <memory>
#include <string>

#include "scene/builtin_models.hpp"
#include "scene/scene_yaml.hpp"
#include "sim/mujoco_plant.hpp"
#include "sim/plant_yaml.hpp"

namespace mrqp::sim::testing {

inline const scene::ModelRegistry& registry() {
  static const scene::ModelRegistry r = [] {
    scene::ModelRegistry reg;
    scene::addBuiltinModels(reg);
    return reg;
  }();
  return r;
}

/// The plant of a scene written in YAML (scene and plant section in one text).
inline std::unique_ptr<MujocoPlant> makePlant(const std::string& yaml) {
  const scene::SceneSpec s = scene::loadSceneString(yaml, "test.yaml");
  const PlantSpec p = loadPlantSpecString(yaml, "test.yaml");
  return std::make_unique<MujocoPlant>(s, p, &registry());
}

}  // namespace mrqp::sim::testing
