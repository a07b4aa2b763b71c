// The timeline section of a scene file (see timeline.hpp).
#include "loop/timeline.hpp"

#include <algorithm>

#include "scene/yaml_reader.hpp"

namespace mrqp::loop {

Timeline Timeline::read(const std::string& text, const std::string& file, const scene::Scene& sc) {
  Timeline tl;
  const YAML::Node doc = scene::parseYamlDocument(text, file);
  if (!doc.IsMap() || !doc["timeline"] || doc["timeline"].IsNull()) return tl;
  const scene::Reader r(file);
  const std::vector<YAML::Node> items = r.list(doc["timeline"], "timeline");
  for (std::size_t i = 0; i < items.size(); ++i) {
    const std::string path = scene::item("timeline", i);
    // Force-control events (mode, user force) are read and played by control/force.
    if (items[i].IsMap() && items[i]["force_control"]) continue;
    const scene::Map m(r, items[i], path, {"at", "task", "contact", "weight", "target", "active"});
    TimelineEvent e;
    e.at = r.number(m.require("at"), m.at("at"), scene::Bound::NonNegative);
    const bool task = m.has("task"), contact = m.has("contact");
    if (task == contact) r.fail(items[i], path, "expected exactly one of 'task' and 'contact'");
    const int changes = (m.has("weight") ? 1 : 0) + (m.has("target") ? 1 : 0) + (m.has("active") ? 1 : 0);
    if (changes != 1) r.fail(items[i], path, "expected exactly one of 'weight', 'target' and 'active'");
    if (m.has("active") && m.boolean("active", true)) {
      r.fail(*m.find("active"), m.at("active"), "only 'active: false' (switching off) is supported");
    }
    if (task) {
      const std::string name = m.name("task");
      const auto it = sc.tasks.find(name);
      if (it == sc.tasks.end()) r.fail(*m.find("task"), m.at("task"), "unknown task '" + name + "'");
      e.id = it->second;
      if (m.has("weight")) {
        e.kind = TimelineEvent::Kind::TaskWeight;
        e.value = r.number(*m.find("weight"), m.at("weight"), scene::Bound::NonNegative);
      } else if (m.has("target")) {
        e.kind = TimelineEvent::Kind::TaskTarget;
        const YAML::Node& t = *m.find("target");
        const int n = t.IsSequence() && t.size() == 1 ? 1 : 3;
        const Eigen::VectorXd v = r.numbers(t, m.at("target"), n);
        e.target = n == 1 ? Eigen::Vector3d(v(0), 0.0, 0.0) : Eigen::Vector3d(v);
      } else {
        e.kind = TimelineEvent::Kind::TaskOff;
      }
    } else {
      const std::string name = m.name("contact");
      const auto it = sc.contacts.find(name);
      if (it == sc.contacts.end())
        r.fail(*m.find("contact"), m.at("contact"), "unknown contact '" + name + "'");
      e.id = it->second;
      if (!m.has("active")) r.fail(items[i], path, "a contact can only be switched off ('active: false')");
      e.kind = TimelineEvent::Kind::ContactOff;
    }
    tl.events_.push_back(e);
  }
  std::stable_sort(tl.events_.begin(), tl.events_.end(),
                   [](const TimelineEvent& a, const TimelineEvent& b) { return a.at < b.at; });
  return tl;
}

void Timeline::onCycle(Controller& c, drivers::TimeNs) noexcept {
  const double t = static_cast<double>(c.cycles()) * c.period();
  problem::MultiRobotProblem& p = c.problem();
  while (next_ < events_.size() && events_[next_].at <= t + 1e-12) {
    const TimelineEvent& e = events_[next_++];
    switch (e.kind) {
      case TimelineEvent::Kind::TaskWeight:
        (void)p.setTaskWeight(e.id, e.value);
        break;
      case TimelineEvent::Kind::TaskTarget:
        (void)p.setTaskTarget(e.id, e.target);
        break;
      case TimelineEvent::Kind::TaskOff:
        (void)p.removeTask(e.id);
        break;
      case TimelineEvent::Kind::ContactOff:
        (void)p.removeContact(e.id);
        break;
    }
  }
}

}  // namespace mrqp::loop
