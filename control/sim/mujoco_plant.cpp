// The MuJoCo plant (see mujoco_plant.hpp).
#include "sim/mujoco_plant.hpp"

#include <unistd.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <stdexcept>

#include "problem/entity.hpp"

namespace mrqp::sim {

namespace {

Eigen::Quaterniond fromRpy(const Eigen::Vector3d& rpy) {
  return Eigen::Quaterniond(Eigen::AngleAxisd(rpy.z(), Eigen::Vector3d::UnitZ()) *
                            Eigen::AngleAxisd(rpy.y(), Eigen::Vector3d::UnitY()) *
                            Eigen::AngleAxisd(rpy.x(), Eigen::Vector3d::UnitX()));
}

/// World rotation of a body (MuJoCo's xmat is row-major).
Eigen::Matrix3d bodyRotation(const mjData* d, int body) {
  Eigen::Matrix3d R;
  for (int r = 0; r < 3; ++r) {
    for (int c = 0; c < 3; ++c) {
      R(r, c) = d->xmat[9 * body + 3 * r + c];
    }
  }
  return R;
}

Eigen::Vector3d vec3(const mjtNum* p) { return {p[0], p[1], p[2]}; }

std::string where(const scene::Source& s) { return s.file + ":" + std::to_string(s.line) + ": "; }

/// Whether `body` is `root` or one of its descendants.
bool inSubtree(const mjModel* m, int body, int root) noexcept {
  for (; body > 0; body = m->body_parentid[body]) {
    if (body == root) return true;
  }
  return body == root;
}

/// The torque (world axes) that the rotational rows of weld `eq`, with constraint forces
/// `f_rot` (efc_force of its rows 3–5), exert on the weld's body1. MuJoCo 2.2 writes the weld's
/// orientation error as the vector part of c = q2⁻¹ q1 r (r: the weld's relative rotation,
/// eq_data[6..9]) times the torque scale s, and its Jacobian rows as ½ s T (ω1 − ω2) with
/// T ω = vec(q2⁻¹ (0, ω) q1 r) = (c_w 1 − [c_v]×) R2ᵀ ω, so the generalised force of the rows,
/// Jᵀ f, is that of the torque ½ s R2 (c_w f + c_v × f) on body1 (and its opposite on body2).
Eigen::Vector3d weldRotationalTorque(const mjModel* m, const mjData* d, int eq, const mjtNum* f_rot) noexcept {
  const mjtNum* data = m->eq_data + mjNEQDATA * eq;
  const int b1 = m->eq_obj1id[eq];
  const int b2 = m->eq_obj2id[eq];
  const mjtNum* x1 = d->xquat + 4 * b1;
  const mjtNum* x2 = d->xquat + 4 * b2;
  const Eigen::Quaterniond q1(x1[0], x1[1], x1[2], x1[3]);
  const Eigen::Quaterniond q2(x2[0], x2[1], x2[2], x2[3]);
  const Eigen::Quaterniond r(data[6], data[7], data[8], data[9]);
  const Eigen::Quaterniond c = q2.conjugate() * q1 * r;
  const Eigen::Vector3d f = vec3(f_rot);
  return 0.5 * data[10] * (bodyRotation(d, b2) * (c.w() * f + c.vec().cross(f)));
}

/// MuJoCo warns through this hook instead of printing; the counts stay in mjData::warning.
void silentWarning(const char* /*message*/) {}

}  // namespace

MujocoPlant::MujocoPlant(const scene::SceneSpec& scene, const PlantSpec& plant,
                         const scene::ModelRegistry* registry)
    : drives_(plant.drives), ft_noise_(plant.noise, plant.seed) {
  mju_user_warning = silentWarning;
  mjcf_ = writeMjcf(scene, plant);
  load(mjcf_.xml);
  placeInitialState(scene, registry);
  if (!mjcf_.welds.empty()) {
    // Second pass: each weld holds the relative pose of its bodies in the initial state.
    std::vector<MjcfWeld> welds = mjcf_.welds;
    for (MjcfWeld& w : welds) {
      const int b1 = mj_name2id(model_, mjOBJ_BODY, w.body1.c_str());
      const int b2 = mj_name2id(model_, mjOBJ_BODY, w.body2.c_str());
      Eigen::Isometry3d x1 = Eigen::Isometry3d::Identity(), x2 = Eigen::Isometry3d::Identity();
      x1.linear() = bodyRotation(data_, b1);
      x1.translation() = vec3(data_->xpos + 3 * b1);
      x2.linear() = bodyRotation(data_, b2);
      x2.translation() = vec3(data_->xpos + 3 * b2);
      w.relative = x1.inverse() * x2;
      w.relative_known = true;
    }
    mjcf_ = writeMjcf(scene, plant, welds);
    mj_deleteData(data_);
    mj_deleteModel(model_);
    data_ = nullptr;
    model_ = nullptr;
    load(mjcf_.xml);
    // A connect's point on body2 is MuJoCo's eq_data[3..5], which the compiler takes from the
    // reference configuration: the grasp's own point instead (its anchor on body1 is that point
    // in the initial state).
    for (const MjcfWeld& w : mjcf_.welds) {
      if (w.point_only) {
        const int id = mj_name2id(model_, mjOBJ_EQUALITY, ("grasp/" + w.contact).c_str());
        for (int k = 0; k < 3; ++k) {
          model_->eq_data[mjNEQDATA * id + 3 + k] = w.point(k);
        }
      }
    }
    placeInitialState(scene, registry);
  }
  if (plant.settle > 0.0) {
    settle(plant.settle);
  }
}

void MujocoPlant::settle(double duration) {
  // Every actuated joint held where the scene puts it (the drive's holding servo with its
  // integral action: it ends there exactly, carrying its load); floating bases, objects and
  // mechanisms settle on their contacts, grasps and springs. The holding commands stay until
  // the drives send theirs (their integrated torque carries over: no sag when they take over).
  for (Joint& j : joints_) {
    if (!j.actuated) {
      continue;
    }
    loop::ServoCommand c;
    c.position = data_->qpos[j.qpos];
    c.kp = drives_.hold_kp;
    c.kd = drives_.hold_kd;
    c.torque_limit = j.effort;
    c.enabled = true;
    j.command = c;
    j.ramp_end = 0.0;
  }
  const long steps = std::max(1L, std::lround(duration / model_->opt.timestep));
  for (long i = 0; i < steps; ++i) {
    applyServos(true);
    mj_step(model_, data_);
  }
  data_->time = 0.0;
  for (Joint& j : joints_) {
    j.ramp_end = 0.0;
  }
  updateDerived();
}

MujocoPlant::~MujocoPlant() {
  if (data_ != nullptr) {
    mj_deleteData(data_);
  }
  if (model_ != nullptr) {
    mj_deleteModel(model_);
  }
}

void MujocoPlant::load(const std::string& xml) {
  // MuJoCo 2.2 reads a model from a file: a private temporary one.
  char path[] = "/tmp/mrqp-mjcf-XXXXXX";
  const int fd = ::mkstemp(path);
  if (fd < 0) {
    throw std::runtime_error("MuJoCo plant: cannot create a temporary file for the model");
  }
  ::close(fd);
  {
    std::ofstream f(path);
    f << xml;
    if (!f) {
      std::remove(path);
      throw std::runtime_error(std::string("MuJoCo plant: cannot write ") + path);
    }
  }
  std::array<char, 1000> error{};
  model_ = mj_loadXML(path, nullptr, error.data(), static_cast<int>(error.size()));
  std::remove(path);
  if (model_ == nullptr) {
    throw std::runtime_error(std::string("MuJoCo plant: the model of the scene is refused: ") + error.data());
  }
  data_ = mj_makeData(model_);
  if (data_ == nullptr) {
    throw std::runtime_error("MuJoCo plant: mj_makeData failed");
  }
}

void MujocoPlant::placeInitialState(const scene::SceneSpec& scene, const scene::ModelRegistry* registry) {
  joints_.clear();
  mimics_.clear();
  entities_.clear();
  mj_resetData(model_, data_);

  for (std::size_t i = 0; i < mjcf_.entities.size(); ++i) {
    const MjcfEntity& me = mjcf_.entities[i];
    const scene::EntitySpec& spec = scene.entities[i];
    Entity e;
    e.name = me.name;
    e.floating = me.floating;
    e.root_body = mj_name2id(model_, mjOBJ_BODY, me.root_body.c_str());
    if (me.floating) {
      const int j = mj_name2id(model_, mjOBJ_JOINT, (me.name + "/root").c_str());
      e.free_qpos = model_->jnt_qposadr[j];
      e.free_dof = model_->jnt_dofadr[j];
      const Eigen::Quaterniond q = fromRpy(spec.pose.rpy);
      mjtNum* qp = data_->qpos + e.free_qpos;
      qp[0] = spec.pose.xyz.x();
      qp[1] = spec.pose.xyz.y();
      qp[2] = spec.pose.xyz.z();
      qp[3] = q.w();
      qp[4] = q.x();
      qp[5] = q.y();
      qp[6] = q.z();
    }
    for (const std::string& link : me.links) {
      e.frames.emplace_back(link, mj_name2id(model_, mjOBJ_BODY, (me.name + "/" + link).c_str()));
    }

    // The joint order and neutral values: the generated model's when the registry has it.
    std::vector<std::string> order = me.joints;
    std::vector<double> neutral;
    std::vector<bool> actuated;  // the generated model's own flags (joints with an effort limit)
    std::vector<double> effort;
    std::unique_ptr<problem::Entity> model_entity;
    if (registry != nullptr && !me.rigid_object && registry->has(me.model)) {
      model_entity = registry->make(me.model, me.name);
    }
    if (model_entity) {
      if (model_entity->floatingBase() != me.floating) {
        throw std::runtime_error(where(spec.source) + "entities." + me.name +
                                 ": the generated model and the MuJoCo model disagree on the base");
      }
      order.clear();
      Eigen::VectorXd q0(model_entity->nq());
      model_entity->neutral(q0);
      const int offset = model_entity->jointOffset();
      for (int k = 0; k < model_entity->nv() - offset; ++k) {
        order.emplace_back(model_entity->jointName(k));
        neutral.push_back(q0(model_entity->qIndexOfV(k + offset)));
        actuated.push_back(model_entity->actuated()[static_cast<std::size_t>(k + offset)] != 0);
        effort.push_back(model_entity->effortLimit()(k + offset));
      }
      if (order.size() + me.mimics.size() != me.joints.size()) {
        throw std::runtime_error(where(spec.source) + "entities." + me.name + ": the generated model has " +
                                 std::to_string(order.size()) + " joints, the URDF in MuJoCo " +
                                 std::to_string(me.joints.size()) + " of which " +
                                 std::to_string(me.mimics.size()) + " mimic joints");
      }
    } else {
      // Without the generated model: every joint but the mimic ones, in MuJoCo's order.
      order.clear();
      for (const std::string& j : me.joints) {
        const bool mimic =
            std::any_of(me.mimics.begin(), me.mimics.end(), [&](const MjcfMimic& m) { return m.joint == j; });
        if (!mimic) {
          order.push_back(j);
        }
      }
    }
    for (std::size_t k = 0; k < order.size(); ++k) {
      const int jid = mj_name2id(model_, mjOBJ_JOINT, (me.name + "/" + order[k]).c_str());
      if (jid < 0) {
        throw std::runtime_error(where(spec.source) + "entities." + me.name + ": joint '" + order[k] +
                                 "' of the generated model is not in the MuJoCo model");
      }
      Joint j;
      j.qpos = model_->jnt_qposadr[jid];
      j.dof = model_->jnt_dofadr[jid];
      j.actuator = mj_name2id(model_, mjOBJ_ACTUATOR, (me.name + "/" + order[k]).c_str());
      double q = k < neutral.size() ? neutral[k] : 0.0;
      if (neutral.empty() && model_->jnt_limited[jid]) {
        q = std::min(std::max(q, model_->jnt_range[2 * jid]), model_->jnt_range[2 * jid + 1]);
      }
      const auto it = spec.q.find(order[k]);
      if (it != spec.q.end()) {
        q = it->second;
      }
      data_->qpos[j.qpos] = q;
      // Actuated as the scene builder decides it (entity keys actuation, actuated, passive).
      bool act = k < actuated.size() ? actuated[k] : true;
      if (spec.actuation == "all") {
        act = true;
      } else if (spec.actuation == "none" || spec.actuation == "list") {
        act = false;
      }
      const auto listed = [&](const std::vector<std::string>& names) {
        return std::find(names.begin(), names.end(), order[k]) != names.end();
      };
      if (listed(spec.actuated_joints)) {
        act = true;
      }
      if (listed(spec.passive_joints)) {
        act = false;
      }
      j.actuated = act && j.actuator >= 0 && !me.rigid_object;
      j.effort = k < effort.size() && effort[k] > 0.0 ? effort[k] : 1e9;
      const auto sp = spec.springs.find(order[k]);
      if (sp != spec.springs.end()) {
        j.spring_k = sp->second.stiffness;
        j.spring_c = sp->second.damping;
        j.spring_o = sp->second.offset;
      }
      e.joints.push_back(static_cast<int>(joints_.size()));
      joints_.push_back(j);
    }
    for (const MjcfMimic& m : me.mimics) {
      const int jm = mj_name2id(model_, mjOBJ_JOINT, (me.name + "/" + m.joint).c_str());
      const int jn = mj_name2id(model_, mjOBJ_JOINT, (me.name + "/" + m.master).c_str());
      if (jm >= 0 && jn >= 0) {
        mimics_.push_back(Mimic{model_->jnt_qposadr[jm], model_->jnt_dofadr[jm], model_->jnt_qposadr[jn],
                                model_->jnt_dofadr[jn], m.multiplier, m.offset});
      }
    }
    for (const auto& kv : spec.q) {
      if (std::find(order.begin(), order.end(), kv.first) == order.end()) {
        throw std::runtime_error(where(spec.source) + "entities." + me.name + ".q: unknown joint '" +
                                 kv.first + "'");
      }
    }
    entities_.push_back(std::move(e));
  }

  placeMimics();  // a mimic joint starts where its master puts it

  // Bodies that carry something (mass, geometry, an equality) in their subtree; a sensor at a
  // body that carries nothing measures the subtree of its nearest ancestor that does.
  const auto nbody = static_cast<std::size_t>(model_->nbody);
  std::vector<char> carries(nbody, 0);
  const auto mark = [&](int b) {
    for (; b > 0; b = model_->body_parentid[b]) carries[static_cast<std::size_t>(b)] = 1;
  };
  for (int b = 1; b < model_->nbody; ++b) {
    if (model_->body_mass[b] > 0.0) mark(b);
  }
  for (int g = 0; g < model_->ngeom; ++g) mark(model_->geom_bodyid[g]);
  for (int k = 0; k < model_->neq; ++k) {
    if (model_->eq_type[k] == mjEQ_WELD || model_->eq_type[k] == mjEQ_CONNECT) {
      mark(model_->eq_obj1id[k]);
      mark(model_->eq_obj2id[k]);
    }
  }
  sensor_body_.assign(nbody, 0);
  for (int b = 0; b < model_->nbody; ++b) {
    int s = b;
    while (s > 0 && !carries[static_cast<std::size_t>(s)]) s = model_->body_parentid[s];
    sensor_body_[static_cast<std::size_t>(b)] = s > 0 ? s : b;
  }
  mj_forward(model_, data_);
  mj_rnePostConstraint(model_, data_);
}

void MujocoPlant::placeMimics() noexcept {
  for (const Mimic& m : mimics_) {
    data_->qpos[m.qpos] = m.offset + m.multiplier * data_->qpos[m.master_qpos];
    data_->qvel[m.dof] = m.multiplier * data_->qvel[m.master_dof];
  }
}

double MujocoPlant::timestep() const noexcept { return model_->opt.timestep; }

int MujocoPlant::entityHandle(const std::string& entity) const {
  for (std::size_t i = 0; i < entities_.size(); ++i) {
    if (entities_[i].name == entity) {
      return static_cast<int>(i);
    }
  }
  return -1;
}

int MujocoPlant::jointHandle(const std::string& entity, const std::string& joint) const {
  const int e = entityHandle(entity);
  if (e < 0) {
    return -1;
  }
  const int jid = mj_name2id(model_, mjOBJ_JOINT, (entity + "/" + joint).c_str());
  if (jid < 0) {
    return -1;
  }
  for (int h : entities_[static_cast<std::size_t>(e)].joints) {
    if (joints_[static_cast<std::size_t>(h)].qpos == model_->jnt_qposadr[jid]) {
      return h;
    }
  }
  return -1;
}

int MujocoPlant::frameHandle(const std::string& entity, const std::string& frame) const {
  const int e = entityHandle(entity);
  if (e < 0) {
    return -1;
  }
  const Entity& ent = entities_[static_cast<std::size_t>(e)];
  for (const auto& f : ent.frames) {
    if (f.first == frame) {
      return f.second;
    }
  }
  return -1;
}

double MujocoPlant::jointPosition(int joint) const noexcept {
  return data_->qpos[joints_[static_cast<std::size_t>(joint)].qpos];
}

double MujocoPlant::jointVelocity(int joint) const noexcept {
  return data_->qvel[joints_[static_cast<std::size_t>(joint)].dof];
}

double MujocoPlant::jointTorque(int joint) const noexcept {
  const Joint& j = joints_[static_cast<std::size_t>(joint)];
  // With Euler, the drive's −kd q̇ is the joint's damping (qfrc_passive): added back here.
  return (j.actuator >= 0 ? data_->actuator_force[j.actuator] : 0.0) -
         model_->dof_damping[j.dof] * data_->qvel[j.dof];
}

void MujocoPlant::setServo(int joint, const loop::ServoCommand& command) noexcept {
  Joint& j = joints_[static_cast<std::size_t>(joint)];
  const loop::ServoCommand& previous = j.command;
  j.ramp_end = data_->time;
  // Interpolation: a cyclic setpoint whose velocity is the rate of its position since the
  // previous one is reached by a ramp over that period (T = Δposition / velocity), not a step.
  if (drives_.interpolate && command.enabled && previous.enabled && command.velocity != 0.0 &&
      command.kp == previous.kp) {
    const double period = (command.position - previous.position) / command.velocity;
    if (std::isfinite(period) && period > 0.0 && period <= 0.1) {
      j.ramp_end = data_->time + period;
    }
  }
  if (!command.enabled) {
    j.integral_torque = 0.0;  // a drive switched off forgets its integral
  }
  j.command = command;
}

void MujocoPlant::applyServos(bool integrate) noexcept {
  // The drive's law as the joint's actuator: force = b0 + b1 q + b2 q̇, clamped to ±limit
  // (see mjcf_writer.cpp). The scene's springs are applied forces.
  for (Joint& j : joints_) {
    const double q = data_->qpos[j.qpos];
    const double v = data_->qvel[j.dof];
    const loop::ServoCommand& c = j.command;
    const double q_ref = c.position - c.velocity * std::max(0.0, j.ramp_end - data_->time);
    if (j.actuator >= 0) {
      mjtNum* bias = model_->actuator_biasprm + mjNBIAS * j.actuator;
      mjtNum* range = model_->actuator_forcerange + 2 * j.actuator;
      // Integral action of a position servo: ∫ kp / Ti (q_ref − q) dt, clamped to the limit.
      if (drives_.integral_time > 0.0 && c.enabled && c.kp > 0.0) {
        if (integrate) {
          const double lim = std::abs(c.torque_limit);
          j.integral_torque += c.kp / drives_.integral_time * (q_ref - q) * model_->opt.timestep;
          j.integral_torque = std::min(std::max(j.integral_torque, -lim), lim);
        }
      } else {
        j.integral_torque = 0.0;
      }
      const double b0 = c.torque + c.kp * q_ref + c.kd * c.velocity + j.integral_torque;
      const bool ok = c.enabled && std::isfinite(b0) && std::isfinite(c.kp) && std::isfinite(c.kd) &&
                      std::isfinite(c.torque_limit);
      bias[0] = ok ? b0 : 0.0;
      bias[1] = ok ? -c.kp : 0.0;
      // The velocity gain where the integrator takes it implicitly: the implicit integrator
      // differentiates the actuator, semi-implicit Euler only the joint damping.
      if (model_->opt.integrator == mjINT_IMPLICIT) {
        bias[2] = ok ? -c.kd : 0.0;
      } else {
        bias[2] = 0.0;
        model_->dof_damping[j.dof] = ok ? c.kd : 0.0;
      }
      const double limit = ok ? std::abs(c.torque_limit) : 0.0;
      range[0] = -limit;
      range[1] = limit;
    }
    data_->qfrc_applied[j.dof] = -(j.spring_k * q + j.spring_c * v + j.spring_o);
  }
}

void MujocoPlant::step(double dt) noexcept {
  const double n = std::round(dt / model_->opt.timestep);
  const long steps = n < 1.0 ? 1 : static_cast<long>(n);
  for (long i = 0; i < steps; ++i) {
    applyServos(true);
    mj_step(model_, data_);
  }
  updateDerived();
}

void MujocoPlant::updateDerived() noexcept {
  applyServos(false);
  mj_forward(model_, data_);
  mj_rnePostConstraint(model_, data_);
}

double MujocoPlant::time() const noexcept { return data_->time; }

loop::Vector6d MujocoPlant::sensorWrench(int frame) const noexcept {
  const int b = sensor_body_[static_cast<std::size_t>(frame)];
  // cfrc_int: the wrench (torque; force) the parent exerts on the subtree of b, about the
  // subtree CoM c of b's tree, world axes. mj_rnePostConstraint (MuJoCo 2.2) counts contacts and
  // equality constraints (the welds of grasps) in cfrc_ext, so cfrc_int includes what the
  // subtree carries through them.
  const Eigen::Vector3d c = vec3(data_->subtree_com + 3 * model_->body_rootid[b]);
  Eigen::Vector3d torque = -vec3(data_->cfrc_int + 6 * b);
  // MuJoCo 2.2's mj_rnePostConstraint adds a weld's rotational constraint force to cfrc_ext as a
  // world torque, as it is: but those rows are written on half the rotation, in body2's axes,
  // scaled by the torque scale and signed by the hemisphere in which the bodies' quaternions meet
  // (weldRotationalTorque): the torque they transmit is ±½ of it, turned by body2's rotation
  // (measured: cfrc_ext carried −2× and +2× the true weld torque). cfrc_int of a subtree that
  // holds one end of a weld carries the difference: taken out here. (The weld's force rows and
  // connects are exact.)
  for (int i = 0; i < data_->ne;) {
    const int eq = data_->efc_id[i];
    const int type = model_->eq_type[eq];
    if (type == mjEQ_WELD) {
      const bool in1 = inSubtree(model_, model_->eq_obj1id[eq], b);
      const bool in2 = inSubtree(model_, model_->eq_obj2id[eq], b);
      if (in1 != in2) {
        const mjtNum* f_rot = data_->efc_force + i + 3;
        const Eigen::Vector3d excess = vec3(f_rot) - weldRotationalTorque(model_, data_, eq, f_rot);
        torque -= in1 ? excess : Eigen::Vector3d(-excess);  // body1 got +excess in cfrc_ext, body2 −excess
      }
    }
    i += type == mjEQ_WELD ? 6 : (type == mjEQ_CONNECT ? 3 : 1);
  }
  const Eigen::Vector3d force = -vec3(data_->cfrc_int + 6 * b + 3);
  const Eigen::Vector3d o = vec3(data_->xpos + 3 * frame);
  const Eigen::Vector3d torque_o = torque + (c - o).cross(force);
  const Eigen::Matrix3d R = bodyRotation(data_, frame);
  loop::Vector6d out;
  out.head<3>() = R.transpose() * force;
  out.tail<3>() = R.transpose() * torque_o;
  return ft_noise_.wrench(out);
}

loop::ImuSample MujocoPlant::imu(int frame) const noexcept {
  const int b = frame;
  loop::ImuSample s;
  const mjtNum* q = data_->xquat + 4 * b;
  s.orientation = Eigen::Quaterniond(q[0], q[1], q[2], q[3]);
  mjtNum vel[6], acc[6];
  mj_objectVelocity(model_, data_, mjOBJ_XBODY, b, vel, 1);
  mj_objectAcceleration(model_, data_, mjOBJ_XBODY, b, acc, 1);
  s.angular_velocity = vec3(vel);
  s.specific_force = vec3(acc + 3);  // MuJoCo's accelerations carry −gravity: a − g
  return s;
}

void MujocoPlant::entityState(int entity, Eigen::Ref<Eigen::VectorXd> q,
                              Eigen::Ref<Eigen::VectorXd> v) const noexcept {
  const Entity& e = entities_[static_cast<std::size_t>(entity)];
  Eigen::Index iq = 0, iv = 0;
  if (e.floating) {
    const mjtNum* qp = data_->qpos + e.free_qpos;
    const mjtNum* qv = data_->qvel + e.free_dof;
    for (int i = 0; i < 7; ++i) {
      q(i) = qp[i];
    }
    const Eigen::Matrix3d R = Eigen::Quaterniond(qp[3], qp[4], qp[5], qp[6]).normalized().toRotationMatrix();
    // MuJoCo's free joint: linear velocity of the body origin in the world frame, then the
    // angular velocity in the body frame.
    v.segment<3>(0) = vec3(qv + 3);
    v.segment<3>(3) = R.transpose() * vec3(qv);
    iq = 7;
    iv = 6;
  }
  for (int h : e.joints) {
    const Joint& j = joints_[static_cast<std::size_t>(h)];
    q(iq++) = data_->qpos[j.qpos];
    v(iv++) = data_->qvel[j.dof];
  }
}

void MujocoPlant::setEntityState(int entity, const Eigen::Ref<const Eigen::VectorXd>& q,
                                 const Eigen::Ref<const Eigen::VectorXd>& v) noexcept {
  const Entity& e = entities_[static_cast<std::size_t>(entity)];
  Eigen::Index iq = 0, iv = 0;
  if (e.floating) {
    mjtNum* qp = data_->qpos + e.free_qpos;
    mjtNum* qv = data_->qvel + e.free_dof;
    const Eigen::Quaterniond quat = Eigen::Quaterniond(q(3), q(4), q(5), q(6)).normalized();
    for (int i = 0; i < 3; ++i) {
      qp[i] = q(i);
    }
    qp[3] = quat.w();
    qp[4] = quat.x();
    qp[5] = quat.y();
    qp[6] = quat.z();
    const Eigen::Vector3d v_world = quat.toRotationMatrix() * v.segment<3>(3);
    for (int i = 0; i < 3; ++i) {
      qv[i] = v_world(i);
      qv[3 + i] = v(i);
    }
    iq = 7;
    iv = 6;
  }
  for (int h : e.joints) {
    const Joint& j = joints_[static_cast<std::size_t>(h)];
    data_->qpos[j.qpos] = q(iq++);
    data_->qvel[j.dof] = v(iv++);
  }
  placeMimics();
  updateDerived();
}

int MujocoPlant::warnings() const noexcept {
  int n = 0;
  for (int i = 0; i < mjNWARNING; ++i) {
    n += data_->warning[i].number;
  }
  return n;
}

int MujocoPlant::entityNq(int entity) const noexcept {
  const Entity& e = entities_[static_cast<std::size_t>(entity)];
  return static_cast<int>(e.joints.size()) + (e.floating ? 7 : 0);
}

int MujocoPlant::entityNv(int entity) const noexcept {
  const Entity& e = entities_[static_cast<std::size_t>(entity)];
  return static_cast<int>(e.joints.size()) + (e.floating ? 6 : 0);
}

Eigen::Isometry3d MujocoPlant::framePose(int frame) const noexcept {
  const int b = frame;
  Eigen::Isometry3d x = Eigen::Isometry3d::Identity();
  x.linear() = bodyRotation(data_, b);
  x.translation() = vec3(data_->xpos + 3 * b);
  return x;
}

}  // namespace mrqp::sim
