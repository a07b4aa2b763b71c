// The force/torque sensor driver against a fake sensor: classic pair with torn-pair detection,
// the FD frame, tare, sequence gaps, missing samples.
#include <catch2/catch.hpp>

#include <mrqp/drivers/ft_sensor_driver.hpp>

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

struct FtRig : drvtest::SingleBusRig<FtRig, FtSensorDriver> {
  explicit FtRig(bool fd) : SingleBusRig(fd, milliseconds(1)) {
    SimNodeConfig nc;
    nc.fd = fd;
    nc.name = "master";
    sensor = std::make_unique<drvtest::FakeFtSensor>(*bus.addNode(nc), 0x30, fd);
    injector = bus.addNode(nc);
    FtConfig c;
    c.produce_sync = true;
    FtSensorConfig s;
    s.node = 0x30;
    s.variant = fd ? FtVariant::Fd : FtVariant::Classic;
    s.scale = fd ? mrqp_fw_ft_scale MRQP_FW_FT_SCALE_FD_DEFAULT_INIT
                 : mrqp_fw_ft_scale MRQP_FW_FT_SCALE_CLASSIC_DEFAULT_INIT;
    s.force_limit = 100.0;
    c.sensors.push_back(s);
    FtSensorConfig ghost = s;  // a second sensor played by the injector
    ghost.node = 0x31;
    c.sensors.push_back(ghost);
    driver = FtSensorDriver::create({router.get()}, c, &error);
    if (driver) {
      driver->start(0);
    }
  }
  std::unique_ptr<drvtest::FakeFtSensor> sensor;
};

// Classic frames of sensor 0x31, hand-encoded: three i16 LE values, seq, status.
mrqp_fw_frame half(unsigned cob, std::int16_t a, std::int16_t b, std::int16_t c, std::uint8_t seq,
                   std::uint8_t status) {
  const auto ua = static_cast<std::uint16_t>(a);
  const auto ub = static_cast<std::uint16_t>(b);
  const auto uc = static_cast<std::uint16_t>(c);
  return makeFrame(cob + 0x31,
                   {static_cast<std::uint8_t>(ua & 0xFF), static_cast<std::uint8_t>(ua >> 8),
                    static_cast<std::uint8_t>(ub & 0xFF), static_cast<std::uint8_t>(ub >> 8),
                    static_cast<std::uint8_t>(uc & 0xFF), static_cast<std::uint8_t>(uc >> 8), seq, status});
}

}  // namespace

TEST_CASE("drivers: F/T classic: SYNC, the pair joined into one sample", "[drivers][ft]") {
  FtRig rig(false);
  REQUIRE(rig.driver != nullptr);
  rig.sensor->setWrench({1.5, -2.25, 10.0, 0.125, -0.5, 0.001});
  rig.cycle();
  rig.cycle();
  const FtSensorState& s = rig.driver->sensor(0);
  REQUIRE(s.valid);
  CHECK(s.fresh);
  CHECK(s.wrench[0] == Approx(1.5).margin(0.01));
  CHECK(s.wrench[1] == Approx(-2.26));
  CHECK(s.wrench[2] == Approx(10.0).margin(0.01));
  CHECK(s.wrench[3] == Approx(0.125).margin(0.0005));
  CHECK(s.wrench[4] == Approx(-0.5).margin(0.0005));
  CHECK(s.wrench[5] == Approx(0.001).margin(0.0005));
  CHECK(s.seq == 1u);
  // Wire: SYNC, forces 0x1B0 (1.5 N = 75 counts = 0x004B ...), moments 0x2B0.
  const auto frames = rig.log.frames();
  REQUIRE(frames.size() >= 3u);
  CHECK(frames[0] == "080#");
  // fy = -2.25 N x 50 = -112.5 counts: rounded away from zero to -113 = 0xFF8F.
  CHECK(frames[1] == "1B0#4B008FFFF4010100");
  CHECK(frames[2] == "2B0#7D000CFE01000100");
}

TEST_CASE("drivers: F/T classic: torn pairs are detected, counted and dropped", "[drivers][ft]") {
  FtRig rig(false);
  REQUIRE(rig.driver != nullptr);
  rig.cycle();
  rig.cycle();
  // Sensor 0x31 (the injector): forces of sample 5 and moments of sample 6.
  const TimeNs quiet = rig.last + microseconds(500);
  REQUIRE(rig.injector->sendAt(half(0x180, 50, 0, 0, 5, 0), quiet) == SendResult::Ok);
  REQUIRE(rig.injector->sendAt(half(0x280, 0, 0, 0, 6, 0), quiet) == SendResult::Ok);
  const FaultReport& r1 = rig.cycle();
  CHECK((r1.devices[1].flags & fault::kTornPair) != 0u);
  CHECK(r1.devices[1].torn_pairs == 1u);
  CHECK(!rig.driver->sensor(1).valid);
  // The moments of sample 6 waited one cycle for their forces: dropped as torn too.
  rig.cycle();
  const FaultReport& r2 = rig.cycle();
  CHECK(r2.devices[1].torn_pairs == 2u);
  // A matching pair (seq 7, same status) makes a sample.
  REQUIRE(rig.injector->sendAt(half(0x180, 50, -100, 0, 7, 0), rig.last + microseconds(500)) ==
          SendResult::Ok);
  REQUIRE(rig.injector->sendAt(half(0x280, 1000, 0, -1000, 7, 0), rig.last + microseconds(500)) ==
          SendResult::Ok);
  rig.cycle();
  const FtSensorState& s = rig.driver->sensor(1);
  REQUIRE(s.valid);
  CHECK(s.seq == 7u);
  CHECK(s.wrench[0] == Approx(1.0));
  CHECK(s.wrench[1] == Approx(-2.0));
  CHECK(s.wrench[3] == Approx(1.0));
  CHECK(s.wrench[5] == Approx(-1.0));
  // Same seq, different status: torn as well.
  REQUIRE(rig.injector->sendAt(half(0x180, 0, 0, 0, 8, 0), rig.last + microseconds(500)) == SendResult::Ok);
  REQUIRE(rig.injector->sendAt(half(0x280, 0, 0, 0, 8, MRQP_FW_FT_STATUS_OVERRANGE),
                               rig.last + microseconds(500)) == SendResult::Ok);
  CHECK(rig.cycle().devices[1].torn_pairs == 3u);
  CHECK(rig.driver->sensor(1).seq == 7u);

  // The real sensor loses a moments frame: the forces half is dropped as torn next cycle.
  CHECK(rig.cycle().devices[0].torn_pairs == 0u);
  rig.sensor->dropMoments(1);
  rig.cycle();
  const FaultReport& r3 = rig.cycle();
  CHECK(r3.devices[0].torn_pairs == 1u);
  CHECK((r3.devices[0].flags & fault::kTornPair) != 0u);
}

TEST_CASE("drivers: F/T: sequence gaps, missing samples, status and range", "[drivers][ft]") {
  FtRig rig(false);
  REQUIRE(rig.driver != nullptr);
  for (int k = 0; k < 3; ++k) {
    rig.cycle();
  }
  CHECK((rig.driver->faults().devices[0].flags) == 0u);
  rig.sensor->skipSeq(2);
  const FaultReport& r1 = rig.cycle();
  CHECK(r1.devices[0].lost_samples == 2u);
  CHECK((r1.devices[0].flags & fault::kSampleLost) != 0u);
  rig.sensor->setSilent(true);
  rig.cycle();
  rig.cycle();
  CHECK((rig.cycle().devices[0].flags & fault::kFeedbackMissing) != 0u);
  rig.sensor->setSilent(false);
  rig.sensor->setWrench({150.0, 0, 0, 0, 0, 0});  // beyond the 100 N limit
  rig.sensor->setStatusExtra(MRQP_FW_FT_STATUS_FAULT);
  rig.cycle();
  const FaultReport& r2 = rig.cycle();
  CHECK((r2.devices[0].flags & (fault::kOutOfRange | fault::kDeviceFault)) ==
        (fault::kOutOfRange | fault::kDeviceFault));
  CHECK((r2.devices[0].flags & fault::kFeedbackMissing) == 0u);
}

TEST_CASE("drivers: F/T tare: the command frame, confirmation by the status bit", "[drivers][ft]") {
  FtRig rig(false);
  REQUIRE(rig.driver != nullptr);
  rig.sensor->setWrench({3.0, 0, 0, 0, 0, 0.5});
  rig.cycle();
  rig.cycle();
  CHECK(rig.driver->sensor(0).wrench[0] == Approx(3.0));
  const TimeNs t0 = rig.t;
  rig.hook = [](FtRig& r) {
    CHECK(r.driver->requestTare(0, true, r.t));
    r.hook = nullptr;
  };
  rig.cycle();
  CHECK(rig.driver->tarePending(0));
  rig.cycle();
  rig.cycle();
  CHECK(!rig.driver->tarePending(0));
  CHECK(rig.sensor->tared());
  CHECK((rig.driver->sensor(0).status & MRQP_FW_FT_STATUS_TARED) != 0u);
  CHECK(rig.driver->sensor(0).wrench[0] == Approx(0.0));
  CHECK(rig.driver->sensor(0).wrench[5] == Approx(0.0));
  // Tare command: 0x200 + node, DLC 2: command, command XOR 0xFF.
  const auto master = rig.masterFrames(t0);
  REQUIRE(master.size() >= 2u);
  CHECK(master[0] == "230#01FE");
  CHECK(master[1] == "080#");
  CHECK(rig.driver->faults().devices[0].flags == 0u);
  // A tare the sensor never confirms times out (100 ms).
  rig.hook = [](FtRig& r) {
    CHECK(r.driver->requestTare(1, true, r.t));
    r.hook = nullptr;
  };
  bool timeout = false;
  for (int k = 0; k < 110 && !timeout; ++k) {
    timeout = (rig.cycle().devices[1].flags & fault::kTimeout) != 0u;
  }
  CHECK(timeout);
}

TEST_CASE("drivers: F/T FD frame: decoded, corrupted frames dropped", "[drivers][ft]") {
  FtRig rig(true);
  REQUIRE(rig.driver != nullptr);
  rig.sensor->setWrench({12.345678, -0.000001, 3.0, 0.25, -0.125, 7.0});
  rig.cycle();
  rig.cycle();
  const FtSensorState& s = rig.driver->sensor(0);
  REQUIRE(s.valid);
  CHECK(s.wrench[0] == Approx(12.345678).margin(1e-6));
  CHECK(s.wrench[1] == Approx(-0.000001).margin(1e-6));
  CHECK(s.wrench[5] == Approx(7.0).margin(1e-6));
  // The FD frame: 0x1B0, 32 bytes, BRS.
  bool seen = false;
  for (const auto& e : rig.log.events) {
    if (e.frame.id == 0x1B0) {
      seen = true;
      CHECK(e.frame.len == 32u);
      CHECK(e.frame.flags == (MRQP_FW_FRAME_FD | MRQP_FW_FRAME_BRS));
    }
  }
  CHECK(seen);
  // A sample of sensor 0x31 with one bit flipped: CRC error, dropped.
  mrqp_fw_ft_sample smp{};
  smp.seq = 1;
  mrqp_fw_ft_scale scale = MRQP_FW_FT_SCALE_FD_DEFAULT_INIT;
  mrqp_fw_frame f;
  REQUIRE(!mrqp_fw_pack_failed(mrqp_fw_ft_pack_fd(&scale, 0x31, &smp, &f)));
  f.data[3] ^= 0x10;
  REQUIRE(rig.injector->sendAt(f, rig.last + microseconds(500)) == SendResult::Ok);
  const FaultReport& r = rig.cycle();
  CHECK(r.devices[1].corrupt_frames == 1u);
  CHECK(!rig.driver->sensor(1).valid);
  CHECK(r.buses[0].rejected_frames == 1u);

  BusBudget b(BusSpec{"arm", 1000000, 5000000, 1000.0, 0.8});
  rig.driver->declareTraffic(0, b);
  CHECK(b.result().time_worst_ns == Approx(55000.0 + 2 * 105600.0));
}
