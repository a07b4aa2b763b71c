#include "scene/scene_builder.hpp"

#include <Eigen/Geometry>

#include <cmath>
#include <sstream>
#include <stdexcept>

#include "problem/rigid_object.hpp"

namespace mrqp::scene {

namespace {

[[noreturn]] void fail(const Source& src, const std::string& field, const std::string& msg) {
  std::ostringstream os;
  os << (src.file.empty() ? "<scene>" : src.file) << ":" << src.line << ": " << field << ": " << msg;
  throw SceneError(os.str());
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

std::vector<std::string> frameNames(const problem::Entity& e) {
  std::vector<std::string> out;
  for (int f = 0; f < e.frameCount(); ++f) out.emplace_back(e.frameName(f));
  return out;
}

struct Resolver {
  const problem::MultiRobotProblem& p;

  int entity(const std::string& name, const Source& src, const std::string& field) const {
    const int i = p.entityIndex(name);
    if (i < 0) {
      std::vector<std::string> names;
      for (int k = 0; k < p.entityCount(); ++k) names.push_back(p.entity(k).name());
      fail(src, field, "unknown entity '" + name + "' (entities: " + listOf(names) + ")");
    }
    return i;
  }
  int frame(int e, const std::string& name, const Source& src, const std::string& field) const {
    const int f = p.entity(e).frameIndex(name);
    if (f < 0) {
      fail(src, field, "entity '" + p.entity(e).name() + "' has no frame '" + name + "' (frames: " +
                           listOf(frameNames(p.entity(e))) + ")");
    }
    return f;
  }
  int joint(int e, const std::string& name, const Source& src, const std::string& field) const {
    const int k = p.entity(e).jointIndex(name);
    if (k < 0) {
      fail(src, field, "entity '" + p.entity(e).name() + "' has no joint '" + name + "' (joints: " +
                           listOf(jointNames(p.entity(e))) + ")");
    }
    return k;
  }
};

std::unique_ptr<problem::Entity> makeEntity(const EntitySpec& es, std::size_t i, const ModelRegistry& models) {
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

problem::TaskType taskType(TaskKind k) {
  switch (k) {
    case TaskKind::Posture: return problem::TaskType::Posture;
    case TaskKind::Com: return problem::TaskType::Com;
    case TaskKind::FramePosition: return problem::TaskType::FramePosition;
    case TaskKind::FrameOrientation: return problem::TaskType::FrameOrientation;
    case TaskKind::FramePose: return problem::TaskType::FramePose;
    case TaskKind::JointTarget: return problem::TaskType::JointTarget;
    case TaskKind::ContactForce: return problem::TaskType::ContactForce;
    case TaskKind::ForceMinimisation: return problem::TaskType::ForceMinimisation;
  }
  return problem::TaskType::Posture;
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
  ps.max_com_dampers = std::max<int>(1, static_cast<int>(spec.com_dampers.size()));
  ps.max_joint_inequalities = std::max<int>(1, static_cast<int>(spec.joint_inequalities.size()));
  ps.contact_stiffness = spec.settings.contact_stiffness;
  ps.contact_damping = spec.settings.contact_damping;
  ps.regularisation = spec.settings.regularisation;
  scene.problem = std::make_unique<problem::MultiRobotProblem>(std::move(entities), ps);
  problem::MultiRobotProblem& p = *scene.problem;
  const Resolver r{p};

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
    const int id = p.addContact(c);
    if (id < 0) fail(cs.source, field, p.lastError());
    scene.contacts[cs.name] = id;
  }
  p.update();  // poses at the start: default targets, established contacts

  for (std::size_t i = 0; i < spec.tasks.size(); ++i) {
    const TaskSpec& ts = spec.tasks[i];
    const std::string field = "tasks[" + std::to_string(i) + "]";
    problem::TaskDesc t;
    t.type = taskType(ts.kind);
    t.weight = ts.weight;
    t.stiffness = ts.stiffness;
    t.damping = ts.damping ? *ts.damping : -1.0;
    t.point = ts.point;
    for (std::size_t k = 0; k < ts.dims.size() && k < 6; ++k) t.dims[k] = ts.dims[k] ? 1 : 0;
    if (t.type == problem::TaskType::FramePose && ts.dims.size() == 6) {
      // The file lists (x, y, z, rx, ry, rz) like the target; the task's rows are (angular; linear).
      for (std::size_t k = 0; k < 3; ++k) {
        t.dims[k] = ts.dims[k + 3] ? 1 : 0;
        t.dims[k + 3] = ts.dims[k] ? 1 : 0;
      }
    }
    const bool force = t.type == problem::TaskType::ContactForce || t.type == problem::TaskType::ForceMinimisation;
    if (force) {
      if (!ts.contact.empty()) {
        auto it = scene.contacts.find(ts.contact);
        if (it == scene.contacts.end()) fail(ts.source, field + ".contact", "unknown contact '" + ts.contact + "'");
        t.contact = it->second;
      } else if (t.type == problem::TaskType::ContactForce) {
        fail(ts.source, field + ".contact", "a force task needs a contact");
      }
      if (ts.target) t.target = ts.target->head<3>();
    } else {
      if (ts.entities.empty()) fail(ts.source, field + ".entity", "missing");
      if (ts.entities.size() == 1) {
        t.entity = r.entity(ts.entities[0], ts.source, field + ".entity");
      } else {
        if (t.type != problem::TaskType::Com) fail(ts.source, field + ".entities", "only a CoM task takes a group");
        for (const auto& n : ts.entities) t.entity_mask |= 1u << r.entity(n, ts.source, field + ".entities");
      }
    }
    if (t.entity >= 0) {
      const problem::Entity& e = p.entity(t.entity);
      switch (t.type) {
        case problem::TaskType::FramePosition:
        case problem::TaskType::FrameOrientation:
        case problem::TaskType::FramePose: {
          t.frame = r.frame(t.entity, ts.frame, ts.source, field + ".frame");
          const problem::Pose P = e.framePose(t.frame);
          t.target = P.R * t.point + P.p;
          t.target_rotation = P.R;
          if (ts.target) {
            if (t.type == problem::TaskType::FramePosition) t.target = ts.target->head<3>();
            if (t.type == problem::TaskType::FrameOrientation) t.target_rotation = rotationFromRpy(ts.target->head<3>());
            if (t.type == problem::TaskType::FramePose) {
              t.target = ts.target->head<3>();
              t.target_rotation = rotationFromRpy(ts.target->segment<3>(3));
            }
          }
          break;
        }
        case problem::TaskType::JointTarget:
          t.joint = r.joint(t.entity, ts.joint, ts.source, field + ".joint");
          t.target.x() = ts.target ? (*ts.target)(0) : e.q()(e.qIndexOfV(t.joint));
          break;
        case problem::TaskType::Com:
          t.target = ts.target ? Eigen::Vector3d(ts.target->head<3>()) : e.com();
          break;
        default:
          break;
      }
    } else if (t.type == problem::TaskType::Com) {
      double m = 0.0;
      Eigen::Vector3d c = Eigen::Vector3d::Zero();
      for (int k = 0; k < p.entityCount(); ++k) {
        if ((t.entity_mask >> k) & 1u) {
          m += p.entity(k).mass();
          c += p.entity(k).mass() * p.entity(k).com();
        }
      }
      t.target = ts.target ? Eigen::Vector3d(ts.target->head<3>()) : Eigen::Vector3d(c / m);
    }
    const int id = p.addTask(t);
    if (id < 0) fail(ts.source, field, p.lastError());
    if (t.type == problem::TaskType::Posture && !ts.posture_target.empty()) {
      const problem::Entity& e = p.entity(t.entity);
      Eigen::VectorXd qj(e.nv() - e.jointOffset());
      for (int k = e.jointOffset(); k < e.nv(); ++k) qj(k - e.jointOffset()) = e.q()(e.qIndexOfV(k));
      for (const auto& [jn, value] : ts.posture_target) {
        qj(r.joint(t.entity, jn, ts.source, field + ".target." + jn) - e.jointOffset()) = value;
      }
      p.setPostureTarget(id, qj);
    }
    if (!ts.active) p.removeTask(id);  // declared but off: the scene's program may add it later
    else scene.tasks[ts.name] = id;
  }

  for (std::size_t i = 0; i < spec.com_dampers.size(); ++i) {
    const ComDamperSpec& ds = spec.com_dampers[i];
    const std::string field = "com_dampers[" + std::to_string(i) + "]";
    problem::ComDamperDesc d;
    d.entity = r.entity(ds.entity, ds.source, field + ".entity");
    d.interaction = ds.interaction;
    d.security = ds.security;
    d.damping = ds.damping;
    if (p.addComDamper(d) < 0) fail(ds.source, field, p.lastError());
  }
  for (std::size_t i = 0; i < spec.joint_inequalities.size(); ++i) {
    const JointInequalitySpec& js = spec.joint_inequalities[i];
    const std::string field = "joint_inequalities[" + std::to_string(i) + "]";
    problem::JointInequalityDesc d;
    if (js.terms.size() > static_cast<std::size_t>(problem::JointInequalityDesc::kMaxTerms)) {
      fail(js.source, field + ".terms", "at most 4 terms");
    }
    d.terms = static_cast<int>(js.terms.size());
    for (std::size_t k = 0; k < js.terms.size(); ++k) {
      const std::string tf = field + ".terms[" + std::to_string(k) + "]";
      d.entity[k] = r.entity(js.terms[k].entity, js.source, tf + ".entity");
      d.joint[k] = r.joint(d.entity[k], js.terms[k].joint, js.source, tf + ".joint");
      d.coeff[k] = js.terms[k].coeff;
    }
    d.upper = js.upper;
    d.interaction = js.interaction;
    d.security = js.security;
    d.damping = js.damping;
    const int id = p.addJointInequality(d);
    if (id < 0) fail(js.source, field, p.lastError());
    scene.joint_inequalities[js.name] = id;
  }
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
