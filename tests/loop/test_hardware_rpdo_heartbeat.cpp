// Two keys of a scene's hardware section (docs/loop.md, "The hardware section"): a robot's
// `rpdo_timeout`, written by the arm master to each CiA 402 drive's 0x1400:05 at boot (read back
// from the emulated drives' object dictionary, an observer independent of the controller), with
// its FILE:LINE: FIELD errors; and `controller_heartbeat`, whose frames the bus budget counts on
// every bus of CiA 402 drives (checked against the worst-case length of a classic CAN frame with
// one data byte and an 11-bit identifier: 55 + 10 n bits with stuffing, n = 1).
#include <catch2/catch.hpp>

#include <mrqp/drivers/arm_driver.hpp>

#include <string>

#include "hardware_scene.hpp"
#include "loop/hardware_check.hpp"
#include "loop/hardware_yaml.hpp"
#include "loop/scene_override.hpp"
#include "loop_setup.hpp"
#include "scene/builtin_models.hpp"
#include "scene/scene_builder.hpp"
#include "scene/scene_yaml.hpp"

using namespace mrqp;

namespace {

// A Panda alone at 1 ms; `hw` is appended as the hardware section (its first line is line 4).
const char* kScene =
    "settings: {dt: 0.001, duration: 1.0, max_tasks: 4, max_contacts: 2, max_contact_generators: 16}\n"  // 1
    "entities:\n"                                                                                        // 2
    "  - {name: panda, model: panda, q: {panda_joint4: -2.0, panda_joint6: 2.0}}\n";                     // 3

const char* kBuses = "hardware:\n  buses:\n    - {name: a}\n    - {name: b}\n  robots:\n";  // lines 4-8
const char* kRobot = "    - entity: panda\n      divisor: 4\n";                             // lines 9-10
const char* kDrives =
    "      cia402:\n"
    "        - {bus: a, joints: [panda_joint1, panda_joint2, panda_joint3, panda_joint4, panda_joint5]}\n"
    "        - {bus: b, first_node: 6, joints: [panda_joint6, panda_joint7, panda_finger_joint1]}\n";

const looptest::HardwareScene kPanda(kScene);

}  // namespace

TEST_CASE("loop: hardware rpdo_timeout: read, resolved and given to the arm master", "[loop][hardware]") {
  const loop::ResolvedHardware with =
      kPanda.resolve(std::string(kBuses) + kRobot + "      rpdo_timeout: 0.05\n" + kDrives);
  REQUIRE(with.robots.size() == 1u);
  CHECK(with.robots[0].rpdo_timeout_s == 0.05);
  drivers::ArmConfig ac;
  loop::applySafetyConfig(ac, with, &with.robots[0]);
  CHECK(ac.rpdo_timeout_ms == 50u);
  // Absent: nothing written.
  const loop::ResolvedHardware without = kPanda.resolve(std::string(kBuses) + kRobot + kDrives);
  CHECK(without.robots[0].rpdo_timeout_s == 0.0);
  drivers::ArmConfig ac0;
  loop::applySafetyConfig(ac0, without, &without.robots[0]);
  CHECK(ac0.rpdo_timeout_ms == 0u);
}

TEST_CASE("loop: hardware rpdo_timeout errors name file, line and field", "[loop][hardware]") {
  const std::string head = std::string(kBuses) + kRobot;
  CHECK(kPanda.errorOf(head + "      rpdo_timeout: 70\n" + kDrives) ==
        "s.yaml:11: hardware.robots[0].rpdo_timeout: expected a time in [0.001, 65.535] s (0x1400:05 holds "
        "milliseconds in 16 bits), got 70");
  CHECK(kPanda.errorOf(head + "      rpdo_timeout: 0.004\n" + kDrives) ==
        "s.yaml:11: hardware.robots[0].rpdo_timeout: must exceed the robot's cycle of 0.004 s (one RPDO per "
        "cycle), got 0.004");
  CHECK(kPanda.errorOf(head + "      rpdo_timeout: -1\n" + kDrives)
            .rfind("s.yaml:11: hardware.robots[0].rpdo_timeout: ", 0) == 0u);
  CHECK(kPanda.errorOf(head + "      rpdo_timeout: fast\n" + kDrives)
            .rfind("s.yaml:11: hardware.robots[0].rpdo_timeout: ", 0) == 0u);
}

TEST_CASE("loop: hardware rpdo_timeout reaches the drives' 0x1400:05 at boot", "[loop][hardware]") {
  std::string text = looptest::sceneText("two_arms.yaml");
  text = loop::applySceneOverride(text, "two_arms.yaml", "hardware.robots[0].rpdo_timeout=0.05");
  looptest::LoopSetup s(text, "two_arms.yaml");
  REQUIRE(s.boot());
  for (const loop::RobotIo& r : s.ctrl->robots()) {
    for (const loop::JointIo& j : r.joints) {
      INFO(j.name);
      std::uint32_t v = 0;
      REQUIRE(s.rig->drive(j.name)->firmware().od(0x1400, 5, &v));
      CHECK(v == (r.name == "left" ? 50u : 0u));  // the right arm: the drive's own default
    }
  }
  for (int k = 0; k < 200; ++k) s.cycle();
  CHECK_FALSE(s.ctrl->safeStopped());  // one RPDO every 4 ms: well within 50 ms
  CHECK(loop::exitDevices(*s.ctrl, s.now, s.period, s.rig.get()).done);
}

TEST_CASE("loop: hardware cia402 identity: read, given to the arm master, and its errors",
          "[loop][hardware]") {
  const std::string drives =
      "      cia402:\n"
      "        - {bus: a, vendor_id: 0x29C, product_code: 1026, joints: [panda_joint1, panda_joint2,\n"
      "                                                              panda_joint3, panda_joint4, "
      "panda_joint5]}\n"
      "        - {bus: b, first_node: 6, device_type: 0x20192, revision: 0x10000,\n"
      "           joints: [panda_joint6, panda_joint7, panda_finger_joint1]}\n";
  const loop::ResolvedHardware r = kPanda.resolve(std::string(kBuses) + kRobot + drives);
  REQUIRE(r.robots[0].drives.size() == 8u);
  drivers::ArmDriveConfig first, last;
  loop::applyDriveIdentity(first, r.robots[0].drives[4]);
  loop::applyDriveIdentity(last, r.robots[0].drives[7]);
  CHECK(first.vendor_id == 0x29Cu);
  CHECK(first.product_code == 1026u);
  CHECK(first.device_type == 0u);  // not checked
  CHECK(first.revision == 0u);
  CHECK(last.device_type == 0x20192u);
  CHECK(last.revision == 0x10000u);
  CHECK(last.vendor_id == 0u);
  CHECK(
      kPanda.errorOf(std::string(kBuses) + kRobot +
                     "      cia402:\n        - {bus: a, vendor_id: 0x100000000, joints: [panda_joint1]}\n") ==
      "s.yaml:12: hardware.robots[0].cia402[0].vendor_id: expected an integer in [0, 0xFFFFFFFF], got "
      "\"0x100000000\"");
  CHECK(kPanda
            .errorOf(std::string(kBuses) + kRobot +
                     "      cia402:\n        - {bus: a, revision: -1, joints: [panda_joint1]}\n")
            .rfind("s.yaml:12: hardware.robots[0].cia402[0].revision: expected an integer in [0, 0xFFFFFFFF]",
                   0) == 0u);
}

TEST_CASE("loop: the controller heartbeat is in the bus budget of every bus of CiA 402 drives",
          "[loop][hardware]") {
  const std::string drives = std::string(kRobot) + kDrives;
  const loop::ResolvedHardware plain = kPanda.resolve(std::string(kBuses) + drives);
  const loop::ResolvedHardware hb =
      kPanda.resolve(std::string(kBuses) + drives +
                     "  controller_heartbeat: {node: 100, period: 0.001, drive_timeout: 0.01}\n");
  REQUIRE(plain.buses.size() == 2u);
  REQUIRE(hb.buses.size() == 2u);
  // Worst case of a 1-byte classic frame: 55 + 10 bits at 1 Mbit/s = 65 µs, once per 1 ms period:
  // 6.5 % of every cycle, whatever the cycle.
  const double expected = 65e-6 / 0.001;
  for (std::size_t b = 0; b < 2; ++b) {
    INFO(hb.buses[b].report);
    CHECK(hb.buses[b].utilisation_worst - plain.buses[b].utilisation_worst == Approx(expected).epsilon(1e-9));
    CHECK(hb.buses[b].report.find("controller heartbeat") != std::string::npos);
    CHECK(plain.buses[b].report.find("controller heartbeat") == std::string::npos);
  }
}
