// The shipped scenes through the controller loop on the MuJoCo plant of their `plant:` sections
// (simulated buses, emulated drives, F/T sensors and IMU; docs/mujoco.md, "The shipped scenes").
// Ground truth is the plant's, never the controller's: panda_door opens its door toward the
// target (true hinge angle against the target); jvrc1_box and comanipulation start where the
// controller thinks they are (floating base and box, estimate against the plant, after boot);
// jvrc1_box (JVRC-1 with `state: commanded`) runs to its end and brings the true box to the
// target of its task.
#include <catch2/catch.hpp>

#include <cmath>

#include "sim_loop.hpp"

using mrqp::sim::testing::shippedScene;
using mrqp::sim::testing::SimLoop;

TEST_CASE("MuJoCo loop: panda_door opens the door toward its target", "[sim][loop]") {
  SimLoop s(shippedScene("panda_door.yaml"), "panda_door.yaml");
  REQUIRE(s.plant_spec.simulator == "mujoco");
  REQUIRE(s.boot());
  const long cycles = std::lround(s.sc.settings.duration / s.sc.settings.dt);
  const long ran = s.run(cycles);
  INFO("safe stop: " << mrqp::loop::stopReasonStr(s.ctrl->stopReason()) << " " << s.ctrl->stopDevice());
  REQUIRE(ran == cycles);
  CHECK(s.plant->warnings() == 0);
  const Eigen::VectorXd door = s.trueQ("door");
  const double target = -0.25;
  INFO("true door angle " << door(0) << ", handle " << door(1) << ", task error "
                          << s.taskError("door_angle"));
  // The ideal plant ends 0.002 rad from the target after these 4 s; the position-controlled arm
  // welded to the handle follows about half as fast here (see docs/mujoco.md): within 0.05 rad,
  // and at least 80 % of the way.
  CHECK(std::abs(door(0) - target) < 0.05);
  // The controller's estimate of the door (from the gripper's kinematics) is the plant's.
  const auto& est = s.sc.problem->entity(s.sc.problem->entityIndex("door")).q();
  CHECK(std::abs(est(0) - door(0)) < 2e-3);
  CHECK(std::abs(est(1) - door(1)) < 2e-3);
}

namespace {

void checkStartsConsistent(const char* file) {
  SimLoop s(shippedScene(file), file);  // the MuJoCo plant of its plant section
  REQUIRE(s.boot());
  s.run(10);
  REQUIRE_FALSE(s.ctrl->safeStopped());
  auto& p = *s.sc.problem;
  const Eigen::VectorXd jvrc = s.trueQ("jvrc");
  const Eigen::VectorXd box = s.trueQ("box");
  const auto& jvrc_est = p.entity(p.entityIndex("jvrc")).q();
  const auto& box_est = p.entity(p.entityIndex("box")).q();
  INFO(file << ": base true " << jvrc.head<3>().transpose() << ", estimated "
            << jvrc_est.head<3>().transpose());
  INFO("box true " << box.head<3>().transpose() << ", estimated " << box_est.head<3>().transpose());
  // Settled on soles that are the scene's contact surfaces, with drives that carry their load:
  // the base and the box are where the scene put them and where the controller estimates them.
  CHECK((jvrc.head<3>() - jvrc_est.head<3>()).norm() < 3e-3);
  CHECK((box.head<3>() - box_est.head<3>()).norm() < 3e-3);
  CHECK((jvrc.head<3>() - Eigen::Vector3d(0, 0, 0.8186)).norm() < 3e-3);
  CHECK(s.plant->warnings() == 0);
}

}  // namespace

TEST_CASE("MuJoCo loop: jvrc1_box starts where the controller thinks it is", "[sim][loop]") {
  checkStartsConsistent("jvrc1_box.yaml");
}

TEST_CASE("MuJoCo loop: comanipulation starts where the controller thinks it is", "[sim][loop]") {
  checkStartsConsistent("comanipulation.yaml");
}

namespace {

/// The world rotation of a scene's roll-pitch-yaw (R = Rz(yaw) Ry(pitch) Rx(roll)).
Eigen::Matrix3d rpyRotation(double roll, double pitch, double yaw) {
  return (Eigen::AngleAxisd(yaw, Eigen::Vector3d::UnitZ()) *
          Eigen::AngleAxisd(pitch, Eigen::Vector3d::UnitY()) *
          Eigen::AngleAxisd(roll, Eigen::Vector3d::UnitX()))
      .toRotationMatrix();
}

}  // namespace

TEST_CASE("MuJoCo loop: jvrc1_box runs to its end and brings the box to its target", "[sim][loop]") {
  SimLoop s(shippedScene("jvrc1_box.yaml"), "jvrc1_box.yaml");
  REQUIRE(s.hw.robots.at(0).state == mrqp::loop::JointState::Commanded);
  REQUIRE(s.boot());
  const long cycles = std::lround(s.sc.settings.duration / s.sc.settings.dt);
  const long ran = s.run(cycles);
  INFO("safe stop: " << mrqp::loop::stopReasonStr(s.ctrl->stopReason()) << " " << s.ctrl->stopDevice()
                     << " at cycle " << s.ctrl->stopCycle());
  REQUIRE(ran == cycles);
  CHECK(s.plant->warnings() == 0);
  // The target of the box's task, from the scene (xyz + rpy), against the plant's true box.
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
  // The ideal plant ends 0.006 from the target after these 3 s (docs/mujoco.md); here the true
  // box, held by welds of finite stiffness and moved by servos that lag a robot cycle, within
  // 3 mm and 5 mrad.
  CHECK(position_error < 3e-3);
  CHECK(rotation_error < 5e-3);
  // The controller's box (from the commanded kinematics of the hands) and base (IMU and feet)
  // are the plant's within 3 mm.
  auto& p = *s.sc.problem;
  const Eigen::VectorXd box_q = s.trueQ("box");
  const Eigen::VectorXd jvrc_q = s.trueQ("jvrc");
  CHECK((p.entity(p.entityIndex("box")).q().head<3>() - box_q.head<3>()).norm() < 3e-3);
  CHECK((p.entity(p.entityIndex("jvrc")).q().head<3>() - jvrc_q.head<3>()).norm() < 3e-3);
}
