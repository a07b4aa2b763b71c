// Scene kind `force` (problem::ContactForceTask): the resultant force of `contact` to `target`
// [fx, fy, fz] (world, on the contact's surface entity; default zero).
#include "problem/tasks/contact_force_task.hpp"
#include "scene/task_kind.hpp"
#include "scene/yaml_reader.hpp"

namespace mrqp::scene {

namespace {

void readSubject(const Map& m, TaskSpec* t) { t->contact = m.name("contact"); }

std::unique_ptr<problem::Task> make(const TaskSpec& ts, const BuildContext& ctx, const std::string& field) {
  if (ts.contact.empty()) BuildContext::fail(ts.source, field + ".contact", "a force task needs a contact");
  const int contact = ctx.contact(ts.contact, ts.source, field + ".contact");
  const Eigen::Vector3d target = ts.target ? Eigen::Vector3d(ts.target->head<3>()) : Eigen::Vector3d::Zero();
  auto task = std::make_unique<problem::ContactForceTask>(contact, target);
  task->setSelection(fileSelection(ts));
  return task;
}

}  // namespace

TaskKindEntry forceKind() {
  return {"force", 3, {{"contact", "target", nullptr, nullptr}}, false, readSubject, nullptr, make};
}

}  // namespace mrqp::scene
