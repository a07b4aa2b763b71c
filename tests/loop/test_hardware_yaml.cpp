// The hardware section of a scene file: every error names file, line and field; the bus budget
// refuses an over-budget configuration with the budget's own message (docs/loop.md).
#include <catch2/catch.hpp>

#include <mrqp/drivers/bus_budget.hpp>

#include "hardware_scene.hpp"
#include "loop/hardware_check.hpp"
#include "loop/hardware_yaml.hpp"
#include "scene/builtin_models.hpp"
#include "scene/scene_builder.hpp"
#include "scene/scene_yaml.hpp"

using namespace mrqp;

namespace {

// A Panda alone; `hw` is appended as the hardware section (its first line is line 12).
const char* kScene =
    "settings: {dt: 0.001, duration: 1.0, max_tasks: 4, max_contacts: 2, max_contact_generators: 16}\n"  // 1
    "entities:\n"                                                                                        // 2
    "  - name: panda\n"                                                                                  // 3
    "    model: panda\n"                                                                                 // 4
    "    q: {panda_joint4: -2.0, panda_joint6: 2.0, panda_finger_joint1: 0.02}\n"                        // 5
    "tasks:\n"                                                                                           // 6
    "  - name: posture\n"                                                                                // 7
    "    type: posture\n"                                                                                // 8
    "    entity: panda\n"                                                                                // 9
    "    weight: 1\n"                                                                                    // 10
    "    stiffness: 1\n";                                                                                // 11

const char* kDrives =
    "      cia402:\n"
    "        - {bus: a, mode: csp, first_node: 1, joints: [panda_joint1, panda_joint2, panda_joint3, "
    "panda_joint4,\n"
    "                                                       panda_joint5]}\n"
    "        - {bus: b, mode: csp, first_node: 6, joints: [panda_joint6, panda_joint7, "
    "panda_finger_joint1]}\n"
    "\n";

const looptest::HardwareScene kPanda(kScene);

const std::string kBuses = "hardware:\n  buses:\n    - {name: a}\n    - {name: b}\n";  // lines 12-15

}  // namespace

TEST_CASE("loop: a valid hardware section resolves joints, nodes and buses", "[loop][hardware]") {
  const std::string hw = kBuses + "  robots:\n    - entity: panda\n      divisor: 4\n" + kDrives;
  const loop::ResolvedHardware r = kPanda.resolve(hw);
  REQUIRE(r.robots.size() == 1);
  REQUIRE(r.robots[0].drives.size() == 8);
  CHECK(r.robots[0].drives[5].node == 6);
  CHECK(r.robots[0].drives[5].bus == 1);
  CHECK(r.robots[0].drives[5].joint_name == "panda_joint6");
  CHECK(r.buses[0].cycle_hz == Approx(250.0));
  // The utilisation is the drivers' own budget of the same traffic.
  drivers::BusSpec spec;
  spec.cycle_hz = 250.0;
  drivers::BusBudget b(spec);
  b.addSync();
  b.addArmDrives(5, true);
  b.addHeartbeats(5, 0.1);
  CHECK(r.buses[0].utilisation_worst == Approx(b.result().utilisation_worst));
}

TEST_CASE("loop: hardware section errors name file, line and field", "[loop][hardware]") {
  const std::string robot = "  robots:\n    - entity: panda\n      divisor: 4\n";  // lines 16-18
  CHECK(kPanda.errorOf(kBuses + robot +
                       "      cia402:\n        - {bus: a, mode: cxp, joints: [panda_joint1]}\n") ==
        "s.yaml:20: hardware.robots[0].cia402[0].mode: expected csp or cst, got \"cxp\"");
  CHECK(kPanda.errorOf(kBuses + robot + "      cia402:\n        - {bus: c, joints: [panda_joint1]}\n") ==
        "s.yaml:20: hardware.robots[0].cia402[0].bus: unknown bus 'c' (not in hardware.buses)");
  CHECK(kPanda.errorOf(kBuses + robot + "      cia402:\n        - {bus: a, joints: [elbow]}\n") ==
        "s.yaml:20: hardware.robots[0].cia402[0].joints[0]: entity 'panda' has no joint 'elbow'");
  CHECK(kPanda.errorOf(kBuses + robot +
                       "      cia402:\n        - {bus: a, joints: [panda_joint1, panda_joint1]}\n") ==
        "s.yaml:20: hardware.robots[0].cia402[0].joints[1]: 'panda_joint1' is listed twice");
  CHECK(kPanda.errorOf(
            kBuses + robot +
            "      cia402:\n        - {bus: a, joints: [panda_joint1]}\n        - {bus: a, first_node: "
            "1, joints: [panda_joint2]}\n") ==
        "s.yaml:21: hardware.robots[0].cia402[1].joints[0]: node id 1 on bus 'a' is already used (line 20)");
  CHECK(kPanda.errorOf(kBuses + robot + "      cia402:\n        - {bus: a, joints: [panda_joint1]}\n") ==
        "s.yaml:17: hardware.robots[0]: actuated joint 'panda_joint2' of 'panda' has no drive");
  CHECK(kPanda.errorOf(kBuses + "  robots:\n    - entity: door\n") ==
        "s.yaml:17: hardware.robots[0].entity: unknown entity 'door'");
  CHECK(kPanda.errorOf(kBuses + robot + "      speed: 3\n") ==
        "s.yaml:19: hardware.robots[0].speed: unknown key");
  CHECK(kPanda.errorOf(kBuses + robot + "      safe_stop: brake\n") ==
        "s.yaml:19: hardware.robots[0].safe_stop: expected hold or quick_stop, got \"brake\"");
  CHECK(kPanda.errorOf(kBuses + "  robots:\n    - entity: panda\n      divisor: 0\n") ==
        "s.yaml:18: hardware.robots[0].divisor: expected an integer in [1, 1000], got 0");
  CHECK(kPanda.errorOf("hardware:\n  buses:\n    - {name: a, bitrate: 5}\n  robots: []\n") ==
        "s.yaml:14: hardware.buses[0].bitrate: expected an integer in [10000, 20000000], got 5");
  CHECK(kPanda.errorOf(kBuses + robot + kDrives +
                       "      imus:\n        - {frame: panda_link8, bus: a, node: 30}\n") ==
        "s.yaml:25: hardware.robots[0].imus: 'panda' has no floating base to estimate");
}

TEST_CASE("loop: an over-budget bus is refused with the budget's message", "[loop][hardware]") {
  // Eight drives at 1 kHz on one bus: ~3.7 ms of frames per 1 ms cycle.
  const std::string hw =
      "hardware:\n  buses:\n    - {name: a}\n  robots:\n    - entity: panda\n      cia402:\n"
      "        - {bus: a, joints: [panda_joint1, panda_joint2, panda_joint3, panda_joint4, panda_joint5,\n"
      "                            panda_joint6, panda_joint7, panda_finger_joint1]}\n";
  drivers::BusSpec spec;
  spec.name = "a";
  spec.cycle_hz = 1000.0;
  drivers::BusBudget b(spec);
  b.addSync();
  b.addArmDrives(8, true);
  b.addHeartbeats(8, 0.1);
  std::string message;
  REQUIRE_FALSE(b.check(&message));
  CHECK(kPanda.errorOf(hw) == "s.yaml:14: hardware.buses[0]: " + message);
}

TEST_CASE("loop: a robot's joint state is measured by default, or commanded", "[loop][hardware]") {
  const std::string robot = "  robots:\n    - entity: panda\n      divisor: 4\n";  // lines 16-18
  CHECK(kPanda.resolve(kBuses + robot + kDrives).robots.at(0).state == loop::JointState::Measured);
  CHECK(kPanda.resolve(kBuses + robot + "      state: commanded\n" + kDrives).robots.at(0).state ==
        loop::JointState::Commanded);
  CHECK(kPanda.resolve(kBuses + robot + "      state: measured\n" + kDrives).robots.at(0).state ==
        loop::JointState::Measured);
  CHECK(kPanda.errorOf(kBuses + robot + "      state: estimated\n" + kDrives) ==
        "s.yaml:19: hardware.robots[0].state: expected measured or commanded, got \"estimated\"");
}

TEST_CASE("loop: a robot's drives interpolate their setpoints only when the section says so", "[loop][hardware]") {
  const std::string robot = "  robots:\n    - entity: panda\n      divisor: 4\n";  // lines 16-18
  CHECK_FALSE(kPanda.resolve(kBuses + robot + kDrives).robots.at(0).interpolating_drives);
  CHECK(kPanda.resolve(kBuses + robot + "      interpolating_drives: true\n" + kDrives).robots.at(0).interpolating_drives);
  CHECK_FALSE(
      kPanda.resolve(kBuses + robot + "      interpolating_drives: false\n" + kDrives).robots.at(0).interpolating_drives);
  const std::string error = kPanda.errorOf(kBuses + robot + "      interpolating_drives: often\n" + kDrives);
  INFO(error);
  CHECK(error.rfind("s.yaml:19: hardware.robots[0].interpolating_drives: ", 0) == 0);
}

TEST_CASE("loop: the frame-loss limit and its window come from the hardware section", "[loop][hardware]") {
  const std::string robot = "  robots:\n    - entity: panda\n      divisor: 4\n";
  const loop::ResolvedHardware d = kPanda.resolve(kBuses + robot + kDrives);
  CHECK(d.frame_loss_window == 100.0);
  CHECK(d.frame_loss_limit == 0.02);
  // "hardware:" is line 12; frame_loss is line 13.
  const std::string with = "hardware:\n  frame_loss: {window: 20, limit: 0.25}\n" + kBuses.substr(10);
  const loop::ResolvedHardware r = kPanda.resolve(with + robot + kDrives);
  CHECK(r.frame_loss_window == 20.0);
  CHECK(r.frame_loss_limit == 0.25);
  CHECK(kPanda.errorOf("hardware:\n  frame_loss: {window: 20, limit: 1.5}\n" + kBuses.substr(10) + robot +
                       kDrives) ==
        "s.yaml:13: hardware.frame_loss.limit: expected a fraction of robot cycles, at most 1");
  CHECK(kPanda.errorOf("hardware:\n  frame_loss: {window: 0}\n" + kBuses.substr(10) + robot + kDrives) ==
        "s.yaml:13: hardware.frame_loss.window: expected an integer in [1, 100000], got 0");
  CHECK(kPanda.errorOf("hardware:\n  frame_loss: {rate: 0.1}\n" + kBuses.substr(10) + robot + kDrives) ==
        "s.yaml:13: hardware.frame_loss.rate: unknown key");
}
