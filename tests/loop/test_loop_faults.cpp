// One test per fault kind (docs/loop.md, "Faults"): the fault is injected where it happens (the
// emulated firmware, the bus, the problem for `infeasible`), the controller detects it within
// the configured timeout and its safe commands go out in the cycle of detection.
#include <catch2/catch.hpp>

#include <mrqp/firmware_if/cia402.h>

#include <cmath>

#include "loop/fault_injector.hpp"
#include "loop/scene_override.hpp"
#include "loop_setup.hpp"

using namespace mrqp;
using looptest::LoopSetup;

namespace {

struct Outcome {
  loop::FaultRecord record;
  loop::StopReason reason = loop::StopReason::None;
  std::uint32_t flags = 0;
  double robot_period = 0.0;
  double heartbeat_timeout = 0.0;
};

Outcome runWithFault(const std::string& spec, double seconds = 1.2) {
  LoopSetup s(looptest::sceneText("panda_door.yaml"), "panda_door.yaml");
  loop::FaultInjector inj({loop::parseFaultRequest(spec)}, s.rig.get(), *s.ctrl, s.hw);
  REQUIRE(s.boot());
  const double dt = s.sc.settings.dt;
  const long cycles = std::lround(seconds / dt);
  for (long k = 0; k < cycles; ++k) {
    inj.beforeCycle(static_cast<double>(k) * dt, s.now);
    s.cycle();
    inj.afterCycle();
  }
  Outcome o;
  o.record = inj.records().at(0);
  o.reason = s.ctrl->stopReason();
  o.flags = s.ctrl->stopFlags();
  o.robot_period = dt * s.hw.robots[0].divisor;
  o.heartbeat_timeout = s.hw.heartbeat_timeout_s;
  return o;
}

void checkTimes(const Outcome& o, double timeout) {
  INFO(o.record.kind << " on " << o.record.device << ": injected " << o.record.injected_at_s
                     << " s, detected " << o.record.detected_at_s << " s");
  REQUIRE(o.record.injected_at_s >= 0.0);
  REQUIRE(o.record.detected_at_s >= o.record.injected_at_s);
  CHECK(o.record.detected_at_s - o.record.injected_at_s <= timeout + 1e-9);
  // Safe commands in the cycle of detection (at most one loop cycle later).
  CHECK(o.record.safe_state_at_s - o.record.detected_at_s <= 0.001 + 1e-9);
}

}  // namespace

TEST_CASE("loop: fault: heartbeat loss", "[loop][faults]") {
  const Outcome o = runWithFault("heartbeat-loss@0.2:panda.panda_joint3");
  CHECK(o.record.device == "panda.panda_joint3");
  CHECK(o.reason == loop::StopReason::DriverFault);
  CHECK((o.flags & drivers::fault::kHeartbeatLost) != 0u);
  // The consumer time, plus the heartbeat period already running, plus the robot cycle that reads it.
  checkTimes(o, o.heartbeat_timeout + 0.1 + 2 * o.robot_period);
}

TEST_CASE("loop: fault: bus-off", "[loop][faults]") {
  const Outcome o = runWithFault("bus-off@0.2:arm1");
  CHECK(o.record.device == "arm1");
  CHECK(o.reason == loop::StopReason::DriverFault);
  CHECK((o.flags & drivers::fault::kBusOff) != 0u);
  checkTimes(o, 2 * o.robot_period);
}

TEST_CASE("loop: fault: frame loss", "[loop][faults]") {
  const Outcome o = runWithFault("frame-loss@0.2", 2.0);
  CHECK(o.record.device == "panda.panda_joint1");
  CHECK(o.reason == loop::StopReason::StaleSensor);
  // The loss rate is averaged over 100 robot cycles.
  checkTimes(o, 100 * o.robot_period);
}

TEST_CASE("loop: fault: corrupt frames", "[loop][faults]") {
  const Outcome o = runWithFault("corrupt-frames@0.2:panda.panda_finger_joint1");
  CHECK(o.reason == loop::StopReason::DriverFault);
  CHECK((o.flags & drivers::fault::kCorruptFrame) != 0u);
  checkTimes(o, 2 * o.robot_period);
}

TEST_CASE("loop: fault: NaN feedback", "[loop][faults]") {
  const Outcome o = runWithFault("nan-feedback@0.2:panda.panda_joint2");
  CHECK(o.reason == loop::StopReason::DriverFault);
  CHECK((o.flags & (drivers::fault::kEmcy | drivers::fault::kDeviceFault)) != 0u);
  checkTimes(o, 3 * o.robot_period);
}

TEST_CASE("loop: fault: infeasible", "[loop][faults]") {
  const Outcome o = runWithFault("infeasible@0.2");
  CHECK(o.reason == loop::StopReason::QpNotOptimal);
  checkTimes(o, 0.001);
}

TEST_CASE("loop: fault: stale F/T", "[loop][faults]") {
  const Outcome o = runWithFault("stale-ft@0.2:panda.panda_link8");
  CHECK(o.record.device == "panda.panda_link8");
  // The F/T driver's own missing-feedback check (stale samples are not fresh) or the loop's.
  CHECK((o.reason == loop::StopReason::DriverFault || o.reason == loop::StopReason::StaleSensor));
  CHECK((o.flags & drivers::fault::kFeedbackMissing) != 0u);
  // More than feedback_missing_cycles (3) robot cycles without a fresh sample.
  checkTimes(o, 5 * o.robot_period);
}

TEST_CASE("loop: fault specs are checked", "[loop][faults]") {
  CHECK_THROWS_WITH(loop::parseFaultRequest("melt@1"), Catch::Contains("unknown kind 'melt'"));
  CHECK_THROWS_WITH(loop::parseFaultRequest("bus-off"), Catch::Contains("expected KIND@SECONDS[:DEVICE]"));
  CHECK_THROWS_WITH(loop::parseFaultRequest("bus-off@x"), Catch::Contains("expected a time"));
  const loop::FaultRequest r = loop::parseFaultRequest("bus-off@1.5:arm0");
  CHECK(r.kind == "bus-off");
  CHECK(r.at_s == 1.5);
  CHECK(r.device == "arm0");
}

TEST_CASE("loop: safe stop: position drives hold with damping", "[loop][faults]") {
  LoopSetup s(looptest::sceneText("panda_door.yaml"), "panda_door.yaml");
  loop::FaultInjector inj({loop::parseFaultRequest("heartbeat-loss@0.2:panda.panda_joint3")}, s.rig.get(),
                          *s.ctrl, s.hw);
  REQUIRE(s.boot());
  const double dt = s.sc.settings.dt;
  std::vector<double> v_stop;
  long stop_cycle = -1;
  for (long k = 0; k < 1200; ++k) {
    inj.beforeCycle(static_cast<double>(k) * dt, s.now);
    s.cycle();
    if (s.ctrl->safeStopped() && stop_cycle < 0) {
      stop_cycle = k;
      v_stop = s.ctrl->robots()[0].v_cmd;
    }
  }
  REQUIRE(stop_cycle > 0);
  // The hold law: the commanded velocity decays by (1 − d·dt) per cycle from the cycle of the stop.
  const loop::RobotIo& r = s.ctrl->robots()[0];
  const double decay = std::pow(1.0 - r.hold_damping * dt, static_cast<double>(1199 - stop_cycle));
  for (std::size_t i = 0; i < r.joints.size(); ++i) {
    INFO(r.joints[i].name);
    CHECK(r.v_cmd[i] == Approx(v_stop[i] * decay).margin(1e-12));
  }
}

TEST_CASE("loop: safe stop: quick_stop robots' drives enter Quick stop active", "[loop][faults]") {
  const std::string text = loop::applySceneOverride(looptest::sceneText("panda_door.yaml"), "panda_door.yaml",
                                                    "hardware.robots[0].safe_stop=quick_stop");
  LoopSetup s(text, "panda_door.yaml");
  loop::FaultInjector inj({loop::parseFaultRequest("nan-feedback@0.2:panda.panda_joint3")}, s.rig.get(),
                          *s.ctrl, s.hw);
  REQUIRE(s.boot());
  for (long k = 0; k < 400; ++k) {
    inj.beforeCycle(static_cast<double>(k) * s.sc.settings.dt, s.now);
    s.cycle();
  }
  REQUIRE(s.ctrl->safeStopped());
  for (const char* j : {"panda.panda_joint1", "panda.panda_joint7", "panda.panda_finger_joint1"}) {
    INFO(j);
    CHECK(s.rig->drive(j)->state() == MRQP_FW_CIA402_QUICK_STOP_ACTIVE);
  }
  CHECK(s.rig->drive("panda.panda_joint3")->state() != MRQP_FW_CIA402_OPERATION_ENABLED);  // the faulted one
}
