// Frame position / orientation / pose tasks, eq. 25–26: rows and error; see frame_task.hpp.
#include "problem/tasks/frame_task.hpp"

#include <Eigen/Geometry>

#include "problem/multi_robot_problem.hpp"

namespace mrqp::problem {

namespace {

/// Rotation vector of R (log map), allocation-free.
Eigen::Vector3d rotationVector(const Eigen::Matrix3d& R) noexcept {
  const Eigen::AngleAxisd aa(R);
  return aa.angle() * aa.axis();
}

}  // namespace

FrameTask::FrameTask(Rows rows, int entity, int frame, const Eigen::Vector3d& point,
                     const Eigen::Vector3d& target, const Eigen::Matrix3d& target_rotation)
    : Task(rows == Rows::Both ? 6 : 3),
      rows_(rows),
      entity_(entity),
      frame_(frame),
      point_(point),
      target_(target),
      target_R_(target_rotation) {}

const char* FrameTask::check(const MultiRobotProblem& p) const noexcept {
  if (entity_ < 0 || entity_ >= p.entityCount()) return "a task names an entity that does not exist";
  if (frame_ < 0 || frame_ >= p.entity(entity_).frameCount())
    return "a frame task names a frame that does not exist";
  if (!point_.allFinite() || !target_.allFinite() || !target_R_.allFinite())
    return "a frame task's point or target is not finite";
  return nullptr;
}

bool FrameTask::setTarget(const Eigen::Vector3d& target) noexcept {
  if (rows_ == Rows::Angular || !target.allFinite()) return false;
  target_ = target;
  return true;
}

bool FrameTask::setTargetRotation(const Eigen::Matrix3d& R) noexcept {
  if (rows_ == Rows::Linear || !R.allFinite()) return false;
  target_R_ = R;
  return true;
}

bool FrameTask::update(const MultiRobotProblem& p, TaskRows& out) noexcept {
  const Entity& e = p.entity(entity_);
  const int o = p.velocityOffset(entity_), nv = e.nv();
  auto J = p.jacobianWork().leftCols(nv);
  e.frameJacobian(frame_, point_, J);
  const Vector6d bias = e.frameBiasAcceleration(frame_, point_);
  const Vector6d vel = J * e.v();
  const Pose P = e.framePose(frame_);
  Vector6d err;
  err.head<3>() = rotationVector(P.R * target_R_.transpose());
  err.tail<3>() = P.R * point_ + P.p - target_;
  const double K = stiffness(), D = dampingUsed();
  int r0 = 0, rows = 6;
  if (rows_ == Rows::Linear) {
    r0 = 3;
    rows = 3;
  } else if (rows_ == Rows::Angular) {
    rows = 3;
  }
  const auto& vref = velocityReference();
  const auto& aref = accelerationReference();
  for (int r = 0; r < rows; ++r) {
    const int k = r0 + r;
    out.t(r) = aref(r) - K * err(k) - D * (vel(k) - vref(r)) - bias(k);
  }
  out.T.block(0, o, rows, nv) = J.middleRows(r0, rows);
  error_.setZero();
  error_.head(rows) = err.segment(r0, rows);
  out.rows = rows;
  out.col0 = o;
  out.cols = nv;
  return true;
}

}  // namespace mrqp::problem
