// The multi-robot QP (eq. 25): slots, layout of x and of the rows, assembly of the core rows
// (EoM, contacts, torque limits, bounds), of the constraint objects and of the task objects.
#include "problem/multi_robot_problem.hpp"

#include "problem/constraints/com_damper.hpp"
#include "problem/constraints/joint_inequality.hpp"

#include <Eigen/Geometry>

#include <algorithm>
#include <cmath>
#include <limits>
#include <new>
#include <stdexcept>

namespace mrqp::problem {

namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();

/// Rotation vector of R (log map), allocation-free.
Eigen::Vector3d rotationVector(const Eigen::Matrix3d& R) noexcept {
  const Eigen::AngleAxisd aa(R);
  return aa.angle() * aa.axis();
}

}  // namespace

MultiRobotProblem::MultiRobotProblem(std::vector<std::unique_ptr<Entity>> entities,
                                     const ProblemSettings& settings)
    : settings_(settings), entities_(std::move(entities)), qp_(0, 0, 0), solver_(0, 0, 0) {
  if (entities_.empty() || static_cast<int>(entities_.size()) > kMaxEntities) {
    throw std::invalid_argument("a problem holds 1 to 32 entities");
  }
  if (const char* why = capacityError(settings_)) {
    throw std::invalid_argument(why);
  }
  for (const auto& e : entities_) {
    v_offset_.push_back(nv_total_);
    nv_total_ += e->nv();
    max_nv_ = std::max(max_nv_, e->nv());
  }
  contacts_.resize(static_cast<std::size_t>(settings_.max_contacts));
  tasks_.resize(static_cast<std::size_t>(std::max(0, settings_.max_tasks)));
  const int constraint_slots = settings_.max_constraints >= 0
                                   ? settings_.max_constraints
                                   : settings_.max_com_dampers + settings_.max_joint_inequalities;
  // (the slots hold objects built in place, which do not move: constructed, never resized)
  constraints_ = std::vector<ConstraintSlot>(static_cast<std::size_t>(std::max(0, constraint_slots)));
  max_constraint_rows_ = settings_.max_constraint_rows >= 0
                             ? settings_.max_constraint_rows
                             : 16 * settings_.max_com_dampers + settings_.max_joint_inequalities;
  max_constraint_equalities_ = std::max(0, settings_.max_constraint_equalities);
  const int n_max = nv_total_ + settings_.max_contact_generators;
  const int me_max = nv_total_ + 6 * settings_.max_contacts + max_constraint_equalities_;
  const int mi_max = nv_total_ + max_constraint_rows_;
  qp_ = qp::QpProblem(n_max, me_max, mi_max);
  solver_ = qp::QpSolver(n_max, me_max, mi_max, settings_.qp);
  E_ = Eigen::MatrixXd::Zero(nv_total_, n_max);
  Nall_ = Eigen::VectorXd::Zero(nv_total_);
  Ja_ = Eigen::MatrixXd::Zero(6, max_nv_);
  Jb_ = Eigen::MatrixXd::Zero(6, max_nv_);
  Jw_ = Eigen::MatrixXd::Zero(6, max_nv_);
  T_ = Eigen::MatrixXd::Zero(6, n_max);
  t_ = Eigen::VectorXd::Zero(std::max({6, max_nv_, settings_.max_contact_generators}));
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

// ---------------------------------------------------------------- tasks and constraints

namespace {

/// The slot for a new object: one holding none, else one holding a removed object (which the
/// caller replaces). −1 when every slot is active.
template <class Slots, class Held>
int freeSlot(const Slots& slots, Held held) noexcept {
  for (std::size_t i = 0; i < slots.size(); ++i) {
    if (!held(slots[i])) return static_cast<int>(i);
  }
  for (std::size_t i = 0; i < slots.size(); ++i) {
    if (!slots[i].active) return static_cast<int>(i);
  }
  return -1;
}

}  // namespace

int MultiRobotProblem::addTask(std::unique_ptr<Task> t) noexcept {
  if (!t) {
    error_ = "no task given";
    return -1;
  }
  if (const char* why = t->check(*this)) {
    error_ = why;
    return -1;
  }
  const int i = freeSlot(tasks_, [](const TaskSlot& s) { return s.task != nullptr; });
  if (i < 0) {
    error_ = "no free task slot (max_tasks)";
    return -1;
  }
  TaskSlot& s = tasks_[static_cast<std::size_t>(i)];
  s.task = std::move(t);
  s.active = true;
  s.task->attach(*this);
  return i;
}

bool MultiRobotProblem::removeTask(int id) noexcept {
  if (!taskActive(id)) return false;
  tasks_[static_cast<std::size_t>(id)].active = false;
  return true;
}

bool MultiRobotProblem::restoreTask(int id) noexcept {
  if (id < 0 || id >= taskCapacity() || !tasks_[static_cast<std::size_t>(id)].task) return false;
  TaskSlot& s = tasks_[static_cast<std::size_t>(id)];
  if (s.active) return true;
  if (const char* why = s.task->check(*this)) {  // e.g. its contact was removed meanwhile
    error_ = why;
    return false;
  }
  s.active = true;
  return true;
}

std::unique_ptr<Task> MultiRobotProblem::releaseTask(int id) noexcept {
  if (id < 0 || id >= taskCapacity()) return nullptr;
  tasks_[static_cast<std::size_t>(id)].active = false;
  return std::move(tasks_[static_cast<std::size_t>(id)].task);
}

bool MultiRobotProblem::taskActive(int id) const noexcept {
  return id >= 0 && id < taskCapacity() && tasks_[static_cast<std::size_t>(id)].active;
}

bool MultiRobotProblem::setTaskWeight(int id, double w) noexcept {
  return taskActive(id) && task(id).setWeight(w);
}

bool MultiRobotProblem::setTaskGains(int id, double k, double d) noexcept {
  return taskActive(id) && task(id).setGains(k, d);
}

bool MultiRobotProblem::setTaskTarget(int id, const Eigen::Vector3d& target) noexcept {
  return taskActive(id) && task(id).setTarget(target);
}

bool MultiRobotProblem::setTaskTargetRotation(int id, const Eigen::Matrix3d& R) noexcept {
  return taskActive(id) && task(id).setTargetRotation(R);
}

bool MultiRobotProblem::setPostureTarget(int id, const Eigen::Ref<const Eigen::VectorXd>& qj) noexcept {
  return taskActive(id) && task(id).setTargetVector(qj);
}

bool MultiRobotProblem::setTaskReference(int id, const Eigen::Ref<const Eigen::VectorXd>& velocity,
                                         const Eigen::Ref<const Eigen::VectorXd>& acceleration) noexcept {
  return taskActive(id) && task(id).setReference(velocity, acceleration);
}

bool MultiRobotProblem::setTaskReference(int id, const Eigen::Vector3d& position,
                                         const Eigen::Vector3d& velocity,
                                         const Eigen::Vector3d& acceleration) noexcept {
  if (!taskActive(id) || task(id).referenceRows() != 3 || !velocity.allFinite() ||
      !acceleration.allFinite()) {
    return false;
  }
  return task(id).setTarget(position) && task(id).setReference(velocity, acceleration);
}

Vector6d MultiRobotProblem::taskError(int id) const noexcept {
  return taskActive(id) ? task(id).error() : Vector6d::Zero();
}

const char* MultiRobotProblem::admit(const Constraint& c) const noexcept {
  if (const char* why = c.check(*this)) return why;
  int rows = c.inequalityRows(), eqs = c.equalityRows();
  for (const auto& s : constraints_) {
    if (s.active && s.constraint != &c) {
      rows += s.constraint->inequalityRows();
      eqs += s.constraint->equalityRows();
    }
  }
  if (rows > max_constraint_rows_ || eqs > max_constraint_equalities_) {
    return "the constraints' rows exceed max_constraint_rows or max_constraint_equalities";
  }
  return nullptr;
}

int MultiRobotProblem::takeConstraintSlot() noexcept {
  const int i = freeSlot(constraints_, [](const ConstraintSlot& s) { return s.constraint != nullptr; });
  if (i < 0) {
    error_ = "no free constraint slot (max_constraints)";
    return -1;
  }
  ConstraintSlot& s = constraints_[static_cast<std::size_t>(i)];
  s.owned.reset();
  s.joint_inequality.reset();
  s.constraint = nullptr;
  return i;
}

int MultiRobotProblem::addConstraint(std::unique_ptr<Constraint> c) noexcept {
  if (!c) {
    error_ = "no constraint given";
    return -1;
  }
  if (const char* why = admit(*c)) {
    error_ = why;
    return -1;
  }
  const int i = takeConstraintSlot();
  if (i < 0) return -1;
  ConstraintSlot& s = constraints_[static_cast<std::size_t>(i)];
  s.owned = std::move(c);
  s.constraint = s.owned.get();
  s.active = true;
  return i;
}

int MultiRobotProblem::addJointInequality(const JointInequalityDesc& d) noexcept {
  if (d.terms < 1 || d.terms > JointInequalityDesc::kMaxTerms) {
    error_ = "a joint inequality needs 1 to 4 terms, interaction > security and damping > 0";
    return -1;
  }
  std::array<JointInequality::Term, JointInequality::kMaxTerms> terms{};
  for (std::size_t k = 0; k < static_cast<std::size_t>(d.terms); ++k) {
    terms[k].entity = d.entity[k];
    terms[k].joint = d.joint[k];
    terms[k].coeff = d.coeff[k];
  }
  const JointInequality candidate(terms.data(), d.terms, d.upper, d.interaction, d.security, d.damping);
  if (const char* why = admit(candidate)) {
    error_ = why;
    return -1;
  }
  const int i = takeConstraintSlot();
  if (i < 0) return -1;
  ConstraintSlot& s = constraints_[static_cast<std::size_t>(i)];
  s.joint_inequality.emplace(terms.data(), d.terms, d.upper, d.interaction, d.security, d.damping);
  s.constraint = &*s.joint_inequality;
  s.active = true;
  return i;
}

int MultiRobotProblem::addComDamper(const ComDamperDesc& d) noexcept {
  std::unique_ptr<Constraint> c(new (std::nothrow) ComDamper(d.entity, d.interaction, d.security, d.damping));
  return addConstraint(std::move(c));
}

bool MultiRobotProblem::removeConstraint(int id) noexcept {
  if (!constraintActive(id)) return false;
  constraints_[static_cast<std::size_t>(id)].active = false;
  return true;
}

bool MultiRobotProblem::restoreConstraint(int id) noexcept {
  if (id < 0 || id >= constraintCapacity() || !constraints_[static_cast<std::size_t>(id)].constraint)
    return false;
  ConstraintSlot& s = constraints_[static_cast<std::size_t>(id)];
  if (s.active) return true;
  if (const char* why = admit(*s.constraint)) {
    error_ = why;
    return false;
  }
  s.active = true;
  return true;
}

std::unique_ptr<Constraint> MultiRobotProblem::releaseConstraint(int id) noexcept {
  if (id < 0 || id >= constraintCapacity()) return nullptr;
  ConstraintSlot& s = constraints_[static_cast<std::size_t>(id)];
  s.active = false;
  s.constraint = nullptr;
  s.joint_inequality.reset();
  return std::move(s.owned);
}

bool MultiRobotProblem::constraintActive(int id) const noexcept {
  return id >= 0 && id < constraintCapacity() && constraints_[static_cast<std::size_t>(id)].active;
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
  assembleConstraints();
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
  int mi = ntorque_rows_;
  for (auto& s : constraints_) {
    if (!s.active) continue;
    s.eq_row = row;
    row += s.constraint->equalityRows();
    s.ineq_row = mi;
    mi += s.constraint->inequalityRows();
  }
  qp_.resize(nv_total_ + nlambda_, row, mi);
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
      if (c.d.free != 0) {
        writeHeldRows(c, sf.R, Jb, -1.0, A.block(c.row_offset, ob, c.rows, nb));
      } else if (c.rows == 6) {
        A.block(c.row_offset, ob, 6, nb) = -Jb;
      } else if (c.rows == 3) {
        A.block(c.row_offset, ob, 3, nb) = -Jb.bottomRows<3>();
      }
    }
    // Relative acceleration = −Kp e − Kd ė (drift correction of the no-slip constraint 15–16).
    const Vector6d rhs = -acc - kp * err - kdv * vel;
    if (c.d.free != 0) {
      // Rows of the held directions of the contact frame only (world rows rotated into it).
      writeHeldRows(c, sf.R, Ja, 1.0, A.block(c.row_offset, oa, c.rows, na));
      const Eigen::Matrix3d Rc = sf.R * contactFrame(c.d.normal);
      Vector6d rhs_c;
      rhs_c.head<3>() = Rc.transpose() * rhs.tail<3>();  // translations
      rhs_c.tail<3>() = Rc.transpose() * rhs.head<3>();  // rotations
      int r = 0;
      for (int k = 0; k < 6; ++k) {
        if (c.d.holds(k)) b(c.row_offset + r++) = rhs_c(k);
      }
    } else if (c.rows == 6) {
      A.block(c.row_offset, oa, 6, na) = Ja;
      b.segment<6>(c.row_offset) = rhs;
    } else if (c.rows == 3) {
      A.block(c.row_offset, oa, 3, na) = Ja.bottomRows<3>();
      b.segment<3>(c.row_offset) = rhs.tail<3>();
    }
  }
}

void MultiRobotProblem::writeHeldRows(const ContactSlot& c, const Eigen::Matrix3d& R_frame,
                                      const Eigen::Ref<const Eigen::MatrixXd>& J, double sign,
                                      Eigen::Ref<Eigen::MatrixXd> rows) noexcept {
  // Held direction k of the contact frame (t1, t2, n; translations then rotations): the row
  // sign · dᵀ J_lin (translation along d) or sign · dᵀ J_ang (rotation about d), d in world axes.
  const Eigen::Matrix3d Rc = R_frame * contactFrame(c.d.normal);
  int r = 0;
  for (int k = 0; k < 6; ++k) {
    if (!c.d.holds(k)) continue;
    const Eigen::Vector3d d = sign * Rc.col(k % 3);
    rows.row(r++).noalias() = d.transpose() * (k < 3 ? J.bottomRows<3>() : J.topRows<3>());
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

void MultiRobotProblem::assembleConstraints() noexcept {
  auto C = qp_.C();
  auto l = qp_.l();
  auto u = qp_.u();
  auto A = qp_.A();
  auto b = qp_.b();
  for (auto& s : constraints_) {
    if (!s.active) continue;
    const int mi = s.constraint->inequalityRows(), me = s.constraint->equalityRows();
    ConstraintRows rows{C.middleRows(s.ineq_row, mi), l.segment(s.ineq_row, mi), u.segment(s.ineq_row, mi),
                        A.middleRows(s.eq_row, me), b.segment(s.eq_row, me)};
    s.constraint->update(*this, rows);
  }
}

void MultiRobotProblem::accumulate(const TaskRows& r, const Task::Selection& sel, double w) noexcept {
  if (w <= 0.0) return;
  auto H = qp_.H();
  auto g = qp_.g();
  if (r.identity) {  // T = I over [col0, col0 + rows): no selection
    for (int k = 0; k < r.rows; ++k) {
      H(r.col0 + k, r.col0 + k) += w;
      g(r.col0 + k) -= w * r.t(k);
    }
    return;
  }
  for (int k = 0; k < r.rows; ++k) {
    if (!sel[static_cast<std::size_t>(k)]) continue;
    const auto Tr = r.T.row(k).segment(r.col0, r.cols);
    H.block(r.col0, r.col0, r.cols, r.cols).noalias() += w * Tr.transpose() * Tr;
    g.segment(r.col0, r.cols).noalias() -= (w * r.t(k)) * Tr.transpose();
  }
}

void MultiRobotProblem::assembleTasks() noexcept {
  for (auto& s : tasks_) {
    if (!s.active) continue;
    TaskRows rows{T_, t_};
    if (s.task->update(*this, rows)) accumulate(rows, s.task->selection(), s.task->weight());
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
