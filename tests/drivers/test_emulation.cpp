// The emulated device firmware of mrqp_emulation (MIT-mode motor, CAN FD hand board, F/T sensor,
// IMU) against the drivers: with ideal physics behind them they put the same frames on the wire
// as the hand-written fakes of fake_devices.hpp (a peer implementation of each protocol's device
// side), the servo they hand to the plant is what the driver commanded, and each fault switch is
// seen by the driver as the fault it stands for.
#include <catch2/catch.hpp>

#include <mrqp/drivers/fd_hand_driver.hpp>
#include <mrqp/drivers/ft_sensor_driver.hpp>
#include <mrqp/drivers/imu_driver.hpp>
#include <mrqp/drivers/mit_hand_driver.hpp>
#include <mrqp/emulation/emulation.hpp>

#include <cmath>
#include <memory>
#include <string>
#include <vector>

#include "arm_rig.hpp"
#include "emulated_node.hpp"
#include "fake_devices.hpp"
#include "sim_trace.hpp"
#include "single_bus_rig.hpp"

using namespace mrqp::drivers;
using mrqp::emulation::EmulatedFtSensor;
using mrqp::emulation::EmulatedHandBoard;
using mrqp::emulation::EmulatedImu;
using mrqp::emulation::EmulatedMitMotor;

namespace {

struct MitRig : drvtest::SingleBusRig<MitRig, MitHandDriver> {
  explicit MitRig(bool emulated) : SingleBusRig(false, milliseconds(1)) {
    SimNode& n = *bus.addNode(SimNodeConfig{});
    MitHandConfig c;
    if (emulated) {
      host = std::make_unique<drvtest::IdealJointHost>(n, false);
      node = std::make_unique<drvtest::EmulatedNode<EmulatedMitMotor>>(n);
    } else {
      fake = std::make_unique<drvtest::FakeMitMotors>(n);
    }
    for (std::uint8_t id = 1; id <= 3; ++id) {
      if (emulated) {
        EmulatedMitMotor::Options o;
        o.motor_id = id;
        o.joint = id - 1u;
        motors.push_back(std::make_unique<EmulatedMitMotor>(*host, o));
        node->add(*motors.back());
      } else {
        fake->add(id);
      }
      MitMotorConfig m;
      m.motor_id = id;
      c.motors.push_back(m);
    }
    driver = MitHandDriver::create({router.get()}, c, &error);
  }
  std::unique_ptr<drvtest::FakeMitMotors> fake;
  std::unique_ptr<drvtest::IdealJointHost> host;
  std::unique_ptr<drvtest::EmulatedNode<EmulatedMitMotor>> node;
  std::vector<std::unique_ptr<EmulatedMitMotor>> motors;
};

void mitProgram(MitRig& r, int k) {
  if (k == 2) {
    r.driver->requestEnable(r.t);
  }
  if (k == 40) {
    r.driver->requestDisable(r.t);
  }
  for (std::size_t i = 0; i < 3; ++i) {
    const float p = static_cast<float>(0.8 * std::sin(0.1 * k + static_cast<double>(i)));
    const mrqp_fw_mit_cmd c{p, 0.5f, 30.0f + 5.0f * static_cast<float>(i), 0.7f, -0.25f};
    (void)r.driver->setCommand(i, c);
  }
}

struct FdRig : drvtest::SingleBusRig<FdRig, FdHandDriver> {
  explicit FdRig(bool emulated) : SingleBusRig(true, milliseconds(1)) {
    SimNodeConfig bcfg;
    bcfg.fd = true;
    SimNode& n = *bus.addNode(bcfg);
    if (emulated) {
      host = std::make_unique<drvtest::IdealJointHost>(n, true);
      node = std::make_unique<drvtest::EmulatedNode<EmulatedHandBoard>>(n);
      EmulatedHandBoard::Options o;
      o.board = 2;
      o.joints = 20;
      board = std::make_unique<EmulatedHandBoard>(*host, o);
      node->add(*board);
    } else {
      fake = std::make_unique<drvtest::FakeHandBoard>(n, 2, 20);
    }
    FdHandConfig c;
    HandBoardConfig h;
    h.board = 2;
    h.joints = 20;
    c.boards.push_back(h);
    driver = FdHandDriver::create({router.get()}, c, &error);
  }
  std::unique_ptr<drvtest::FakeHandBoard> fake;
  std::unique_ptr<drvtest::IdealJointHost> host;
  std::unique_ptr<drvtest::EmulatedNode<EmulatedHandBoard>> node;
  std::unique_ptr<EmulatedHandBoard> board;
};

void fdProgram(FdRig& r, int k) {
  if (k == 2) {
    r.driver->requestEnable(r.t);
  }
  for (std::size_t j = 0; j < 20; ++j) {
    const double ph = 0.1 * k + 0.3 * static_cast<double>(j);
    (void)r.driver->setJoint(0, j, static_cast<float>(std::sin(ph)), static_cast<float>(2.0 * std::cos(ph)),
                             static_cast<float>(0.5 * std::sin(2.0 * ph)));
  }
}

struct FtRig : drvtest::SingleBusRig<FtRig, FtSensorDriver> {
  FtRig(bool emulated, bool fd) : SingleBusRig(fd, milliseconds(1)) {
    SimNodeConfig nc;
    nc.fd = fd;
    SimNode& n = *bus.addNode(nc);
    const std::array<double, 6> w{{10.0, -20.0, 30.5, 0.25, -0.5, 1.125}};
    if (emulated) {
      host = std::make_unique<drvtest::ConstantFtHost>(n);
      host->value = w;
      node = std::make_unique<drvtest::EmulatedNode<EmulatedFtSensor>>(n);
      EmulatedFtSensor::Options o;
      o.node = 0x30;
      o.fd = fd;
      o.scale = fd ? mrqp_fw_ft_scale MRQP_FW_FT_SCALE_FD_DEFAULT_INIT
                   : mrqp_fw_ft_scale MRQP_FW_FT_SCALE_CLASSIC_DEFAULT_INIT;
      sensor = std::make_unique<EmulatedFtSensor>(*host, o);
      node->add(*sensor);
    } else {
      fake = std::make_unique<drvtest::FakeFtSensor>(n, 0x30, fd);
      fake->setWrench(w);
    }
    FtConfig c;
    c.produce_sync = true;
    FtSensorConfig s;
    s.node = 0x30;
    s.variant = fd ? FtVariant::Fd : FtVariant::Classic;
    s.scale = fd ? mrqp_fw_ft_scale MRQP_FW_FT_SCALE_FD_DEFAULT_INIT
                 : mrqp_fw_ft_scale MRQP_FW_FT_SCALE_CLASSIC_DEFAULT_INIT;
    c.sensors.push_back(s);
    driver = FtSensorDriver::create({router.get()}, c, &error);
    if (driver) {
      driver->start(0);
    }
  }
  std::unique_ptr<drvtest::FakeFtSensor> fake;
  std::unique_ptr<drvtest::ConstantFtHost> host;
  std::unique_ptr<drvtest::EmulatedNode<EmulatedFtSensor>> node;
  std::unique_ptr<EmulatedFtSensor> sensor;
};

struct ImuRig : drvtest::SingleBusRig<ImuRig, ImuDriver> {
  explicit ImuRig(bool emulated, TimeNs align_until = 0) : SingleBusRig(true, milliseconds(1)) {
    SimNodeConfig nc;
    nc.fd = true;
    SimNode& n = *bus.addNode(nc);
    mrqp::emulation::ImuValues v;
    v.orientation = {{0.6, 0.0, 0.8, 0.0}};
    v.angular_velocity = {{0.5, -1.25, 3.0}};
    v.specific_force = {{0.1, 0.2, 9.81}};
    if (emulated) {
      host = std::make_unique<drvtest::ConstantImuHost>(n);
      host->value = v;
      node = std::make_unique<drvtest::EmulatedNode<EmulatedImu>>(n);
      EmulatedImu::Options o;
      o.node = 0x40;
      o.align_until = align_until;
      imu = std::make_unique<EmulatedImu>(*host, o);
      node->add(*imu);
    } else {
      fake = std::make_unique<drvtest::FakeImu>(n, 0x40);
      for (std::size_t k = 0; k < 4; ++k) {
        fake->sample().orientation[k] = v.orientation[k];
      }
      for (std::size_t k = 0; k < 3; ++k) {
        fake->sample().angular_velocity[k] = v.angular_velocity[k];
        fake->sample().specific_force[k] = v.specific_force[k];
      }
    }
    ImuConfig c;
    c.produce_sync = true;
    ImuSensorConfig s;
    s.node = 0x40;
    c.imus.push_back(s);
    driver = ImuDriver::create({router.get()}, c, &error);
    if (driver) {
      driver->start(0);
    }
  }
  std::unique_ptr<drvtest::FakeImu> fake;
  std::unique_ptr<drvtest::ConstantImuHost> host;
  std::unique_ptr<drvtest::EmulatedNode<EmulatedImu>> node;
  std::unique_ptr<EmulatedImu> imu;
};

template <class Rig>
std::vector<std::string> wire(Rig& r) {
  r.bus.advanceTo(r.t);
  return r.log.frames();
}

/// Cycles until `flag` is reported (at most `max` cycles); the number of cycles, or -1.
template <class Rig>
int cyclesUntil(Rig& r, std::uint32_t flag, int max = 20) {
  for (int k = 1; k <= max; ++k) {
    if (r.cycle().has(flag)) {
      return k;
    }
  }
  return -1;
}

}  // namespace

TEST_CASE("emulation: MIT motors put the frames of the fake on the wire and servo as commanded",
          "[drivers][emulation][hand]") {
  MitRig fake(false);
  MitRig emu(true);
  REQUIRE(fake.driver != nullptr);
  REQUIRE(emu.driver != nullptr);
  for (int k = 0; k < 50; ++k) {
    fake.hook = [k](MitRig& r) { mitProgram(r, k); };
    emu.hook = [k](MitRig& r) { mitProgram(r, k); };
    fake.cycle();
    emu.cycle();
    if (k == 30) {
      // Enabled and commanded: the servo is the command as decoded from the wire.
      for (std::size_t i = 0; i < 3; ++i) {
        const mrqp::emulation::ServoCommand& s = emu.motors[i]->servo();
        CHECK(s.enabled);
        CHECK(s.kp == Approx(30.0 + 5.0 * static_cast<double>(i)).margin(500.0 / 4095.0));
        CHECK(s.kd == Approx(0.7).margin(5.0 / 4095.0));
        CHECK(s.torque == Approx(-0.25).margin(0.01));
        CHECK(s.velocity == Approx(0.5).margin(0.02));
      }
    }
  }
  const auto a = wire(fake);
  CHECK(a.size() > 250u);
  CHECK(a == wire(emu));
  CHECK_FALSE(emu.motors[0]->enabled());  // disabled at k = 40
  CHECK(emu.driver->faults().flags == 0u);
}

TEST_CASE("emulation: MIT motor fault switches", "[drivers][emulation][hand]") {
  MitRig r(true);
  REQUIRE(r.driver != nullptr);
  for (int k = 0; k < 5; ++k) {
    r.cycle();
  }
  REQUIRE(r.driver->faults().flags == 0u);
  r.motors[1]->corruptReplies(1);
  CHECK(cyclesUntil(r, fault::kCorruptFrame) >= 1);
  CHECK(r.driver->faults().devices[1].corrupt_frames == 1u);
  r.motors[2]->setSilent(true);
  CHECK(cyclesUntil(r, fault::kFeedbackMissing) == 3);  // 3 cycles without a reply
  CHECK(r.driver->faults().devices[2].flags == fault::kFeedbackMissing);
  r.motors[2]->setSilent(false);
  r.cycle();
  CHECK(r.cycle().flags == 0u);
  // A tripped controller stops answering: feedback missing until it is powered on again.
  r.motors[0]->raiseFault(r.t);
  CHECK(cyclesUntil(r, fault::kFeedbackMissing) == 3);
  r.motors[0]->powerOn(r.t);
  r.cycle();
  CHECK(r.cycle().flags == 0u);
  // Stale: replies keep coming with the last measurement although the joint moves.
  r.motors[0]->setStale(true);
  r.host->p[0] = 1.0f;
  r.cycle();
  r.cycle();
  CHECK(r.driver->motor(0).position == Approx(0.0).margin(1e-3));
  r.motors[0]->setStale(false);
  r.cycle();
  r.cycle();
  CHECK(r.driver->motor(0).position == Approx(1.0).margin(1e-3));
}

TEST_CASE("emulation: the hand board puts the frames of the fake on the wire", "[drivers][emulation][hand]") {
  FdRig fake(false);
  FdRig emu(true);
  REQUIRE(fake.driver != nullptr);
  REQUIRE(emu.driver != nullptr);
  for (int k = 0; k < 30; ++k) {
    fake.hook = [k](FdRig& r) { fdProgram(r, k); };
    emu.hook = [k](FdRig& r) { fdProgram(r, k); };
    fake.cycle();
    emu.cycle();
  }
  const auto a = wire(fake);
  CHECK(a.size() > 100u);
  CHECK(a == wire(emu));
  CHECK(emu.driver->allEnabled());
  // The board's servo: its PD on the last commanded position, velocity and torque (k = 29).
  const mrqp::emulation::ServoCommand& s = emu.board->servo(7);
  CHECK(s.enabled);
  CHECK(s.kp == 5.0);
  CHECK(s.position == Approx(std::sin(2.9 + 2.1)).margin(0.5e-4));
  CHECK(s.velocity == Approx(2.0 * std::cos(2.9 + 2.1)).margin(0.01));
  CHECK(s.torque == Approx(0.5 * std::sin(2.0 * (2.9 + 2.1))).margin(0.5e-3));
}

TEST_CASE("emulation: hand board fault switches, HOLD and the command timeout",
          "[drivers][emulation][hand]") {
  FdRig r(true);
  REQUIRE(r.driver != nullptr);
  r.hook = [](FdRig& rr) {
    if (rr.t == milliseconds(2)) {
      rr.driver->requestEnable(rr.t);
    }
  };
  for (int k = 0; k < 8; ++k) {
    r.cycle();
  }
  REQUIRE(r.driver->allEnabled());
  REQUIRE(r.driver->faults().flags == 0u);
  r.board->corruptFeedback(1);
  CHECK(cyclesUntil(r, fault::kCorruptFrame) >= 1);
  r.cycle();
  r.cycle();
  r.board->setStale(true);
  CHECK(cyclesUntil(r, fault::kSampleLost) >= 1);
  r.board->setStale(false);
  r.board->setSilent(true);
  CHECK(cyclesUntil(r, fault::kFeedbackMissing) >= 1);
  r.board->setSilent(false);
  r.cycle();
  r.cycle();
  r.board->raiseFault(r.t);
  CHECK(cyclesUntil(r, fault::kDeviceFault) >= 1);
  CHECK_FALSE(r.host->servo[3].enabled);
  // Cleared by a DISABLED command, then enabled again.
  r.driver->requestDisable(r.t);
  r.cycle();
  r.cycle();
  r.driver->requestEnable(r.t);
  r.hook = nullptr;
  for (int k = 0; k < 5; ++k) {
    r.cycle();
  }
  CHECK(r.driver->allEnabled());
  CHECK((r.board->status() & MRQP_FW_HAND_STATUS_FAULT) == 0u);
  // Quick stop (HOLD): the servo holds the position measured when HOLD began.
  r.bus.advanceTo(r.t);  // the last POSITION command applied
  r.host->p[4] = 0.25f;
  r.driver->requestQuickStop(r.t);
  r.cycle();
  r.cycle();
  CHECK(r.board->mode() == MRQP_FW_HAND_MODE_HOLD);
  CHECK(r.host->servo[4].position == Approx(0.25));
  CHECK(r.host->servo[4].kp == 5.0);

  // The command timeout: a board with 5 ms that stops receiving commands goes to HOLD.
  SimBus bus;
  SimNode& n = *bus.addNode(SimNodeConfig{});
  drvtest::IdealJointHost host(n, true);
  EmulatedHandBoard::Options o;
  o.joints = 2;
  o.command_timeout = milliseconds(5);
  EmulatedHandBoard b(host, o);
  mrqp_fw_hand_cmd c{};
  c.seq = 1;
  c.mode = MRQP_FW_HAND_MODE_TORQUE;
  c.count = 2;
  mrqp_fw_frame f;
  const mrqp_fw_hand_scale scale = MRQP_FW_HAND_SCALE_DEFAULT_INIT;
  REQUIRE(!mrqp_fw_pack_failed(mrqp_fw_hand_pack_cmd(&scale, 0, &c, &f, nullptr)));
  CHECK(b.onFrame(f, milliseconds(1)));
  CHECK(b.nextEvent() == milliseconds(6));
  b.advance(milliseconds(5));
  CHECK(b.mode() == MRQP_FW_HAND_MODE_TORQUE);
  b.advance(milliseconds(6));
  CHECK(b.mode() == MRQP_FW_HAND_MODE_HOLD);
  CHECK((b.status() & MRQP_FW_HAND_STATUS_COMMAND_TIMEOUT) != 0u);
  CHECK(b.nextEvent() == EmulatedHandBoard::kNever);
}

TEST_CASE("emulation: the F/T sensor puts the frames of the fake on the wire, faults",
          "[drivers][emulation][ft]") {
  for (const bool fd : {false, true}) {
    FtRig fake(false, fd);
    FtRig emu(true, fd);
    REQUIRE(fake.driver != nullptr);
    REQUIRE(emu.driver != nullptr);
    for (int k = 0; k < 20; ++k) {
      if (k == 5) {
        fake.driver->requestTare(0, true, fake.t);
        emu.driver->requestTare(0, true, emu.t);
      }
      fake.cycle();
      emu.cycle();
    }
    const auto a = wire(fake);
    CHECK(a.size() >= (fd ? 40u : 60u));
    CHECK(a == wire(emu));
    CHECK(emu.sensor->tared());
    CHECK_FALSE(emu.driver->tarePending(0));
    REQUIRE(emu.driver->faults().flags == 0u);

    FtRig& r = emu;
    r.sensor->corruptSamples(1);
    CHECK(cyclesUntil(r, fault::kCorruptFrame) >= 1);
    r.cycle();
    r.cycle();
    r.sensor->setStale(true);
    CHECK(cyclesUntil(r, fault::kDeviceWarning) >= 1);
    CHECK(cyclesUntil(r, fault::kFeedbackMissing) >= 1);
    r.sensor->setStale(false);
    r.sensor->raiseFault();
    CHECK(cyclesUntil(r, fault::kDeviceFault) >= 1);
    r.sensor->clearFault();
    r.sensor->setSilent(true);
    CHECK(cyclesUntil(r, fault::kFeedbackMissing) >= 1);
    r.sensor->setSilent(false);
    if (!fd) {
      r.cycle();
      r.cycle();
      r.sensor->dropMoments(1);
      CHECK(cyclesUntil(r, fault::kTornPair) >= 1);
    }
  }
}

TEST_CASE("emulation: the IMU puts the frames of the fake on the wire, aligning and faults",
          "[drivers][emulation][imu]") {
  ImuRig fake(false);
  ImuRig emu(true);
  REQUIRE(fake.driver != nullptr);
  REQUIRE(emu.driver != nullptr);
  for (int k = 0; k < 10; ++k) {
    fake.cycle();
    emu.cycle();
  }
  const auto a = wire(fake);
  CHECK(a.size() == 20u);
  CHECK(a == wire(emu));
  CHECK(emu.driver->ready());
  CHECK(emu.driver->imu(0).orientation[2] == Approx(0.8).margin(1e-4));

  ImuRig r(true, milliseconds(5));
  REQUIRE(r.driver != nullptr);
  for (int k = 0; k < 5; ++k) {
    r.cycle();
  }
  CHECK(r.driver->state(0).valid);
  CHECK_FALSE(r.driver->ready());
  r.cycle();
  r.cycle();
  CHECK(r.driver->ready());
  REQUIRE(r.cycle().flags == 0u);
  r.imu->corruptSamples(2);
  CHECK(cyclesUntil(r, fault::kCorruptFrame) >= 1);
  r.cycle();
  r.cycle();
  CHECK(r.driver->faults().devices[0].corrupt_frames == 2u);
  r.imu->setStale(true);
  CHECK(cyclesUntil(r, fault::kFeedbackMissing) >= 1);
  r.imu->setStale(false);
  r.imu->raiseFault();
  CHECK(cyclesUntil(r, fault::kDeviceFault) >= 1);
  r.imu->clearFault();
  r.imu->setSilent(true);
  CHECK(cyclesUntil(r, fault::kFeedbackMissing) >= 1);
}

TEST_CASE("emulation: CiA 402 drive fault switches: corrupt TPDOs, silence", "[drivers][emulation][arm]") {
  ArmConfig c;
  c.cycle_period = milliseconds(1);
  drvtest::ArmRig r({{0, 1}, {0, 2}}, c);
  REQUIRE(r.arm != nullptr);
  REQUIRE(r.boot() < 400);
  for (int k = 0; k < 5; ++k) {
    r.cycle();
  }
  REQUIRE(r.arm->faults().flags == 0u);
  r.fakes[1]->corruptPdos(1);
  CHECK(cyclesUntil(r, fault::kCorruptFrame) >= 1);
  CHECK(r.arm->faults().devices[1].corrupt_frames == 1u);
  CHECK(r.arm->faults().devices[0].corrupt_frames == 0u);
  r.cycle();
  r.cycle();
  REQUIRE(r.cycle().flags == 0u);
  // Silent: feedback missing after 3 cycles, heartbeat lost after the consumer time (250 ms).
  r.fakes[0]->setSilent(true);
  CHECK(cyclesUntil(r, fault::kFeedbackMissing) == 3);
  const int lost = cyclesUntil(r, fault::kHeartbeatLost, 400);
  CHECK(lost > 100);
  CHECK(r.arm->faults().devices[1].flags == 0u);
}
