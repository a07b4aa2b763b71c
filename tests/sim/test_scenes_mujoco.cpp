// The shipped scenes through the controller loop on the MuJoCo plant of their `plant:` sections
// (simulated buses, emulated drives, F/T sensors and IMU; docs/mujoco.md, "The shipped scenes").
// Ground truth is the plant's, never the controller's: panda_door opens its door toward the
// target (true hinge angle against the target); jvrc1_box and comanipulation start where the
// controller thinks they are (floating base and box, estimate against the plant, after boot);
// jvrc1_box (JVRC-1 with `state: commanded`) runs to its end and brings the true box to the
// target of its task.
#include <catch2/catch.hpp>

#include <cmath>

#include "box_at_target.hpp"
#include "sim_loop.hpp"

using mrqp::sim::testing::checkBoxReachesTarget;
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

TEST_CASE("MuJoCo loop: jvrc1_box runs to its end and brings the box to its target", "[sim][loop]") {
  SimLoop s(shippedScene("jvrc1_box.yaml"), "jvrc1_box.yaml");
  REQUIRE(s.hw.robots.at(0).state == mrqp::loop::JointState::Commanded);
  REQUIRE(s.boot());
  checkBoxReachesTarget(s);
}
