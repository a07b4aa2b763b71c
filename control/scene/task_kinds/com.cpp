// Scene kind `com` (problem::ComTask): the CoM of `entity`, or of the group `entities`, to
// `target` [x, y, z] (default: the CoM at start).
#include "problem/tasks/com_task.hpp"
#include "scene/task_kind.hpp"
#include "scene/yaml_reader.hpp"

namespace mrqp::scene {

namespace {

void readSubject(const Map& m, TaskSpec* t) {
  const Reader& r = m.reader();
  if (m.has("entities")) {
    m.forbid("entity", "give either 'entity' or 'entities', not both");
    t->entities = r.names(m.require("entities"), m.at("entities"));
    if (t->entities.empty()) {
      r.fail(m.require("entities"), m.at("entities"), "expected at least one entity");
    }
  } else {
    readEntitySubject(m, t);
  }
}

std::unique_ptr<problem::Task> make(const TaskSpec& ts, const BuildContext& ctx, const std::string& field) {
  const problem::MultiRobotProblem& p = ctx.problem();
  if (ts.entities.empty()) BuildContext::fail(ts.source, field + ".entity", "missing");
  std::uint32_t mask = 0;
  Eigen::Vector3d target;
  if (ts.entities.size() == 1) {
    const int e = ctx.entity(ts.entities[0], ts.source, field + ".entity");
    mask = 1u << e;
    target = p.entity(e).com();
  } else {
    for (const auto& n : ts.entities) mask |= 1u << ctx.entity(n, ts.source, field + ".entities");
    double m = 0.0;
    Eigen::Vector3d c = Eigen::Vector3d::Zero();
    for (int k = 0; k < p.entityCount(); ++k) {
      if ((mask >> k) & 1u) {
        m += p.entity(k).mass();
        c += p.entity(k).mass() * p.entity(k).com();
      }
    }
    target = c / m;
  }
  if (ts.target) target = ts.target->head<3>();
  auto task = std::make_unique<problem::ComTask>(mask, target);
  task->setSelection(fileSelection(ts));
  return task;
}

}  // namespace

TaskKindEntry comKind() {
  return {"com", 3, {{"entity", "entities", "target", nullptr}}, false, readSubject, nullptr, make};
}

}  // namespace mrqp::scene
