// The force_control section of a scene file (see force_control_yaml.hpp).
#include "force/force_control_yaml.hpp"

#include <algorithm>

#include "problem/tasks/contact_force_task.hpp"
#include "problem/tasks/frame_task.hpp"
#include "scene/yaml_reader.hpp"

namespace mrqp::force {

namespace {

using scene::Bound;
using scene::Map;
using scene::nameList;
using scene::Reader;

/// Task id by name, active or declared inactive; −1 when unknown.
int findTask(const scene::Scene& sc, const std::string& name) {
  if (const auto it = sc.tasks.find(name); it != sc.tasks.end()) return it->second;
  if (const auto it = sc.inactive_tasks.find(name); it != sc.inactive_tasks.end()) return it->second;
  return -1;
}

bool isFrameTask(const problem::Task& t) {
  const std::string k = t.kind();
  return (k == "frame_position" || k == "frame_pose") &&
         dynamic_cast<const problem::FrameTask*>(&t) != nullptr;
}

bool isForceTask(const problem::Task& t) {
  return dynamic_cast<const problem::ContactForceTask*>(&t) != nullptr;
}

/// Names of the scene's tasks that pass `keep`, for messages.
template <class Keep>
std::string taskNames(const scene::Scene& sc, Keep keep) {
  std::vector<std::string> out;
  for (const auto* m : {&sc.tasks, &sc.inactive_tasks}) {
    for (const auto& [name, id] : *m) {
      if (keep(sc.problem->task(id))) out.push_back(name);
    }
  }
  std::sort(out.begin(), out.end());
  return nameList(out);
}

bool touches(const problem::ContactDesc& c, int entity) {
  return c.entity == entity || c.other_entity == entity;
}

/// The keys a mode needs (contact, force task, user force).
void requireForMode(const Reader& r, const YAML::Node& at, const std::string& field, const EndEffectorSpec& e,
                    ForceMode mode, bool force_given) {
  const std::string name = forceModeName(mode);
  if (targetFromQp(mode) && e.contact < 0) {
    r.fail(at, field,
           "mode '" + name + "' tracks the QP's force on a contact: end-effector '" + e.name +
               "' needs 'contact' (or 'force_task')");
  }
  if (forceTaskOn(mode) && e.force_task < 0) {
    r.fail(at, field,
           "mode '" + name + "' gives the user force to the QP: end-effector '" + e.name +
               "' needs 'force_task' (a task of type force)");
  }
  if (usesUserForce(mode) && !force_given) {
    r.fail(at, field, "mode '" + name + "' uses the user force: give 'force'");
  }
}

ForceMode readMode(const Reader& r, const YAML::Node& n, const std::string& field) {
  const std::string s = r.name(n, field);
  ForceMode m = ForceMode::Off;
  if (!parseForceMode(s.c_str(), &m)) {
    r.fail(n, field, "expected autonomous, direct, qp, guided or off, got \"" + s + "\"");
  }
  return m;
}

EndEffectorSpec readEndEffector(const Reader& r, const YAML::Node& n, const std::string& path,
                                const scene::Scene& sc, const loop::ResolvedHardware& hw, double dt) {
  const Map m(r, n, path,
              {"name", "entity", "task", "sensor", "normal", "normal_frame", "mode", "force", "contact",
               "force_task", "gain", "velocity_limits", "cutoff", "tool_mass"});
  const problem::MultiRobotProblem& p = *sc.problem;
  EndEffectorSpec e;
  e.name = m.name("name");
  e.source = m.source();

  // The task, and through it the entity.
  const std::string task = m.name("task");
  e.task = findTask(sc, task);
  if (e.task < 0 || !isFrameTask(p.task(e.task))) {
    r.fail(m.require("task"), m.at("task"),
           "no frame_position or frame_pose task '" + task + "' (frame tasks: " +
               taskNames(sc, [](const problem::Task& t) { return isFrameTask(t); }) + ")");
  }
  e.entity = dynamic_cast<const problem::FrameTask&>(p.task(e.task)).entity();
  const std::string entity = p.entity(e.entity).name();
  if (m.has("entity") && m.name("entity") != entity) {
    r.fail(m.require("entity"), m.at("entity"),
           "task '" + task + "' is on entity '" + entity + "', not '" + m.name("entity") + "'");
  }

  // The F/T sensor, from the hardware section.
  const std::string sensor = m.name("sensor");
  const loop::ResolvedRobot* robot = nullptr;
  for (std::size_t i = 0; i < hw.robots.size(); ++i) {
    if (hw.robots[i].entity == e.entity) {
      robot = &hw.robots[i];
      e.sensor_robot = static_cast<int>(i);
    }
  }
  if (robot == nullptr) {
    std::vector<std::string> robots;
    for (const loop::ResolvedRobot& rr : hw.robots) robots.push_back(rr.name);
    r.fail(
        m.require("sensor"), m.at("sensor"),
        "entity '" + entity + "' has no hardware (robots of the hardware section: " + nameList(robots) + ")");
  }
  std::vector<std::string> sensors;
  for (std::size_t i = 0; i < robot->ft_sensors.size(); ++i) {
    sensors.push_back(robot->ft_sensors[i].frame_name);
    if (robot->ft_sensors[i].frame_name == sensor) {
      e.sensor = static_cast<int>(i);
      e.sensor_frame = robot->ft_sensors[i].frame;
    }
  }
  if (e.sensor < 0) {
    r.fail(m.require("sensor"), m.at("sensor"),
           "entity '" + entity + "' has no F/T sensor on frame '" + sensor +
               "' (its F/T sensors: " + nameList(sensors) + ")");
  }
  e.divisor = robot->divisor;

  // The normal.
  const Eigen::Vector3d normal = r.vec3(m.require("normal"), m.at("normal"));
  if (!(normal.norm() > 1e-9)) r.fail(m.require("normal"), m.at("normal"), "expected a non-zero direction");
  e.normal = normal.normalized();
  if (const YAML::Node* f = m.find("normal_frame")) {
    const std::string s = r.name(*f, m.at("normal_frame"));
    if (s != "task" && s != "world")
      r.fail(*f, m.at("normal_frame"), "expected task or world, got \"" + s + "\"");
    e.normal_in_world = s == "world";
  }

  // The contact and the force task.
  if (const YAML::Node* c = m.find("contact")) {
    const std::string name = r.name(*c, m.at("contact"));
    const auto it = sc.contacts.find(name);
    if (it == sc.contacts.end()) {
      std::vector<std::string> names;
      for (const auto& [cn, id] : sc.contacts) names.push_back(cn);
      r.fail(*c, m.at("contact"), "unknown contact '" + name + "' (contacts: " + nameList(names) + ")");
    }
    e.contact = it->second;
    if (!touches(p.contact(e.contact), e.entity)) {
      r.fail(*c, m.at("contact"), "contact '" + name + "' does not touch entity '" + entity + "'");
    }
  }
  if (const YAML::Node* f = m.find("force_task")) {
    const std::string name = r.name(*f, m.at("force_task"));
    const int id = findTask(sc, name);
    if (id < 0 || !isForceTask(p.task(id))) {
      r.fail(*f, m.at("force_task"),
             "no force task '" + name + "' (force tasks: " + taskNames(sc, [](const problem::Task& t) {
               return isForceTask(t);
             }) + ")");
    }
    const int contact = dynamic_cast<const problem::ContactForceTask&>(p.task(id)).contact();
    if (e.contact >= 0 && contact != e.contact) {
      r.fail(*f, m.at("force_task"),
             "force task '" + name + "' is not on contact '" + m.name("contact") + "'");
    }
    if (!touches(p.contact(contact), e.entity)) {
      r.fail(*f, m.at("force_task"),
             "force task '" + name + "' is on a contact that does not touch entity '" + entity + "'");
    }
    e.force_task = id;
    e.contact = contact;
  }

  // The user force and the gains.
  if (const YAML::Node* f = m.find("force")) {
    e.force = r.number(*f, m.at("force"));
    e.force_set = true;
  }
  e.gains.gain = m.number("gain", Bound::Positive, e.gains.gain);
  if (const YAML::Node* l = m.find("velocity_limits")) {
    const Eigen::VectorXd v = r.numbers(*l, m.at("velocity_limits"), 2);
    if (!(v(0) <= 0.0) || !(v(1) >= 0.0) || !(v(0) < v(1))) {
      r.fail(*l, m.at("velocity_limits"),
             "expected [v_min, v_max] with v_min <= 0 <= v_max and v_min < v_max");
    }
    e.gains.v_min = v(0);
    e.gains.v_max = v(1);
  }
  e.gains.cutoff_hz = m.number("cutoff", Bound::Positive, e.gains.cutoff_hz);
  const double rate = 1.0 / (dt * e.divisor);
  if (!(e.gains.cutoff_hz < 0.5 * rate)) {
    r.fail(m.has("cutoff") ? m.require("cutoff") : n, m.has("cutoff") ? m.at("cutoff") : path,
           "the cutoff " + scene::formatNumber(e.gains.cutoff_hz) +
               " Hz is not below half the rate of robot '" + entity + "' (" + scene::formatNumber(rate) +
               " Hz)");
  }
  e.tool_mass = m.number("tool_mass", Bound::NonNegative, 0.0);

  e.mode = readMode(r, m.require("mode"), m.at("mode"));
  requireForMode(r, m.require("mode"), m.at("mode"), e, e.mode, e.force_set);
  return e;
}

}  // namespace

ForceControlSpec readForceControl(const std::string& text, const std::string& file, const scene::Scene& sc,
                                  const loop::ResolvedHardware& hw, double dt) {
  ForceControlSpec out;
  const YAML::Node doc = scene::parseYamlDocument(text, file);
  if (!doc.IsMap()) return out;
  const Reader r(file);
  if (doc["force_control"] && !doc["force_control"].IsNull()) {
    out.present = true;
    const YAML::Node section = doc["force_control"];
    const std::vector<YAML::Node> items = r.list(section, "force_control");
    scene::UniqueNames names(r, "end-effector");
    for (std::size_t i = 0; i < items.size(); ++i) {
      const std::string path = scene::item("force_control", i);
      EndEffectorSpec e = readEndEffector(r, items[i], path, sc, hw, dt);
      names.add(e.name, items[i], path + ".name");
      for (const EndEffectorSpec& o : out.end_effectors) {
        if (o.task == e.task) {
          r.fail(items[i], path + ".task",
                 "the task already has an admittance (end-effector '" + o.name + "', line " +
                     std::to_string(o.source.line) + ")");
        }
      }
      out.end_effectors.push_back(std::move(e));
    }
  }

  // Timeline items that name `force_control` (the other items are the loop's: loop/timeline.hpp).
  const YAML::Node timeline = doc["timeline"];
  if (timeline && timeline.IsSequence()) {
    for (std::size_t i = 0; i < timeline.size(); ++i) {
      const YAML::Node it = timeline[i];
      if (!it.IsMap() || !it["force_control"]) continue;
      const std::string path = scene::item("timeline", i);
      const Map m(r, it, path, {"at", "force_control", "mode", "force"});
      ForceEvent ev;
      ev.at = r.number(m.require("at"), m.at("at"), Bound::NonNegative);
      const std::string name = m.name("force_control");
      std::vector<std::string> known;
      for (std::size_t k = 0; k < out.end_effectors.size(); ++k) {
        known.push_back(out.end_effectors[k].name);
        if (out.end_effectors[k].name == name) ev.end_effector = static_cast<int>(k);
      }
      if (ev.end_effector < 0) {
        r.fail(m.require("force_control"), m.at("force_control"),
               "unknown end-effector '" + name + "' (force_control: " + nameList(known) + ")");
      }
      if (!m.has("mode") && !m.has("force")) r.fail(it, path, "expected 'mode', 'force' or both");
      const EndEffectorSpec& e = out.end_effectors[static_cast<std::size_t>(ev.end_effector)];
      if (const YAML::Node* f = m.find("force")) {
        ev.set_force = true;
        ev.force = r.number(*f, m.at("force"));
      }
      if (const YAML::Node* mode = m.find("mode")) {
        ev.set_mode = true;
        ev.mode = readMode(r, *mode, m.at("mode"));
        requireForMode(r, *mode, m.at("mode"), e, ev.mode, e.force_set || ev.set_force);
      }
      out.events.push_back(ev);
    }
  }
  std::stable_sort(out.events.begin(), out.events.end(),
                   [](const ForceEvent& a, const ForceEvent& b) { return a.at < b.at; });
  return out;
}

}  // namespace mrqp::force
