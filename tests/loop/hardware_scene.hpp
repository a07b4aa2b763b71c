// A scene for the tests of the hardware section (docs/loop.md, "The hardware section"): the text
// of its other sections, to which each test appends a hardware section, builds the scene with the
// built-in models and resolves the hardware against it as mrqp-run does; or reads the
// FILE:LINE: FIELD error that stops it (the file is named "s.yaml").
#pragma once

#include <string>
#include <utility>

#include "loop/hardware_check.hpp"
#include "loop/hardware_yaml.hpp"
#include "scene/builtin_models.hpp"
#include "scene/scene_builder.hpp"
#include "scene/scene_yaml.hpp"

namespace looptest {

class HardwareScene {
 public:
  explicit HardwareScene(std::string scene_text) : scene_text_(std::move(scene_text)) {}

  // The scene's text followed by `hw`, built and its hardware resolved (throws scene::SceneError).
  mrqp::loop::ResolvedHardware resolve(const std::string& hw) const {
    using namespace mrqp;
    const std::string text = scene_text_ + hw;
    scene::ModelRegistry models;
    scene::addBuiltinModels(models);
    const scene::Scene sc = scene::buildScene(scene::loadSceneString(text, "s.yaml"), models);
    return loop::resolveHardware(loop::readHardwareString(text, "s.yaml"), *sc.problem, sc.settings.dt);
  }

  // The message of the error resolve(hw) throws, or "(no error)".
  std::string errorOf(const std::string& hw) const {
    try {
      resolve(hw);
    } catch (const mrqp::scene::SceneError& e) {
      return e.what();
    }
    return "(no error)";
  }

 private:
  std::string scene_text_;
};

}  // namespace looptest
