// From a SceneSpec (names) to a ready MultiRobotProblem (indices): entities made from the model
// registry and placed, contacts added, tasks and constraints built by their kinds' factories
// (task_registry.cpp, constraint_registry.cpp) and added. Every name is checked here; an error
// throws SceneError "FILE:LINE: FIELD: message" pointing at the element of the scene file.
#pragma once

#include <map>
#include <memory>
#include <string>

#include "problem/multi_robot_problem.hpp"
#include "scene/model_registry.hpp"
#include "scene/scene_spec.hpp"
#include "scene/scene_yaml.hpp"

namespace mrqp::scene {

struct Scene {
  SettingsSpec settings;
  std::unique_ptr<problem::MultiRobotProblem> problem;
  std::map<std::string, int> contacts;  ///< contact name → id
  std::map<std::string, int> tasks;     ///< task name → id (the active ones)
  /// Tasks declared `active: false`: built, then removed; restoreTask(id) activates one.
  std::map<std::string, int> inactive_tasks;
  std::map<std::string, int> joint_inequalities;  ///< joint inequality name → constraint id
  std::map<std::string, int> constraints;         ///< named constraints of every kind → id

  int contact(const std::string& name) const;  ///< throws std::out_of_range naming it
  int task(const std::string& name) const;
};

Scene buildScene(const SceneSpec& spec, const ModelRegistry& models);

/// loadSceneFile + buildScene.
Scene loadScene(const std::string& path, const ModelRegistry& models);

/// R = Rz(yaw) Ry(pitch) Rx(roll), as URDF.
Eigen::Matrix3d rotationFromRpy(const Eigen::Vector3d& rpy);

}  // namespace mrqp::scene
