// Scene kind `joint` (problem::JointTask): `joint` of `entity` to `target` (a number, or a list of
// one; default: its value at start).
#include "problem/tasks/joint_task.hpp"
#include "scene/task_kind.hpp"
#include "scene/yaml_reader.hpp"

namespace mrqp::scene {

namespace {

void readSubject(const Map& m, TaskSpec* t) {
  readEntitySubject(m, t);
  t->joint = m.name("joint");
}

void readTarget(const Reader& r, const YAML::Node& n, const std::string& path, TaskSpec* t) {
  t->target = n.IsScalar() ? Eigen::VectorXd::Constant(1, r.number(n, path)) : r.numbers(n, path, 1);
}

std::unique_ptr<problem::Task> make(const TaskSpec& ts, const BuildContext& ctx, const std::string& field) {
  const int entity = taskEntity(ts, ctx, field);
  const problem::Entity& e = ctx.problem().entity(entity);
  const int joint = ctx.joint(entity, ts.joint, ts.source, field + ".joint");
  const double target = ts.target ? (*ts.target)(0) : e.q()(e.qIndexOfV(joint));
  return std::make_unique<problem::JointTask>(entity, joint, target);
}

}  // namespace

TaskKindEntry jointKind() {
  return {"joint", 1, {{"entity", "joint", "target", nullptr}}, false, readSubject, readTarget, make};
}

}  // namespace mrqp::scene
