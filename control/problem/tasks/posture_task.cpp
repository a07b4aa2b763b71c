// Posture task, eq. 26: identity rows over one entity's joints; see posture_task.hpp.
#include "problem/tasks/posture_task.hpp"

#include "problem/multi_robot_problem.hpp"

namespace mrqp::problem {

PostureTask::PostureTask(int entity, int joints)
    : Task(joints), entity_(entity), target_(Eigen::VectorXd::Zero(joints)) {}

const char* PostureTask::check(const MultiRobotProblem& p) const noexcept {
  if (entity_ < 0 || entity_ >= p.entityCount()) return "a task names an entity that does not exist";
  const Entity& e = p.entity(entity_);
  if (target_.size() != e.nv() - e.jointOffset())
    return "a posture task's size is not its entity's joint count";
  return nullptr;
}

void PostureTask::attach(const MultiRobotProblem& p) noexcept {
  if (target_set_) return;
  const Entity& e = p.entity(entity_);
  for (int k = e.jointOffset(); k < e.nv(); ++k) target_(k - e.jointOffset()) = e.q()(e.qIndexOfV(k));
  target_set_ = true;  // kept when the task is released and added again
}

bool PostureTask::setTargetVector(const Eigen::Ref<const Eigen::VectorXd>& q_joints) noexcept {
  if (q_joints.size() != target_.size() || !q_joints.allFinite()) return false;
  target_ = q_joints;
  target_set_ = true;
  return true;
}

bool PostureTask::update(const MultiRobotProblem& p, TaskRows& out) noexcept {
  const Entity& e = p.entity(entity_);
  const double K = stiffness(), D = dampingUsed();
  const int j0 = e.jointOffset();
  const auto& vref = velocityReference();
  const auto& aref = accelerationReference();
  for (int k = j0; k < e.nv(); ++k) {
    const int r = k - j0;
    const double err = e.q()(e.qIndexOfV(k)) - target_(r);
    out.t(r) = aref(r) - K * err - D * (e.v()(k) - vref(r));
  }
  out.identity = true;
  out.rows = e.nv() - j0;
  out.col0 = p.velocityOffset(entity_) + j0;
  out.cols = out.rows;
  return true;
}

}  // namespace mrqp::problem
