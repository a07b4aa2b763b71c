// One check shared by the MuJoCo tests of the scenes that carry a box to a target
// (jvrc1_box, comanipulation): the scene runs its whole duration through the controller loop
// without a safe stop or a MuJoCo warning, the plant's true box ends within 3 mm and 5 mrad of the
// target of the `box_pose` task (read from the scene), and the controller's box and floating base
// are the plant's within 3 mm. Ground truth is the plant's, never the controller's. The
// tolerances: servo lag of a robot cycle, welds and point grasps of finite stiffness, soft feet
// (docs/mujoco.md; the ideal plant ends within 0.5–6 mm of these targets after the same time).
#pragma once

#include <catch2/catch.hpp>

#include <cmath>

#include "sim_loop.hpp"

namespace mrqp::sim::testing {

/// The world rotation of a scene's roll-pitch-yaw (R = Rz(yaw) Ry(pitch) Rx(roll)).
inline Eigen::Matrix3d rpyRotation(double roll, double pitch, double yaw) {
  return (Eigen::AngleAxisd(yaw, Eigen::Vector3d::UnitZ()) *
          Eigen::AngleAxisd(pitch, Eigen::Vector3d::UnitY()) *
          Eigen::AngleAxisd(roll, Eigen::Vector3d::UnitX()))
      .toRotationMatrix();
}

/// Runs the booted loop `s` for its scene's duration and checks the box against its target.
inline void checkBoxReachesTarget(SimLoop& s) {
  const long cycles = std::lround(s.sc.settings.duration / s.sc.settings.dt);
  const long ran = s.run(cycles);
  INFO("safe stop: " << mrqp::loop::stopReasonStr(s.ctrl->stopReason()) << " " << s.ctrl->stopDevice()
                     << " at cycle " << s.ctrl->stopCycle());
  REQUIRE(ran == cycles);
  CHECK(s.plant->warnings() == 0);
  const mrqp::scene::TaskSpec* task = nullptr;
  for (const auto& t : s.spec.tasks) {
    if (t.name == "box_pose") task = &t;
  }
  REQUIRE(task != nullptr);
  REQUIRE(task->target.has_value());
  const Eigen::VectorXd& target = *task->target;
  const Eigen::Isometry3d box = s.truePose("box", "box");
  const double position_error = (box.translation() - target.head<3>()).norm();
  const double rotation_error =
      Eigen::AngleAxisd(
          Eigen::Matrix3d(box.linear() * rpyRotation(target(3), target(4), target(5)).transpose()))
          .angle();
  INFO("true box " << box.translation().transpose() << ", position error " << position_error
                   << " m, rotation error " << rotation_error << " rad; controller's task error "
                   << s.taskError("box_pose"));
  CHECK(position_error < 3e-3);
  CHECK(rotation_error < 5e-3);
  // The controller's box (from the kinematics of the hands) and base (IMU and feet).
  auto& p = *s.sc.problem;
  const Eigen::VectorXd box_q = s.trueQ("box");
  const Eigen::VectorXd jvrc_q = s.trueQ("jvrc");
  CHECK((p.entity(p.entityIndex("box")).q().head<3>() - box_q.head<3>()).norm() < 3e-3);
  CHECK((p.entity(p.entityIndex("jvrc")).q().head<3>() - jvrc_q.head<3>()).norm() < 3e-3);
}

}  // namespace mrqp::sim::testing
