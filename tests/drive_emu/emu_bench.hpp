// The ArmDriver against mrqp-drive-emu's emulator on one SimBus, for the tests of the emulator:
// the master drives every node of the emulator's configuration (with the node's scale) at a 2 ms
// cycle; the cycle is the master's (bus, router, driver update and transmit) on one simulated clock.
#pragma once

#include <emu_sim.hpp>
#include <mrqp/drivers/arm_driver.hpp>
#include <mrqp/drivers/bus_router.hpp>
#include <mrqp/drivers/sim_bus.hpp>

#include <cstdint>
#include <memory>
#include <string>

namespace drive_emu_test {

using namespace mrqp::drivers;
using namespace mrqp::drive_emu;

struct Bench {
  /// `master_rpdo_timeout_ms`: ArmConfig::rpdo_timeout_ms, the deadline the master writes to
  /// each drive's 0x1400:05 (0: none).
  explicit Bench(const EmuConfig& emu_cfg, std::uint16_t master_rpdo_timeout_ms = 0) {
    SimNodeConfig mc;
    mc.name = "master";
    mc.rx_queue = 2048;
    master = bus.addNode(mc);
    SimNodeConfig ec;
    ec.name = "drive-emu";
    ec.tx_queue = 256;
    emu = std::make_unique<SimDriveEmulator>(*bus.addNode(ec), emu_cfg);
    router = std::make_unique<BusRouter>(*master);
    config.cycle_period = milliseconds(2);  // 3 drives x (RPDO, TPDO1, TPDO2) + SYNC fit in 2 ms at 1 Mbit/s
    config.rpdo_timeout_ms = master_rpdo_timeout_ms;
    for (const EmuNode& n : emu_cfg.nodes) {
      ArmDriveConfig d;
      d.node = n.node;
      d.scale = n.scale;
      config.drives.push_back(d);
    }
    arm = ArmDriver::create({router.get()}, config, &error);
  }

  /// One cycle of the master; its fault flags are also collected in `flags`.
  const FaultReport& cycle() {
    bus.advanceTo(t);
    router->poll(t);
    const FaultReport& r = arm->update(t);
    flags |= r.flags;
    arm->transmit(t);
    t += config.cycle_period;
    return r;
  }

  /// Boots (up to 2000 cycles) and enables (up to 200 cycles) every drive, then runs
  /// `extra_cycles` more; whether every drive is enabled then (false at once when the boot did
  /// not complete).
  bool bootAndEnable(int extra_cycles = 0) {
    arm->start(t);
    for (int k = 0; k < 2000 && arm->phase() != ArmPhase::Running; ++k) cycle();
    if (arm->phase() != ArmPhase::Running) return false;
    arm->requestEnable(t);
    for (int k = 0; k < 200 && !arm->allEnabled(); ++k) cycle();
    for (int k = 0; k < extra_cycles; ++k) cycle();
    return arm->allEnabled();
  }

  /// The master falls silent (no RPDO, no SYNC) for `ms` milliseconds.
  void silence(int ms) { bus.advanceTo(t + milliseconds(ms)); }

  SimBus bus;
  SimNode* master = nullptr;
  std::unique_ptr<SimDriveEmulator> emu;
  std::unique_ptr<BusRouter> router;
  ArmConfig config;
  std::unique_ptr<ArmDriver> arm;
  std::string error;
  std::uint32_t flags = 0;
  TimeNs t = 0;
};

}  // namespace drive_emu_test
