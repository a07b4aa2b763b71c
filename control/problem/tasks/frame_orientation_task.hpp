// Frame orientation task: a frame's orientation to a world orientation; rows angular (world axes), as described in problem/tasks/frame_task.hpp (eq. 25–26).
#pragma once

#include "problem/tasks/frame_task.hpp"

namespace mrqp::problem {

class FrameOrientationTask final : public FrameTask {
 public:
  /// `point`: the controlled point in frame coordinates; targets in world coordinates.
  FrameOrientationTask(int entity, int frame, const Eigen::Vector3d& point, const Eigen::Vector3d& target,
                       const Eigen::Matrix3d& target_rotation = Eigen::Matrix3d::Identity())
      : FrameTask(Rows::Angular, entity, frame, point, target, target_rotation) {}

  const char* kind() const noexcept override { return "frame_orientation"; }
};

}  // namespace mrqp::problem
