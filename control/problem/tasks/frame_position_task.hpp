// Frame position task: a point of a frame to a world position; rows linear (x, y, z), as described in problem/tasks/frame_task.hpp (eq. 25–26).
#pragma once

#include "problem/tasks/frame_task.hpp"

namespace mrqp::problem {

class FramePositionTask final : public FrameTask {
 public:
  /// `point`: the controlled point in frame coordinates; targets in world coordinates.
  FramePositionTask(int entity, int frame, const Eigen::Vector3d& point, const Eigen::Vector3d& target,
                    const Eigen::Matrix3d& target_rotation = Eigen::Matrix3d::Identity())
      : FrameTask(Rows::Linear, entity, frame, point, target, target_rotation) {}

  const char* kind() const noexcept override { return "frame_position"; }
};

}  // namespace mrqp::problem
