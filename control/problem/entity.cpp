#include "problem/entity.hpp"

#include <cstring>
#include <limits>

namespace mrqp::problem {

Entity::Entity(std::string name, int nq, int nv, bool floating_base)
    : name_(std::move(name)),
      nq_(nq),
      nv_(nv),
      floating_(floating_base),
      q_(Eigen::VectorXd::Zero(nq)),
      v_(Eigen::VectorXd::Zero(nv)),
      q_lower_(Eigen::VectorXd::Constant(nv, -std::numeric_limits<double>::infinity())),
      q_upper_(Eigen::VectorXd::Constant(nv, std::numeric_limits<double>::infinity())),
      v_limit_(Eigen::VectorXd::Constant(nv, std::numeric_limits<double>::infinity())),
      effort_limit_(Eigen::VectorXd::Constant(nv, std::numeric_limits<double>::infinity())),
      actuated_(static_cast<std::size_t>(nv), 0),
      springs_(static_cast<std::size_t>(nv)),
      M_(Eigen::MatrixXd::Zero(nv, nv)),
      Jc_(Eigen::MatrixXd::Zero(3, nv)),
      N_(Eigen::VectorXd::Zero(nv)),
      spring_work_(Eigen::VectorXd::Zero(nv)) {}

int Entity::jointIndex(const std::string& name) const noexcept {
  for (int j = 0; j < nv_ - jointOffset(); ++j) {
    if (name == jointName(j)) return j + jointOffset();
  }
  return -1;
}

bool Entity::fullyActuated() const noexcept {
  if (floating_) return false;
  for (auto a : actuated_) {
    if (!a) return false;
  }
  return true;
}

bool Entity::setActuated(int k, bool on) noexcept {
  if (k < jointOffset() || k >= nv_) return false;
  actuated_[static_cast<std::size_t>(k)] = on ? 1 : 0;
  return true;
}

void Entity::setAllJointsActuated(bool on) noexcept {
  for (int k = jointOffset(); k < nv_; ++k) actuated_[static_cast<std::size_t>(k)] = on ? 1 : 0;
}

bool Entity::setSpring(int k, const JointSpring& s) noexcept {
  if (k < jointOffset() || k >= nv_) return false;
  springs_[static_cast<std::size_t>(k)] = s;
  return true;
}

void Entity::springTorque(Eigen::Ref<Eigen::VectorXd> out) const noexcept {
  out.setZero();
  for (int k = jointOffset(); k < nv_; ++k) {
    const JointSpring& s = springs_[static_cast<std::size_t>(k)];
    if (s.stiffness != 0.0 || s.damping != 0.0 || s.offset != 0.0) {
      out(k) = s.stiffness * q_(qIndexOfV(k)) + s.damping * v_(k) + s.offset;
    }
  }
}

void Entity::update() noexcept {
  computeDynamics();
  springTorque(spring_work_);
  N_ += spring_work_;
}

void Entity::integrate(const Eigen::Ref<const Eigen::VectorXd>& a, double dt) noexcept {
  v_.noalias() += dt * a;
  integrateConfiguration(dt);
}

}  // namespace mrqp::problem
