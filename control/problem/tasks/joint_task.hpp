// Joint task: one joint of an entity to a value (e.g. a door angle). One identity row:
//
//   q̈_j = q̈ʳᵉᶠ − K (q_j − qʳᵉᶠ) − D (q̇_j − q̇ʳᵉᶠ)                    (eq. 26)
//
// The target is target.x() of setTarget (or setTargetVector of size 1).
#pragma once

#include "problem/task.hpp"

namespace mrqp::problem {

class JointTask final : public Task {
 public:
  /// `joint`: velocity index within the entity (≥ jointOffset()).
  JointTask(int entity, int joint, double target);

  const char* kind() const noexcept override { return "joint"; }
  const char* check(const MultiRobotProblem& p) const noexcept override;
  bool update(const MultiRobotProblem& p, TaskRows& rows) noexcept override;
  bool setTarget(const Eigen::Vector3d& target) noexcept override;
  bool setTargetVector(const Eigen::Ref<const Eigen::VectorXd>& target) noexcept override;

  int entity() const noexcept { return entity_; }
  int joint() const noexcept { return joint_; }
  double target() const noexcept { return target_; }

 private:
  int entity_, joint_;
  double target_;
};

}  // namespace mrqp::problem
