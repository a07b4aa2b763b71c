// libFuzzer harness: scene files (docs/scenes.md) read and built, with the models mrqp ships
// (panda, jvrc1, door): yaml-cpp through the one YAML checker (control/scene/yaml_reader.hpp), the
// scene reader, the capacity checks and the scene builder up to a ready MultiRobotProblem.
//
// Properties beyond "no crash, no undefined behaviour, no allocation beyond libFuzzer's limit, no
// hang": every rejection is a SceneError whose message starts with the file name and a line
// ("FILE:LINE: ..."), never another exception; a scene that builds has the capacities its file asked
// for.
#include <cstddef>
#include <cstdint>
#include <string>

#include "fuzz_check.hpp"
#include "scene/builtin_models.hpp"
#include "scene/scene_builder.hpp"
#include "scene/scene_yaml.hpp"

namespace {

const char* const kFile = "fuzz.yaml";

bool startsWithFileLine(const std::string& message) {
  const std::string prefix = std::string(kFile) + ":";
  if (message.compare(0, prefix.size(), prefix) != 0) return false;
  std::size_t i = prefix.size();
  const std::size_t digits = i;
  while (i < message.size() && message[i] >= '0' && message[i] <= '9') ++i;
  return i > digits && i < message.size() && message[i] == ':';
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  static const mrqp::scene::ModelRegistry* const models = [] {
    auto* r = new mrqp::scene::ModelRegistry;
    mrqp::scene::addBuiltinModels(*r);
    return r;
  }();
  const std::string text(reinterpret_cast<const char*>(data), size);
  mrqp::scene::SceneSpec spec;
  try {
    spec = mrqp::scene::loadSceneString(text, kFile);
  } catch (const mrqp::scene::SceneError& e) {
    MRQP_FUZZ_CHECK(startsWithFileLine(e.what()));
    return 0;
  }
  try {
    const mrqp::scene::Scene scene = mrqp::scene::buildScene(spec, *models);
    MRQP_FUZZ_CHECK(scene.problem != nullptr);
    MRQP_FUZZ_CHECK(scene.problem->taskCapacity() == spec.settings.max_tasks);
    MRQP_FUZZ_CHECK(scene.problem->contactCapacity() == spec.settings.max_contacts);
  } catch (const mrqp::scene::SceneError& e) {
    MRQP_FUZZ_CHECK(startsWithFileLine(e.what()));
  }
  return 0;
}
