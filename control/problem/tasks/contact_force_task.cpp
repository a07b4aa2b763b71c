// Contact force task (Sec. III): W_f λ = fʳᵉᶠ over one contact's λ; see contact_force_task.hpp.
#include "problem/tasks/contact_force_task.hpp"

#include "problem/multi_robot_problem.hpp"

namespace mrqp::problem {

ContactForceTask::ContactForceTask(int contact, const Eigen::Vector3d& target)
    : Task(3), contact_(contact), target_(target) {}

const char* ContactForceTask::check(const MultiRobotProblem& p) const noexcept {
  if (!p.contactActive(contact_)) return "a force task needs an existing contact";
  return nullptr;
}

bool ContactForceTask::setTarget(const Eigen::Vector3d& target) noexcept {
  if (!target.allFinite()) return false;
  target_ = target;
  return true;
}

bool ContactForceTask::update(const MultiRobotProblem& p, TaskRows& out) noexcept {
  error_.setZero();
  if (!p.contactActive(contact_)) return false;
  const int ng = p.contact(contact_).variables();
  const int c0 = p.lambdaOffset(contact_);
  out.T.block(0, c0, 3, ng) = p.contactWrenchBasis(contact_).block(3, 0, 3, ng);
  out.t.head<3>() = target_;
  error_.head<3>() = p.contactForce(contact_) - target_;
  out.rows = 3;
  out.col0 = c0;
  out.cols = ng;
  return true;
}

}  // namespace mrqp::problem
