// The `plant:` section of a scene file (docs/mujoco.md, "The plant section").
#include "sim/plant_yaml.hpp"

#include <yaml-cpp/yaml.h>

#include "scene/yaml_reader.hpp"

namespace mrqp::sim {

using scene::Bound;
using scene::Map;
using scene::Reader;

namespace {

ContactParams readContact(const Reader& r, const YAML::Node& n, const std::string& path,
                          const ContactParams& defaults, double timestep) {
  const Map m(r, n, path, {"friction", "timeconst", "dampratio"});
  ContactParams p;
  p.friction = m.number("friction", Bound::NonNegative, defaults.friction);
  p.timeconst = m.number("timeconst", Bound::Positive, defaults.timeconst);
  p.dampratio = m.number("dampratio", Bound::Positive, defaults.dampratio);
  if (p.timeconst < 2.0 * timestep) {
    const YAML::Node* at = m.find("timeconst");
    r.fail(at != nullptr ? *at : n, m.at("timeconst"),
           "must be at least two time steps (" + scene::formatNumber(2.0 * timestep) +
               " s), or the contact is stiffer than the integrator can resolve");
  }
  return p;
}

NoiseSpec readNoise(const Reader& r, const YAML::Node& n, const std::string& path) {
  const Map m(r, n, path, {"stddev", "bias"});
  return NoiseSpec{m.number("stddev", Bound::NonNegative, 0.0), m.number("bias", Bound::Any, 0.0)};
}

scene::PoseSpec readPose(const Reader& r, const YAML::Node& n, const std::string& path) {
  const Map m(r, n, path, {"xyz", "rpy"});
  scene::PoseSpec p;
  p.xyz = m.vec3("xyz", Eigen::Vector3d::Zero());
  p.rpy = m.vec3("rpy", Eigen::Vector3d::Zero());
  return p;
}

GeomSpec readGeom(const Reader& r, const YAML::Node& n, const std::string& path) {
  const Map m(r, n, path, {"entity", "link", "type", "size", "pose", "replace"});
  GeomSpec g;
  g.source = m.source();
  g.entity = m.name("entity");
  if (m.has("link")) {
    g.link = m.name("link");
  }
  const std::string type = m.name("type");
  int count = 0;
  if (type == "box") {
    g.type = GeomSpec::Type::Box;
    count = 3;
  } else if (type == "sphere") {
    g.type = GeomSpec::Type::Sphere;
    count = 1;
  } else if (type == "cylinder") {
    g.type = GeomSpec::Type::Cylinder;
    count = 2;
  } else if (type == "capsule") {
    g.type = GeomSpec::Type::Capsule;
    count = 2;
  } else {
    r.fail(m.require("type"), m.at("type"),
           "expected box, sphere, cylinder or capsule, got \"" + type + "\"");
  }
  const YAML::Node& size = m.require("size");
  const Eigen::VectorXd s = r.numbers(size, m.at("size"), count);
  for (int i = 0; i < count; ++i) {
    if (!(s(i) > 0.0)) {
      r.fail(size, scene::item(m.at("size"), static_cast<std::size_t>(i)),
             "expected a number > 0, got " + scene::formatNumber(s(i)));
    }
    g.size(i) = s(i);
  }
  if (const YAML::Node* p = m.find("pose")) {
    g.pose = readPose(r, *p, m.at("pose"));
  }
  g.replace = m.boolean("replace", false);
  return g;
}

/// A grasp: a contact's name (a weld with the section's softness) or
/// {contact, hold: pose | point, point, timeconst, dampratio}.
GraspSpec readGrasp(const Reader& r, const YAML::Node& n, const std::string& path, const PlantSpec& s) {
  GraspSpec g;
  g.source = r.source(n);
  g.timeconst = s.grasp_timeconst;
  g.dampratio = s.grasp_dampratio;
  if (!n.IsMap()) {
    g.contact = r.name(n, path);
    return g;
  }
  const Map m(r, n, path, {"contact", "hold", "point", "timeconst", "dampratio"});
  g.contact = m.name("contact");
  if (m.has("hold")) {
    const std::string hold = m.name("hold");
    if (hold == "point") {
      g.hold = GraspSpec::Hold::Point;
    } else if (hold != "pose") {
      r.fail(m.require("hold"), m.at("hold"), "expected pose or point, got \"" + hold + "\"");
    }
  }
  if (m.has("point")) {
    g.point_given = true;
    g.point = m.vec3("point", Eigen::Vector3d::Zero());
  } else if (g.hold == GraspSpec::Hold::Point) {
    r.fail(n, path, "missing required field 'point' (hold: point holds the bodies at that point)");
  }
  g.timeconst = m.number("timeconst", Bound::Positive, g.timeconst);
  g.dampratio = m.number("dampratio", Bound::Positive, g.dampratio);
  if (g.timeconst < 2.0 * s.timestep) {
    r.fail(m.require("timeconst"), m.at("timeconst"),
           "must be at least two time steps (" + scene::formatNumber(2.0 * s.timestep) + " s)");
  }
  return g;
}

}  // namespace

PlantSpec readPlantSection(const Reader& r, const YAML::Node* node) {
  PlantSpec s;
  if (node == nullptr) {
    return s;
  }
  const std::string path = "plant";
  const Map m(r, *node, path,
              {"simulator", "timestep", "integrator", "seed", "drives", "settle", "contact", "pairs", "geoms",
               "grasps", "grasp_softness", "noise", "package_path"});
  s.present = true;
  s.source = m.source();
  s.simulator = "mujoco";
  if (m.has("simulator")) {
    s.simulator = m.name("simulator");
    if (s.simulator != "mujoco" && s.simulator != "ideal") {
      r.fail(m.require("simulator"), m.at("simulator"),
             "expected mujoco or ideal, got \"" + s.simulator + "\"");
    }
  }
  s.timestep = m.number("timestep", Bound::Positive, s.timestep);
  if (s.timestep > 0.01) {
    r.fail(m.require("timestep"), m.at("timestep"),
           "expected at most 0.01 s, got " + scene::formatNumber(s.timestep));
  }
  if (m.has("integrator")) {
    s.integrator = m.name("integrator");
    if (s.integrator != "euler" && s.integrator != "implicit") {
      r.fail(m.require("integrator"), m.at("integrator"),
             "expected euler or implicit, got \"" + s.integrator + "\"");
    }
  }
  s.seed = static_cast<std::uint64_t>(m.integer("seed", 0, INT_MAX, 1));
  if (const YAML::Node* d = m.find("drives")) {
    const Map dm(r, *d, m.at("drives"), {"integral_time", "interpolate", "hold_kp", "hold_kd"});
    s.drives.integral_time = dm.number("integral_time", Bound::NonNegative, s.drives.integral_time);
    if (s.drives.integral_time > 0.0 && s.drives.integral_time < 2.0 * s.timestep) {
      r.fail(dm.require("integral_time"), dm.at("integral_time"),
             "must be 0 (none) or at least two time steps (" + scene::formatNumber(2.0 * s.timestep) + " s)");
    }
    s.drives.interpolate = dm.boolean("interpolate", s.drives.interpolate);
    s.drives.hold_kp = dm.number("hold_kp", Bound::Positive, s.drives.hold_kp);
    s.drives.hold_kd = dm.number("hold_kd", Bound::NonNegative, s.drives.hold_kd);
  }
  s.settle = m.number("settle", Bound::NonNegative, s.settle);
  if (s.settle > 10.0) {
    r.fail(m.require("settle"), m.at("settle"),
           "expected at most 10 s, got " + scene::formatNumber(s.settle));
  }
  const ContactParams defaults;
  if (const YAML::Node* c = m.find("contact")) {
    s.contact = readContact(r, *c, m.at("contact"), defaults, s.timestep);
  } else {
    s.contact = readContact(r, YAML::Node(YAML::NodeType::Map), m.at("contact"), defaults, s.timestep);
  }
  if (const YAML::Node* p = m.find("pairs")) {
    const std::vector<YAML::Node> items = r.list(*p, m.at("pairs"));
    for (std::size_t i = 0; i < items.size(); ++i) {
      const std::string ip = scene::item(m.at("pairs"), i);
      const Map pm(r, items[i], ip, {"between", "collide", "friction", "timeconst", "dampratio"});
      PairSpec pair;
      pair.source = pm.source();
      const std::vector<std::string> between = r.names(pm.require("between"), pm.at("between"));
      if (between.size() != 2) {
        r.fail(pm.require("between"), pm.at("between"),
               "expected two entity names (or ground), got a list of " + std::to_string(between.size()));
      }
      pair.a = between[0];
      pair.b = between[1];
      pair.collide = pm.boolean("collide", true);
      // The pair's own numbers over the section defaults: read it as a contact map without
      // the key "between".
      YAML::Node rest(YAML::NodeType::Map);
      for (const scene::Entry& e : pm.entries()) {
        if (e.key != "between" && e.key != "collide") {
          rest[e.key] = e.value;
        }
      }
      pair.params =
          readContact(r, rest.size() > 0 ? rest : YAML::Node(YAML::NodeType::Map), ip, s.contact, s.timestep);
      for (const PairSpec& other : s.pairs) {
        if ((other.a == pair.a && other.b == pair.b) || (other.a == pair.b && other.b == pair.a)) {
          r.fail(items[i], ip,
                 "pair " + pair.a + " / " + pair.b + " is listed twice (first at line " +
                     std::to_string(other.source.line) + ")");
        }
      }
      s.pairs.push_back(pair);
    }
  }
  if (const YAML::Node* g = m.find("geoms")) {
    const std::vector<YAML::Node> items = r.list(*g, m.at("geoms"));
    for (std::size_t i = 0; i < items.size(); ++i) {
      s.geoms.push_back(readGeom(r, items[i], scene::item(m.at("geoms"), i)));
    }
  }
  if (const YAML::Node* g = m.find("grasp_softness")) {
    const Map gm(r, *g, m.at("grasp_softness"), {"timeconst", "dampratio"});
    s.grasp_timeconst = gm.number("timeconst", Bound::Positive, s.grasp_timeconst);
    s.grasp_dampratio = gm.number("dampratio", Bound::Positive, s.grasp_dampratio);
    if (s.grasp_timeconst < 2.0 * s.timestep) {
      r.fail(gm.require("timeconst"), gm.at("timeconst"),
             "must be at least two time steps (" + scene::formatNumber(2.0 * s.timestep) + " s)");
    }
  }
  if (const YAML::Node* g = m.find("grasps")) {
    const std::vector<YAML::Node> items = r.list(*g, m.at("grasps"));
    for (std::size_t i = 0; i < items.size(); ++i) {
      s.grasps.push_back(readGrasp(r, items[i], scene::item(m.at("grasps"), i), s));
    }
  }
  if (const YAML::Node* n = m.find("noise")) {
    const Map nm(
        r, *n, m.at("noise"),
        {"joint_position", "joint_velocity", "joint_torque", "force", "torque", "gyro", "accelerometer"});
    const auto read = [&](const char* key, NoiseSpec& out) {
      if (const YAML::Node* v = nm.find(key)) {
        out = readNoise(r, *v, nm.at(key));
      }
    };
    read("joint_position", s.noise.joint_position);
    read("joint_velocity", s.noise.joint_velocity);
    read("joint_torque", s.noise.joint_torque);
    read("force", s.noise.force);
    read("torque", s.noise.torque);
    read("gyro", s.noise.gyro);
    read("accelerometer", s.noise.accelerometer);
  }
  if (const YAML::Node* p = m.find("package_path")) {
    s.package_path = r.names(*p, m.at("package_path"));
  }
  return s;
}

PlantSpec loadPlantSpecString(const std::string& text, const std::string& file_name_for_messages) {
  const Reader r(file_name_for_messages);
  const YAML::Node root = scene::parseYamlDocument(text, file_name_for_messages);
  if (!root.IsMap()) {
    return readPlantSection(r, nullptr);
  }
  try {
    const YAML::Node plant = root["plant"];
    return plant ? readPlantSection(r, &plant) : readPlantSection(r, nullptr);
  } catch (const YAML::Exception& e) {
    scene::yamlError(file_name_for_messages, e);
  }
}

PlantSpec loadPlantSpec(const std::string& path) {
  return loadPlantSpecString(scene::readTextFile(path), path);
}

}  // namespace mrqp::sim
