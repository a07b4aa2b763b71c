// The controller's safety through the drivers (docs/loop.md, "Safety"), on the simulated buses with
// the emulated CiA 402 drives of panda_door: after a trip the drives are where the robot's
// configuration says (quick_stop: CiA 402 Quick stop active within one robot cycle; hold: still
// Operation enabled, holding) and the arm driver is in its safe state (no recovery any more); the
// safe exit leaves every drive Switch on disabled in the NMT state of hardware.safe_exit; what
// stopped the controller is told with the drivers' text (the EMCY code the firmware raised, the
// CANopen heartbeat error); with a controller heartbeat the drive reacts to a lost heartbeat by
// itself; the recovery policy brings a rebooted drive back and gives up after its attempts.
// The drives' states are read from the emulated firmware, never from the controller.
#include <catch2/catch.hpp>

#include <mrqp/firmware_if/cia402.h>
#include <mrqp/firmware_if/nmt.h>
#include <mrqp/drivers/arm_driver.hpp>

#include <cmath>
#include <string>
#include <vector>

#include "loop/device_lifecycle.hpp"
#include "loop/fault_injector.hpp"
#include "loop/scene_override.hpp"
#include "loop_setup.hpp"

using namespace mrqp;
using looptest::LoopSetup;

namespace {

std::string door(const std::vector<std::string>& sets) {
  std::string text = looptest::sceneText("panda_door.yaml");
  for (const std::string& s : sets) text = loop::applySceneOverride(text, "panda_door.yaml", s);
  return text;
}

std::vector<std::string> driveNames(const LoopSetup& s) {
  std::vector<std::string> names;
  for (const loop::JointIo& j : s.ctrl->robots()[0].joints) names.push_back(j.name);
  return names;
}

drivers::ArmDriver* armOf(const LoopSetup& s) {
  for (const auto& d : s.ctrl->robots()[0].devices) {
    if (auto* a = dynamic_cast<drivers::ArmDriver*>(d.get())) return a;
  }
  return nullptr;
}

/// Cycles until the controller stops (at most `limit` cycles); returns the cycles run.
long runUntilStop(LoopSetup& s, loop::FaultInjector* inj, long limit) {
  long k = 0;
  for (; k < limit && !s.ctrl->safeStopped(); ++k) {
    if (inj != nullptr) inj->beforeCycle(static_cast<double>(k) * s.sc.settings.dt, s.now);
    s.cycle();
    if (inj != nullptr) inj->afterCycle();
  }
  return k;
}

bool contains(const std::string& text, const std::string& part) {
  return text.find(part) != std::string::npos;
}

}  // namespace

TEST_CASE("loop: safety: quick_stop drives in Quick stop active, the safe exit, the driver's text",
          "[loop][safety]") {
  LoopSetup s(door({"hardware.robots[0].safe_stop=quick_stop"}), "panda_door.yaml");
  loop::FaultInjector inj({loop::parseFaultRequest("nan-feedback@0.2:panda.panda_joint3")}, s.rig.get(),
                          *s.ctrl, s.hw);
  REQUIRE(s.boot());
  runUntilStop(s, &inj, 1000);
  REQUIRE(s.ctrl->safeStopped());
  CHECK(s.ctrl->stopReason() == loop::StopReason::DriverFault);
  // One robot cycle later every other drive is in Quick stop active (the faulted one in Fault).
  for (int k = 0; k < s.hw.robots[0].divisor; ++k) s.cycle();
  for (const std::string& j : driveNames(s)) {
    INFO(j);
    CHECK(s.rig->drive(j)->state() ==
          (j == "panda.panda_joint3" ? MRQP_FW_CIA402_FAULT : MRQP_FW_CIA402_QUICK_STOP_ACTIVE));
  }
  drivers::ArmDriver* arm = armOf(s);
  REQUIRE(arm != nullptr);
  CHECK(arm->safeState());
  CHECK(arm->requestRecovery(s.now) == 0u);  // never recovered from the controller's safe stop
  // The drivers' text names the device and the EMCY the firmware raised (0x7305, incremental
  // sensor 1 fault).
  const std::string why = s.ctrl->stopDescription();
  INFO(why);
  CHECK(contains(why, "panda.panda_joint3: "));
  CHECK(contains(why, "0x7305"));
  bool event = false;
  for (std::size_t i = 0; i < s.ctrl->faultEventCount(); ++i) {
    const auto& e = s.ctrl->faultEvent(i);
    event = event || (*e.where == "panda.panda_joint3" && contains(loop::Controller::describe(e), "0x7305"));
  }
  CHECK(event);

  // The safe exit (default: quick stop, then NMT pre-operational).
  const loop::LifecycleResult exit = loop::exitDevices(*s.ctrl, s.now, s.period, s.rig.get());
  CHECK(exit.done);
  CHECK(s.ctrl->exitDone());
  for (const std::string& j : driveNames(s)) {
    INFO(j);
    const auto& fw = s.rig->drive(j)->firmware();
    CHECK(fw.state() ==
          (j == "panda.panda_joint3" ? MRQP_FW_CIA402_FAULT : MRQP_FW_CIA402_SWITCH_ON_DISABLED));
    CHECK(fw.nmt() == MRQP_FW_NMT_STATE_PRE_OPERATIONAL);
  }
}

TEST_CASE("loop: safety: hold keeps the drives enabled, the safe exit with disable voltage and NMT stop",
          "[loop][safety]") {
  LoopSetup s(door({"hardware.safe_exit={stop: disable_voltage, nmt: stopped}"}), "panda_door.yaml");
  loop::FaultInjector inj({loop::parseFaultRequest("heartbeat-loss@0.2:panda.panda_joint3")}, s.rig.get(),
                          *s.ctrl, s.hw);
  REQUIRE(s.boot());
  runUntilStop(s, &inj, 1000);
  REQUIRE(s.ctrl->safeStopped());
  for (int k = 0; k < 10 * s.hw.robots[0].divisor; ++k) s.cycle();
  for (const std::string& j : driveNames(s)) {
    INFO(j);
    CHECK(s.rig->drive(j)->state() == MRQP_FW_CIA402_OPERATION_ENABLED);  // holding with damping
  }
  REQUIRE(armOf(s) != nullptr);
  CHECK(armOf(s)->safeState());
  INFO(s.ctrl->stopDescription());
  CHECK(contains(s.ctrl->stopDescription(), "panda.panda_joint3: heartbeat lost (node 3)"));
  // Without a controller heartbeat the drive never watches one: no reaction of its own.
  CHECK(s.rig->drive("panda.panda_joint3")->firmware().heartbeatErrors() == 0u);

  CHECK(loop::exitDevices(*s.ctrl, s.now, s.period, s.rig.get()).done);
  for (const std::string& j : driveNames(s)) {
    INFO(j);
    const auto& fw = s.rig->drive(j)->firmware();
    CHECK(fw.state() == MRQP_FW_CIA402_SWITCH_ON_DISABLED);
    CHECK(fw.nmt() == MRQP_FW_NMT_STATE_STOPPED);
  }
}

TEST_CASE("loop: safety: with a controller heartbeat a lost heartbeat shows the drive's own reaction",
          "[loop][safety]") {
  LoopSetup s(door({"hardware.controller_heartbeat={node: 100, period: 0.1, drive_timeout: 0.3}"}),
              "panda_door.yaml");
  loop::FaultInjector inj({loop::parseFaultRequest("heartbeat-loss@0.2:panda.panda_joint3")}, s.rig.get(),
                          *s.ctrl, s.hw);
  REQUIRE(s.boot());
  const auto& fw = s.rig->drive("panda.panda_joint3")->firmware();
  std::uint32_t consumer = 0;
  REQUIRE(fw.od(0x1016, 1, &consumer));
  CHECK(consumer == ((100u << 16) | 300u));
  for (long k = 0; k < 1000; ++k) {
    inj.beforeCycle(static_cast<double>(k) * s.sc.settings.dt, s.now);
    s.cycle();
    inj.afterCycle();
  }
  REQUIRE(s.ctrl->safeStopped());
  // The drive's heartbeat consumer timed out: EMCY 0x8130, pre-operational (0x1029:01 = 0), Fault
  // (0x6007 = 1); the controller reports it with the drivers' text.
  CHECK(fw.heartbeatErrors() == 1u);
  CHECK(fw.state() == MRQP_FW_CIA402_FAULT);
  CHECK(fw.nmt() == MRQP_FW_NMT_STATE_PRE_OPERATIONAL);
  bool reaction = false;
  for (std::size_t i = 0; i < s.ctrl->faultEventCount(); ++i) {
    const auto& e = s.ctrl->faultEvent(i);
    if (*e.where == "panda.panda_joint3" && contains(loop::Controller::describe(e), "0x8130"))
      reaction = true;
  }
  CHECK(reaction);
  // The other drives heard the controller's heartbeat all along.
  CHECK(s.rig->drive("panda.panda_joint1")->firmware().heartbeatErrors() == 0u);
}

TEST_CASE("loop: safety: the recovery policy brings a rebooted drive back", "[loop][safety]") {
  for (const bool policy : {true, false}) {
    INFO((policy ? "recovery: {max_attempts: 3, backoff: 0.5}" : "no recovery policy"));
    LoopSetup s(policy ? door({"hardware.recovery={max_attempts: 3, backoff: 0.5}"}) : door({}),
                "panda_door.yaml");
    REQUIRE(s.boot());
    const double dt = s.sc.settings.dt;
    // Later than the drives' enable timeout (1 s) after they were enabled: the recovery's own
    // limit applies, not that one.
    for (long k = 0; k < std::lround(1.2 / dt); ++k) s.cycle();
    // The drive of joint 3 loses power and boots again: its configuration is gone.
    s.rig->drive("panda.panda_joint3")->firmware().powerOn(s.now);
    bool held = false;
    for (long k = 0; k < std::lround(2.7 / dt) && !s.ctrl->safeStopped(); ++k) {
      s.cycle();
      held = held || s.ctrl->recovering();
    }
    if (!policy) {
      CHECK(s.ctrl->safeStopped());
      CHECK((s.ctrl->stopFlags() & (drivers::fault::kStateMismatch | drivers::fault::kFeedbackMissing)) !=
            0u);
      continue;
    }
    CHECK_FALSE(s.ctrl->safeStopped());
    CHECK(held);
    CHECK_FALSE(s.ctrl->recovering());
    CHECK(s.ctrl->recoveries() == 1u);
    REQUIRE(armOf(s) != nullptr);
    CHECK(armOf(s)->faults().devices[2].recoveries == 1u);
    CHECK(s.rig->drive("panda.panda_joint3")->state() == MRQP_FW_CIA402_OPERATION_ENABLED);
    CHECK(s.ctrl->lastStatus() == qp::QpStatus::Optimal);
  }
}

TEST_CASE("loop: safety: a recovery that does not succeed stops after max_attempts", "[loop][safety]") {
  LoopSetup s(door({"hardware.recovery={max_attempts: 2, backoff: 0.2}"}), "panda_door.yaml");
  REQUIRE(s.boot());
  const double dt = s.sc.settings.dt;
  for (long k = 0; k < std::lround(0.3 / dt); ++k) s.cycle();
  s.rig->drive("panda.panda_joint3")->firmware().setSilent(true);  // gone for good
  for (long k = 0; k < std::lround(2.0 / dt) && !s.ctrl->safeStopped(); ++k) s.cycle();
  REQUIRE(s.ctrl->safeStopped());
  CHECK(s.ctrl->stopReason() == loop::StopReason::DriverFault);
  CHECK(s.ctrl->stopDevice() == "panda.panda_joint3");
  // Detected within a few robot cycles of 0.3 s (missing feedback); two attempts of 0.2 s, then
  // the stop.
  const double robot_period = dt * s.hw.robots[0].divisor;
  const double stopped = static_cast<double>(s.ctrl->stopTime()) * 1e-9;
  INFO("stopped " << stopped << " s");
  CHECK(stopped >= 0.3 + 0.4 - 1e-9);
  CHECK(stopped <= 0.3 + 0.4 + 5 * robot_period + 1e-9);
  CHECK(contains(s.ctrl->stopDescription(), "panda.panda_joint3: "));
}

TEST_CASE("loop: safety: the hardware section's safety keys are checked", "[loop][safety]") {
  auto error = [](const std::string& set) {
    try {
      LoopSetup s(door({set}), "panda_door.yaml");
    } catch (const std::exception& e) {
      return std::string(e.what());
    }
    return std::string("no error");
  };
  CHECK_THAT(
      error("hardware.controller_heartbeat={node: 100, period: 0.3, drive_timeout: 0.2}"),
      Catch::Contains("hardware.controller_heartbeat.drive_timeout: the drives' consumer time must exceed "
                      "the heartbeat period"));
  CHECK_THAT(
      error("hardware.controller_heartbeat={node: 3}"),
      Catch::Contains("hardware.controller_heartbeat.node: node 3 is a CiA 402 drive of 'panda' on bus "
                      "'arm0'"));
  CHECK_THAT(error("hardware.controller_heartbeat={node: 200}"),
             Catch::Contains("hardware.controller_heartbeat.node"));
  CHECK_THAT(
      error("hardware.safe_exit={stop: brake}"),
      Catch::Contains("hardware.safe_exit.stop: expected quick_stop or disable_voltage, got \"brake\""));
  CHECK_THAT(error("hardware.safe_exit={nmt: off}"),
             Catch::Contains("hardware.safe_exit.nmt: expected pre_operational, stopped or unchanged"));
  CHECK_THAT(error("hardware.recovery={max_attempts: -1}"),
             Catch::Contains("hardware.recovery.max_attempts"));
  CHECK_THAT(error("hardware.recovery={backoff: 0}"), Catch::Contains("hardware.recovery.backoff"));
  CHECK_THAT(error("hardware.recovery={retries: 2}"), Catch::Contains("hardware.recovery"));
  // Every message names the file and a line.
  CHECK_THAT(error("hardware.safe_exit={stop: brake}"), Catch::StartsWith("panda_door.yaml:"));
}
