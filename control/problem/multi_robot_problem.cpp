#include "problem/multi_robot_problem.hpp"

#include <Eigen/Geometry>

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

namespace mrqp::problem {

namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();

/// Rotation vector of R (log map), allocation-free.
Eigen::Vector3d rotationVector(const Eigen::Matrix3d& R) noexcept {
  const Eigen::AngleAxisd aa(R);
  return aa.angle() * aa.axis();
}

template <class Slots>
int countUsed(const Slots& slots) noexcept {
  int n = 0;
  for (const auto& s : slots) n += s.used ? 1 : 0;
  return n;
}

}  // namespace

int taskDimension(TaskType t) noexcept {
  switch (t) {
    case TaskType::FramePose: return 6;
    case TaskType::JointTarget: return 1;
    case TaskType::Posture:
    case TaskType::ForceMinimisation: return 0;  // variable
    default: return 3;
  }
}

MultiRobotProblem::MultiRobotProblem(std::vector<std::unique_ptr<Entity>> entities,
                                     const ProblemSettings& settings)
    : settings_(settings),
      entities_(std::move(entities)),
      qp_(0, 0, 0),
      solver_(0, 0, 0) {
  if (entities_.empty() || static_cast<int>(entities_.size()) > kMaxEntities) {
    throw std::invalid_argument("a problem holds 1 to 32 entities");
  }
  for (const auto& e : entities_) {
    v_offset_.push_back(nv_total_);
    nv_total_ += e->nv();
    max_nv_ = std::max(max_nv_, e->nv());
  }
  contacts_.resize(static_cast<std::size_t>(settings_.max_contacts));
  tasks_.resize(static_cast<std::size_t>(settings_.max_tasks));
  for (auto& t : tasks_) t.posture = Eigen::VectorXd::Zero(max_nv_);
  dampers_.resize(static_cast<std::size_t>(settings_.max_com_dampers));
  joint_ineqs_.resize(static_cast<std::size_t>(settings_.max_joint_inequalities));
  const int n_max = nv_total_ + settings_.max_contact_generators;
  const int me_max = nv_total_ + 6 * settings_.max_contacts;
  const int mi_max = nv_total_ + kDamperRows * settings_.max_com_dampers + settings_.max_joint_inequalities;
  qp_ = qp::QpProblem(n_max, me_max, mi_max);
  solver_ = qp::QpSolver(n_max, me_max, mi_max, settings_.qp);
  E_ = Eigen::MatrixXd::Zero(nv_total_, n_max);
  Nall_ = Eigen::VectorXd::Zero(nv_total_);
  Ja_ = Eigen::MatrixXd::Zero(6, max_nv_);
  Jb_ = Eigen::MatrixXd::Zero(6, max_nv_);
  T_ = Eigen::MatrixXd::Zero(6, n_max);
  t_.setZero();
  x_ = Eigen::VectorXd::Zero(n_max);
  tau_ = Eigen::VectorXd::Zero(nv_total_);
  for (auto& e : entities_) {
    e->setGravity(settings_.gravity);
    e->update();
  }
}

int MultiRobotProblem::entityIndex(const std::string& name) const noexcept {
  for (std::size_t i = 0; i < entities_.size(); ++i) {
    if (entities_[i]->name() == name) return static_cast<int>(i);
  }
  return -1;
}

// ---------------------------------------------------------------- contacts

int MultiRobotProblem::addContact(const ContactDesc& c) noexcept {
  if (const char* why = validateContact(c)) {
    error_ = why;
    return -1;
  }
  if (c.entity >= entityCount() || c.other_entity >= entityCount() ||
      c.frame >= entity(c.entity).frameCount() ||
      (c.other_entity >= 0 && c.other_frame >= entity(c.other_entity).frameCount())) {
    error_ = "a contact names an entity or frame that does not exist";
    return -1;
  }
  int vars = c.variables();
  for (const auto& s : contacts_) vars += s.used ? s.d.variables() : 0;
  if (vars > settings_.max_contact_generators) {
    error_ = "the contacts' generators exceed max_contact_generators";
    return -1;
  }
  for (std::size_t i = 0; i < contacts_.size(); ++i) {
    ContactSlot& s = contacts_[i];
    if (s.used) continue;
    s.d = c;
    s.d.normal.normalize();
    s.used = true;
    s.established = false;
    s.lambda.setZero();
    s.wrench.setZero();
    s.c_local.setZero();
    for (int k = 0; k < c.npoints; ++k) s.c_local += c.points[static_cast<std::size_t>(k)];
    s.c_local /= static_cast<double>(c.npoints);
    return static_cast<int>(i);
  }
  error_ = "no free contact slot (max_contacts)";
  return -1;
}

bool MultiRobotProblem::removeContact(int id) noexcept {
  if (id < 0 || id >= contactCapacity() || !contacts_[static_cast<std::size_t>(id)].used) return false;
  contacts_[static_cast<std::size_t>(id)].used = false;
  contacts_[static_cast<std::size_t>(id)].var_offset = -1;
  return true;
}

bool MultiRobotProblem::contactActive(int id) const noexcept {
  return id >= 0 && id < contactCapacity() && contacts_[static_cast<std::size_t>(id)].used;
}

void MultiRobotProblem::establish(ContactSlot& c) noexcept {
  const Pose sf = entity(c.d.entity).framePose(c.d.frame);
  const Eigen::Vector3d cw = sf.R * c.c_local + sf.p;
  if (c.d.other_entity < 0) {
    c.target_p = cw;
    c.target_R = sf.R;
  } else {
    const Pose of = entity(c.d.other_entity).framePose(c.d.other_frame);
    c.target_p = of.R.transpose() * (cw - of.p);
    c.target_R = of.R.transpose() * sf.R;
  }
  c.established = true;
}

// ---------------------------------------------------------------- tasks

int MultiRobotProblem::addTask(const TaskDesc& t) noexcept {
  const bool force = t.type == TaskType::ContactForce || t.type == TaskType::ForceMinimisation;
  const bool group = t.type == TaskType::Com && t.entity < 0;
  if (!(t.weight >= 0.0) || !(t.stiffness >= 0.0) || !std::isfinite(t.weight) ||
      !std::isfinite(t.stiffness) || !std::isfinite(t.damping)) {
    error_ = "a task's weight and gains must be finite and ≥ 0";
    return -1;
  }
  if (force) {
    if (t.type == TaskType::ContactForce && !contactActive(t.contact)) {
      error_ = "a force task needs an existing contact";
      return -1;
    }
  } else if (group) {
    if (t.entity_mask == 0 || (entityCount() < 32 && (t.entity_mask >> entityCount()) != 0)) {
      error_ = "a group CoM task needs a non-empty set of existing entities";
      return -1;
    }
  } else {
    if (t.entity < 0 || t.entity >= entityCount()) {
      error_ = "a task names an entity that does not exist";
      return -1;
    }
    const Entity& e = entity(t.entity);
    const bool frame_task = t.type == TaskType::FramePosition || t.type == TaskType::FrameOrientation ||
                            t.type == TaskType::FramePose;
    if (frame_task && (t.frame < 0 || t.frame >= e.frameCount())) {
      error_ = "a frame task names a frame that does not exist";
      return -1;
    }
    if (t.type == TaskType::JointTarget && (t.joint < e.jointOffset() || t.joint >= e.nv())) {
      error_ = "a joint task names a joint that does not exist";
      return -1;
    }
  }
  for (std::size_t i = 0; i < tasks_.size(); ++i) {
    TaskSlot& s = tasks_[i];
    if (s.used) continue;
    s.d = t;
    s.used = true;
    s.error.setZero();
    if (t.type == TaskType::Posture) {
      const Entity& e = entity(t.entity);
      for (int k = e.jointOffset(); k < e.nv(); ++k) s.posture(k) = e.q()(e.qIndexOfV(k));
    }
    return static_cast<int>(i);
  }
  error_ = "no free task slot (max_tasks)";
  return -1;
}

bool MultiRobotProblem::removeTask(int id) noexcept {
  if (!taskActive(id)) return false;
  tasks_[static_cast<std::size_t>(id)].used = false;
  return true;
}

bool MultiRobotProblem::taskActive(int id) const noexcept {
  return id >= 0 && id < taskCapacity() && tasks_[static_cast<std::size_t>(id)].used;
}

bool MultiRobotProblem::setTaskWeight(int id, double w) noexcept {
  if (!taskActive(id) || !(w >= 0.0) || !std::isfinite(w)) return false;
  tasks_[static_cast<std::size_t>(id)].d.weight = w;
  return true;
}

bool MultiRobotProblem::setTaskGains(int id, double k, double d) noexcept {
  if (!taskActive(id) || !(k >= 0.0) || !std::isfinite(k) || !std::isfinite(d)) return false;
  tasks_[static_cast<std::size_t>(id)].d.stiffness = k;
  tasks_[static_cast<std::size_t>(id)].d.damping = d;
  return true;
}

bool MultiRobotProblem::setTaskTarget(int id, const Eigen::Vector3d& target) noexcept {
  if (!taskActive(id) || !target.allFinite()) return false;
  tasks_[static_cast<std::size_t>(id)].d.target = target;
  return true;
}

bool MultiRobotProblem::setTaskTargetRotation(int id, const Eigen::Matrix3d& R) noexcept {
  if (!taskActive(id) || !R.allFinite()) return false;
  tasks_[static_cast<std::size_t>(id)].d.target_rotation = R;
  return true;
}

bool MultiRobotProblem::setPostureTarget(int id, const Eigen::Ref<const Eigen::VectorXd>& qj) noexcept {
  if (!taskActive(id)) return false;
  TaskSlot& s = tasks_[static_cast<std::size_t>(id)];
  if (s.d.type != TaskType::Posture) return false;
  const Entity& e = entity(s.d.entity);
  if (qj.size() != e.nv() - e.jointOffset() || !qj.allFinite()) return false;
  s.posture.segment(e.jointOffset(), qj.size()) = qj;
  return true;
}

Vector6d MultiRobotProblem::taskError(int id) const noexcept {
  return taskActive(id) ? tasks_[static_cast<std::size_t>(id)].error : Vector6d::Zero();
}

double MultiRobotProblem::kd(const TaskDesc& t) const noexcept {
  return t.damping >= 0.0 ? t.damping : 2.0 * std::sqrt(t.stiffness);
}

// ---------------------------------------------------------------- dampers

int MultiRobotProblem::addComDamper(const ComDamperDesc& d) noexcept {
  if (d.entity < 0 || d.entity >= entityCount() || !(d.interaction > d.security) ||
      !(d.security >= 0.0) || !(d.damping > 0.0)) {
    error_ = "a CoM damper needs an entity, interaction > security ≥ 0 and damping > 0";
    return -1;
  }
  for (std::size_t i = 0; i < dampers_.size(); ++i) {
    if (dampers_[i].used) continue;
    dampers_[i].d = d;
    dampers_[i].used = true;
    dampers_[i].polygon.clear();
    return static_cast<int>(i);
  }
  error_ = "no free CoM damper slot (max_com_dampers)";
  return -1;
}

int MultiRobotProblem::addJointInequality(const JointInequalityDesc& d) noexcept {
  if (d.terms < 1 || d.terms > JointInequalityDesc::kMaxTerms || !(d.interaction > d.security) ||
      !(d.damping > 0.0) || !std::isfinite(d.upper)) {
    error_ = "a joint inequality needs 1 to 4 terms, interaction > security and damping > 0";
    return -1;
  }
  for (int k = 0; k < d.terms; ++k) {
    const int e = d.entity[static_cast<std::size_t>(k)];
    const int j = d.joint[static_cast<std::size_t>(k)];
    if (e < 0 || e >= entityCount() || j < entity(e).jointOffset() || j >= entity(e).nv()) {
      error_ = "a joint inequality names a joint that does not exist";
      return -1;
    }
  }
  for (std::size_t i = 0; i < joint_ineqs_.size(); ++i) {
    if (joint_ineqs_[i].used) continue;
    joint_ineqs_[i].d = d;
    joint_ineqs_[i].used = true;
    return static_cast<int>(i);
  }
  error_ = "no free joint inequality slot (max_joint_inequalities)";
  return -1;
}

bool MultiRobotProblem::removeJointInequality(int id) noexcept {
  if (id < 0 || id >= static_cast<int>(joint_ineqs_.size()) || !joint_ineqs_[static_cast<std::size_t>(id)].used) {
    return false;
  }
  joint_ineqs_[static_cast<std::size_t>(id)].used = false;
  return true;
}

// ---------------------------------------------------------------- the cycle

UpdateStatus MultiRobotProblem::update() noexcept {
  for (auto& e : entities_) {
    if (!e->q().allFinite() || !e->v().allFinite()) {
      error_ = "an entity's state is not finite";
      return UpdateStatus::NonFiniteState;
    }
  }
  for (auto& e : entities_) e->update();
  for (auto& c : contacts_) {
    if (c.used && !c.established) establish(c);
  }
  layout();
  qp_.H().setZero();
  qp_.g().setZero();
  qp_.A().setZero();
  qp_.b().setZero();
  qp_.C().setZero();
  qp_.l().setConstant(-kInf);
  qp_.u().setConstant(kInf);
  assembleContacts();
  assembleDynamics();
  assembleBounds();
  assembleDampers();
  assembleTasks();
  qp_.H().diagonal().array() += settings_.regularisation;
  return UpdateStatus::Ok;
}

void MultiRobotProblem::layout() noexcept {
  nlambda_ = 0;
  ncontact_rows_ = 0;
  for (std::size_t i = 0; i < contacts_.size(); ++i) {
    ContactSlot& c = contacts_[i];
    if (!c.used) continue;
    c.var_offset = nv_total_ + nlambda_;
    nlambda_ += c.d.variables();
    c.rows = c.d.rows();
    for (std::size_t j = 0; j < i; ++j) {
      const ContactSlot& o = contacts_[j];
      if (o.used && o.rows == 6 && o.d.entity == c.d.entity && o.d.frame == c.d.frame &&
          o.d.other_entity == c.d.other_entity && o.d.other_frame == c.d.other_frame) {
        c.rows = 0;
        break;
      }
    }
    ncontact_rows_ += c.rows;
  }
  nunactuated_ = 0;
  ntorque_rows_ = 0;
  for (const auto& e : entities_) {
    for (int k = 0; k < e->nv(); ++k) {
      if (!e->actuated()[static_cast<std::size_t>(k)]) {
        ++nunactuated_;
      } else if (std::isfinite(e->effortLimit()(k))) {
        ++ntorque_rows_;
      }
    }
  }
  int row = nunactuated_;
  for (auto& c : contacts_) {
    if (!c.used) continue;
    c.row_offset = row;
    row += c.rows;
  }
  const int mi = ntorque_rows_ + kDamperRows * countUsed(dampers_) + countUsed(joint_ineqs_);
  qp_.resize(nv_total_ + nlambda_, nunactuated_ + ncontact_rows_, mi);
}

void MultiRobotProblem::assembleContacts() noexcept {
  const int n = qp_.n();
  E_.leftCols(n).setZero();
  auto A = qp_.A();
  auto b = qp_.b();
  const double kp = settings_.contact_stiffness, kdv = settings_.contact_damping;
  for (auto& c : contacts_) {
    if (!c.used) continue;
    const Entity& ea = entity(c.d.entity);
    const Pose sf = ea.framePose(c.d.frame);
    c.c_world = sf.R * c.c_local + sf.p;
    // Wrench basis: generator k of point i, force on the surface entity, moment about c_world.
    int col = 0;
    for (int i = 0; i < c.d.npoints; ++i) {
      const Eigen::Vector3d pw = sf.R * c.d.points[static_cast<std::size_t>(i)] + sf.p;
      for (int k = 0; k < c.d.generators; ++k, ++col) {
        const Eigen::Vector3d g = sf.R * coneGenerator(c.d.normal, c.d.friction, k, c.d.generators);
        c.W.col(col).head<3>() = (pw - c.c_world).cross(g);
        c.W.col(col).tail<3>() = g;
      }
    }
    const int ng = c.d.variables();
    const int oa = velocityOffset(c.d.entity), na = ea.nv();
    auto Ja = Ja_.leftCols(na);
    ea.frameJacobian(c.d.frame, c.c_local, Ja);
    Vector6d acc = ea.frameBiasAcceleration(c.d.frame, c.c_local);
    Vector6d vel = Ja * ea.v();
    Vector6d err;
    // Generalised force on the surface entity: Jaᵀ W λ, so τ = M q̈ + N − Jaᵀ W λ.
    E_.block(oa, c.var_offset, na, ng).noalias() -= Ja.transpose() * c.W.leftCols(ng);
    if (c.d.other_entity < 0) {
      err.head<3>() = rotationVector(sf.R * c.target_R.transpose());
      err.tail<3>() = c.c_world - c.target_p;
    } else {
      const Entity& eb = entity(c.d.other_entity);
      const Pose of = eb.framePose(c.d.other_frame);
      const Eigen::Vector3d cb_local = of.R.transpose() * (c.c_world - of.p);
      const int ob = velocityOffset(c.d.other_entity), nb = eb.nv();
      auto Jb = Jb_.leftCols(nb);
      eb.frameJacobian(c.d.other_frame, cb_local, Jb);
      acc -= eb.frameBiasAcceleration(c.d.other_frame, cb_local);
      vel.noalias() -= Jb * eb.v();
      // The reaction: −W λ on the other entity at the same point.
      E_.block(ob, c.var_offset, nb, ng).noalias() += Jb.transpose() * c.W.leftCols(ng);
      const Eigen::Matrix3d Rb = of.R * c.target_R;
      err.head<3>() = rotationVector(sf.R * Rb.transpose());
      err.tail<3>() = c.c_world - (of.R * c.target_p + of.p);
      if (c.rows == 6) {
        A.block(c.row_offset, ob, 6, nb) = -Jb;
      } else if (c.rows == 3) {
        A.block(c.row_offset, ob, 3, nb) = -Jb.bottomRows<3>();
      }
    }
    // Relative acceleration = −Kp e − Kd ė (drift correction of the no-slip constraint 15–16).
    const Vector6d rhs = -acc - kp * err - kdv * vel;
    if (c.rows == 6) {
      A.block(c.row_offset, oa, 6, na) = Ja;
      b.segment<6>(c.row_offset) = rhs;
    } else if (c.rows == 3) {
      A.block(c.row_offset, oa, 3, na) = Ja.bottomRows<3>();
      b.segment<3>(c.row_offset) = rhs.tail<3>();
    }
  }
}

void MultiRobotProblem::assembleDynamics() noexcept {
  const int n = qp_.n();
  auto A = qp_.A();
  auto b = qp_.b();
  auto C = qp_.C();
  auto l = qp_.l();
  auto u = qp_.u();
  int eq = 0, iq = 0;
  for (int i = 0; i < entityCount(); ++i) {
    const Entity& e = entity(i);
    const int o = velocityOffset(i);
    E_.block(o, o, e.nv(), e.nv()) = e.massMatrix();
    Nall_.segment(o, e.nv()) = e.bias();
    for (int k = 0; k < e.nv(); ++k) {
      const int r = o + k;
      if (!e.actuated()[static_cast<std::size_t>(k)]) {
        A.row(eq) = E_.row(r).head(n);  // unactuated: E x + N = 0
        b(eq) = -Nall_(r);
        ++eq;
      } else if (std::isfinite(e.effortLimit()(k))) {
        C.row(iq) = E_.row(r).head(n);  // −τmax ≤ E x + N ≤ τmax (20)
        l(iq) = -e.effortLimit()(k) - Nall_(r);
        u(iq) = e.effortLimit()(k) - Nall_(r);
        ++iq;
      }
    }
  }
}

void MultiRobotProblem::assembleBounds() noexcept {
  auto xl = qp_.xl();
  auto xu = qp_.xu();
  xl.setConstant(-kInf);
  xu.setConstant(kInf);
  const double dt = settings_.dt;
  const double T = std::max(dt, settings_.joint_limit_horizon);
  for (int i = 0; i < entityCount(); ++i) {
    const Entity& e = entity(i);
    const int o = velocityOffset(i);
    for (int k = e.jointOffset(); k < e.nv(); ++k) {
      const double q = e.q()(e.qIndexOfV(k)), v = e.v()(k);
      const double vmax = e.vLimit()(k);
      double lo = -kInf, hi = kInf;
      if (std::isfinite(vmax)) {  // (22)
        lo = (-vmax - v) / dt;
        hi = (vmax - v) / dt;
      }
      // (23) over the look-ahead T, for the semi-implicit Euler step q⁺ = q + (v + q̈T)T.
      double plo = -kInf, phi = kInf;
      if (std::isfinite(e.qLower()(k))) plo = (e.qLower()(k) - q - v * T) / (T * T);
      if (std::isfinite(e.qUpper()(k))) phi = (e.qUpper()(k) - q - v * T) / (T * T);
      if (std::max(lo, plo) <= std::min(hi, phi)) {
        lo = std::max(lo, plo);
        hi = std::min(hi, phi);
      }  // else outside its range already: only the velocity limit is kept
      xl(o + k) = lo;
      xu(o + k) = hi;
    }
  }
  for (const auto& c : contacts_) {
    if (c.used) xl.segment(c.var_offset, c.d.variables()).setZero();  // (17)
  }
}

void MultiRobotProblem::assembleDampers() noexcept {
  auto C = qp_.C();
  auto l = qp_.l();
  const double dt = settings_.dt;
  int row = ntorque_rows_;
  for (auto& dm : dampers_) {
    if (!dm.used) continue;
    const Entity& e = entity(dm.d.entity);
    const int o = velocityOffset(dm.d.entity);
    dm.polygon.clear();
    for (const auto& c : contacts_) {
      if (!c.used || c.d.entity != dm.d.entity || c.d.other_entity >= 0) continue;
      const Pose sf = e.framePose(c.d.frame);
      for (int i = 0; i < c.d.npoints; ++i) dm.polygon.add(sf.R * c.d.points[static_cast<std::size_t>(i)] + sf.p);
    }
    dm.polygon.build();
    const Eigen::Vector2d cxy = e.com().head<2>();
    Eigen::Vector3d cv;
    cv.noalias() = e.comJacobian() * e.v();
    const Eigen::Vector2d vxy = cv.head<2>();
    const int edges = std::min(dm.polygon.edges(), kDamperRows);
    for (int i = 0; i < edges; ++i) {
      const double d = dm.polygon.distance(i, cxy);
      if (d >= dm.d.interaction) continue;  // row stays free (l = −inf)
      const Eigen::Vector2d a = dm.polygon.normal(i);
      // ḋ + d̈Δt ≥ −ξ (d − d_s)/(d_i − d_s), d̈ = aᵀ(Jc q̈ + J̇c q̇)
      C.block(row + i, o, 1, e.nv()).noalias() = dt * a.transpose() * e.comJacobian().topRows<2>();
      l(row + i) = -dm.d.damping * (d - dm.d.security) / (dm.d.interaction - dm.d.security) -
                   a.dot(vxy) - dt * a.dot(e.comBias().head<2>());
    }
    row += kDamperRows;
  }
  for (const auto& ji : joint_ineqs_) {
    if (!ji.used) continue;
    double s = ji.d.upper, sdot = 0.0;
    for (int k = 0; k < ji.d.terms; ++k) {
      const Entity& e = entity(ji.d.entity[static_cast<std::size_t>(k)]);
      const int j = ji.d.joint[static_cast<std::size_t>(k)];
      s -= ji.d.coeff[static_cast<std::size_t>(k)] * e.q()(e.qIndexOfV(j));
      sdot -= ji.d.coeff[static_cast<std::size_t>(k)] * e.v()(j);
    }
    if (s < ji.d.interaction) {
      // ṡ + s̈Δt ≥ −ξ (s − s_s)/(s_i − s_s), s̈ = −Σ c q̈
      for (int k = 0; k < ji.d.terms; ++k) {
        const int col = velocityOffset(ji.d.entity[static_cast<std::size_t>(k)]) + ji.d.joint[static_cast<std::size_t>(k)];
        C(row, col) -= dt * ji.d.coeff[static_cast<std::size_t>(k)];
      }
      l(row) = -ji.d.damping * (s - ji.d.security) / (ji.d.interaction - ji.d.security) - sdot;
    }
    ++row;
  }
}

void MultiRobotProblem::accumulate(int rows, int c0, int nc, const std::array<std::uint8_t, 6>& sel,
                                   double w) noexcept {
  if (w <= 0.0) return;
  auto H = qp_.H();
  auto g = qp_.g();
  for (int r = 0; r < rows; ++r) {
    if (!sel[static_cast<std::size_t>(r)]) continue;
    const auto Tr = T_.row(r).segment(c0, nc);
    H.block(c0, c0, nc, nc).noalias() += w * Tr.transpose() * Tr;
    g.segment(c0, nc).noalias() -= (w * t_(r)) * Tr.transpose();
  }
}

void MultiRobotProblem::assembleTasks() noexcept {
  for (auto& t : tasks_) {
    if (t.used) addTaskCost(t);
  }
}

void MultiRobotProblem::addTaskCost(TaskSlot& s) noexcept {
  const TaskDesc& t = s.d;
  const double K = t.stiffness, D = kd(t);
  auto H = qp_.H();
  auto g = qp_.g();
  s.error.setZero();
  switch (t.type) {
    case TaskType::Posture: {
      const Entity& e = entity(t.entity);
      const int o = velocityOffset(t.entity);
      for (int k = e.jointOffset(); k < e.nv(); ++k) {
        const double err = e.q()(e.qIndexOfV(k)) - s.posture(k);
        const double ad = -K * err - D * e.v()(k);
        H(o + k, o + k) += t.weight;
        g(o + k) -= t.weight * ad;
      }
      return;
    }
    case TaskType::JointTarget: {
      const Entity& e = entity(t.entity);
      const int col = velocityOffset(t.entity) + t.joint;
      const double err = e.q()(e.qIndexOfV(t.joint)) - t.target.x();
      s.error(0) = err;
      const double ad = -K * err - D * e.v()(t.joint);
      H(col, col) += t.weight;
      g(col) -= t.weight * ad;
      return;
    }
    case TaskType::ForceMinimisation: {
      for (int i = 0; i < contactCapacity(); ++i) {
        const auto& c = contacts_[static_cast<std::size_t>(i)];
        if (!c.used || (t.contact >= 0 && t.contact != i)) continue;
        H.diagonal().segment(c.var_offset, c.d.variables()).array() += t.weight;
      }
      return;
    }
    case TaskType::ContactForce: {
      if (!contactActive(t.contact)) return;
      const auto& c = contacts_[static_cast<std::size_t>(t.contact)];
      const int ng = c.d.variables();
      T_.topLeftCorner(3, qp_.n()).setZero();
      T_.block(0, c.var_offset, 3, ng) = c.W.block(3, 0, 3, ng);
      t_.head<3>() = t.target;
      s.error.head<3>() = c.wrench.tail<3>() - t.target;
      accumulate(3, c.var_offset, ng, t.dims, t.weight);
      return;
    }
    case TaskType::Com: {
      // One entity, or the group CoM Σ mᵢcᵢ / Σ mᵢ with Jacobian blocks mᵢ/M · Jcᵢ.
      int c0 = qp_.n(), c1 = 0;
      double mtot = 0.0;
      Eigen::Vector3d c = Eigen::Vector3d::Zero(), cdot = Eigen::Vector3d::Zero(), bias = Eigen::Vector3d::Zero();
      for (int i = 0; i < entityCount(); ++i) {
        const bool in = t.entity >= 0 ? i == t.entity : ((t.entity_mask >> i) & 1u) != 0;
        if (!in) continue;
        mtot += entity(i).mass();
        c0 = std::min(c0, velocityOffset(i));
        c1 = std::max(c1, velocityOffset(i) + entity(i).nv());
      }
      if (mtot <= 0.0) return;
      T_.block(0, c0, 3, c1 - c0).setZero();
      for (int i = 0; i < entityCount(); ++i) {
        const bool in = t.entity >= 0 ? i == t.entity : ((t.entity_mask >> i) & 1u) != 0;
        if (!in) continue;
        const Entity& e = entity(i);
        const double f = e.mass() / mtot;
        T_.block(0, velocityOffset(i), 3, e.nv()) = f * e.comJacobian();
        c += f * e.com();
        Eigen::Vector3d cv;
        cv.noalias() = e.comJacobian() * e.v();
        cdot += f * cv;
        bias += f * e.comBias();
      }
      s.error.head<3>() = c - t.target;
      t_.head<3>() = -K * (c - t.target) - D * cdot - bias;
      accumulate(3, c0, c1 - c0, t.dims, t.weight);
      return;
    }
    case TaskType::FramePosition:
    case TaskType::FrameOrientation:
    case TaskType::FramePose: {
      const Entity& e = entity(t.entity);
      const int o = velocityOffset(t.entity), nv = e.nv();
      auto J = Ja_.leftCols(nv);
      e.frameJacobian(t.frame, t.point, J);
      const Vector6d bias = e.frameBiasAcceleration(t.frame, t.point);
      const Vector6d vel = J * e.v();
      const Pose P = e.framePose(t.frame);
      Vector6d err;
      err.head<3>() = rotationVector(P.R * t.target_rotation.transpose());
      err.tail<3>() = P.R * t.point + P.p - t.target;
      const Vector6d ad = -K * err - D * vel - bias;
      int r0 = 0, rows = 6;
      if (t.type == TaskType::FramePosition) {
        r0 = 3;
        rows = 3;
      } else if (t.type == TaskType::FrameOrientation) {
        rows = 3;
      }
      T_.block(0, o, rows, nv) = J.middleRows(r0, rows);
      t_.head(rows) = ad.segment(r0, rows);
      s.error.head(rows) = err.segment(r0, rows);
      accumulate(rows, o, nv, t.dims, t.weight);
      return;
    }
  }
}

qp::QpStatus MultiRobotProblem::solve() noexcept {
  const qp::QpStatus st = solver_.solve(qp_);
  if (st != qp::QpStatus::Optimal) {
    error_ = "the QP has no optimal solution (see solver().info())";
    return st;
  }
  const int n = qp_.n();
  x_.head(n) = solver_.x();
  tau_.noalias() = E_.leftCols(n) * x_.head(n);
  tau_ += Nall_;
  for (int i = 0; i < entityCount(); ++i) {
    const Entity& e = entity(i);
    const int o = velocityOffset(i);
    for (int k = 0; k < e.nv(); ++k) {
      if (!e.actuated()[static_cast<std::size_t>(k)]) tau_(o + k) = 0.0;
    }
  }
  for (auto& c : contacts_) {
    if (!c.used) continue;
    const int ng = c.d.variables();
    c.lambda.head(ng) = x_.segment(c.var_offset, ng);
    c.wrench.noalias() = c.W.leftCols(ng) * c.lambda.head(ng);
  }
  return st;
}

void MultiRobotProblem::integrate(double dt) noexcept {
  for (int i = 0; i < entityCount(); ++i) {
    entity(i).integrate(x_.segment(velocityOffset(i), entity(i).nv()), dt);
  }
}

Eigen::Ref<const Eigen::VectorXd> MultiRobotProblem::acceleration(int i) const noexcept {
  return x_.segment(velocityOffset(i), entity(i).nv());
}

Eigen::Ref<const Eigen::VectorXd> MultiRobotProblem::torque(int i) const noexcept {
  return tau_.segment(velocityOffset(i), entity(i).nv());
}

Eigen::Ref<const Eigen::VectorXd> MultiRobotProblem::lambda(int id) const noexcept {
  const auto& c = contacts_[static_cast<std::size_t>(id)];
  return c.lambda.head(c.used ? c.d.variables() : 0);
}

Vector6d MultiRobotProblem::contactWrench(int id) const noexcept {
  return contactActive(id) ? contacts_[static_cast<std::size_t>(id)].wrench : Vector6d::Zero();
}

}  // namespace mrqp::problem
