// Scene files (docs/scenes.md): YAML → SceneSpec. Every error names file, 1-based line and the
// dotted path of the offending key.
#include "scene/scene_yaml.hpp"

#include "problem/contact.hpp"
#include "problem/problem_settings.hpp"
#include "scene/constraint_kind.hpp"
#include "scene/task_kind.hpp"
#include "scene/yaml_reader.hpp"

#include <yaml-cpp/yaml.h>

#include <Eigen/Eigenvalues>

#include <algorithm>
#include <cerrno>
#include <climits>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <initializer_list>
#include <memory>
#include <optional>
#include <sstream>
#include <utility>
#include <vector>

namespace mrqp::scene {

namespace {

// ---- settings ----------------------------------------------------------------------------------

SettingsSpec readSettings(const Reader& r, const YAML::Node* n) {
  SettingsSpec s;
  s.source = Source{r.file(), 1};
  if (n == nullptr) {
    return s;
  }
  const Map m(r, *n, "settings",
              {"dt", "duration", "gravity", "max_tasks", "max_contacts", "max_contact_generators",
               "contact_stiffness", "contact_damping", "regularisation"});
  s.source = m.source();
  s.dt = m.number("dt", Bound::Positive, s.dt);
  s.duration = m.number("duration", Bound::Positive, s.duration);
  s.gravity = m.vec3("gravity", s.gravity);
  // capacities: at most the problem's limits (problem_settings.hpp, docs/robustness.md)
  s.max_tasks = m.integer("max_tasks", 1, problem::kMaxTasksCapacity, s.max_tasks);
  s.max_contacts = m.integer("max_contacts", 1, problem::kMaxContactsCapacity, s.max_contacts);
  s.max_contact_generators = m.integer("max_contact_generators", 1, problem::kMaxContactGeneratorsCapacity,
                                       s.max_contact_generators);
  s.contact_stiffness = m.number("contact_stiffness", Bound::NonNegative, s.contact_stiffness);
  s.contact_damping = m.number("contact_damping", Bound::NonNegative, s.contact_damping);
  s.regularisation = m.number("regularisation", Bound::Positive, s.regularisation);
  return s;
}

// ---- entities ----------------------------------------------------------------------------------

PoseSpec readPose(const Reader& r, const YAML::Node& n, const std::string& path) {
  const Map m(r, n, path, {"xyz", "rpy"});
  PoseSpec p;
  p.xyz = m.vec3("xyz", p.xyz);
  p.rpy = m.vec3("rpy", p.rpy);
  return p;
}

/// [ixx, iyy, izz] or [ixx, ixy, ixz, iyy, iyz, izz]; symmetric positive definite.
Eigen::Matrix3d readInertia(const Reader& r, const YAML::Node& n, const std::string& path) {
  if (!n.IsSequence() || (n.size() != 3 && n.size() != 6)) {
    r.fail(n, path, "expected [ixx, iyy, izz] or [ixx, ixy, ixz, iyy, iyz, izz], got " + describe(n));
  }
  const Eigen::VectorXd v = r.numbers(n, path, static_cast<int>(n.size()));
  Eigen::Matrix3d I = Eigen::Matrix3d::Zero();
  if (v.size() == 3) {
    I.diagonal() = v;
  } else {
    I << v(0), v(1), v(2), v(1), v(3), v(4), v(2), v(4), v(5);
  }
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eig(I, Eigen::EigenvaluesOnly);
  const double smallest = eig.eigenvalues().minCoeff();
  if (!(smallest > 0.0)) {
    r.fail(n, path, "not positive definite (smallest eigenvalue " + formatNumber(smallest) + ")");
  }
  return I;
}

std::map<std::string, SpringSpec> readSprings(const Reader& r, const YAML::Node& n, const std::string& path) {
  std::map<std::string, SpringSpec> out;
  for (const Entry& e : r.entries(n, path)) {
    const Map m(r, e.value, child(path, e.key), {"stiffness", "damping", "offset"});
    SpringSpec s;
    s.stiffness = r.number(m.require("stiffness"), m.at("stiffness"), Bound::NonNegative);
    s.damping = m.number("damping", Bound::NonNegative, 0.0);
    s.offset = m.number("offset", Bound::Any, 0.0);
    s.source = r.source(e.key_node);
    out[e.key] = s;
  }
  return out;
}

void readActuation(const Map& m, EntitySpec* e) {
  const Reader& r = m.reader();
  if (const YAML::Node* a = m.find("actuation")) {
    e->actuation = r.name(*a, m.at("actuation"));
    if (e->actuation != "all" && e->actuation != "none" && e->actuation != "list") {
      r.fail(*a, m.at("actuation"), "expected all, none or list, got " + describe(*a));
    }
  }
  if (e->actuation == "list") {
    e->actuated_joints = r.names(m.require("actuated"), m.at("actuated"));
  } else {
    m.forbid("actuated", "only used with actuation: list");
  }
  if (const YAML::Node* p = m.find("passive")) {
    e->passive_joints = r.names(*p, m.at("passive"));
    for (const std::string& j : e->passive_joints) {
      if (std::find(e->actuated_joints.begin(), e->actuated_joints.end(), j) != e->actuated_joints.end()) {
        r.fail(*p, m.at("passive"), "joint '" + j + "' is also listed in 'actuated'");
      }
    }
  }
}

EntitySpec readEntity(const Reader& r, const YAML::Node& n, const std::string& path) {
  const Map m(r, n, path,
              {"name", "model", "pose", "q", "actuation", "actuated", "passive", "springs", "mass", "com",
               "inertia"});
  EntitySpec e;
  e.source = m.source();
  e.name = m.name("name");
  if (e.name == "ground") {
    r.fail(m.require("name"), m.at("name"), "'ground' is reserved for the environment");
  }
  e.model = m.name("model");
  if (const YAML::Node* p = m.find("pose")) {
    e.pose = readPose(r, *p, m.at("pose"));
  }
  if (e.model == "rigid_object") {
    for (const char* key : {"q", "actuation", "actuated", "passive", "springs"}) {
      m.forbid(key, "not used by a rigid_object (it has no joints)");
    }
    e.object.mass = r.number(m.require("mass"), m.at("mass"), Bound::Positive);
    e.object.com = m.vec3("com", e.object.com);
    e.object.inertia = readInertia(r, m.require("inertia"), m.at("inertia"));
    return e;
  }
  for (const char* key : {"mass", "com", "inertia"}) {
    m.forbid(key, "only used with model: rigid_object");
  }
  if (const YAML::Node* q = m.find("q")) {
    e.q = r.numberMap(*q, m.at("q"));
  }
  readActuation(m, &e);
  if (const YAML::Node* s = m.find("springs")) {
    e.springs = readSprings(r, *s, m.at("springs"));
  }
  return e;
}

// ---- contacts ----------------------------------------------------------------------------------

void readOther(const Reader& r, const YAML::Node& n, const std::string& path, ContactSpec* c) {
  if (n.IsScalar()) {
    if (n.Scalar() != "ground") {
      r.fail(n, path, "expected ground or a map {entity, frame}, got " + describe(n));
    }
    return;
  }
  if (!n.IsMap()) {
    r.fail(n, path, "expected ground or a map {entity, frame}, got " + describe(n));
  }
  const Map m(r, n, path, {"entity", "frame"});
  c->other_entity = m.name("entity");
  c->other_frame = m.name("frame");
  if (c->other_entity == "ground") {
    r.fail(m.require("entity"), m.at("entity"), "write other: ground for the environment");
  }
  if (c->other_entity == c->entity && c->other_frame == c->frame) {
    r.fail(n, path, "a frame cannot be in contact with itself");
  }
}

std::vector<Eigen::Vector3d> readPoints(const Reader& r, const YAML::Node& n, const std::string& path) {
  if (!n.IsSequence() || n.size() < 1 || n.size() > 8) {
    r.fail(n, path, "expected a list of 1 to 8 points, got " + describe(n));
  }
  std::vector<Eigen::Vector3d> points;
  for (std::size_t i = 0; i < n.size(); ++i) {
    points.push_back(r.vec3(n[i], item(path, i)));
  }
  return points;
}

// `free:` words: directions of the contact frame (t1, t2, n) the no-slip constraint leaves to
// the tasks (problem/contact.hpp).
struct FreeWord {
  const char* word;
  std::uint8_t bits;
};
constexpr FreeWord kFreeWords[] = {{"normal", problem::kFreeNormal},
                                   {"tangent", problem::kFreeTangent},
                                   {"twist", problem::kFreeTwist},
                                   {"tilt", problem::kFreeTilt}};

std::uint8_t readFree(const Reader& r, const YAML::Node& n, const std::string& path, std::size_t npoints) {
  std::vector<std::string> words;
  for (const FreeWord& w : kFreeWords) words.emplace_back(w.word);
  const std::vector<YAML::Node> items = r.list(n, path);
  std::uint8_t free = 0;
  for (std::size_t i = 0; i < items.size(); ++i) {
    const std::string word = r.name(items[i], item(path, i));
    const FreeWord* found = nullptr;
    for (const FreeWord& w : kFreeWords) {
      if (word == w.word) found = &w;
    }
    if (found == nullptr) {
      r.fail(items[i], item(path, i), "unknown direction '" + word + "' (expected " + nameList(words) + ")");
    }
    if ((free & found->bits) != 0) {
      r.fail(items[i], item(path, i), "direction '" + word + "' is given twice");
    }
    if (npoints == 1 && (found->bits & problem::kFreeRotations) != 0) {
      r.fail(items[i], item(path, i),
             "a single-point contact holds no rotation: '" + word + "' does not apply (normal, tangent)");
    }
    free = static_cast<std::uint8_t>(free | found->bits);
  }
  return free;
}

ContactSpec readContact(const Reader& r, const YAML::Node& n, const std::string& path) {
  const Map m(r, n, path,
              {"name", "entity", "frame", "other", "points", "normal", "friction", "generators", "free",
               "active"});
  ContactSpec c;
  c.source = m.source();
  c.name = m.name("name");
  c.entity = m.name("entity");
  c.frame = m.name("frame");
  readOther(r, m.require("other"), m.at("other"), &c);
  c.points = readPoints(r, m.require("points"), m.at("points"));
  if (const YAML::Node* nn = m.find("normal")) {
    const Eigen::Vector3d normal = r.vec3(*nn, m.at("normal"));
    if (!(normal.norm() > 1e-12)) {
      r.fail(*nn, m.at("normal"), "expected a non-zero vector");
    }
    c.normal = normal.normalized();
  }
  c.friction = m.number("friction", Bound::Positive, c.friction);
  c.generators = m.integer("generators", 3, 16, c.generators);
  if (const YAML::Node* f = m.find("free")) {
    c.free = readFree(r, *f, m.at("free"), c.points.size());
  }
  c.active = m.boolean("active", c.active);
  return c;
}

// ---- tasks -------------------------------------------------------------------------------------

bool taskUsesKey(const TaskKindEntry& k, const std::string& key) {
  static const char* const common[] = {"name", "type", "weight", "stiffness", "damping", "dims", "active"};
  const auto is = [&](const char* c) { return c != nullptr && key == c; };
  return std::any_of(std::begin(common), std::end(common), is) ||
         std::any_of(k.keys.begin(), k.keys.end(), is);
}

const TaskKindEntry& readTaskKind(const Reader& r, const YAML::Node& n, const std::string& path) {
  const std::string type = r.name(n, path);
  if (const TaskKindEntry* k = findTaskKind(type)) {
    return *k;
  }
  r.fail(n, path, "expected " + taskKindNames() + ", got " + describe(n));
}

std::vector<int> readDims(const Reader& r, const YAML::Node& n, const std::string& path,
                          const TaskKindEntry& k) {
  const std::vector<YAML::Node> items = r.list(n, path);
  const int count = static_cast<int>(items.size());
  if (k.size >= 0 && count != k.size) {
    r.fail(n, path,
           "expected " + std::to_string(k.size) + " entries for a " + k.name + " task, got " +
               std::to_string(count));
  }
  if (count == 0 && !k.dims_may_be_empty) {
    r.fail(n, path, "expected at least one entry");
  }
  std::vector<int> dims;
  for (std::size_t i = 0; i < items.size(); ++i) {
    dims.push_back(r.integer(items[i], item(path, i), 0, 1));
  }
  return dims;
}

void readTarget(const Reader& r, const YAML::Node& n, const std::string& path, const TaskKindEntry& k,
                TaskSpec* t) {
  if (k.read_target != nullptr) {
    k.read_target(r, n, path, t);
  } else {
    t->target = r.numbers(n, path, k.size);
  }
}

TaskSpec readTask(const Reader& r, const YAML::Node& n, const std::string& path) {
  const Map m(r, n, path,
              {"name", "type", "entity", "entities", "frame", "point", "joint", "contact", "weight",
               "stiffness", "damping", "dims", "target", "active"});
  TaskSpec t;
  t.source = m.source();
  t.name = m.name("name");
  const TaskKindEntry& k = readTaskKind(r, m.require("type"), m.at("type"));
  t.type = k.name;
  for (const Entry& e : m.entries()) {
    if (!taskUsesKey(k, e.key)) {
      r.fail(e.key_node, m.at(e.key), std::string("not used by a ") + k.name + " task");
    }
  }
  k.read_subject(m, &t);
  t.weight = m.number("weight", Bound::NonNegative, t.weight);
  t.stiffness = m.number("stiffness", Bound::NonNegative, t.stiffness);
  if (m.has("damping")) {
    t.damping = m.number("damping", Bound::NonNegative, 0.0);
  }
  if (const YAML::Node* d = m.find("dims")) {
    t.dims = readDims(r, *d, m.at("dims"), k);
  }
  if (const YAML::Node* target = m.find("target")) {
    readTarget(r, *target, m.at("target"), k, &t);
  }
  t.active = m.boolean("active", t.active);
  return t;
}

// ---- the file ----------------------------------------------------------------------------------

YAML::Node fieldOf(const YAML::Node& map, const char* key) { return map[key]; }

/// Reads every item of the top-level list `key` with `read`; `unique` (may be null) names the
/// field of each item that must be distinct, and `what` describes it in the message.
template <class Spec, class Read, class KeyOf>
std::vector<Spec> readList(const Reader& r, const Map& top, const char* key, Read read, const char* unique,
                           const char* what, KeyOf keyOf) {
  std::vector<Spec> out;
  const YAML::Node* n = top.find(key);
  if (n == nullptr) {
    return out;
  }
  UniqueNames seen(r, what);
  const std::vector<YAML::Node> items = r.list(*n, key);
  for (std::size_t i = 0; i < items.size(); ++i) {
    const std::string path = item(key, i);
    out.push_back(read(r, items[i], path));
    const std::string k = keyOf(out.back());
    if (unique != nullptr && !k.empty()) {
      seen.add(k, fieldOf(items[i], unique), child(path, unique));
    }
  }
  return out;
}

/// The capacity the listed constraints need, kind by kind as the builder reserves it, within the
/// problem's limits (problem_settings.hpp): the error names the list that goes over.
void checkConstraintCapacity(const Reader& r, const Map& top, const SceneSpec& s) {
  long long slots = 0, rows = 0, equalities = 0;
  for (const ConstraintKindEntry& k : constraintKinds()) {
    int kind_slots = 0, kind_rows = 0, kind_equalities = 0;
    k.reserve(s, &kind_slots, &kind_rows, &kind_equalities);
    slots += kind_slots;
    rows += kind_rows;
    equalities += kind_equalities;
    const YAML::Node* n = top.find(k.key);
    const auto over = [&](const char* what, long long need, int limit) {
      if (need > limit) {
        const std::string message = "the constraints listed need " + std::to_string(need) + " " + what +
                                    ", more than the limit of " + std::to_string(limit);
        if (n != nullptr) {
          r.fail(*n, k.key, message);
        }
        r.fail(1, k.key, message);
      }
    };
    over("constraint slots", slots, problem::kMaxConstraintsCapacity);
    over("inequality rows", rows, problem::kMaxConstraintRowsCapacity);
    over("equality rows", equalities, problem::kMaxConstraintEqualitiesCapacity);
  }
}

/// The top-level keys: the scene's own lists, each constraint kind's list, and the sections the
/// controller loop reads (control/loop, docs/scenes.md), which are not the problem's.
std::vector<std::string> topLevelKeys() {
  std::vector<std::string> keys = {"settings", "entities", "contacts", "tasks"};
  for (const ConstraintKindEntry& k : constraintKinds()) keys.emplace_back(k.key);
  for (const char* loop : {"hardware", "plant", "timeline", "force_control", "estimation", "trajectories"})
    keys.emplace_back(loop);
  return keys;
}

SceneSpec readScene(const Reader& r, const YAML::Node& root) {
  if (!root.IsMap() && !root.IsNull()) {
    r.fail(root, "", "expected a map, got " + describe(root));
  }
  const Map top(r, root, "", topLevelKeys());
  SceneSpec s;
  s.file = r.file();
  s.settings = readSettings(r, top.find("settings"));
  const YAML::Node& entities = top.require("entities");
  if (r.list(entities, "entities").empty()) {
    r.fail(entities, "entities", "expected at least one entity");
  }
  const auto name = [](const auto& spec) { return spec.name; };
  s.entities = readList<EntitySpec>(r, top, "entities", readEntity, "name", "entity name", name);
  s.contacts = readList<ContactSpec>(r, top, "contacts", readContact, "name", "contact name", name);
  s.tasks = readList<TaskSpec>(r, top, "tasks", readTask, "name", "task name", name);
  for (const ConstraintKindEntry& k : constraintKinds()) {
    const YAML::Node* n = top.find(k.key);
    if (n == nullptr) {
      continue;
    }
    UniqueNames seen(r, k.what);
    const std::vector<YAML::Node> items = r.list(*n, k.key);
    for (std::size_t i = 0; i < items.size(); ++i) {
      const std::string path = item(k.key, i);
      const std::string key = k.read(r, items[i], path, &s);
      if (k.unique != nullptr && !key.empty()) {
        seen.add(key, fieldOf(items[i], k.unique), child(path, k.unique));
      }
    }
  }
  checkConstraintCapacity(r, top, s);
  return s;
}

}  // namespace

SceneSpec loadSceneString(const std::string& text, const std::string& file_name_for_messages) {
  const Reader r(file_name_for_messages);
  const YAML::Node root = parseYamlDocument(text, file_name_for_messages);
  if (root.IsNull()) {
    r.fail(1, "", "missing required field 'entities'");
  }
  try {
    return readScene(r, root);
  } catch (const YAML::Exception& e) {
    yamlError(file_name_for_messages, e);
  }
}

SceneSpec loadSceneFile(const std::string& path) { return loadSceneString(readTextFile(path), path); }

}  // namespace mrqp::scene
