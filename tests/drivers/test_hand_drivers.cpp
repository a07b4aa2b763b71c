// The MIT-mode hand driver and the CAN FD hand-board driver against fake devices.
#include <catch2/catch.hpp>

#include <mrqp/drivers/fd_hand_driver.hpp>
#include <mrqp/drivers/mit_hand_driver.hpp>

#include <cmath>
#include <memory>
#include <string>
#include <vector>

#include "fake_devices.hpp"
#include "sim_trace.hpp"
#include "single_bus_rig.hpp"

using namespace mrqp::drivers;
using drvtest::makeFrame;
using drvtest::WireLog;

namespace {

struct MitRig : drvtest::SingleBusRig<MitRig, MitHandDriver> {
  explicit MitRig(TimeNs cycle_period = milliseconds(2)) : SingleBusRig(false, cycle_period) {
    motors = std::make_unique<drvtest::FakeMitMotors>(*bus.addNode(SimNodeConfig{}));
    injector = bus.addNode(SimNodeConfig{});
    MitHandConfig c;
    for (std::uint8_t id = 1; id <= 3; ++id) {
      motors->add(id);
      MitMotorConfig m;
      m.motor_id = id;
      c.motors.push_back(m);
    }
    driver = MitHandDriver::create({router.get()}, c, &error);
  }
  std::unique_ptr<drvtest::FakeMitMotors> motors;
};

}  // namespace

TEST_CASE("drivers: MIT hand: zero-gain polling, enable until answered, impedance commands",
          "[drivers][hand]") {
  MitRig rig;
  REQUIRE(rig.driver != nullptr);
  rig.cycle();
  rig.bus.advanceTo(rig.t);
  // Disabled: p = 0, v = 0, kp = 0, kd = 0, t = 0 -> codes 0x8000, 0x800, 0, 0, 0x800.
  CHECK(rig.masterFrames(0) ==
        std::vector<std::string>{"001#8000800000000800", "002#8000800000000800", "003#8000800000000800"});
  // Replies: id, p 0x8000, v 0x800, t 0x800 (docs/protocol.md example).
  CHECK(rig.log.frames(static_cast<long>(1)) ==
        std::vector<std::string>{"000#018000800800", "000#028000800800", "000#038000800800"});
  rig.cycle();
  CHECK(rig.driver->motor(0).valid);
  CHECK(rig.driver->motor(0).position == Approx(1.9e-4).margin(1e-6));  // 0 is not a code
  CHECK(rig.driver->faults().flags == 0u);

  TimeNs t0 = rig.t;
  rig.hook = [](MitRig& r) {
    r.driver->requestEnable(r.t);
    r.hook = nullptr;
  };
  rig.cycle();
  CHECK(rig.driver->motor(0).mode == MitMode::Enabling);
  rig.cycle();
  CHECK(rig.driver->allOn());
  CHECK(rig.motors->enabled(1));
  auto frames = rig.masterFrames(t0);
  REQUIRE(frames.size() >= 3u);
  CHECK(frames[0] == "001#FFFFFFFFFFFFFFFC");
  CHECK(frames[2] == "003#FFFFFFFFFFFFFFFC");

  // The protocol's example command: p 0, v 0, kp 100, kd 1, t 0 -> 80 00 80 03 33 33 38 00.
  t0 = rig.t;
  rig.hook = [](MitRig& r) {
    const mrqp_fw_mit_cmd c{0.0f, 0.0f, 100.0f, 1.0f, 0.0f};
    CHECK(r.driver->setCommand(0, c) == SetpointResult::Ok);
  };
  rig.cycle();
  frames = rig.masterFrames(t0);
  REQUIRE(!frames.empty());
  CHECK(frames[0] == "001#8000800333333800");

  // NaN is refused and never sent: the previous command stays.
  t0 = rig.t;
  rig.hook = [](MitRig& r) {
    const mrqp_fw_mit_cmd c{NAN, 0.0f, 100.0f, 1.0f, 0.0f};
    CHECK(r.driver->setCommand(0, c) == SetpointResult::Refused);
    r.hook = nullptr;
  };
  rig.cycle();
  const FaultReport& rep = rig.cycle();
  CHECK((rep.devices[0].flags & fault::kSetpointRefused) != 0u);
  CHECK(rep.devices[0].refused_setpoints == 1u);
  REQUIRE(!rig.masterFrames(t0).empty());
  CHECK(rig.masterFrames(t0)[0] == "001#8000800333333800");
  // Beyond the wire range: clamped and flagged (kp 600 > 500).
  rig.hook = [](MitRig& r) {
    const mrqp_fw_mit_cmd c{0.0f, 0.0f, 600.0f, 1.0f, 0.0f};
    CHECK(r.driver->setCommand(1, c) == SetpointResult::Limited);
    r.hook = nullptr;
  };
  rig.cycle();
  CHECK((rig.cycle().devices[1].flags & fault::kSetpointLimited) != 0u);

  // Disable: exit motor mode until answered.
  t0 = rig.t;
  rig.hook = [](MitRig& r) {
    r.driver->requestDisable(r.t);
    r.hook = nullptr;
  };
  rig.cycle();
  rig.cycle();
  CHECK(rig.driver->allOff());
  CHECK(!rig.motors->enabled(2));
  REQUIRE(rig.masterFrames(t0).size() >= 2u);
  CHECK(rig.masterFrames(t0)[1] == "002#FFFFFFFFFFFFFFFD");
}

TEST_CASE("drivers: MIT hand: missing replies, corrupted and unknown replies", "[drivers][hand]") {
  MitRig rig;
  REQUIRE(rig.driver != nullptr);
  for (int k = 0; k < 3; ++k) {
    rig.cycle();
  }
  rig.motors->setSilent(2, true);
  CHECK(rig.cycle().devices[1].missed_cycles == 1u);
  CHECK(rig.cycle().devices[1].missed_cycles == 2u);
  const FaultReport& r = rig.cycle();
  CHECK((r.devices[1].flags & fault::kFeedbackMissing) != 0u);
  CHECK(r.devices[0].flags == 0u);
  rig.motors->setSilent(2, false);
  rig.cycle();
  CHECK(rig.cycle().flags == 0u);

  // Injected at a quiet moment of the cycle (replies use identifier 0x000 too).
  const TimeNs quiet = rig.last + microseconds(1200);
  REQUIRE(rig.injector->sendAt(makeFrame(0x000, {0x01, 0x80, 0x00, 0x80}), quiet) ==
          SendResult::Ok);  // DLC 4
  REQUIRE(rig.injector->sendAt(makeFrame(0x000, {0x05, 0x80, 0x00, 0x80, 0x08, 0x00}), quiet) ==
          SendResult::Ok);
  REQUIRE(rig.injector->sendAt(makeFrame(0x000, {}), quiet) == SendResult::Ok);
  REQUIRE(rig.injector->sendAt(makeFrame(0x055, {1}), quiet) == SendResult::Ok);
  const FaultReport& r2 = rig.cycle();
  CHECK(r2.devices[0].corrupt_frames == 1u);
  CHECK((r2.devices[0].flags & fault::kCorruptFrame) != 0u);
  CHECK(r2.buses[0].rejected_frames == 3u);  // motor 1's short reply, motor 5 (unknown), empty
  CHECK(r2.buses[0].unknown_frames == 1u);   // 0x055 is nobody's
  CHECK(rig.driver->motor(0).position == Approx(1.9e-4).margin(1e-6));

  // A position beyond the +/-12.5 rad wire range comes back saturated: out of range.
  rig.motors->setPosition(3, 20.0f);
  rig.cycle();
  const FaultReport& r3 = rig.cycle();
  CHECK((r3.devices[2].flags & fault::kOutOfRange) != 0u);
  CHECK(rig.driver->motor(2).position == Approx(12.5f));

  BusBudget b(BusSpec{"hand", 1000000, 0, 1000.0, 0.8});
  rig.driver->declareTraffic(0, b);
  CHECK(b.result().nominal_bits_worst == Approx(3 * 250.0));
}

namespace {

struct FdRig : drvtest::SingleBusRig<FdRig, FdHandDriver> {
  FdRig() : SingleBusRig(true, milliseconds(1)) {
    SimNodeConfig bcfg;
    bcfg.fd = true;
    board = std::make_unique<drvtest::FakeHandBoard>(*bus.addNode(bcfg), 2, 20);
    injector = bus.addNode(bcfg);
    FdHandConfig c;
    HandBoardConfig h;
    h.board = 2;
    h.joints = 20;
    c.boards.push_back(h);
    driver = FdHandDriver::create({router.get()}, c, &error);
  }
  std::unique_ptr<drvtest::FakeHandBoard> board;
};

}  // namespace

TEST_CASE("drivers: FD hand board: two 64-byte frames each way per cycle for 20 joints", "[drivers][hand]") {
  FdRig rig;
  REQUIRE(rig.driver != nullptr);
  rig.cycle();
  rig.cycle();
  rig.bus.advanceTo(rig.t);
  std::vector<WireEvent> ev;
  for (const auto& e : rig.log.events) {
    if (e.start >= rig.last) {
      ev.push_back(e);
    }
  }
  REQUIRE(ev.size() == 4u);
  // Commands: seq 2 (BE), version 1 | mode 0 (disabled), first 0 / 11, count 11 / 9.
  CHECK(ev[0].frame.id == 0x122u);
  CHECK(ev[0].frame.len == 64u);
  CHECK(ev[0].frame.flags == (MRQP_FW_FRAME_FD | MRQP_FW_FRAME_BRS));
  CHECK(ev[0].frame.data[0] == 0x00);
  CHECK(ev[0].frame.data[1] == 0x02);
  CHECK(ev[0].frame.data[2] == 0x10);
  CHECK(ev[0].frame.data[3] == 0);
  CHECK(ev[0].frame.data[4] == 11);
  CHECK(ev[1].frame.id == 0x122u);
  CHECK(ev[1].frame.data[3] == 11);
  CHECK(ev[1].frame.data[4] == 9);
  // Feedback: 0x142, 64 bytes each, after the commands; 169.6 us per frame (worst case).
  CHECK(ev[2].frame.id == 0x142u);
  CHECK(ev[3].frame.id == 0x142u);
  CHECK(ev[3].frame.len == 64u);
  CHECK(ev[0].end - ev[0].start == 169600);
  rig.cycle();
  const HandBoardState& s = rig.driver->board(0);
  CHECK(s.valid);
  CHECK(s.fresh);
  CHECK(s.mode == MRQP_FW_HAND_MODE_DISABLED);
  CHECK(s.seq_echo == 2u);
  CHECK(rig.driver->faults().flags == 0u);
}

TEST_CASE("drivers: FD hand board: enable, setpoints, NaN refused, limits", "[drivers][hand]") {
  FdRig rig;
  REQUIRE(rig.driver != nullptr);
  rig.cycle();
  rig.hook = [](FdRig& r) {
    r.driver->requestEnable(r.t);
    r.hook = nullptr;
  };
  rig.cycle();
  rig.cycle();
  CHECK(rig.driver->allEnabled());
  CHECK(rig.board->mode() == MRQP_FW_HAND_MODE_POSITION);
  rig.hook = [](FdRig& r) {
    CHECK(r.driver->setJoint(0, 5, 0.25f, 0.0f, 0.1f) == SetpointResult::Ok);
    CHECK(r.driver->setJoint(0, 19, -1.0f, 0.5f, 0.0f) == SetpointResult::Ok);
    CHECK(r.driver->setJoint(0, 20, 0.0f, 0.0f, 0.0f) == SetpointResult::BadIndex);
  };
  rig.cycle();
  rig.cycle();
  CHECK(rig.board->position(5) == Approx(0.25f).margin(5e-5));
  CHECK(rig.driver->joint(0, 5).position == Approx(0.25f).margin(5e-5));
  CHECK(rig.driver->joint(0, 19).position == Approx(-1.0f).margin(5e-5));
  CHECK(rig.driver->joint(0, 19).velocity == Approx(0.5f).margin(0.01));
  rig.hook = [](FdRig& r) {
    CHECK(r.driver->setJoint(0, 5, NAN, 0.0f, 0.0f) == SetpointResult::Refused);
    CHECK(r.driver->setJoint(0, 6, 10.0f, 0.0f, 0.0f) == SetpointResult::Limited);
    r.hook = nullptr;
  };
  rig.cycle();
  const FaultReport& r = rig.cycle();
  CHECK((r.devices[0].flags & (fault::kSetpointRefused | fault::kSetpointLimited)) ==
        (fault::kSetpointRefused | fault::kSetpointLimited));
  CHECK(rig.board->position(5) == Approx(0.25f).margin(5e-5));    // NaN never sent
  CHECK(rig.board->position(6) == Approx(3.2767f).margin(5e-5));  // clamped to the wire range
}

TEST_CASE("drivers: FD hand board: lost, corrupted, missing and stale feedback, board faults",
          "[drivers][hand]") {
  FdRig rig;
  REQUIRE(rig.driver != nullptr);
  for (int k = 0; k < 3; ++k) {
    rig.cycle();
  }
  REQUIRE(rig.driver->faults().flags == 0u);
  rig.board->skipCounter(3);  // 3 feedback frames lost
  const FaultReport& r1 = rig.cycle();
  CHECK((r1.devices[0].flags & fault::kSampleLost) != 0u);
  CHECK(r1.devices[0].lost_samples == 3u);

  // A feedback frame with a broken CRC, injected when the bus is quiet: dropped and counted.
  mrqp_fw_hand_fb fb{};
  fb.count = 1;
  fb.first_joint = 0;
  mrqp_fw_hand_scale scale = MRQP_FW_HAND_SCALE_DEFAULT_INIT;
  mrqp_fw_frame f;
  REQUIRE(!mrqp_fw_pack_failed(mrqp_fw_hand_pack_fb(&scale, 2, &fb, &f, nullptr)));
  f.data[8] ^= 0x01;
  REQUIRE(rig.injector->sendAt(f, rig.last + microseconds(800)) == SendResult::Ok);
  const FaultReport& r2 = rig.cycle();
  CHECK(r2.devices[0].corrupt_frames == 1u);
  CHECK(r2.buses[0].rejected_frames == 1u);

  rig.board->setSilent(true);
  rig.cycle();
  rig.cycle();
  CHECK((rig.cycle().devices[0].flags & fault::kFeedbackMissing) != 0u);
  rig.board->setSilent(false);
  rig.cycle();
  CHECK(rig.cycle().flags == 0u);

  // A board that stops applying commands: its sequence echo lags behind.
  rig.board->setFrozen(true);
  rig.cycle();                                     // lag 1
  CHECK(!rig.cycle().has(fault::kStateMismatch));  // lag 2 = max_seq_lag
  CHECK((rig.cycle().devices[0].flags & fault::kStateMismatch) != 0u);
  rig.board->setFrozen(false);
  rig.cycle();
  CHECK(rig.cycle().flags == 0u);

  // Status bits: fault, over-temperature.
  rig.board->setStatusExtra(MRQP_FW_HAND_STATUS_FAULT | MRQP_FW_HAND_STATUS_OVER_TEMPERATURE);
  rig.cycle();
  const FaultReport& r3 = rig.cycle();
  CHECK((r3.devices[0].flags & (fault::kDeviceFault | fault::kDeviceWarning)) ==
        (fault::kDeviceFault | fault::kDeviceWarning));
}

TEST_CASE("drivers: FD hand driver refuses a classic bus", "[drivers][hand]") {
  SimBus classic;
  SimNodeConfig mc;
  mc.fd = true;
  SimNode* m = classic.addNode(mc);
  BusRouter router(*m);
  FdHandConfig c;
  c.boards.push_back(HandBoardConfig{});
  std::string err;
  CHECK(FdHandDriver::create({&router}, c, &err) == nullptr);
  CHECK_THAT(err, Catch::Matchers::Contains("is not CAN FD enabled"));
}
