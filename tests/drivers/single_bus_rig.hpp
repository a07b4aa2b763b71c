// A test bench for a driver on one simulated bus: the bus and its wire log, the master node and
// its router, the driver, and the cycle as the control loop runs it (advance, poll, update, hook,
// transmit). A rig derives from it (CRTP, so that hooks get the derived rig), adds its fake
// devices and the `injector` node (frames put on the wire by hand), and creates the driver.
#pragma once

#include <mrqp/drivers/bus_router.hpp>
#include <mrqp/drivers/faults.hpp>
#include <mrqp/drivers/sim_bus.hpp>

#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "sim_trace.hpp"

namespace drvtest {

template <class Rig, class Driver>
struct SingleBusRig {
  /// A classic bus, or with `fd` a CAN FD bus (5 Mbit/s data phase) and an FD master.
  SingleBusRig(bool fd, TimeNs cycle_period) : period(cycle_period), bus(busConfig(fd)) {
    bus.setTap(&log);
    mrqp::drivers::SimNodeConfig mc;
    mc.fd = fd;
    mc.name = "master";
    master = bus.addNode(mc);
    router = std::make_unique<mrqp::drivers::BusRouter>(*master);
  }

  /// One control cycle at time t, then t += period.
  const mrqp::drivers::FaultReport& cycle() {
    bus.advanceTo(t);
    router->poll(t);
    const mrqp::drivers::FaultReport& r = driver->update(t);
    if (hook) {
      hook(static_cast<Rig&>(*this));
    }
    driver->transmit(t);
    last = t;
    t += period;
    return r;
  }

  /// Frames the master sent since `from`, the last transmit's included.
  std::vector<std::string> masterFrames(TimeNs from) {
    bus.advanceTo(t);
    return log.frames(static_cast<long>(master->index()), from);
  }

  static mrqp::drivers::SimBusConfig busConfig(bool fd) {
    mrqp::drivers::SimBusConfig bc;
    bc.data_bps = fd ? 5000000u : 0u;
    return bc;
  }

  TimeNs period;
  mrqp::drivers::SimBus bus;
  WireLog log;
  mrqp::drivers::SimNode* master = nullptr;
  mrqp::drivers::SimNode* injector = nullptr;
  std::unique_ptr<mrqp::drivers::BusRouter> router;
  std::unique_ptr<Driver> driver;
  std::string error;
  std::function<void(Rig&)> hook;
  TimeNs t = 0;
  TimeNs last = 0;
};

}  // namespace drvtest
