// The estimation section of a scene file (see estimation_yaml.hpp).
#include "estimation/estimation_yaml.hpp"

#include <algorithm>

#include "estimation/regressor_factory.hpp"
#include "scene/yaml_reader.hpp"

namespace mrqp::estimation {

namespace {

using scene::Bound;
using scene::Map;
using scene::nameList;
using scene::Reader;

/// The standard deviation of plant.noise.KEY (absent: 0); the plant section's reader checks the rest.
double plantNoise(const Reader& r, const YAML::Node& doc, const char* key) {
  const YAML::Node plant = doc["plant"];
  if (!plant || !plant.IsMap()) return 0.0;
  const YAML::Node noise = plant["noise"];
  if (!noise || !noise.IsMap()) return 0.0;
  const YAML::Node n = noise[key];
  if (!n || !n.IsMap() || !n["stddev"]) return 0.0;
  return r.number(n["stddev"], std::string("plant.noise.") + key + ".stddev", Bound::NonNegative);
}

BodyEstimate readEstimate(const Reader& r, const YAML::Node& n, const std::string& field) {
  const std::string s = r.name(n, field);
  if (s == "none") return BodyEstimate::None;
  if (s == "mass") return BodyEstimate::Mass;
  if (s == "mass_com") return BodyEstimate::MassCom;
  if (s == "full") return BodyEstimate::Full;
  r.fail(n, field, "expected mass, mass_com, full or none, got \"" + s + "\"");
}

Eigen::Vector3d positive3(const Reader& r, const YAML::Node& n, const std::string& field) {
  const Eigen::Vector3d v = r.vec3(n, field);
  if (!(v.minCoeff() > 0.0)) r.fail(n, field, "expected three positive standard deviations");
  return v;
}

EstimationHandSpec readHand(const Reader& r, const YAML::Node& n, const std::string& path, int entity,
                            const scene::Scene& sc, const loop::ResolvedHardware& hw) {
  const Map m(r, n, path, {"contact", "sensor", "tool_mass", "tool_com"});
  const problem::MultiRobotProblem& p = *sc.problem;
  EstimationHandSpec h;
  h.source = m.source();
  const std::string contact = m.name("contact");
  const auto it = sc.contacts.find(contact);
  if (it == sc.contacts.end()) {
    std::vector<std::string> names;
    for (const auto& [cn, id] : sc.contacts) names.push_back(cn);
    r.fail(m.require("contact"), m.at("contact"),
           "unknown contact '" + contact + "' (contacts: " + nameList(names) + ")");
  }
  h.contact = it->second;
  const problem::ContactDesc& c = p.contact(h.contact);
  if (c.entity == entity && c.other_entity >= 0) {
    h.object_frame = c.frame;
    h.robot_entity = c.other_entity;
  } else if (c.other_entity == entity) {
    h.object_frame = c.other_frame;
    h.robot_entity = c.entity;
  } else {
    r.fail(m.require("contact"), m.at("contact"),
           "contact '" + contact + "' is not between entity '" + p.entity(entity).name() + "' and a robot");
  }
  const std::string robot_name = p.entity(h.robot_entity).name();
  for (std::size_t i = 0; i < hw.robots.size(); ++i) {
    if (hw.robots[i].entity == h.robot_entity) h.robot = static_cast<int>(i);
  }
  const std::string sensor = m.name("sensor");
  if (h.robot < 0) {
    r.fail(m.require("sensor"), m.at("sensor"), "entity '" + robot_name + "' has no hardware");
  }
  const loop::ResolvedRobot& robot = hw.robots[static_cast<std::size_t>(h.robot)];
  std::vector<std::string> sensors;
  for (std::size_t i = 0; i < robot.ft_sensors.size(); ++i) {
    sensors.push_back(robot.ft_sensors[i].frame_name);
    if (robot.ft_sensors[i].frame_name == sensor) {
      h.sensor = static_cast<int>(i);
      h.sensor_frame = robot.ft_sensors[i].frame;
    }
  }
  if (h.sensor < 0) {
    r.fail(m.require("sensor"), m.at("sensor"),
           "entity '" + robot_name + "' has no F/T sensor on frame '" + sensor +
               "' (its F/T sensors: " + nameList(sensors) + ")");
  }
  h.divisor = robot.divisor;
  h.tool_mass = m.number("tool_mass", Bound::NonNegative, 0.0);
  h.tool_com = m.vec3("tool_com", Eigen::Vector3d::Zero());
  return h;
}

EntityEstimationSpec readEntity(const Reader& r, const YAML::Node& n, const std::string& path,
                                const YAML::Node& doc, const scene::SceneSpec& spec, const scene::Scene& sc,
                                const loop::ResolvedHardware& hw) {
  const Map m(r, n, path,
              {"entity", "estimate", "initial", "springs", "hands", "cutoff", "settle", "observation_floor",
               "process_noise", "min_mass", "feed_back"});
  const problem::MultiRobotProblem& p = *sc.problem;
  EntityEstimationSpec e;
  e.source = m.source();
  e.name = m.name("entity");
  const scene::EntitySpec* es = nullptr;
  std::vector<std::string> entities;
  for (const scene::EntitySpec& x : spec.entities) {
    entities.push_back(x.name);
    if (x.name == e.name) es = &x;
  }
  if (es == nullptr) {
    r.fail(m.require("entity"), m.at("entity"),
           "unknown entity '" + e.name + "' (entities: " + nameList(entities) + ")");
  }
  e.entity = p.entityIndex(e.name);
  e.model = es->model;
  if (!hasRegressor(e.model)) {
    r.fail(m.require("entity"), m.at("entity"),
           "entity '" + e.name + "' is a '" + e.model +
               "': no regressor for it in this build (models: " + regressorModels() + ")");
  }
  const problem::Entity& ent = p.entity(e.entity);

  if (const YAML::Node* x = m.find("estimate")) e.estimate = readEstimate(r, *x, m.at("estimate"));
  if (e.estimate != BodyEstimate::None && e.model != "rigid_object") {
    r.fail(m.require("estimate"), m.at("estimate"),
           "link parameters are estimated for rigid objects only in this build ('" + e.name + "' is a '" +
               e.model + "'); use none and estimate its springs");
  }
  if (e.model == "rigid_object") {
    e.true_mass = es->object.mass;
    e.true_com = es->object.com;
  }
  if (const YAML::Node* x = m.find("initial")) {
    if (e.estimate == BodyEstimate::None)
      r.fail(*x, m.at("initial"), "only with estimate mass, mass_com or full");
    const Map im(r, *x, m.at("initial"), {"mass", "mass_std", "com", "com_std"});
    e.initial_mass = im.number("mass", Bound::Positive, 0.0);
    e.initial_mass_std = im.number("mass_std", Bound::Positive, e.initial_mass_std);
    e.initial_com = im.vec3("com", Eigen::Vector3d::Zero());
    e.initial_com_std = im.number("com_std", Bound::Positive, e.initial_com_std);
  } else if (e.estimate != BodyEstimate::None) {
    r.fail(n, path, "estimate '" + m.name("estimate") + "' needs 'initial' (at least its mass)");
  }
  if (e.estimate != BodyEstimate::None && !(e.initial_mass > 0.0)) {
    r.fail(m.require("initial"), m.at("initial") + ".mass", "expected a positive initial mass");
  }

  if (const YAML::Node* x = m.find("springs")) {
    const std::vector<YAML::Node> items = r.list(*x, m.at("springs"));
    for (std::size_t i = 0; i < items.size(); ++i) {
      const std::string sp = scene::item(m.at("springs"), i);
      const Map sm(r, items[i], sp, {"joint", "initial", "std"});
      EstimatedSpringSpec s;
      s.joint = sm.name("joint");
      const int k = ent.jointIndex(s.joint);
      if (k < 0) {
        std::vector<std::string> joints;
        for (int j = 0; j < ent.nv() - ent.jointOffset(); ++j) joints.emplace_back(ent.jointName(j));
        r.fail(sm.require("joint"), sm.at("joint"),
               "entity '" + e.name + "' has no joint '" + s.joint + "' (joints: " + nameList(joints) + ")");
      }
      s.velocity_index = ent.jointOffset() + k;
      for (const EstimatedSpringSpec& o : e.springs) {
        if (o.joint == s.joint)
          r.fail(sm.require("joint"), sm.at("joint"), "joint '" + s.joint + "' given twice");
      }
      s.initial = sm.vec3("initial", Eigen::Vector3d::Zero());
      if (const YAML::Node* d = sm.find("std")) s.initial_std = positive3(r, *d, sm.at("std"));
      if (const auto t = es->springs.find(s.joint); t != es->springs.end()) {
        s.truth = Eigen::Vector3d(t->second.stiffness, t->second.damping, t->second.offset);
      }
      s.truth_known = true;  // a joint without a spring in the scene has none: (0, 0, 0)
      e.springs.push_back(s);
    }
  }
  if (e.estimate == BodyEstimate::None && e.springs.empty()) {
    r.fail(n, path, "nothing to estimate: give 'estimate' (rigid objects) or 'springs'");
  }

  const std::vector<YAML::Node> hands = r.list(m.require("hands"), m.at("hands"));
  if (hands.empty()) r.fail(m.require("hands"), m.at("hands"), "expected at least one hand");
  for (std::size_t i = 0; i < hands.size(); ++i) {
    const std::string hp = scene::item(m.at("hands"), i);
    e.hands.push_back(readHand(r, hands[i], hp, e.entity, sc, hw));
    if (e.hands.back().divisor != e.hands.front().divisor) {
      r.fail(hands[i], hp + ".sensor", "its robot runs at another rate than the first hand's");
    }
  }

  const double rate = 1.0 / (sc.settings.dt * e.hands.front().divisor);
  e.cutoff_hz = m.number("cutoff", Bound::Positive, e.cutoff_hz);
  if (!(e.cutoff_hz < 0.5 * rate)) {
    r.fail(m.has("cutoff") ? m.require("cutoff") : n, m.has("cutoff") ? m.at("cutoff") : path,
           "the cutoff " + scene::formatNumber(e.cutoff_hz) + " Hz is not below half the F/T rate (" +
               scene::formatNumber(rate) + " Hz)");
  }
  e.settle_s = m.number("settle", Bound::NonNegative, e.settle_s);
  e.observation_floor = m.number("observation_floor", Bound::Positive, e.observation_floor);
  e.process_noise = m.number("process_noise", Bound::NonNegative, e.process_noise);
  e.min_mass = m.number("min_mass", Bound::Positive, e.min_mass);
  e.feed_back = m.boolean("feed_back", false);
  e.force_noise = plantNoise(r, doc, "force");
  e.torque_noise = plantNoise(r, doc, "torque");
  return e;
}

}  // namespace

EstimationSpec readEstimation(const std::string& text, const std::string& file, const scene::SceneSpec& spec,
                              const scene::Scene& sc, const loop::ResolvedHardware& hw) {
  EstimationSpec out;
  const YAML::Node doc = scene::parseYamlDocument(text, file);
  if (!doc.IsMap() || !doc["estimation"] || doc["estimation"].IsNull()) return out;
  const Reader r(file);
  out.present = true;
  const std::vector<YAML::Node> items = r.list(doc["estimation"], "estimation");
  scene::UniqueNames names(r, "estimated entity");
  for (std::size_t i = 0; i < items.size(); ++i) {
    const std::string path = scene::item("estimation", i);
    EntityEstimationSpec e = readEntity(r, items[i], path, doc, spec, sc, hw);
    names.add(e.name, items[i], path + ".entity");
    out.entities.push_back(std::move(e));
  }
  return out;
}

}  // namespace mrqp::estimation
