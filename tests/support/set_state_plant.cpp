// A plant whose entity states are set by hand (see set_state_plant.hpp).
#include "set_state_plant.hpp"

namespace mrqp::testing {

SetStatePlant::SetStatePlant(const problem::MultiRobotProblem& p) {
  for (int i = 0; i < p.entityCount(); ++i) add(p.entity(i).name(), p.entity(i).q(), p.entity(i).nv());
}

int SetStatePlant::add(const std::string& name, const Eigen::VectorXd& q) {
  return add(name, q, 0);  // v reads zero whatever size the caller asks for
}

int SetStatePlant::add(const std::string& name, const Eigen::VectorXd& q, Eigen::Index nv) {
  names_.push_back(name);
  q_.push_back(q);
  v_.push_back(Eigen::VectorXd::Zero(nv));
  return static_cast<int>(names_.size()) - 1;
}

void SetStatePlant::place(int entity, const Eigen::Vector3d& position,
                          const Eigen::Quaterniond& orientation) {
  Eigen::VectorXd& x = q(entity);
  x.head<3>() = position;
  x(3) = orientation.w();
  x(4) = orientation.x();
  x(5) = orientation.y();
  x(6) = orientation.z();
}

int SetStatePlant::entityHandle(const std::string& entity) const {
  for (std::size_t i = 0; i < names_.size(); ++i) {
    if (names_[i] == entity) return static_cast<int>(i);
  }
  return -1;
}

void SetStatePlant::entityState(int entity, Eigen::Ref<Eigen::VectorXd> q,
                                Eigen::Ref<Eigen::VectorXd> v) const noexcept {
  const auto e = static_cast<std::size_t>(entity);
  q = q_[e];
  if (v.size() == v_[e].size()) {
    v = v_[e];
  } else {
    v.setZero();
  }
}

}  // namespace mrqp::testing
