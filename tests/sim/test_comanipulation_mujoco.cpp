// comanipulation through the controller loop on the MuJoCo plant of its `plant:` section
// (simulated buses, emulated drives, F/T sensors and IMU; docs/mujoco.md, "The shipped scenes on
// MuJoCo"): JVRC-1 and the Panda (both `state: commanded`, the Panda's hand holding the box's
// front face as a point) bring the box to the target of its task in the scene's duration. Ground truth is the
// plant's, never the controller's: the true box against the task's target (read from the scene),
// and the controller's box and base against the plant's.
#include <catch2/catch.hpp>

#include <cmath>

#include "sim_loop.hpp"

using mrqp::sim::testing::shippedScene;
using mrqp::sim::testing::SimLoop;

namespace {

/// The world rotation of a scene's roll-pitch-yaw (R = Rz(yaw) Ry(pitch) Rx(roll)).
Eigen::Matrix3d rpyRotation(double roll, double pitch, double yaw) {
  return (Eigen::AngleAxisd(yaw, Eigen::Vector3d::UnitZ()) *
          Eigen::AngleAxisd(pitch, Eigen::Vector3d::UnitY()) *
          Eigen::AngleAxisd(roll, Eigen::Vector3d::UnitX()))
      .toRotationMatrix();
}

}  // namespace

TEST_CASE("MuJoCo loop: comanipulation runs to its end and brings the true box to its target", "[sim][loop]") {
  SimLoop s(shippedScene("comanipulation.yaml"), "comanipulation.yaml");
  REQUIRE(s.boot());
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
                   << " m, rotation error " << rotation_error
                   << " rad; controller's task error " << s.taskError("box_pose"));
  // Tolerances as jvrc1_box's on MuJoCo (3 mm, 5 mrad): servo lag, welds and a point grasp of
  // finite stiffness, soft feet; the ideal plant ends 0.5 mm from the target after 3 s.
  CHECK(position_error < 3e-3);
  CHECK(rotation_error < 5e-3);
  auto& p = *s.sc.problem;
  const Eigen::VectorXd box_q = s.trueQ("box");
  const Eigen::VectorXd jvrc_q = s.trueQ("jvrc");
  CHECK((p.entity(p.entityIndex("box")).q().head<3>() - box_q.head<3>()).norm() < 3e-3);
  CHECK((p.entity(p.entityIndex("jvrc")).q().head<3>() - jvrc_q.head<3>()).norm() < 3e-3);
}
