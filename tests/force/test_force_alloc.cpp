// The admittance on the controller's cycle allocates nothing: 10,000 cycles of the loop over CAN
// with the plant (the F/T sensor reading a virtual wall), mode and force changes from the
// timeline, counted by the replaced global allocator, with Eigen's run-time check armed in the
// force library's and the loop's own sources compiled here with EIGEN_RUNTIME_NO_MALLOC.
#include <catch2/catch.hpp>

#include "counting_allocator.hpp"
#include "force_setup.hpp"
#include "loop_cycle_allocations.hpp"

TEST_CASE("force: 10,000 loop cycles with the admittance allocate nothing", "[force][realtime]") {
  std::string text = forcetest::dataText("panda_press.yaml");
  text = forcetest::replaced(text, "active: false", "active: true\n    free: [normal]");
  text = forcetest::replaced(text, "    mode: direct\n", "    mode: qp\n    force_task: press_force\n");
  text +=
      "timeline:\n"
      "  - {at: 2.0, force_control: tool, mode: autonomous}\n"
      "  - {at: 4.0, force_control: tool, mode: guided, force: 8}\n"
      "  - {at: 6.0, force_control: tool, mode: direct}\n"
      "  - {at: 8.0, force_control: tool, mode: off}\n"
      "  - {at: 9.0, force_control: tool, mode: qp, force: 5}\n";
  forcetest::ForceSetup s(text, "p.yaml");
  REQUIRE(s.boot());
  const long in_cycle = mrqp::testing::loopCycleAllocations(s, 10000);  // after 10 warm-up cycles
  CHECK_FALSE(s.ctrl->safeStopped());
  CHECK(s.hook->eventsPlayed() == 5);
  CHECK(s.hook->state(0).mode == mrqp::force::ForceMode::Qp);
  CHECK(in_cycle == 0);
  // The counter counts: a self-check.
  CHECK(mrqp::testing::allocationsIn([] { delete new volatile int(3); }) >= 1);
}
