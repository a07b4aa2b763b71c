// Posture task: every joint of one entity (not its floating base) to a reference configuration.
// Identity rows over the entity's joint accelerations, one per joint k:
//
//   q̈_k = q̈ʳᵉᶠ_k − K (q_k − qʳᵉᶠ_k) − D (q̇_k − q̇ʳᵉᶠ_k)          (eq. 26, T = I, J̇q̇ = 0)
//
// Without a target set, it takes the entity's joint positions when first added to a problem. Its
// error() stays zero (the error has one row per joint; read it from the entity).
#pragma once

#include "problem/task.hpp"

namespace mrqp::problem {

class PostureTask final : public Task {
 public:
  /// `joints`: nv − jointOffset() of the entity (the size of the target and the references).
  PostureTask(int entity, int joints);

  const char* kind() const noexcept override { return "posture"; }
  const char* check(const MultiRobotProblem& p) const noexcept override;
  void attach(const MultiRobotProblem& p) noexcept override;
  bool update(const MultiRobotProblem& p, TaskRows& rows) noexcept override;
  bool setTargetVector(const Eigen::Ref<const Eigen::VectorXd>& q_joints) noexcept override;

  int entity() const noexcept { return entity_; }
  const Eigen::VectorXd& target() const noexcept { return target_; }

 private:
  int entity_;
  bool target_set_ = false;
  Eigen::VectorXd target_;  // joint positions, jointOffset() .. nv − 1 of the entity
};

}  // namespace mrqp::problem
