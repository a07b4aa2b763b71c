// The registry of task kinds: ONE line per kind (docs/adding-a-task.md). The order is the order in
// which the error message for an unknown `type:` lists them.
#include <algorithm>

#include "scene/task_kind.hpp"
#include "scene/yaml_reader.hpp"

namespace mrqp::scene {

// Each kind lives in task_kinds/<kind>.cpp.
TaskKindEntry postureKind();
TaskKindEntry comKind();
TaskKindEntry framePositionKind();
TaskKindEntry frameOrientationKind();
TaskKindEntry framePoseKind();
TaskKindEntry jointKind();
TaskKindEntry forceKind();
TaskKindEntry forceMinKind();

const std::vector<TaskKindEntry>& taskKinds() {
  static const std::vector<TaskKindEntry> kinds = {
      postureKind(),   comKind(),   framePositionKind(), frameOrientationKind(),
      framePoseKind(), jointKind(), forceKind(),         forceMinKind(),
  };
  return kinds;
}

const TaskKindEntry* findTaskKind(const std::string& name) {
  const auto& kinds = taskKinds();
  const auto it =
      std::find_if(kinds.begin(), kinds.end(), [&](const TaskKindEntry& k) { return name == k.name; });
  return it == kinds.end() ? nullptr : &*it;
}

std::string taskKindNames() {
  const auto& kinds = taskKinds();
  std::string s;
  for (std::size_t i = 0; i < kinds.size(); ++i) {
    if (i > 0) s += i + 1 == kinds.size() ? " or " : ", ";
    s += kinds[i].name;
  }
  return s;
}

void readEntitySubject(const Map& m, TaskSpec* t) { t->entities.push_back(m.name("entity")); }

int taskEntity(const TaskSpec& t, const BuildContext& ctx, const std::string& field) {
  if (t.entities.empty()) BuildContext::fail(t.source, field + ".entity", "missing");
  if (t.entities.size() > 1)
    BuildContext::fail(t.source, field + ".entities", "only a CoM task takes a group");
  return ctx.entity(t.entities[0], t.source, field + ".entity");
}

problem::Task::Selection fileSelection(const TaskSpec& t) {
  problem::Task::Selection sel{{1, 1, 1, 1, 1, 1}};
  for (std::size_t k = 0; k < t.dims.size() && k < 6; ++k) sel[k] = t.dims[k] ? 1 : 0;
  return sel;
}

}  // namespace mrqp::scene
