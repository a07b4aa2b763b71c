// One constraint kind as the scene files know it (docs/scenes.md, docs/adding-a-task.md): a
// top-level list of the file (`com_dampers`, `joint_inequalities`, ...), how one item is read,
// the capacity its items need in the problem, and how they are built into problem::Constraint
// objects once names can be resolved. Every kind is one line of the registry
// (constraint_registry.cpp). Host-side: allocates and throws.
#pragma once

#include <string>
#include <vector>

#include "problem/multi_robot_problem.hpp"
#include "scene/build_context.hpp"
#include "scene/scene_spec.hpp"

namespace YAML {
class Node;
}

namespace mrqp::scene {

class Map;
class Reader;
struct Scene;

struct ConstraintKindEntry {
  const char* key;     ///< the top-level list in the file
  const char* unique;  ///< field of an item that must be distinct among the items (nullptr: none)
  const char* what;    ///< how the duplicate message names that field ("joint inequality name")
  /// Reads item `path` of the list into the spec; returns the value of `unique` ("" when absent).
  std::string (*read)(const Reader& r, const YAML::Node& n, const std::string& path, SceneSpec* s);
  /// Adds the slots, inequality rows and equality rows the spec's items of this kind need.
  void (*reserve)(const SceneSpec& s, int* slots, int* rows, int* equalities);
  /// Builds every item of this kind and adds it to the problem (errors at "key[i]...").
  void (*build)(const SceneSpec& s, const BuildContext& ctx, problem::MultiRobotProblem& p, Scene* scene);
};

/// The registry: every constraint kind, in the order the file's lists are read and built.
const std::vector<ConstraintKindEntry>& constraintKinds();

/// interaction > security ≥ 0, damping > 0, with the messages of the velocity dampers.
void readDamperGains(const Map& m, double* interaction, double* security, double* damping);

}  // namespace mrqp::scene
