// Force minimisation task: identity rows over the λ of one or every contact; see force_min_task.hpp.
#include "problem/tasks/force_min_task.hpp"

#include "problem/multi_robot_problem.hpp"

namespace mrqp::problem {

ForceMinTask::ForceMinTask(int contact) : Task(0), contact_(contact) {}

const char* ForceMinTask::check(const MultiRobotProblem& p) const noexcept {
  if (contact_ >= p.contactCapacity()) return "a force task names a contact that does not exist";
  return nullptr;
}

bool ForceMinTask::update(const MultiRobotProblem& p, TaskRows& out) noexcept {
  // The λ of the active contacts are contiguous, from totalVelocities(), in slot order.
  if (contact_ >= 0) {
    if (!p.contactActive(contact_)) return false;
    out.col0 = p.lambdaOffset(contact_);
    out.rows = p.contact(contact_).variables();
  } else {
    out.col0 = p.totalVelocities();
    out.rows = p.lambdaCount();
  }
  if (out.rows == 0) return false;
  out.t.head(out.rows).setZero();
  out.identity = true;
  out.cols = out.rows;
  return true;
}

}  // namespace mrqp::problem
