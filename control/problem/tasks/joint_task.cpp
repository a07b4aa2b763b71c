// Joint task, eq. 26: one identity row on one joint; see joint_task.hpp.
#include "problem/tasks/joint_task.hpp"

#include <cmath>

#include "problem/multi_robot_problem.hpp"

namespace mrqp::problem {

JointTask::JointTask(int entity, int joint, double target)
    : Task(1), entity_(entity), joint_(joint), target_(target) {}

const char* JointTask::check(const MultiRobotProblem& p) const noexcept {
  if (entity_ < 0 || entity_ >= p.entityCount()) return "a task names an entity that does not exist";
  const Entity& e = p.entity(entity_);
  if (joint_ < e.jointOffset() || joint_ >= e.nv()) return "a joint task names a joint that does not exist";
  return nullptr;
}

bool JointTask::setTarget(const Eigen::Vector3d& target) noexcept {
  if (!std::isfinite(target.x())) return false;
  target_ = target.x();
  return true;
}

bool JointTask::setTargetVector(const Eigen::Ref<const Eigen::VectorXd>& target) noexcept {
  if (target.size() != 1 || !std::isfinite(target(0))) return false;
  target_ = target(0);
  return true;
}

bool JointTask::update(const MultiRobotProblem& p, TaskRows& out) noexcept {
  const Entity& e = p.entity(entity_);
  const double err = e.q()(e.qIndexOfV(joint_)) - target_;
  error_.setZero();
  error_(0) = err;
  out.t(0) = accelerationReference()(0) - stiffness() * err -
             dampingUsed() * (e.v()(joint_) - velocityReference()(0));
  out.identity = true;
  out.rows = 1;
  out.col0 = p.velocityOffset(entity_) + joint_;
  out.cols = 1;
  return true;
}

}  // namespace mrqp::problem
