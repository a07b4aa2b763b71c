// The controller's cycle allocates nothing: 10,000 cycles of the loop with the CAN drivers on the
// simulated buses and the plant behind them (panda_door, jvrc1_box, and panda_door with its
// gripper on an MIT motor and on a CAN FD hand board), counted by the replaced global allocator (which also
// sees Eigen's heap: Eigen allocates through malloc), with Eigen's run-time check armed in the
// loop's own sources compiled here with EIGEN_RUNTIME_NO_MALLOC.
#include <catch2/catch.hpp>

#include <string>

#include "counting_allocator.hpp"
#include "loop/scene_override.hpp"
#include "loop_setup.hpp"

using looptest::LoopSetup;

namespace {

/// panda_door with its gripper on hand actuators: an MIT motor on a bus of its own, or a CAN FD
/// hand board.
std::string withHand(bool mit) {
  std::string t = looptest::sceneText("panda_door.yaml");
  auto replace = [&t](const std::string& from, const std::string& to) {
    const std::size_t at = t.find(from);
    REQUIRE(at != std::string::npos);
    t.replace(at, from.size(), to);
  };
  replace("    - {name: arm1, bitrate: 1000000}\n",
          mit ? "    - {name: arm1, bitrate: 1000000}\n    - {name: hand, bitrate: 1000000}\n"
              : "    - {name: arm1, bitrate: 1000000}\n    - {name: hand, bitrate: 1000000, data_bitrate: "
                "5000000}\n");
  replace("joints: [panda_joint6, panda_joint7, panda_finger_joint1]}",
          "joints: [panda_joint6, panda_joint7]}");
  replace("        - {frame: panda_link8, bus: arm1, node: 20}\n",
          std::string("        - {frame: panda_link8, bus: arm1, node: 20}\n") +
              (mit ? "      mit:\n        - {bus: hand, first_id: 3, joints: [panda_finger_joint1]}\n"
                   : "      fd:\n        - {bus: hand, board: 1, joints: [panda_finger_joint1]}\n"));
  return t;
}

}  // namespace

TEST_CASE("loop: 10,000 loop cycles over CAN with the plant allocate nothing", "[loop][realtime]") {
  const std::string door_mit = withHand(true), door_fd = withHand(false);
  for (const char* name :
       {"panda_door.yaml", "jvrc1_box.yaml", "door with an MIT finger", "door with an FD board"}) {
    INFO(name);
    const std::string n = name;
    const std::string text = n == "door with an MIT finger" ? door_mit
                             : n == "door with an FD board" ? door_fd
                                                            : looptest::sceneText(name);
    LoopSetup s(text, n.find(".yaml") == std::string::npos ? "panda_door.yaml" : name);
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

TEST_CASE(
    "loop: 10,000 cycles with the drives' safety (events, a recovery, a trip) and the safe exit allocate "
    "nothing",
    "[loop][realtime][safety]") {
  std::string text = looptest::sceneText("panda_door.yaml");
  for (const char* set : {"hardware.recovery={max_attempts: 3, backoff: 0.5}",
                          "hardware.controller_heartbeat={node: 100, period: 0.1, drive_timeout: 0.3}",
                          "hardware.robots[0].safe_stop=quick_stop"}) {
    text = mrqp::loop::applySceneOverride(text, "panda_door.yaml", set);
  }
  LoopSetup s(text, "panda_door.yaml");
  REQUIRE(s.boot());
  for (int k = 0; k < 10; ++k) s.cycle();  // warm-up: first solves
  long in_cycle = 0;
  for (int k = 0; k < 10000; ++k) {
    if (k == 1000) s.rig->drive("panda.panda_joint3")->firmware().powerOn(s.now);  // rebooted: recovered
    if (k == 6000) s.rig->drive("panda.panda_joint5")->breakEncoder();             // EMCY 0x7305: the trip
    in_cycle += mrqp::testing::allocationsIn([&] { s.ctrl->cycle(s.now); });
    s.plant->setFollowing(!s.ctrl->holding());
    s.rig->advanceTo(s.now + s.period);
    s.now += s.period;
  }
  INFO("stopped: " << s.ctrl->stopDescription());
  CHECK(s.ctrl->recoveries() == 1u);
  CHECK(s.ctrl->safeStopped());
  CHECK(s.ctrl->faultEventCount() > 0u);
  CHECK(in_cycle == 0);
  // The safe exit's cycles allocate nothing either.
  long in_exit = mrqp::testing::allocationsIn([&] { s.ctrl->requestSafeExit(s.now); });
  bool done = false;
  for (int k = 0; k < 2000 && !done; ++k) {
    in_exit += mrqp::testing::allocationsIn([&] { done = s.ctrl->exitCycle(s.now); });
    s.rig->advanceTo(s.now + s.period);
    s.now += s.period;
  }
  CHECK(done);
  CHECK(in_exit == 0);
}
