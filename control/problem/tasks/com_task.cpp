// CoM task (one entity or a group), eq. 25–26: rows and error; see com_task.hpp.
#include "problem/tasks/com_task.hpp"

#include <algorithm>

#include "problem/multi_robot_problem.hpp"

namespace mrqp::problem {

ComTask::ComTask(std::uint32_t entity_mask, const Eigen::Vector3d& target)
    : Task(3), mask_(entity_mask), target_(target) {}

const char* ComTask::check(const MultiRobotProblem& p) const noexcept {
  const int n = p.entityCount();
  if (mask_ == 0 || (n < 32 && (mask_ >> n) != 0)) {
    return "a CoM task needs a non-empty set of existing entities";
  }
  return nullptr;
}

bool ComTask::setTarget(const Eigen::Vector3d& target) noexcept {
  if (!target.allFinite()) return false;
  target_ = target;
  return true;
}

bool ComTask::update(const MultiRobotProblem& p, TaskRows& out) noexcept {
  int c0 = p.qp().n(), c1 = 0;
  double mtot = 0.0;
  for (int i = 0; i < p.entityCount(); ++i) {
    if (!involves(i)) continue;
    mtot += p.entity(i).mass();
    c0 = std::min(c0, p.velocityOffset(i));
    c1 = std::max(c1, p.velocityOffset(i) + p.entity(i).nv());
  }
  error_.setZero();
  if (mtot <= 0.0) return false;
  Eigen::Vector3d c = Eigen::Vector3d::Zero(), cdot = Eigen::Vector3d::Zero(), bias = Eigen::Vector3d::Zero();
  out.T.block(0, c0, 3, c1 - c0).setZero();
  for (int i = 0; i < p.entityCount(); ++i) {
    if (!involves(i)) continue;
    const Entity& e = p.entity(i);
    const double f = e.mass() / mtot;
    out.T.block(0, p.velocityOffset(i), 3, e.nv()) = f * e.comJacobian();
    c += f * e.com();
    Eigen::Vector3d cv;
    cv.noalias() = e.comJacobian() * e.v();
    cdot += f * cv;
    bias += f * e.comBias();
  }
  const double K = stiffness(), D = dampingUsed();
  error_.head<3>() = c - target_;
  out.t.head<3>() = accelerationReference() - K * (c - target_) - D * (cdot - velocityReference()) - bias;
  out.rows = 3;
  out.col0 = c0;
  out.cols = c1 - c0;
  return true;
}

}  // namespace mrqp::problem
