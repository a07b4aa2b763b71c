// loop::DeviceSet with loop::bootDevices / exitDevices (control/loop/device_set.hpp): arm drivers
// booted, enabled and stopped on a simulated bus, checked against the emulated firmware's own
// state (CiA 402 power state and NMT state of each fake drive, independent of the driver's view),
// a failed boot ending the boot early, a stop request ending it at once.
#include <mrqp/drivers/arm_driver.hpp>
#include <mrqp/drivers/bus_router.hpp>
#include <mrqp/drivers/sim_bus.hpp>

#include <catch2/catch.hpp>

#include <memory>
#include <vector>

#include "fake_cia402_drive.hpp"
#include "loop/device_set.hpp"

using namespace mrqp::drivers;
using mrqp::loop::DeviceSet;

namespace {

struct Bench {
  SimBus bus;
  SimNode* master = nullptr;
  std::unique_ptr<BusRouter> router;
  std::vector<std::unique_ptr<drvtest::FakeCia402Drive>> fakes;
  std::unique_ptr<ArmDriver> arm;
  TimeNs t = 0;
  TimeNs period = 0;

  explicit Bench(const std::vector<std::int32_t>& positions, ExitStop stop = ExitStop::QuickStop,
                 ExitNmt nmt = ExitNmt::PreOperational, std::uint16_t abort_index = 0) {
    SimNodeConfig mc;
    mc.name = "master";
    mc.rx_queue = 2048;
    master = bus.addNode(mc);
    router = std::make_unique<BusRouter>(*master);
    ArmConfig cfg;
    cfg.cycle_period = periodOfHz(500.0);
    cfg.exit_stop = stop;
    cfg.exit_nmt = nmt;
    period = cfg.cycle_period;
    for (std::size_t i = 0; i < positions.size(); ++i) {
      drvtest::FakeDriveOptions o;
      o.node = static_cast<std::uint8_t>(i + 1);
      o.initial_position = positions[i];
      SimNodeConfig nc;
      nc.name = "drive";
      fakes.push_back(std::make_unique<drvtest::FakeCia402Drive>(*bus.addNode(nc), o));
      ArmDriveConfig d;
      d.node = o.node;
      cfg.drives.push_back(d);
    }
    if (abort_index != 0) fakes.back()->abortOnWrite(abort_index, 0, MRQP_FW_SDO_ABORT_INVALID_VALUE);
    std::string err;
    arm = ArmDriver::create({router.get()}, cfg, &err);
    REQUIRE(arm != nullptr);
  }
  /// The next cycle's time, the bus run up to it (a simulated clock).
  mrqp::loop::NextCycleTime next() {
    return [this]() {
      t += period;
      bus.advanceTo(t);
      return t;
    };
  }
};

}  // namespace

TEST_CASE("loop: a device set boots, enables and stops arm drives as the firmware sees it",
          "[loop][devices]") {
  const bool quick = GENERATE(true, false);
  Bench b({1000, -2500}, quick ? ExitStop::QuickStop : ExitStop::DisableVoltage,
          quick ? ExitNmt::PreOperational : ExitNmt::Stopped);
  DeviceSet set({b.router.get()}, {b.arm.get()});
  const auto boot = mrqp::loop::bootDevices(set, b.t, b.period, 5.0, b.next());
  REQUIRE(boot.done);
  CHECK(boot.cycles < 5 * 500);
  CHECK(set.enableRequestedAfter() > 0);
  CHECK(set.enableRequestedAfter() < boot.cycles);
  CHECK_FALSE(set.bootFailed());
  for (std::size_t i = 0; i < b.fakes.size(); ++i) {
    CHECK(b.fakes[i]->nmt() == MRQP_FW_NMT_STATE_OPERATIONAL);
    CHECK(b.fakes[i]->state() == MRQP_FW_CIA402_OPERATION_ENABLED);
  }
  // Held where they were during the boot: the firmware's target is its own initial position.
  CHECK(b.fakes[0]->targetPosition() == 1000);
  CHECK(b.fakes[1]->targetPosition() == -2500);

  const auto ex = mrqp::loop::exitDevices(set, b.t, b.period, 2.0, b.next());
  CHECK(ex.done);
  CHECK(ex.cycles >= 3);
  CHECK(set.exitDone());
  for (const auto& f : b.fakes) {
    CHECK(f->nmt() == (quick ? MRQP_FW_NMT_STATE_PRE_OPERATIONAL : MRQP_FW_NMT_STATE_STOPPED));
    CHECK(f->state() != MRQP_FW_CIA402_OPERATION_ENABLED);
  }
}

TEST_CASE("loop: a device set's boot ends early on a failed boot or a stop request", "[loop][devices]") {
  SECTION("an SDO abort fails the boot") {
    Bench b({0, 0}, ExitStop::QuickStop, ExitNmt::PreOperational, 0x6060);
    DeviceSet set({b.router.get()}, {b.arm.get()});
    const auto boot = mrqp::loop::bootDevices(set, b.t, b.period, 5.0, b.next());
    CHECK_FALSE(boot.done);
    CHECK(set.bootFailed());
    CHECK(b.arm->phase() == ArmPhase::Failed);
    CHECK(boot.cycles < 500);  // far less than the 5 s limit
    CHECK((boot.flags & fault::kBootFailed) != 0u);
    CHECK(set.enableRequestedAfter() < 0);
    CHECK(b.fakes[1]->state() != MRQP_FW_CIA402_OPERATION_ENABLED);
  }
  SECTION("a stop request") {
    Bench b({0});
    DeviceSet set({b.router.get()}, {b.arm.get()});
    int asked = 0;
    const auto boot =
        mrqp::loop::bootDevices(set, b.t, b.period, 5.0, b.next(), [&] { return ++asked >= 3; });
    CHECK_FALSE(boot.done);
    CHECK(boot.cycles == 3);
    CHECK(b.t == 3 * b.period);
  }
}
