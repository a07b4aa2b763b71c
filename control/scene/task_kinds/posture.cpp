// Scene kind `posture` (problem::PostureTask): every joint of `entity` to `target`, a map joint
// name → value (joints not named keep their initial value).
#include "problem/tasks/posture_task.hpp"
#include "scene/task_kind.hpp"
#include "scene/yaml_reader.hpp"

namespace mrqp::scene {

namespace {

void readTarget(const Reader& r, const YAML::Node& n, const std::string& path, TaskSpec* t) {
  t->posture_target = r.numberMap(n, path);
}

std::unique_ptr<problem::Task> make(const TaskSpec& ts, const BuildContext& ctx, const std::string& field) {
  const int entity = taskEntity(ts, ctx, field);
  const problem::Entity& e = ctx.problem().entity(entity);
  Eigen::VectorXd qj(e.nv() - e.jointOffset());
  for (int k = e.jointOffset(); k < e.nv(); ++k) qj(k - e.jointOffset()) = e.q()(e.qIndexOfV(k));
  for (const auto& [jn, value] : ts.posture_target) {
    qj(ctx.joint(entity, jn, ts.source, field + ".target." + jn) - e.jointOffset()) = value;
  }
  auto task = std::make_unique<problem::PostureTask>(entity, static_cast<int>(qj.size()));
  if (!ts.posture_target.empty()) task->setTargetVector(qj);
  return task;
}

}  // namespace

TaskKindEntry postureKind() {
  return {"posture",  -1,  {{"entity", "target", nullptr, nullptr}}, false, readEntitySubject,
          readTarget, make};
}

}  // namespace mrqp::scene
