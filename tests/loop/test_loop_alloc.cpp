// The controller's cycle allocates nothing: 10,000 cycles of the loop with the CAN drivers on the
// simulated buses and the plant behind them, counted by the replaced global allocator (which also
// sees Eigen's heap: Eigen allocates through malloc), with Eigen's run-time check armed in the
// loop's own sources compiled here with EIGEN_RUNTIME_NO_MALLOC.
#include <catch2/catch.hpp>

#include "counting_allocator.hpp"
#include "loop_setup.hpp"

using looptest::LoopSetup;

TEST_CASE("loop: 10,000 loop cycles over CAN with the plant allocate nothing", "[loop][realtime]") {
  for (const char* name : {"panda_door.yaml", "jvrc1_box.yaml"}) {
    INFO(name);
    LoopSetup s(looptest::sceneText(name), name);
    mrqp::loop::LogRing ring;
    s.ctrl->attachLog(ring);
    ring.freeze(16);  // full after 16 rows: the dropping path runs too
    REQUIRE(s.boot());
    for (int k = 0; k < 10; ++k) s.cycle();  // warm-up: first solves
    long in_cycle = 0;
    for (int k = 0; k < 10000; ++k) {
      in_cycle += mrqp::testing::allocationsIn([&] { s.ctrl->cycle(s.now); });
      s.plant->setFollowing(!s.ctrl->safeStopped());
      s.rig->advanceTo(s.now + s.period);
      s.now += s.period;
    }
    CHECK_FALSE(s.ctrl->safeStopped());
    CHECK(in_cycle == 0);
    // The counter counts: a self-check.
    CHECK(mrqp::testing::allocationsIn([] { delete new volatile int(3); }) >= 1);
  }
}
