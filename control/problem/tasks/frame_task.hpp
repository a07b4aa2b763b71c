// The frame tasks' common part: a point p of a frame (frame coordinates) and the frame's
// orientation R, against a world target (pʳᵉᶠ, Rʳᵉᶠ). With J the frame Jacobian at p (rows
// angular; linear) and the error e = (log(R Rʳᵉᶠᵀ); R p + o − pʳᵉᶠ), the rows are
//
//   J q̈ = g̈ʳᵉᶠ − K e − D (J q̇ − ġʳᵉᶠ) − J̇ q̇                           (eq. 25–26)
//
// restricted to the angular rows (FrameOrientationTask), the linear rows (FramePositionTask) or
// all six (FramePoseTask). ġʳᵉᶠ and g̈ʳᵉᶠ are given in the same rows (world axes).
#pragma once

#include "problem/task.hpp"

namespace mrqp::problem {

class FrameTask : public Task {
 public:
  enum class Rows { Angular, Linear, Both };

  const char* check(const MultiRobotProblem& p) const noexcept override;
  bool update(const MultiRobotProblem& p, TaskRows& rows) noexcept override;
  bool setTarget(const Eigen::Vector3d& target) noexcept override;
  bool setTargetRotation(const Eigen::Matrix3d& R) noexcept override;

  int entity() const noexcept { return entity_; }
  int frame() const noexcept { return frame_; }
  const Eigen::Vector3d& point() const noexcept { return point_; }
  const Eigen::Vector3d& target() const noexcept { return target_; }
  const Eigen::Matrix3d& targetRotation() const noexcept { return target_R_; }

 protected:
  FrameTask(Rows rows, int entity, int frame, const Eigen::Vector3d& point, const Eigen::Vector3d& target,
            const Eigen::Matrix3d& target_rotation);

 private:
  Rows rows_;
  int entity_, frame_;
  Eigen::Vector3d point_, target_;
  Eigen::Matrix3d target_R_;
};

}  // namespace mrqp::problem
