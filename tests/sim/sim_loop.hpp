// The controller loop of a shipped scene on the MuJoCo plant, for the tests: the scene's text
// (tools/scenes), the MuJoCo plant of its `plant:` section, the emulated rig (simulated buses, the
// emulated drives, F/T sensors and IMU on the plant), the controller, and the cycle as mrqp-run
// runs it on one simulated clock: controller cycle, then buses and plant to the next cycle.
// Ground truth comes from the plant (entity states, frame poses), never from the controller.
#pragma once

#include <cmath>
#include <memory>
#include <string>
#include <vector>

#include "loop/controller.hpp"
#include "loop/device_lifecycle.hpp"
#include "loop/emulated_rig.hpp"
#include "loop/hardware_check.hpp"
#include "loop/hardware_yaml.hpp"
#include "scene/builtin_models.hpp"
#include "scene/scene_builder.hpp"
#include "scene/scene_yaml.hpp"
#include "scene/yaml_reader.hpp"
#include "sim/mujoco_plant.hpp"
#include "sim/plant_yaml.hpp"

namespace mrqp::sim::testing {

inline std::string shippedScene(const std::string& name) {
  return scene::readTextFile(std::string(MRQP_SCENES_DIR) + "/" + name);
}

struct SimLoop {
  SimLoop(const std::string& text, const std::string& file) {
    scene::addBuiltinModels(models);
    spec = scene::loadSceneString(text, file);
    sc = scene::buildScene(spec, models);
    plant_spec = loadPlantSpecString(text, file);
    hw = loop::resolveHardware(loop::readHardwareString(text, file), *sc.problem, sc.settings.dt);
    plant = std::make_unique<MujocoPlant>(spec, plant_spec, &models);
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
    rig->advanceTo(now + period);
    now += period;
  }

  /// Runs up to `cycles` cycles; stops early at a safe stop. Returns the cycles run.
  long run(long cycles) noexcept {
    long k = 0;
    for (; k < cycles && !ctrl->safeStopped(); ++k) cycle();
    return k;
  }

  /// The plant's true world pose of a frame of an entity.
  Eigen::Isometry3d truePose(const std::string& entity, const std::string& frame) const {
    return plant->framePose(plant->frameHandle(entity, frame));
  }

  /// The plant's true state of an entity (the problem's convention).
  Eigen::VectorXd trueQ(const std::string& entity) const {
    const int e = plant->entityHandle(entity);
    Eigen::VectorXd q(plant->entityNq(e)), v(plant->entityNv(e));
    plant->entityState(e, q, v);
    return q;
  }

  double taskError(const std::string& task) const { return sc.problem->taskError(sc.tasks.at(task)).norm(); }

  scene::ModelRegistry models;
  scene::SceneSpec spec;
  scene::Scene sc;
  PlantSpec plant_spec;
  loop::ResolvedHardware hw;
  std::unique_ptr<MujocoPlant> plant;
  std::unique_ptr<loop::EmulatedRig> rig;
  std::unique_ptr<loop::Controller> ctrl;
  drivers::TimeNs now = 0;
  drivers::TimeNs period = 1000000;
};

}  // namespace mrqp::sim::testing
