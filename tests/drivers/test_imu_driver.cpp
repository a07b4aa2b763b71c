// The IMU driver against a fake IMU (tests/drivers/fake_devices.hpp) on a simulated CAN FD bus:
// samples decoded within half a wire step, the ALIGNING / STALE / FAULT / OVERRANGE status, lost
// and missing samples, corrupt frames counted and dropped, and the set-up errors.
#include <catch2/catch.hpp>

#include <mrqp/drivers/imu_driver.hpp>

#include <memory>
#include <string>
#include <vector>

#include "fake_devices.hpp"
#include "sim_trace.hpp"
#include "single_bus_rig.hpp"

using namespace mrqp::drivers;
using drvtest::makeFrame;

namespace {

struct ImuRig : drvtest::SingleBusRig<ImuRig, ImuDriver> {
  ImuRig() : SingleBusRig(true, milliseconds(1)) {
    SimNodeConfig nc;
    nc.fd = true;
    imu = std::make_unique<drvtest::FakeImu>(*bus.addNode(nc), 0x40);
    injector = bus.addNode(nc);
    ImuConfig c;
    c.produce_sync = true;
    ImuSensorConfig s;
    s.node = 0x40;
    s.rate_limit = 20.0;
    c.imus.push_back(s);
    driver = ImuDriver::create({router.get()}, c, &error);
    if (driver) {
      driver->start(0);
    }
  }
  std::unique_ptr<drvtest::FakeImu> imu;
};

}  // namespace

TEST_CASE("drivers: IMU: samples on SYNC, decoded within half a wire step", "[drivers][imu]") {
  ImuRig rig;
  REQUIRE(rig.driver != nullptr);
  ImuDevice& dev = *rig.driver;
  CHECK(std::string(dev.kind()) == "imu");
  CHECK(dev.imuCount() == 1u);
  mrqp_fw_imu_sample& s = rig.imu->sample();
  s.orientation[0] = 0.6;
  s.orientation[1] = 0.0;
  s.orientation[2] = 0.0;
  s.orientation[3] = -0.8;
  s.angular_velocity[0] = 0.1234;
  s.angular_velocity[2] = -3.0;
  s.specific_force[2] = 9.81;
  CHECK_FALSE(dev.ready());
  for (int k = 0; k < 5; ++k) {
    rig.cycle();
  }
  CHECK(rig.driver->faults().flags == 0u);
  CHECK(dev.ready());
  const ImuFeedback fb = dev.imu(0);
  CHECK(fb.valid);
  CHECK(fb.fresh);
  CHECK(fb.orientation[0] == Approx(0.6).margin(0.5 / 32767.0));
  CHECK(fb.orientation[3] == Approx(-0.8).margin(0.5 / 32767.0));
  CHECK(fb.angular_velocity[0] == Approx(0.1234).margin(0.5e-3));
  CHECK(fb.angular_velocity[2] == Approx(-3.0).margin(1e-12));
  CHECK(fb.specific_force[2] == Approx(9.81).margin(2.5e-3));
  CHECK(fb.timestamp > 0);
  CHECK_FALSE(dev.imu(1).valid);
  // One SYNC and one 24-byte FD answer per cycle.
  rig.bus.advanceTo(rig.t);
  const auto frames = rig.log.framesBetween(rig.last, rig.t);
  REQUIRE(frames.size() == 2u);
  CHECK(frames[0] == "080#");
  CHECK(frames[1].substr(0, 6) == "1C0##1");
  CHECK(frames[1].size() == 6u + 48u);
  // The budget line: SYNC and one IMU frame.
  BusSpec spec;
  spec.data_bps = 5000000;
  BusBudget budget(spec);
  dev.declareTraffic(0, budget);
  REQUIRE(budget.lines().size() == 2u);
  CHECK(budget.lines()[1].len == 24u);
}

TEST_CASE("drivers: IMU: aligning, stale, fault, over-range and lost samples", "[drivers][imu]") {
  ImuRig rig;
  REQUIRE(rig.driver != nullptr);
  mrqp_fw_imu_sample& s = rig.imu->sample();
  s.status = MRQP_FW_IMU_STATUS_ALIGNING;
  for (int k = 0; k < 4; ++k) {
    rig.cycle();
  }
  CHECK(rig.driver->state(0).valid);
  CHECK_FALSE(rig.driver->ready());
  CHECK(rig.cycle().flags == fault::kDeviceWarning);
  s.status = 0;
  rig.cycle();
  rig.cycle();
  CHECK(rig.cycle().flags == 0u);
  CHECK(rig.driver->ready());

  // STALE: repeated values are not fresh; after 3 cycles the samples count as missing.
  s.status = MRQP_FW_IMU_STATUS_STALE;
  rig.cycle();
  rig.cycle();
  const FaultReport& r1 = rig.cycle();
  CHECK(r1.has(fault::kDeviceWarning));
  CHECK_FALSE(rig.driver->imu(0).fresh);
  rig.cycle();
  CHECK(rig.cycle().has(fault::kFeedbackMissing));
  s.status = 0;
  rig.cycle();
  rig.cycle();
  CHECK(rig.cycle().flags == 0u);

  // FAULT and OVERRANGE (from the status bit and from the configured rate limit).
  s.status = MRQP_FW_IMU_STATUS_FAULT;
  rig.cycle();
  rig.cycle();
  CHECK(rig.cycle().has(fault::kDeviceFault));
  s.status = 0;
  s.angular_velocity[1] = 25.0;  // beyond rate_limit = 20 rad/s, within the wire range
  rig.cycle();
  rig.cycle();
  const FaultReport& r2 = rig.cycle();
  CHECK(r2.flags == fault::kOutOfRange);
  s.angular_velocity[1] = 40.0;  // beyond the wire range: saturated, OVERRANGE status
  rig.cycle();
  rig.cycle();
  CHECK(rig.cycle().flags == fault::kOutOfRange);
  CHECK((rig.driver->state(0).status & MRQP_FW_IMU_STATUS_OVERRANGE) != 0u);
  s.angular_velocity[1] = 0.0;
  rig.cycle();
  rig.cycle();
  CHECK(rig.cycle().flags == 0u);

  // Three samples skipped in the sequence: lost samples counted once.
  rig.imu->skipSeq(3);
  rig.cycle();
  rig.cycle();
  const FaultReport& r3 = rig.cycle();
  CHECK(r3.flags == 0u);
  CHECK(rig.driver->faults().devices[0].lost_samples == 3u);

  // Silent: feedback missing after 3 cycles, the last sample stays valid but not fresh.
  rig.imu->setSilent(true);
  rig.cycle();
  rig.cycle();
  rig.cycle();
  rig.cycle();
  CHECK(rig.cycle().has(fault::kFeedbackMissing));
  CHECK(rig.driver->imu(0).valid);
  CHECK_FALSE(rig.driver->imu(0).fresh);
}

TEST_CASE("drivers: IMU: corrupt frames are counted and dropped", "[drivers][imu]") {
  ImuRig rig;
  REQUIRE(rig.driver != nullptr);
  rig.imu->sample().angular_velocity[0] = 1.0;
  for (int k = 0; k < 4; ++k) {
    rig.cycle();
  }
  REQUIRE(rig.driver->faults().flags == 0u);
  // A frame of node 0x40 with one bit flipped after packing (CRC wrong).
  mrqp_fw_imu_sample bad{};
  bad.orientation[0] = 1.0;
  bad.angular_velocity[0] = -5.0;
  const mrqp_fw_imu_scale scale = MRQP_FW_IMU_SCALE_DEFAULT_INIT;
  mrqp_fw_frame f{};
  REQUIRE(mrqp_fw_imu_pack(&scale, 0x40, &bad, &f) == MRQP_FW_PACK_OK);
  f.data[8] ^= 0x01;
  rig.hook = [&f](ImuRig& r) {
    (void)r.injector->send(f);
    r.hook = nullptr;
  };
  rig.cycle();
  const FaultReport& r = rig.cycle();
  CHECK(r.has(fault::kCorruptFrame));
  CHECK(rig.driver->faults().devices[0].corrupt_frames == 1u);
  CHECK(r.buses[0].rejected_frames == 1u);
  CHECK(rig.driver->imu(0).angular_velocity[0] == Approx(1.0));  // the bad sample was dropped
  // A classic frame on the IMU's identifier is not a sample either.
  rig.hook = [](ImuRig& r2) {
    (void)r2.injector->send(makeFrame(0x1C0, {1, 2, 3}));
    r2.hook = nullptr;
  };
  rig.cycle();
  CHECK(rig.cycle().has(fault::kCorruptFrame));
  CHECK(rig.driver->faults().devices[0].corrupt_frames == 2u);
  rig.cycle();
  CHECK(rig.cycle().flags == 0u);
}

TEST_CASE("drivers: IMU: set-up errors name the IMU and the field", "[drivers][imu]") {
  SimBus classic;
  SimNode* m = classic.addNode(SimNodeConfig{});
  BusRouter router(*m);
  ImuConfig c;
  std::string err;
  CHECK(ImuDriver::create({&router}, c, &err) == nullptr);
  CHECK(err == "IMU driver: no IMU configured");
  c.imus.push_back(ImuSensorConfig{});
  CHECK(ImuDriver::create({&router}, c, &err) == nullptr);
  CHECK(err.find("IMU 0 (node 1)") != std::string::npos);
  CHECK(err.find("not CAN FD enabled") != std::string::npos);
  c.imus[0].node = 0;
  CHECK(ImuDriver::create({&router}, c, &err) == nullptr);
  CHECK(err.find("node id must be 1..127") != std::string::npos);
}
