// A controller loop on the emulated rig for the tests: a scene (text) with its hardware section,
// the ideal plant, the simulated buses with the emulated drives, the controller, and the cycle as
// mrqp-run runs it on one simulated clock (controller cycle, then buses and plant to the next).
#pragma once

#include <memory>
#include <string>

#include "loop/controller.hpp"
#include "loop/device_lifecycle.hpp"
#include "loop/emulated_rig.hpp"
#include "loop/hardware_check.hpp"
#include "loop/hardware_yaml.hpp"
#include "loop/ideal_plant.hpp"
#include "scene/builtin_models.hpp"
#include "scene/scene_builder.hpp"
#include "scene/scene_yaml.hpp"
#include "scene/yaml_reader.hpp"

namespace looptest {

using namespace mrqp;

inline std::string sceneText(const std::string& name) {
  return scene::readTextFile(std::string(MRQP_SCENES_DIR) + "/" + name);
}

struct LoopSetup {
  LoopSetup(const std::string& text, const std::string& file) {
    scene::addBuiltinModels(models);
    spec = scene::loadSceneString(text, file);
    sc = scene::buildScene(spec, models);
    hw = loop::resolveHardware(loop::readHardwareString(text, file), *sc.problem, sc.settings.dt);
    plant = std::make_unique<loop::IdealPlant>(scene::buildScene(spec, models).problem, *sc.problem);
    rig = std::make_unique<loop::EmulatedRig>(hw, *sc.problem, *plant);
    std::vector<drivers::Bus*> buses;
    for (std::size_t b = 0; b < rig->busCount(); ++b) buses.push_back(&rig->master(b));
    ctrl = std::make_unique<loop::Controller>(*sc.problem, hw, buses);
    period = static_cast<drivers::TimeNs>(std::llround(sc.settings.dt * 1e9));
  }

  /// Boots and enables every device; false when not ready within 10 s.
  bool boot() { return loop::bootDevices(*ctrl, now, period, rig.get()).done; }

  /// One loop cycle: the controller at `now`, then the buses and the plant to the next cycle.
  void cycle() noexcept {
    ctrl->cycle(now);
    plant->setFollowing(!ctrl->holding());
    rig->advanceTo(now + period);
    now += period;
  }

  scene::ModelRegistry models;
  scene::SceneSpec spec;
  scene::Scene sc;
  loop::ResolvedHardware hw;
  std::unique_ptr<loop::IdealPlant> plant;
  std::unique_ptr<loop::EmulatedRig> rig;
  std::unique_ptr<loop::Controller> ctrl;
  drivers::TimeNs now = 0;
  drivers::TimeNs period = 1000000;
};

}  // namespace looptest
