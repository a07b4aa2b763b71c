// The plant factory of mrqp-run and mrqp-plant: "ideal" (the problem's own model, loop/ideal_plant.hpp) or "mujoco"
// (control/sim, when this build has it; otherwise a clear error).
#pragma once

#include <memory>
#include <string>

#include "loop/plant.hpp"
#include "problem/multi_robot_problem.hpp"
#include "scene/model_registry.hpp"
#include "scene/scene_spec.hpp"

namespace mrqp::run {

/// `text` is the scene file's text (with --set applied), `file` its name for messages; `model`
/// the controller's problem (the ideal plant follows its solution).
std::unique_ptr<loop::Plant> makePlant(const std::string& kind, const scene::SceneSpec& spec,
                                       const std::string& text, const std::string& file,
                                       const scene::ModelRegistry& models,
                                       const problem::MultiRobotProblem& model);

}  // namespace mrqp::run
