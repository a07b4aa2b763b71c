// A test bench for the arm driver: simulated buses, fake CiA 402 drives, routers, the driver,
// and the cycle as the control loop runs it (advance, poll, update, hook, transmit).
#pragma once

#include <mrqp/drivers/arm_driver.hpp>
#include <mrqp/drivers/bus_router.hpp>
#include <mrqp/drivers/sim_bus.hpp>

#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "fake_cia402_drive.hpp"
#include "sim_trace.hpp"

namespace drvtest {

struct ArmRig {
  /// drives[i] = {bus, node}. The master is node 0 of every bus; with `echo_own` it receives its
  /// own frames (TX echo). `boot_delay`: the fake drives' power-on / reset -> boot-up time.
  /// `profile`: how strict the fake drives are (vendor_profile.hpp).
  ArmRig(const std::vector<std::pair<std::size_t, std::uint8_t>>& drives, mrqp::drivers::ArmConfig cfg,
         std::size_t master_tx_queue = 64, std::vector<std::int32_t> initial_positions = {},
         bool echo_own = false, mrqp::drivers::TimeNs boot_delay = 2000000,
         const mrqp::emulation::VendorProfile& profile = mrqp::emulation::VendorProfile::lenient()) {
    using namespace mrqp::drivers;
    std::size_t nbus = 1;
    for (const auto& d : drives) {
      nbus = std::max(nbus, d.first + 1);
    }
    for (std::size_t b = 0; b < nbus; ++b) {
      buses.push_back(std::make_unique<SimBus>());
      logs.push_back(std::make_unique<WireLog>());
      buses[b]->setTap(logs[b].get());
      SimNodeConfig mc;
      mc.name = "master";
      mc.rx_queue = 2048;
      mc.tx_queue = master_tx_queue;
      mc.echo_own = echo_own;
      masters.push_back(buses[b]->addNode(mc));
      routers.push_back(std::make_unique<BusRouter>(*masters[b]));
    }
    for (std::size_t i = 0; i < drives.size(); ++i) {
      FakeDriveOptions o;
      o.node = drives[i].second;
      o.initial_position = i < initial_positions.size() ? initial_positions[i] : 0;
      o.boot_delay = boot_delay;
      o.profile = profile;
      SimNodeConfig nc;
      nc.name = "drive";
      fakes.push_back(std::make_unique<FakeCia402Drive>(*buses[drives[i].first]->addNode(nc), o));
      ArmDriveConfig d;
      d.bus = drives[i].first;
      d.node = drives[i].second;
      if (i < cfg.drives.size()) {
        // keep per-drive settings given by the test, but bus and node from `drives`
        d = cfg.drives[i];
        d.bus = drives[i].first;
        d.node = drives[i].second;
      }
      if (i < cfg.drives.size()) {
        cfg.drives[i] = d;
      } else {
        cfg.drives.push_back(d);
      }
    }
    config = cfg;
    std::vector<BusRouter*> r;
    for (auto& p : routers) {
      r.push_back(p.get());
    }
    arm = ArmDriver::create(r, cfg, &error);
  }

  /// One control cycle at time t, then t += period.
  const mrqp::drivers::FaultReport& cycle() {
    for (auto& b : buses) {
      b->advanceTo(t);
    }
    for (auto& r : routers) {
      r->poll(t);
    }
    const mrqp::drivers::FaultReport& rep = arm->update(t);
    if (hook) {
      hook(*this);
    }
    arm->transmit(t);
    last = t;
    t += config.cycle_period;
    return rep;
  }

  /// Boots: start() then cycles until Running (or `max` cycles). Returns the cycles used.
  int boot(int max = 400) {
    arm->start(t);
    int k = 0;
    while (arm->phase() != mrqp::drivers::ArmPhase::Running &&
           arm->phase() != mrqp::drivers::ArmPhase::Failed && k < max) {
      cycle();
      ++k;
    }
    flush();
    return k;
  }

  /// Runs the buses up to the next cycle time: the frames of the last transmit are on the wire.
  void flush() {
    for (auto& b : buses) {
      b->advanceTo(t);
    }
  }

  /// Frames the master sent on `bus` since `from` (after flush()).
  std::vector<std::string> masterFrames(mrqp::drivers::TimeNs from = 0, std::size_t bus = 0) {
    flush();
    return logs[bus]->frames(static_cast<long>(masters[bus]->index()), from);
  }

  /// Every frame on `bus` (after flush()).
  std::vector<std::string> wire(std::size_t bus = 0) {
    flush();
    return logs[bus]->frames();
  }

  std::vector<std::unique_ptr<mrqp::drivers::SimBus>> buses;
  std::vector<std::unique_ptr<WireLog>> logs;
  std::vector<mrqp::drivers::SimNode*> masters;
  std::vector<std::unique_ptr<mrqp::drivers::BusRouter>> routers;
  std::vector<std::unique_ptr<FakeCia402Drive>> fakes;
  mrqp::drivers::ArmConfig config;
  std::unique_ptr<mrqp::drivers::ArmDriver> arm;
  std::string error;
  std::function<void(ArmRig&)> hook;
  mrqp::drivers::TimeNs t = 0;
  mrqp::drivers::TimeNs last = 0;
};

}  // namespace drvtest
