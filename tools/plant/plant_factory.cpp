// The plant factory of mrqp-run and mrqp-plant (see plant_factory.hpp).
#include "plant_factory.hpp"

#include <stdexcept>

#include "loop/ideal_plant.hpp"
#include "scene/scene_builder.hpp"
#ifdef MRQP_RUN_HAVE_MUJOCO
#include "sim/mujoco_plant.hpp"
#include "sim/plant_yaml.hpp"
#endif

namespace mrqp::run {

std::unique_ptr<loop::Plant> makePlant(const std::string& kind, const scene::SceneSpec& spec,
                                       const std::string& text, const std::string& file,
                                       const scene::ModelRegistry& models,
                                       const problem::MultiRobotProblem& model) {
  if (kind == "ideal") {
    // The world: a problem of its own, built from the same scene.
    scene::Scene world = scene::buildScene(spec, models);
    return std::make_unique<loop::IdealPlant>(std::move(world.problem), model);
  }
  if (kind == "mujoco") {
#ifdef MRQP_RUN_HAVE_MUJOCO
    return std::make_unique<sim::MujocoPlant>(spec, sim::loadPlantSpecString(text, file), &models);
#else
    (void)text;
    (void)file;
    throw std::runtime_error("--plant mujoco: this build has no MuJoCo plant (use --plant ideal)");
#endif
  }
  throw std::invalid_argument("unknown plant '" + kind + "' (mujoco or ideal)");
}

}  // namespace mrqp::run
