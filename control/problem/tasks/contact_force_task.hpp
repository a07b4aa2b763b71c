// Contact force task (the QP force task of Sec. III): the resultant force f = W_f λ of one contact
// (on its surface entity, world axes; W_f the force rows of the contact's wrench basis) to a
// target. Three rows over the contact's λ:
//
//   W_f λ = fʳᵉᶠ
//
// The target is the position reference; the gains and the velocity and acceleration references
// do not enter (the admittance of Sec. III turns a force error into a kinematic reference).
#pragma once

#include "problem/task.hpp"

namespace mrqp::problem {

class ContactForceTask final : public Task {
 public:
  ContactForceTask(int contact, const Eigen::Vector3d& target);

  const char* kind() const noexcept override { return "force"; }
  const char* check(const MultiRobotProblem& p) const noexcept override;
  bool update(const MultiRobotProblem& p, TaskRows& rows) noexcept override;
  bool setTarget(const Eigen::Vector3d& target) noexcept override;

  int contact() const noexcept { return contact_; }
  const Eigen::Vector3d& target() const noexcept { return target_; }

 private:
  int contact_;
  Eigen::Vector3d target_;
};

}  // namespace mrqp::problem
