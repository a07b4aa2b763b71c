// The estimator on the controller's cycle allocates nothing: 10,000 cycles of the loop over CAN
// with the door_estimate scene (the handle turned by its timeline, the F/T sensor reading the
// holding wrench, the estimate fed back into the QP's model), counted by the replaced global
// allocator, with Eigen's run-time check armed in the estimation's and the loop's own sources
// compiled here with EIGEN_RUNTIME_NO_MALLOC.
#include <catch2/catch.hpp>

#include "counting_allocator.hpp"
#include "estimation_loop_setup.hpp"
#include "loop_cycle_allocations.hpp"

TEST_CASE("estimation: 10,000 loop cycles with the estimator allocate nothing", "[estimation][realtime]") {
  esttest::EstimationSetup s(esttest::sceneText("door_estimate.yaml"), "door_estimate.yaml", 0.2, 0.01);
  REQUIRE(s.boot());
  const long in_cycle = mrqp::testing::loopCycleAllocations(s, 10000);  // after 10 warm-up cycles
  CHECK_FALSE(s.ctrl->safeStopped());
  CHECK(s.hook->updates(0) > 2000);  // the filter ran (settled after 0.5 s, 250 Hz)
  CHECK(in_cycle == 0);
  // The counter counts: a self-check.
  CHECK(mrqp::testing::allocationsIn([] { delete new volatile int(3); }) >= 1);
}
