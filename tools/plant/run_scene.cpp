// The scene of a run (see run_scene.hpp).
#include "run_scene.hpp"

#include "loop/hardware_yaml.hpp"
#include "loop/scene_override.hpp"
#include "plant_factory.hpp"
#include "scene/builtin_models.hpp"
#include "scene/yaml_reader.hpp"

namespace mrqp::run {

std::unique_ptr<RunScene> loadRunScene(const std::string& file, const std::vector<std::string>& sets,
                                       const std::string& plant_kind) {
  auto rs = std::make_unique<RunScene>();
  rs->file = file;
  rs->text = scene::readTextFile(file);
  for (const std::string& s : sets) rs->text = loop::applySceneOverride(rs->text, file, s);
  scene::addBuiltinModels(rs->models);
  rs->spec = scene::loadSceneString(rs->text, file);
  rs->scene = scene::buildScene(rs->spec, rs->models);
  const loop::HardwareSpec hw = loop::readHardwareString(rs->text, file);
  if (!hw.present) {
    throw scene::SceneError(file + ":1: hardware: the scene has no hardware section (docs/loop.md)");
  }
  rs->hardware = loop::resolveHardware(hw, *rs->scene.problem, rs->scene.settings.dt);
  std::string kind = plant_kind;
  if (kind.empty()) kind = loop::readPlantSimulatorString(rs->text, file);
  if (kind.empty()) kind = "ideal";
  rs->plant = makePlant(kind, rs->spec, rs->text, file, rs->models, *rs->scene.problem);
  return rs;
}

}  // namespace mrqp::run
