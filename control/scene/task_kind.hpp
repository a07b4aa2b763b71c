// One task kind as the scene files know it (docs/scenes.md, docs/adding-a-task.md): its name (the
// `type:` of a task), the keys it takes beyond the common ones (name, type, weight, stiffness,
// damping, dims, active), the size of its `dims` and `target`, how to read what it acts on, and
// the factory that turns the TaskSpec into a problem::Task once the names can be resolved. Every
// kind is one line of the registry (task_registry.cpp). Host-side: allocates and throws.
#pragma once

#include <array>
#include <memory>
#include <string>
#include <vector>

#include "problem/task.hpp"
#include "scene/build_context.hpp"
#include "scene/scene_spec.hpp"

namespace YAML {
class Node;
}

namespace mrqp::scene {

class Map;
class Reader;

struct TaskKindEntry {
  const char* name;                 ///< `type:` in the file
  int size;                         ///< entries of dims and target; −1: any
  std::array<const char*, 4> keys;  ///< keys beyond the common ones (nullptr: unused)
  bool dims_may_be_empty;           ///< `dims: []` accepted
  /// Reads the keys of `keys` that name what the task acts on (entity, frame, joint, contact) into
  /// the spec (the target and the common keys are read by the caller).
  void (*read_subject)(const Map& m, TaskSpec* t);
  /// Reads `target:`; nullptr: a list of `size` numbers into TaskSpec::target.
  void (*read_target)(const Reader& r, const YAML::Node& n, const std::string& path, TaskSpec* t);
  /// Builds the task (names resolved through `ctx`, errors at `field`); the caller then sets the
  /// weight and the gains and adds it to the problem.
  std::unique_ptr<problem::Task> (*make)(const TaskSpec& t, const BuildContext& ctx,
                                         const std::string& field);
};

/// The registry: every task kind, in the order error messages list them.
const std::vector<TaskKindEntry>& taskKinds();
/// nullptr when no kind has that name.
const TaskKindEntry* findTaskKind(const std::string& name);
/// "posture, com, … or force_min".
std::string taskKindNames();

// Helpers shared by the kinds.
/// `entity: NAME` into t->entities.
void readEntitySubject(const Map& m, TaskSpec* t);
/// The single entity of a task (field.entity).
int taskEntity(const TaskSpec& t, const BuildContext& ctx, const std::string& field);
/// dims as written in the file (0/1 per row; rows not written stay selected).
problem::Task::Selection fileSelection(const TaskSpec& t);

}  // namespace mrqp::scene
