// A boot that does not complete leaves every device safe (docs/loop.md, "Safety"), on the
// simulated buses with the emulated CiA 402 drives of two_arms (two robots, four buses): a drive
// whose firmware refuses one configuration write (SDO abort) ends the boot at once, the error text
// names that drive, the abort code, its CiA 301 meaning and the object, and the safe exit leaves
// every drive of both robots in the NMT state of hardware.safe_exit; a drive that never reports
// its state keeps the others from being used: those that were enabled meanwhile are stopped
// (Switch on disabled) and left in that NMT state. The drives' states are read from the emulated
// firmware, an observer independent of the controller.
#include <catch2/catch.hpp>

#include <mrqp/firmware_if/cia402.h>
#include <mrqp/firmware_if/nmt.h>

#include <string>
#include <vector>

#include "loop/device_lifecycle.hpp"
#include "loop/scene_override.hpp"
#include "loop_setup.hpp"

using namespace mrqp;
using looptest::LoopSetup;

namespace {

std::string twoArmsText(const std::string& safe_exit) {
  std::string text = looptest::sceneText("two_arms.yaml");
  if (!safe_exit.empty())
    text = loop::applySceneOverride(text, "two_arms.yaml", "hardware.safe_exit=" + safe_exit);
  return text;
}

/// two_arms on the emulated rig (two robots, four buses); `safe_exit`, when not empty, the value of
/// its hardware.safe_exit.
struct TwoArms : LoopSetup {
  explicit TwoArms(const std::string& safe_exit) : LoopSetup(twoArmsText(safe_exit), "two_arms.yaml") {}

  std::vector<std::string> driveNames() const {
    std::vector<std::string> names;
    for (const loop::RobotIo& r : ctrl->robots()) {
      for (const loop::JointIo& j : r.joints) names.push_back(j.name);
    }
    return names;
  }

  /// The safe exit after the boot: it completes, and once its last frames have reached the drives,
  /// every drive's firmware is in the NMT state `nmt`. Returns the exit's result.
  loop::LifecycleResult checkSafeExit(mrqp_fw_nmt_state nmt) {
    const loop::LifecycleResult exit = loop::exitDevices(*ctrl, now, period, rig.get());
    CHECK(exit.done);
    // Let the last frames reach the drives.
    rig->advanceTo(now + 5 * period);
    for (const std::string& j : driveNames()) {
      INFO(j);
      CHECK(rig->drive(j)->firmware().nmt() == nmt);
    }
    return exit;
  }
};

std::string joined(const std::vector<std::string>& lines) {
  std::string all;
  for (const std::string& l : lines) all += l + "\n";
  return all;
}

}  // namespace

TEST_CASE("loop: boot failure: an SDO abort ends the boot, is reported, and every drive gets the safe exit",
          "[loop][safety][boot]") {
  TwoArms s("{stop: disable_voltage, nmt: stopped}");
  // The right arm's second drive refuses TPDO1's transmission type (0x1800:02): a value its
  // firmware does not support.
  loop::PlantCia402Drive* bad = s.rig->drive("right.panda_joint2");
  REQUIRE(bad != nullptr);
  bad->firmware().abortOnWrite(0x1800, 2, 0x06090030u);

  const double timeout_s = 10.0;
  const loop::LifecycleResult boot = loop::bootDevices(*s.ctrl, s.now, s.period, s.rig.get(), timeout_s);
  CHECK_FALSE(boot.done);
  CHECK(loop::bootFailed(boot));
  // The boot ended with the failure, long before the time limit.
  CHECK(static_cast<double>(boot.cycles) * s.sc.settings.dt < 1.0);

  const std::vector<std::string> why = loop::describeBootFailure(*s.ctrl);
  const std::string text = joined(why);
  INFO(text);
  CHECK(text.find("right.panda_joint2: ") != std::string::npos);
  CHECK(text.find("0x06090030") != std::string::npos);
  CHECK(text.find("0x1800:02") != std::string::npos);
  CHECK(text.find("node 2") != std::string::npos);
  // The meaning of the code as CiA 301 (v4.2, table 22) words it.
  CHECK(text.find("invalid value for parameter (download only)") != std::string::npos);
  // Only the failing drive has a line of its own; the left arm is told in one line.
  CHECK(text.find("right.panda_joint1:") == std::string::npos);
  CHECK(text.find("left: its ") != std::string::npos);

  const loop::LifecycleResult exit = s.checkSafeExit(MRQP_FW_NMT_STATE_STOPPED);
  for (const std::string& j : s.driveNames()) {
    INFO(j);
    CHECK(s.rig->drive(j)->firmware().state() != MRQP_FW_CIA402_OPERATION_ENABLED);
  }
  CHECK_THAT(loop::describeSafeExit(s.hw, exit),
             Catch::Contains("disable voltage, then NMT stop") && Catch::Contains(": done after"));
}

TEST_CASE("loop: boot failure: drives enabled before the boot gave up are stopped by the safe exit",
          "[loop][safety][boot]") {
  TwoArms s("{stop: quick_stop, nmt: stopped}");
  // The right arm's second drive sends no PDO: it is started but never reports being enabled.
  s.rig->drive("right.panda_joint2")->firmware().setPdoSilent(true);

  const double timeout_s = 1.0;
  const loop::LifecycleResult boot = loop::bootDevices(*s.ctrl, s.now, s.period, s.rig.get(), timeout_s);
  REQUIRE_FALSE(boot.done);
  CHECK_FALSE(loop::bootFailed(boot));
  // Meanwhile every other drive was enabled (the independent observer: the firmware).
  for (const std::string& j : s.driveNames()) {
    if (j == "right.panda_joint2") continue;
    INFO(j);
    CHECK(s.rig->drive(j)->firmware().state() == MRQP_FW_CIA402_OPERATION_ENABLED);
    CHECK(s.rig->drive(j)->firmware().nmt() == MRQP_FW_NMT_STATE_OPERATIONAL);
  }
  const std::string text = joined(loop::describeBootFailure(*s.ctrl));
  INFO(text);
  CHECK(text.find("right.panda_joint2: ") != std::string::npos);
  CHECK(text.find("left.panda_joint1") == std::string::npos);

  s.checkSafeExit(MRQP_FW_NMT_STATE_STOPPED);
  for (const std::string& j : s.driveNames()) {
    INFO(j);
    const auto& fw = s.rig->drive(j)->firmware();
    CHECK(fw.state() == MRQP_FW_CIA402_SWITCH_ON_DISABLED);
    if (j != "right.panda_joint2") CHECK(fw.lastControlword() == 0x0000u);  // disable voltage, last
  }
}

TEST_CASE("loop: boot failure: a stop request (a signal) ends the boot, the safe exit follows",
          "[loop][safety][boot]") {
  TwoArms s("");
  int asked = 0;
  const loop::LifecycleResult boot =
      loop::bootDevices(*s.ctrl, s.now, s.period, s.rig.get(), 10.0, {}, [&asked] { return ++asked >= 5; });
  CHECK_FALSE(boot.done);
  CHECK_FALSE(loop::bootFailed(boot));
  CHECK(boot.cycles == 5);
  s.checkSafeExit(MRQP_FW_NMT_STATE_PRE_OPERATIONAL);  // the default safe_exit
  for (const std::string& j : s.driveNames()) {
    INFO(j);
    CHECK(s.rig->drive(j)->firmware().state() != MRQP_FW_CIA402_OPERATION_ENABLED);
  }
}
