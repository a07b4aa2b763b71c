// What a task kind's factory sees while a scene is built (scene_builder.cpp): the problem with its
// entities and contacts, the contact names, and the element's place in the file. Resolves names to
// indices and throws SceneError "FILE:LINE: FIELD: message" (listing the known names) when a name
// does not exist. Host-side: allocates and throws.
#pragma once

#include <map>
#include <string>

#include "problem/multi_robot_problem.hpp"
#include "scene/scene_spec.hpp"

namespace mrqp::scene {

class BuildContext {
 public:
  BuildContext(const problem::MultiRobotProblem& p, const std::map<std::string, int>& contacts)
      : p_(p), contacts_(contacts) {}

  const problem::MultiRobotProblem& problem() const { return p_; }

  [[noreturn]] static void fail(const Source& src, const std::string& field, const std::string& msg);

  int entity(const std::string& name, const Source& src, const std::string& field) const;
  int frame(int entity, const std::string& name, const Source& src, const std::string& field) const;
  /// Velocity index within the entity.
  int joint(int entity, const std::string& name, const Source& src, const std::string& field) const;
  int contact(const std::string& name, const Source& src, const std::string& field) const;

 private:
  const problem::MultiRobotProblem& p_;
  const std::map<std::string, int>& contacts_;
};

}  // namespace mrqp::scene
