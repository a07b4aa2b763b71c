// comanipulation through the controller loop on the MuJoCo plant of its `plant:` section
// (simulated buses, emulated drives, F/T sensors and IMU; docs/mujoco.md, "The shipped scenes on
// MuJoCo"): JVRC-1 and the Panda (both `state: commanded`, the Panda's hand holding the box's
// front face as a point) bring the box to the target of its task in the scene's duration
// (box_at_target.hpp: the true box against the task's target, the controller's box and base
// against the plant's).
#include <catch2/catch.hpp>

#include "box_at_target.hpp"
#include "sim_loop.hpp"

using mrqp::sim::testing::checkBoxReachesTarget;
using mrqp::sim::testing::shippedScene;
using mrqp::sim::testing::SimLoop;

TEST_CASE("MuJoCo loop: comanipulation runs to its end and brings the true box to its target",
          "[sim][loop]") {
  SimLoop s(shippedScene("comanipulation.yaml"), "comanipulation.yaml");
  REQUIRE(s.boot());
  checkBoxReachesTarget(s);
}
