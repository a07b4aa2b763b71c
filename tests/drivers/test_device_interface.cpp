// The four drivers through the shared device interface (device.hpp): two identical rigs, one
// driven through the driver's own named methods (setPosition / setTorque, setCommand,
// setJoint(board, joint, ...), sensor()), the other only through JointDevice / WrenchDevice;
// every frame on the wire (the master's and the fake devices') must be the same, and the
// interface's feedback must be the driver's own state.
#include <catch2/catch.hpp>

#include <mrqp/drivers/arm_driver.hpp>
#include <mrqp/drivers/device.hpp>
#include <mrqp/drivers/fd_hand_driver.hpp>
#include <mrqp/drivers/ft_sensor_driver.hpp>
#include <mrqp/drivers/mit_hand_driver.hpp>

#include <algorithm>
#include <cmath>
#include <memory>
#include <string>
#include <vector>

#include "arm_rig.hpp"
#include "fake_devices.hpp"
#include "sim_trace.hpp"
#include "single_bus_rig.hpp"

using namespace mrqp::drivers;

namespace {

/// A setpoint that changes every cycle (rad, rad/s, N m).
double wave(int k, double amplitude, double phase) {
  return amplitude * std::sin(0.05 * static_cast<double>(k) + phase);
}

drvtest::ArmRig makeArm() {
  ArmConfig c;
  c.cycle_period = milliseconds(1);
  ArmDriveConfig csp;
  csp.torque_limit = 50.0;
  ArmDriveConfig cst = csp;
  cst.mode = MRQP_FW_MODE_CST;
  c.drives = {csp, cst};
  return drvtest::ArmRig({{0, 1}, {0, 2}}, c);
}

struct MitRig : drvtest::SingleBusRig<MitRig, MitHandDriver> {
  MitRig() : SingleBusRig(false, milliseconds(1)) {
    motors = std::make_unique<drvtest::FakeMitMotors>(*bus.addNode(SimNodeConfig{}));
    MitHandConfig c;
    for (std::uint8_t id = 1; id <= 3; ++id) {
      motors->add(id);
      MitMotorConfig m;
      m.motor_id = id;
      m.default_kp = 20.0f;
      m.default_kd = 0.5f;
      m.quick_stop_kd = 2.0f;
      c.motors.push_back(m);
    }
    driver = MitHandDriver::create({router.get()}, c, &error);
  }
  std::unique_ptr<drvtest::FakeMitMotors> motors;
};

struct FdRig : drvtest::SingleBusRig<FdRig, FdHandDriver> {
  explicit FdRig(std::uint8_t mode) : SingleBusRig(true, milliseconds(1)) {
    SimNodeConfig bcfg;
    bcfg.fd = true;
    board_a = std::make_unique<drvtest::FakeHandBoard>(*bus.addNode(bcfg), 2, 7);
    board_b = std::make_unique<drvtest::FakeHandBoard>(*bus.addNode(bcfg), 5, 13);
    FdHandConfig c;
    c.enabled_mode = mode;
    HandBoardConfig h;
    h.board = 2;
    h.joints = 7;
    c.boards.push_back(h);
    h.board = 5;
    h.joints = 13;
    c.boards.push_back(h);
    driver = FdHandDriver::create({router.get()}, c, &error);
  }
  std::unique_ptr<drvtest::FakeHandBoard> board_a;
  std::unique_ptr<drvtest::FakeHandBoard> board_b;
};

struct FtRig : drvtest::SingleBusRig<FtRig, FtSensorDriver> {
  FtRig() : SingleBusRig(false, milliseconds(1)) {
    sensor = std::make_unique<drvtest::FakeFtSensor>(*bus.addNode(SimNodeConfig{}), 0x30, false);
    FtConfig c;
    c.produce_sync = true;
    FtSensorConfig s;
    s.node = 0x30;
    c.sensors.push_back(s);
    driver = FtSensorDriver::create({router.get()}, c, &error);
  }
  std::unique_ptr<drvtest::FakeFtSensor> sensor;
};

}  // namespace

TEST_CASE(
    "drivers: device interface: the arm through JointDevice sends the frames of set_position/set_torque",
    "[drivers][device]") {
  drvtest::ArmRig named = makeArm();
  drvtest::ArmRig face = makeArm();
  REQUIRE(named.arm != nullptr);
  REQUIRE(face.arm != nullptr);
  JointDevice& dev = *face.arm;
  CHECK(std::string(dev.kind()) == "arm");
  REQUIRE(dev.jointCount() == 2u);
  CHECK(dev.jointMode(0) == JointMode::Position);
  CHECK(dev.jointMode(1) == JointMode::Torque);
  CHECK(dev.setJoint(2, JointCommand{}) == SetpointResult::BadIndex);

  CHECK(named.boot() == face.boot());
  CHECK(face.arm->phase() == ArmPhase::Running);
  CHECK_FALSE(dev.ready());
  named.arm->requestEnable(named.t);
  dev.requestEnable(face.t);
  int k = 0;
  named.hook = [&k](drvtest::ArmRig& r) {
    if (r.arm->allEnabled()) {
      (void)r.arm->setPosition(0, wave(k, 0.5, 0.0));
      (void)r.arm->setTorque(0, wave(k, 2.0, 1.0));
      (void)r.arm->setTorque(1, wave(k, 3.0, 2.0));
    }
  };
  face.hook = [&k](drvtest::ArmRig& r) {
    JointDevice& d = *r.arm;
    if (d.ready()) {
      JointCommand c;
      c.position = wave(k, 0.5, 0.0);
      c.velocity = 1.0;  // not on the wire of the arm
      c.torque = wave(k, 2.0, 1.0);
      (void)d.setJoint(0, c);
      JointCommand t;
      t.position = 3.0;  // ignored in CST
      t.torque = wave(k, 3.0, 2.0);
      (void)d.setJoint(1, t);
    }
  };
  bool was_ready = false;
  for (k = 0; k < 200; ++k) {
    named.cycle();
    face.cycle();
    was_ready = was_ready || dev.ready();
  }
  CHECK(was_ready);
  CHECK(face.arm->allEnabled());
  const auto wire_named = named.wire();
  const auto wire_face = face.wire();
  CHECK(wire_named.size() > 400u);
  CHECK(wire_named == wire_face);
  // Not vacuous: the drives received the setpoints.
  CHECK(face.fakes[0]->targetPosition() != 0);
  CHECK(face.fakes[1]->targetTorque() != 0);
  for (std::size_t i = 0; i < 2; ++i) {
    const JointFeedback fb = dev.joint(i);
    const ArmDriveState& s = face.arm->drive(i);
    CHECK(fb.valid == s.valid);
    CHECK(fb.fresh == s.fresh);
    CHECK(fb.position == s.position);
    CHECK(fb.velocity == s.velocity);
    CHECK(fb.torque == s.torque);
    CHECK(fb.timestamp == s.timestamp);
  }
  CHECK_FALSE(dev.joint(2).valid);
  // Quick stop through the interface: the drives leave Operation enabled, as with the named call.
  named.arm->requestQuickStop(named.t);
  dev.requestQuickStop(face.t);
  for (int n = 0; n < 10; ++n) {
    named.cycle();
    face.cycle();
  }
  CHECK(named.wire() == face.wire());
  CHECK_FALSE(dev.ready());
  CHECK(dev.faults().cycle == face.arm->faults().cycle);
}

TEST_CASE("drivers: device interface: the MIT hand through JointDevice sends the frames of set_command",
          "[drivers][device][hand]") {
  MitRig named;
  MitRig face;
  REQUIRE(named.driver != nullptr);
  REQUIRE(face.driver != nullptr);
  JointDevice& dev = *face.driver;
  CHECK(std::string(dev.kind()) == "mit_hand");
  REQUIRE(dev.jointCount() == 3u);
  CHECK(dev.jointMode(2) == JointMode::Impedance);
  int k = 0;
  named.hook = [&k](MitRig& r) {
    if (k == 2) {
      r.driver->requestEnable(r.t);
    }
    for (std::size_t i = 0; i < 3; ++i) {
      const float p = static_cast<float>(wave(k, 1.0, static_cast<double>(i)));
      // Motor 0 with explicit gains, the others with the defaults of the configuration.
      const mrqp_fw_mit_cmd c{p, 0.25f, i == 0 ? 50.0f : 20.0f, i == 0 ? 1.5f : 0.5f, -0.5f};
      (void)r.driver->setCommand(i, c);
    }
  };
  face.hook = [&k](MitRig& r) {
    JointDevice& d = *r.driver;
    if (k == 2) {
      d.requestEnable(r.t);
    }
    for (std::size_t i = 0; i < 3; ++i) {
      JointCommand c;
      c.position = wave(k, 1.0, static_cast<double>(i));
      c.velocity = 0.25;
      c.torque = -0.5;
      if (i == 0) {
        c.stiffness = 50.0;
        c.damping = 1.5;
      }
      (void)d.setJoint(i, c);
    }
  };
  for (k = 0; k < 60; ++k) {
    named.cycle();
    face.cycle();
  }
  CHECK(dev.ready());
  named.bus.advanceTo(named.t);
  face.bus.advanceTo(face.t);
  CHECK(named.log.frames().size() > 300u);
  CHECK(named.log.frames() == face.log.frames());
  CHECK(face.motors->position(1) != 0.0f);
  for (std::size_t i = 0; i < 3; ++i) {
    const JointFeedback fb = dev.joint(i);
    const MitMotorState& s = face.driver->motor(i);
    CHECK(fb.valid);
    CHECK(fb.position == static_cast<double>(s.position));
    CHECK(fb.velocity == static_cast<double>(s.velocity));
    CHECK(fb.torque == static_cast<double>(s.torque));
    CHECK(fb.timestamp == s.timestamp);
  }
  // Quick stop: damping only at the measured position, later setpoints ignored.
  const TimeNs t0 = face.t;
  face.hook = [](MitRig& r) {
    JointCommand c;
    c.position = 1.0;
    c.stiffness = 100.0;
    (void)r.driver->setJoint(0, c);
  };
  const float held = face.driver->motor(0).position;
  dev.requestQuickStop(face.t);
  CHECK(face.driver->quickStopped());
  face.cycle();
  face.cycle();
  face.bus.advanceTo(face.t);
  const auto frames = face.log.frames(static_cast<long>(face.master->index()), t0);
  REQUIRE(frames.size() >= 3u);
  mrqp_fw_frame f{};
  f.id = 1;
  f.len = 8;
  const mrqp_fw_mit_ranges ranges = MRQP_FW_MIT_RANGES_DEFAULT_INIT;
  mrqp_fw_mit_cmd expect{};
  expect.p = held;
  expect.kd = 2.0f;
  (void)mrqp_fw_mit_pack_cmd(&ranges, 1, &expect, &f);
  CHECK(frames.back().substr(0, 3) == "003");
  CHECK(std::find(frames.begin(), frames.end(), drvtest::frameStr(f)) != frames.end());
}

TEST_CASE("drivers: device interface: the FD hand's flat joint index runs over every board in order",
          "[drivers][device][hand]") {
  for (const std::uint8_t mode :
       {std::uint8_t{MRQP_FW_HAND_MODE_POSITION}, std::uint8_t{MRQP_FW_HAND_MODE_TORQUE}}) {
    FdRig named(mode);
    FdRig face(mode);
    REQUIRE(named.driver != nullptr);
    REQUIRE(face.driver != nullptr);
    JointDevice& dev = *face.driver;
    CHECK(std::string(dev.kind()) == "fd_hand");
    REQUIRE(dev.jointCount() == 20u);
    CHECK(dev.jointMode(19) == (mode == MRQP_FW_HAND_MODE_TORQUE ? JointMode::Torque : JointMode::Position));
    CHECK(dev.setJoint(20, JointCommand{}) == SetpointResult::BadIndex);
    int k = 0;
    named.hook = [&k](FdRig& r) {
      if (k == 2) {
        r.driver->requestEnable(r.t);
      }
      for (std::size_t b = 0; b < 2; ++b) {
        const std::size_t n = b == 0 ? 7u : 13u;
        for (std::size_t j = 0; j < n; ++j) {
          const double phase = static_cast<double>(b * 7 + j);
          (void)r.driver->setJoint(b, j, static_cast<float>(wave(k, 0.8, phase)),
                                   static_cast<float>(wave(k, 2.0, phase + 1.0)),
                                   static_cast<float>(wave(k, 1.0, phase + 2.0)));
        }
      }
    };
    face.hook = [&k](FdRig& r) {
      JointDevice& d = *r.driver;
      if (k == 2) {
        d.requestEnable(r.t);
      }
      for (std::size_t i = 0; i < d.jointCount(); ++i) {
        const double phase = static_cast<double>(i);
        JointCommand c;
        c.position = static_cast<float>(wave(k, 0.8, phase));
        c.velocity = static_cast<float>(wave(k, 2.0, phase + 1.0));
        c.torque = static_cast<float>(wave(k, 1.0, phase + 2.0));
        (void)d.setJoint(i, c);
      }
    };
    for (k = 0; k < 40; ++k) {
      named.cycle();
      face.cycle();
    }
    CHECK(dev.ready());
    named.bus.advanceTo(named.t);
    face.bus.advanceTo(face.t);
    CHECK(named.log.frames().size() > 150u);
    CHECK(named.log.frames() == face.log.frames());
    // Flat index 7 + j is joint j of the second board.
    for (std::size_t j = 0; j < 13; ++j) {
      const JointFeedback fb = dev.joint(7 + j);
      CHECK(fb.valid);
      CHECK(fb.position == static_cast<double>(face.driver->joint(1, j).position));
      CHECK(fb.torque == static_cast<double>(face.driver->joint(1, j).torque));
    }
    CHECK(dev.joint(3).position == static_cast<double>(face.driver->joint(0, 3).position));
    if (mode == MRQP_FW_HAND_MODE_POSITION) {
      CHECK(face.board_b->position(12) != 0.0f);
    }
    // Quick stop: the boards are commanded to HOLD.
    dev.requestQuickStop(face.t);
    face.cycle();
    face.cycle();
    CHECK(face.board_a->mode() == MRQP_FW_HAND_MODE_HOLD);
    CHECK(face.board_b->mode() == MRQP_FW_HAND_MODE_HOLD);
  }
}

TEST_CASE("drivers: device interface: the F/T driver through WrenchDevice", "[drivers][device][ft]") {
  FtRig named;
  FtRig face;
  REQUIRE(named.driver != nullptr);
  REQUIRE(face.driver != nullptr);
  WrenchDevice& dev = *face.driver;
  CHECK(std::string(dev.kind()) == "ft");
  CHECK(dev.sensorCount() == 1u);
  named.driver->start(0);
  dev.start(0);
  CHECK_FALSE(dev.ready());
  const std::array<double, 6> w{{12.5, -3.0, 40.0, 0.5, -0.25, 1.0}};
  named.sensor->setWrench(w);
  face.sensor->setWrench(w);
  for (int k = 0; k < 10; ++k) {
    named.cycle();
    face.cycle();
  }
  CHECK(dev.ready());
  named.bus.advanceTo(named.t);
  face.bus.advanceTo(face.t);
  CHECK(named.log.frames().size() >= 30u);
  CHECK(named.log.frames() == face.log.frames());
  const WrenchFeedback fb = dev.wrench(0);
  const FtSensorState& s = face.driver->sensor(0);
  CHECK(fb.valid);
  CHECK(fb.fresh == s.fresh);
  CHECK(fb.timestamp == s.timestamp);
  for (std::size_t i = 0; i < 6; ++i) {
    CHECK(fb.wrench[i] == s.wrench[i]);
    CHECK(fb.wrench[i] == Approx(w[i]).margin(0.05));
  }
  CHECK_FALSE(dev.wrench(1).valid);
}
