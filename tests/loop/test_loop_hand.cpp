// Hand actuators in the loop (docs/loop.md, "The hardware section"): the Panda's finger as an
// MIT-mode motor on a classic bus of its own, or as a joint of a CAN FD hand board, beside the
// arm's CiA 402 drives. The loop boots and enables them, writes their command every robot cycle
// (the emulated firmware receives exactly what the controller commanded), the finger follows its
// task in the plant as the model run does, and a silent motor or a faulted board stops the
// controller as a driver fault naming the joint.
#include <catch2/catch.hpp>

#include <cmath>
#include <string>

#include "loop/fault_injector.hpp"
#include "loop/solution_integrator.hpp"
#include "loop_setup.hpp"

using namespace mrqp;
using looptest::LoopSetup;

namespace {

// panda_reach with a task that opens the gripper from 0.02 to 0.035 m; `hand` is the hand part
// of the hardware section.
std::string handScene(const std::string& hand_bus, const std::string& hand) {
  return looptest::sceneText("panda_reach.yaml") +
         "  - {name: grip, type: joint, entity: panda, joint: panda_finger_joint1, weight: 10, stiffness: "
         "4,\n"
         "     target: [0.035]}\n"
         "hardware:\n"
         "  buses:\n"
         "    - {name: arm0, bitrate: 1000000}\n"
         "    - {name: arm1, bitrate: 1000000}\n" +
         hand_bus +
         "  robots:\n"
         "    - entity: panda\n"
         "      divisor: 4\n"
         "      cia402:\n"
         "        - {bus: arm0, mode: csp, first_node: 1,\n"
         "           joints: [panda_joint1, panda_joint2, panda_joint3, panda_joint4, panda_joint5]}\n"
         "        - {bus: arm1, mode: csp, first_node: 6, joints: [panda_joint6, panda_joint7]}\n" +
         hand;
}

const std::string kMitBus = "    - {name: hand, bitrate: 1000000}\n";
const std::string kMit =
    "      mit:\n        - {bus: hand, first_id: 3, joints: [panda_finger_joint1], kp: 200, kd: 2}\n";
const std::string kFdBus = "    - {name: hand, bitrate: 1000000, data_bitrate: 5000000}\n";
const std::string kFd = "      fd:\n        - {bus: hand, board: 2, joints: [panda_finger_joint1]}\n";

/// The finger's final opening in the model run (the problem as its own plant).
double modelRunFinger(const std::string& text, long cycles) {
  scene::ModelRegistry models;
  scene::addBuiltinModels(models);
  scene::Scene sc = scene::buildScene(scene::loadSceneString(text, "hand.yaml"), models);
  auto& p = *sc.problem;
  for (long k = 0; k < cycles; ++k) {
    p.update();
    REQUIRE(p.solve() == qp::QpStatus::Optimal);
    loop::integrateSolution(p, sc.settings.dt);
  }
  const problem::Entity& e = p.entity(p.entityIndex("panda"));
  return e.q()(e.qIndexOfV(e.jointIndex("panda_finger_joint1")));
}

double plantFinger(LoopSetup& s) {
  return s.plant->jointPosition(s.plant->jointHandle("panda", "panda_finger_joint1"));
}

const loop::JointIo& fingerIo(LoopSetup& s) {
  for (const loop::JointIo& j : s.ctrl->robots().at(0).joints) {
    if (j.name == "panda.panda_finger_joint1") return j;
  }
  FAIL("no finger joint in the I/O map");
  return s.ctrl->robots().at(0).joints.at(0);
}

/// The finger reached its target in the plant as the model run did: the grip task's final error
/// within 2e-3 m of the model run's (the criterion of test_loop's comparisons: the loop sees the
/// arm through 19-bit encoders and the finger through the actuator's 16-bit position and 12-bit
/// velocity codes, one robot cycle of 4 ms late; the model run has its exact state every 1 ms —
/// measured: 0.0353 (MIT) and 0.0353 (hand board) against 0.0336 after 2 s), and the plant's
/// finger at the controller's command (the joint tracking error).
void checkFinger(LoopSetup& s, const std::string& text, long cycles) {
  const double target = 0.035;
  const double model = modelRunFinger(text, cycles);
  const double plant = plantFinger(s);
  INFO("finger: plant " << plant << " m, model run " << model << " m, target " << target << " m");
  CHECK(model - 0.02 > 0.8 * (target - 0.02));  // the task moved the finger
  CHECK(std::fabs(std::fabs(plant - target) - std::fabs(model - target)) <= 2e-3);
  for (const loop::RobotIo& r : s.ctrl->robots()) {
    INFO(r.name << ": tracking error " << r.tracking_error_max);
    CHECK(r.tracking_error_max < 1e-4);
  }
}

}  // namespace

TEST_CASE("loop: hand: the finger as an MIT motor follows its task, commanded every robot cycle",
          "[loop][hand]") {
  const std::string text = handScene(kMitBus, kMit);
  LoopSetup s(text, "hand.yaml");
  const loop::JointIo& io = fingerIo(s);
  CHECK(io.kind == loop::JointKind::Impedance);
  CHECK(std::string(io.device->kind()) == "mit_hand");
  emulation::EmulatedMitMotor* motor = s.rig->mitMotor("panda.panda_finger_joint1");
  REQUIRE(motor != nullptr);
  CHECK(motor->motorId() == 3);
  REQUIRE(s.boot());
  CHECK(motor->enabled());
  const unsigned frames0 = motor->frames();
  const long cycles = 2000;
  for (long k = 0; k < cycles; ++k) {
    s.cycle();
    if (k > 0 && k % 4 == 1) {
      // The command of the last robot cycle arrived as sent: the motor's servo is the controller's
      // command to the MIT frame's resolution (16 bits over ±12.5 rad, 12 bits over 0..500 N·m/rad).
      const std::size_t i = static_cast<std::size_t>(&io - s.ctrl->robots()[0].joints.data());
      INFO("cycle " << k);
      REQUIRE(std::fabs(motor->servo().position - s.ctrl->robots()[0].q_cmd[i]) < 25.0 / 65535.0);
      REQUIRE(std::fabs(motor->servo().kp - 200.0) < 500.0 / 4095.0);
    }
  }
  REQUIRE_FALSE(s.ctrl->safeStopped());
  CHECK(motor->frames() - frames0 == static_cast<unsigned>(cycles / 4));
  checkFinger(s, text, cycles);
}

TEST_CASE("loop: hand: the finger on a CAN FD hand board follows its task", "[loop][hand]") {
  const std::string text = handScene(kFdBus, kFd);
  LoopSetup s(text, "hand.yaml");
  const loop::JointIo& io = fingerIo(s);
  CHECK(std::string(io.device->kind()) == "fd_hand");
  emulation::EmulatedHandBoard* board = s.rig->handBoard("panda.panda_finger_joint1");
  REQUIRE(board != nullptr);
  REQUIRE(s.boot());
  CHECK(board->mode() == MRQP_FW_HAND_MODE_POSITION);
  const unsigned commands0 = board->commands();
  const long cycles = 2000;
  for (long k = 0; k < cycles; ++k) s.cycle();
  REQUIRE_FALSE(s.ctrl->safeStopped());
  CHECK(board->commands() - commands0 == static_cast<unsigned>(cycles / 4));
  checkFinger(s, text, cycles);
}

TEST_CASE("loop: hand: a silent MIT motor stops the controller as a driver fault", "[loop][hand][faults]") {
  LoopSetup s(handScene(kMitBus, kMit), "hand.yaml");
  REQUIRE(s.boot());
  for (int k = 0; k < 200; ++k) s.cycle();
  REQUIRE_FALSE(s.ctrl->safeStopped());
  s.rig->mitMotor("panda.panda_finger_joint1")->setSilent(true);
  const std::uint64_t silent_at = s.ctrl->cycles();
  for (int k = 0; k < 100 && !s.ctrl->safeStopped(); ++k) s.cycle();
  REQUIRE(s.ctrl->safeStopped());
  CHECK(s.ctrl->stopReason() == loop::StopReason::DriverFault);
  CHECK((s.ctrl->stopFlags() & drivers::fault::kFeedbackMissing) != 0u);
  CHECK(s.ctrl->stopDevice() == "panda.panda_finger_joint1");
  // Missing for more than feedback_missing_cycles robot cycles, read at the next robot cycle.
  CHECK(s.ctrl->stopCycle() - silent_at <=
        static_cast<std::uint64_t>(4 * (s.hw.feedback_missing_cycles + 2)));
}

TEST_CASE("loop: hand: a faulted hand board stops the controller as a driver fault", "[loop][hand][faults]") {
  LoopSetup s(handScene(kFdBus, kFd), "hand.yaml");
  REQUIRE(s.boot());
  for (int k = 0; k < 200; ++k) s.cycle();
  REQUIRE_FALSE(s.ctrl->safeStopped());
  s.rig->handBoard("panda.panda_finger_joint1")->raiseFault(s.now);
  const std::uint64_t fault_at = s.ctrl->cycles();
  for (int k = 0; k < 100 && !s.ctrl->safeStopped(); ++k) s.cycle();
  REQUIRE(s.ctrl->safeStopped());
  CHECK(s.ctrl->stopReason() == loop::StopReason::DriverFault);
  CHECK((s.ctrl->stopFlags() & drivers::fault::kDeviceFault) != 0u);
  CHECK(s.ctrl->stopDevice() == "panda.panda_finger_joint1");
  CHECK(s.ctrl->stopCycle() - fault_at <= 8u);
}

TEST_CASE("loop: hand: --fault on a hand actuator's joint is injected in its firmware and detected",
          "[loop][hand][faults]") {
  struct Case {
    const std::string* bus;
    const std::string* hand;
    const char* spec;
    std::uint32_t flag;
  };
  const Case cases[] = {
      {&kMitBus, &kMit, "corrupt-frames@0.2:panda.panda_finger_joint1", drivers::fault::kCorruptFrame},
      {&kMitBus, &kMit, "heartbeat-loss@0.2:panda.panda_finger_joint1", drivers::fault::kFeedbackMissing},
      {&kFdBus, &kFd, "nan-feedback@0.2:panda.panda_finger_joint1", drivers::fault::kDeviceFault},
  };
  for (const Case& c : cases) {
    INFO(c.spec);
    LoopSetup s(handScene(*c.bus, *c.hand), "hand.yaml");
    loop::FaultInjector inj({loop::parseFaultRequest(c.spec)}, s.rig.get(), *s.ctrl, s.hw);
    REQUIRE(s.boot());
    const double dt = s.sc.settings.dt;
    for (long k = 0; k < 400; ++k) {
      inj.beforeCycle(static_cast<double>(k) * dt, s.now);
      s.cycle();
      inj.afterCycle();
    }
    const loop::FaultRecord& r = inj.records().at(0);
    CHECK(r.device == "panda.panda_finger_joint1");
    CHECK(s.ctrl->stopReason() == loop::StopReason::DriverFault);
    CHECK((s.ctrl->stopFlags() & c.flag) != 0u);
    REQUIRE(r.detected_at_s >= r.injected_at_s);
    // Within feedback_missing_cycles + 2 robot cycles of 4 ms; safe commands in the same cycle.
    CHECK(r.detected_at_s - r.injected_at_s <= 0.004 * (s.hw.feedback_missing_cycles + 2) + 1e-9);
    CHECK(r.safe_state_at_s - r.detected_at_s <= 0.001 + 1e-9);
  }
  LoopSetup s(handScene(kMitBus, kMit), "hand.yaml");
  CHECK_THROWS_WITH(loop::FaultInjector({loop::parseFaultRequest("frame-loss@0.2:panda.panda_finger_joint1")},
                                        s.rig.get(), *s.ctrl, s.hw),
                    Catch::Contains("not emulated for MIT motors and hand boards"));
}

TEST_CASE("loop: hand: MIT motors need a bus of their own, hand boards a CAN FD bus", "[loop][hand]") {
  auto errorOf = [](const std::string& text) -> std::string {
    try {
      LoopSetup s(text, "hand.yaml");
    } catch (const std::exception& e) {
      return e.what();
    }
    return "(no error)";
  };
  // The MIT motor on the bus of CiA 402 drives: its replies (identifier 0x000) are NMT commands there.
  std::string mit_on_arm =
      handScene("", "      mit:\n        - {bus: arm1, first_id: 3, joints: [panda_finger_joint1]}\n");
  CHECK_THAT(errorOf(mit_on_arm), Catch::Contains("hand.yaml:") && Catch::Contains("mit") &&
                                      Catch::Contains("a bus of their own"));
  CHECK_THAT(errorOf(handScene(
                 kMitBus, "      fd:\n        - {bus: hand, board: 0, joints: [panda_finger_joint1]}\n")),
             Catch::Contains("hand.yaml:") && Catch::Contains("data_bitrate"));
  // The MIT frame's ranges bound the gains (firmware_if/mit_frame.h: kp 0..500).
  CHECK_THAT(
      errorOf(handScene(kMitBus,
                        "      mit:\n        - {bus: hand, first_id: 3, joints: [panda_finger_joint1], "
                        "kp: 600}\n")),
      Catch::Contains("hand.yaml:") && Catch::Contains(".kp: above 500"));
}
