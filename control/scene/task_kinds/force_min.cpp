// Scene kind `force_min` (problem::ForceMinTask): ‖λ‖² of `contact`, or of every contact when
// `contact` is not given.
#include "problem/tasks/force_min_task.hpp"
#include "scene/task_kind.hpp"
#include "scene/yaml_reader.hpp"

namespace mrqp::scene {

namespace {

void readSubject(const Map& m, TaskSpec* t) {
  if (m.has("contact")) t->contact = m.name("contact");
}

std::unique_ptr<problem::Task> make(const TaskSpec& ts, const BuildContext& ctx, const std::string& field) {
  const int contact = ts.contact.empty() ? -1 : ctx.contact(ts.contact, ts.source, field + ".contact");
  return std::make_unique<problem::ForceMinTask>(contact);
}

}  // namespace

TaskKindEntry forceMinKind() {
  return {"force_min", -1, {{"contact", nullptr, nullptr, nullptr}}, true, readSubject, nullptr, make};
}

}  // namespace mrqp::scene
