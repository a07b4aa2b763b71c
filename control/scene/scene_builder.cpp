#include "scene/scene_builder.hpp"

#include <Eigen/Geometry>

#include <cmath>
#include <sstream>
#include <stdexcept>

#include "problem/rigid_object.hpp"
#include "scene/build_context.hpp"
#include "scene/constraint_kind.hpp"
#include "scene/task_kind.hpp"

namespace mrqp::scene {

namespace {

[[noreturn]] void fail(const Source& src, const std::string& field, const std::string& msg) {
  BuildContext::fail(src, field, msg);
}

std::string listOf(const std::vector<std::string>& names) {
  std::string s;
  for (std::size_t i = 0; i < names.size() && i < 60; ++i) s += (i ? ", " : "") + names[i];
  if (names.size() > 60) s += ", …";
  return s;
}

std::vector<std::string> jointNames(const problem::Entity& e) {
  std::vector<std::string> out;
  for (int j = 0; j < e.nv() - e.jointOffset(); ++j) out.emplace_back(e.jointName(j));
  return out;
}

std::unique_ptr<problem::Entity> makeEntity(const EntitySpec& es, std::size_t i,
                                            const ModelRegistry& models) {
  const std::string field = "entities[" + std::to_string(i) + "]";
  std::unique_ptr<problem::Entity> e;
  if (es.model == "rigid_object") {
    try {
      e = std::make_unique<problem::RigidObject>(es.name, es.object.mass, es.object.com, es.object.inertia);
    } catch (const std::invalid_argument& ex) {
      fail(es.source, field, ex.what());
    }
  } else {
    e = models.make(es.model, es.name);
    if (!e) {
      fail(es.source, field + ".model",
           "unknown model '" + es.model + "' (known: rigid_object, " + listOf(models.names()) + ")");
    }
  }
  const Eigen::Matrix3d R = rotationFromRpy(es.pose.rpy);
  if (e->floatingBase()) {
    e->q().head<3>() = es.pose.xyz;
    const Eigen::Quaterniond qr(R);
    e->q()(3) = qr.w();
    e->q()(4) = qr.x();
    e->q()(5) = qr.y();
    e->q()(6) = qr.z();
  } else {
    problem::Pose base;
    base.R = R;
    base.p = es.pose.xyz;
    e->setBasePose(base);
  }
  for (const auto& [jn, value] : es.q) {
    const int k = e->jointIndex(jn);
    if (k < 0) {
      fail(es.source, field + ".q." + jn,
           "model '" + es.model + "' has no joint '" + jn + "' (joints: " + listOf(jointNames(*e)) + ")");
    }
    if (value < e->qLower()(k) || value > e->qUpper()(k)) {
      std::ostringstream os;
      os << value << " is outside the joint's range [" << e->qLower()(k) << ", " << e->qUpper()(k) << "]";
      fail(es.source, field + ".q." + jn, os.str());
    }
    e->q()(e->qIndexOfV(k)) = value;
  }
  if (es.actuation == "all") {
    e->setAllJointsActuated(true);
  } else if (es.actuation == "none" || es.actuation == "list") {
    e->setAllJointsActuated(false);
  }
  for (const auto& jn : es.actuated_joints) {
    const int k = e->jointIndex(jn);
    if (k < 0) fail(es.source, field + ".actuated", "no joint '" + jn + "' in model '" + es.model + "'");
    e->setActuated(k, true);
  }
  for (const auto& jn : es.passive_joints) {
    const int k = e->jointIndex(jn);
    if (k < 0) fail(es.source, field + ".passive", "no joint '" + jn + "' in model '" + es.model + "'");
    e->setActuated(k, false);
  }
  for (const auto& [jn, s] : es.springs) {
    const int k = e->jointIndex(jn);
    if (k < 0) fail(s.source, field + ".springs." + jn, "no joint '" + jn + "' in model '" + es.model + "'");
    e->setSpring(k, problem::JointSpring{s.stiffness, s.damping, s.offset});
  }
  return e;
}

}  // namespace

Eigen::Matrix3d rotationFromRpy(const Eigen::Vector3d& rpy) {
  return (Eigen::AngleAxisd(rpy.z(), Eigen::Vector3d::UnitZ()) *
          Eigen::AngleAxisd(rpy.y(), Eigen::Vector3d::UnitY()) *
          Eigen::AngleAxisd(rpy.x(), Eigen::Vector3d::UnitX()))
      .toRotationMatrix();
}

int Scene::contact(const std::string& name) const {
  auto it = contacts.find(name);
  if (it == contacts.end()) throw std::out_of_range("no contact named '" + name + "'");
  return it->second;
}

int Scene::task(const std::string& name) const {
  auto it = tasks.find(name);
  if (it == tasks.end()) throw std::out_of_range("no task named '" + name + "'");
  return it->second;
}

Scene buildScene(const SceneSpec& spec, const ModelRegistry& models) {
  Scene scene;
  scene.settings = spec.settings;
  std::vector<std::unique_ptr<problem::Entity>> entities;
  for (std::size_t i = 0; i < spec.entities.size(); ++i) {
    entities.push_back(makeEntity(spec.entities[i], i, models));
  }
  if (entities.empty()) fail(Source{spec.file, 1}, "entities", "a scene needs at least one entity");
  if (entities.size() > static_cast<std::size_t>(problem::MultiRobotProblem::kMaxEntities)) {
    fail(spec.entities.back().source, "entities", "at most 32 entities");
  }
  problem::ProblemSettings ps;
  ps.dt = spec.settings.dt;
  ps.gravity = spec.settings.gravity;
  ps.max_tasks = spec.settings.max_tasks;
  ps.max_contacts = spec.settings.max_contacts;
  ps.max_contact_generators = spec.settings.max_contact_generators;
  ps.max_constraints = 0;
  ps.max_constraint_rows = 0;
  ps.max_constraint_equalities = 0;
  for (const ConstraintKindEntry& k : constraintKinds()) {
    k.reserve(spec, &ps.max_constraints, &ps.max_constraint_rows, &ps.max_constraint_equalities);
  }
  ps.contact_stiffness = spec.settings.contact_stiffness;
  ps.contact_damping = spec.settings.contact_damping;
  ps.regularisation = spec.settings.regularisation;
  scene.problem = std::make_unique<problem::MultiRobotProblem>(std::move(entities), ps);
  problem::MultiRobotProblem& p = *scene.problem;
  const BuildContext r(p, scene.contacts);

  for (std::size_t i = 0; i < spec.contacts.size(); ++i) {
    const ContactSpec& cs = spec.contacts[i];
    const std::string field = "contacts[" + std::to_string(i) + "]";
    problem::ContactDesc c;
    c.entity = r.entity(cs.entity, cs.source, field + ".entity");
    c.frame = r.frame(c.entity, cs.frame, cs.source, field + ".frame");
    if (!cs.other_entity.empty()) {
      c.other_entity = r.entity(cs.other_entity, cs.source, field + ".other.entity");
      c.other_frame = r.frame(c.other_entity, cs.other_frame, cs.source, field + ".other.frame");
    }
    if (cs.points.size() > static_cast<std::size_t>(problem::kMaxContactPoints)) {
      fail(cs.source, field + ".points", "at most 8 points");
    }
    c.npoints = static_cast<int>(cs.points.size());
    for (std::size_t k = 0; k < cs.points.size(); ++k) c.points[k] = cs.points[k];
    c.normal = cs.normal;
    c.friction = cs.friction;
    c.generators = cs.generators;
    c.free = cs.free;
    const int id = p.addContact(c);
    if (id < 0) fail(cs.source, field, p.lastError());
    scene.contacts[cs.name] = id;
  }
  p.update();  // poses at the start: default targets, established contacts

  for (std::size_t i = 0; i < spec.tasks.size(); ++i) {
    const TaskSpec& ts = spec.tasks[i];
    const std::string field = "tasks[" + std::to_string(i) + "]";
    const TaskKindEntry* kind = findTaskKind(ts.type);
    if (kind == nullptr) fail(ts.source, field + ".type", "unknown task type '" + ts.type + "'");
    std::unique_ptr<problem::Task> task = kind->make(ts, r, field);
    if (!task->setWeight(ts.weight) || !task->setGains(ts.stiffness, ts.damping ? *ts.damping : -1.0)) {
      fail(ts.source, field, "a task's weight and gains must be finite and ≥ 0");
    }
    const int id = p.addTask(std::move(task));
    if (id < 0) fail(ts.source, field, p.lastError());
    if (!ts.active) {  // declared but off: the scene's program may restore it later
      p.removeTask(id);
      scene.inactive_tasks[ts.name] = id;
    } else {
      scene.tasks[ts.name] = id;
    }
  }

  for (const ConstraintKindEntry& k : constraintKinds()) k.build(spec, r, p, &scene);
  for (std::size_t i = 0; i < spec.contacts.size(); ++i) {
    if (!spec.contacts[i].active) p.removeContact(scene.contacts[spec.contacts[i].name]);
  }
  p.update();
  return scene;
}

Scene loadScene(const std::string& path, const ModelRegistry& models) {
  return buildScene(loadSceneFile(path), models);
}

}  // namespace mrqp::scene
