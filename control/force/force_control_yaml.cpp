// The force_control section of a scene file (see force_control_yaml.hpp).
#include "force/force_control_yaml.hpp"

#include <algorithm>
#include <cmath>
#include <utility>

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
               "force_task", "gain", "velocity_limits", "cutoff", "tool_mass", "max_displacement"});
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
  e.gains.max_displacement = m.number("max_displacement", Bound::Positive, e.gains.max_displacement);

  e.mode = readMode(r, m.require("mode"), m.at("mode"));
  requireForMode(r, m.require("mode"), m.at("mode"), e, e.mode, e.force_set);
  return e;
}

/// The admittance's normal in world axes at the scene's start.
Eigen::Vector3d worldNormal(const problem::MultiRobotProblem& p, const EndEffectorSpec& e) {
  if (e.normal_in_world) return e.normal;
  const auto& t = dynamic_cast<const problem::FrameTask&>(p.task(e.task));
  return p.entity(t.entity()).framePose(t.frame()).R * e.normal;
}

/// A contact that holds the end-effector along its admittance's normal, found by checkMotion.
struct HeldGrasp {
  int contact = -1;
  std::string contact_name;
  int other = -1;  ///< the entity on the contact's other side
  Eigen::Vector3d normal = Eigen::Vector3d::Zero();  ///< the admittance's normal, world
};

std::string contactName(const scene::Scene& sc, int id) {
  for (const auto& [name, cid] : sc.contacts) {
    if (cid == id) return name;
  }
  return "#" + std::to_string(id);
}

/// An admittance moves its end-effector along n (every mode but off). Each active contact of the
/// end-effector's task frame (and its `contact`) must let it: free along its normal, that normal
/// (world, at the start) within 10° of the admittance's; or, holding the normal, a grasp of
/// another entity, which the end-effector then carries along n (what resists that entity's motion
/// — a mechanism's spring, an object's weight — makes the force). A contact with the environment
/// that holds the normal cannot let the end-effector move at all: refused. Returns the grasps
/// that hold the normal (the caller refuses two of them squeezing one entity).
std::vector<HeldGrasp> checkMotion(const Reader& r, const YAML::Node& at, const std::string& field,
                                   const scene::Scene& sc, const EndEffectorSpec& e) {
  const problem::MultiRobotProblem& p = *sc.problem;
  const auto& t = dynamic_cast<const problem::FrameTask&>(p.task(e.task));
  const Eigen::Vector3d n = worldNormal(p, e);
  std::vector<HeldGrasp> held;
  for (int id = 0; id < p.contactCapacity(); ++id) {
    if (!p.contactActive(id)) continue;
    const problem::ContactDesc& c = p.contact(id);
    const bool surface_side = c.entity == t.entity() && c.frame == t.frame();
    const bool other_side = c.other_entity == t.entity() && c.other_frame == t.frame();
    if (!surface_side && !other_side && id != e.contact) continue;
    const std::string name = contactName(sc, id);
    const Eigen::Vector3d cn = p.entity(c.entity).framePose(c.frame).R * c.normal;
    const double cosine = std::fabs(cn.dot(n));
    if ((c.free & problem::kFreeNormal) != 0) {
      if (cosine < std::cos(10.0 * M_PI / 180.0)) {
        r.fail(at, field,
               "contact '" + name + "' is free along its normal, which is " +
                   scene::formatNumber(std::round(std::acos(std::min(1.0, cosine)) * 180.0 / M_PI)) +
                   "° from end-effector '" + e.name + "''s normal: the admittance's motion is held");
      }
      continue;
    }
    const int other = c.entity == t.entity() ? c.other_entity : c.entity;
    if (other < 0) {
      r.fail(at, field,
             "mode '" + std::string(forceModeName(e.mode)) + "' moves end-effector '" + e.name +
                 "' along its normal, which contact '" + name +
                 "' holds: give the contact free: [normal] (docs/force-control.md)");
    }
    held.push_back({id, name, other, n});
  }
  return held;
}

}  // namespace

ForceControlSpec readForceControl(const std::string& text, const std::string& file, const scene::Scene& sc,
                                  const loop::ResolvedHardware& hw, double dt) {
  ForceControlSpec out;
  std::vector<YAML::Node> nodes;  // each end-effector's item
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
      // Motion along n (any mode but off, initially or from the timeline): checked below.
      out.end_effectors.push_back(std::move(e));
      nodes.push_back(items[i]);
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

  // The admittances that move (a mode other than off at the start or from the timeline) against
  // the contacts of their end-effectors; two grasps holding one entity along opposite normals
  // squeeze it by position only: refused (free their normals).
  std::vector<std::pair<std::size_t, HeldGrasp>> grasps;
  for (std::size_t i = 0; i < out.end_effectors.size(); ++i) {
    const EndEffectorSpec& e = out.end_effectors[i];
    bool moves = e.mode != ForceMode::Off;
    for (const ForceEvent& ev : out.events) {
      moves = moves || (ev.end_effector == static_cast<int>(i) && ev.set_mode && ev.mode != ForceMode::Off);
    }
    if (!moves) continue;
    const std::string path = scene::item("force_control", i);
    const YAML::Node& node = nodes[i];
    const YAML::Node at = node["mode"] ? node["mode"] : node;
    for (HeldGrasp& g : checkMotion(r, at, path + ".mode", sc, e)) {
      for (const auto& [j, o] : grasps) {
        if (o.other == g.other && o.normal.dot(g.normal) < -0.9) {
          r.fail(at, path + ".mode",
                 "end-effectors '" + out.end_effectors[j].name + "' and '" + e.name + "' squeeze entity '" +
                     sc.problem->entity(g.other).name() + "' from opposite sides through contacts '" +
                     o.contact_name + "' and '" + g.contact_name +
                     "', which hold their normals: the admittances cannot press; give the contacts "
                     "free: [normal] (docs/force-control.md)");
        }
      }
      grasps.emplace_back(i, std::move(g));
    }
  }
  return out;
}

}  // namespace mrqp::force
