// A set of devices on their buses' routers, booted and stopped as the controller boots and stops
// its robots' devices (docs/loop.md, "Safety"), for a program that drives devices without a
// scene (mrqp-stream): the same boot cycle (poll the routers, update every device, enable once
// every arm driver runs, hold every joint at its feedback until enabled, transmit) and the same
// safe exit (ArmDriver::requestSafeExit for arm drivers, disable for the others), through the
// same cycle runner (device_cycles.hpp) as loop::bootDevices / exitDevices for a Controller.
//
// The routers and devices are not owned. Set-up allocates; startDevices, bootCycle,
// requestSafeExit and exitCycle are real-time safe (no allocation, no lock, no throw).
#pragma once

#include <mrqp/drivers/arm_driver.hpp>
#include <mrqp/drivers/bus_router.hpp>
#include <mrqp/drivers/device.hpp>

#include <cstdint>
#include <functional>
#include <vector>

#include "loop/device_cycles.hpp"

namespace mrqp::loop {

class DeviceSet {
 public:
  DeviceSet(std::vector<drivers::BusRouter*> routers, std::vector<drivers::Device*> devices);

  void startDevices(drivers::TimeNs now) noexcept;
  /// One boot cycle; true when every device is ready (booted and enabled). Fault flags seen are
  /// OR-ed into bootFlags().
  bool bootCycle(drivers::TimeNs now) noexcept;
  std::uint32_t bootFlags() const noexcept { return boot_flags_; }
  /// The boot cycles run before the enable was requested (every arm driver running); -1 before.
  long enableRequestedAfter() const noexcept { return enable_after_; }
  /// Some arm driver's boot failed (ArmPhase::Failed): it will not become ready.
  bool bootFailed() const noexcept;

  void requestSafeExit(drivers::TimeNs now) noexcept;
  /// One cycle of the safe exit; true once every arm driver has stopped its drives and the
  /// others' disable has gone out for three cycles.
  bool exitCycle(drivers::TimeNs now) noexcept;
  bool exitDone() const noexcept;
  std::uint32_t exitFlags() const noexcept { return exit_flags_; }

 private:
  std::vector<drivers::BusRouter*> routers_;
  std::vector<drivers::Device*> devices_;
  std::vector<drivers::ArmDriver*> arms_;
  std::uint32_t boot_flags_ = 0;
  std::uint32_t exit_flags_ = 0;
  long boot_cycle_ = 0;
  long enable_after_ = -1;
  long exit_cycle_ = 0;
};

/// Stop asked for from outside (e.g. a signal), checked after each cycle.
using StopRequested = std::function<bool()>;

/// Boots and enables every device of `set` (see device_lifecycle.hpp for a Controller); ends
/// early when an arm driver's boot has failed or `stop` says so. `now` is advanced per cycle.
LifecycleResult bootDevices(DeviceSet& set, drivers::TimeNs& now, drivers::TimeNs period,
                            double timeout_s = 10.0, const NextCycleTime& next = NextCycleTime(),
                            const StopRequested& stop = StopRequested());

/// The safe exit of every device of `set`.
LifecycleResult exitDevices(DeviceSet& set, drivers::TimeNs& now, drivers::TimeNs period,
                            double timeout_s = 2.0, const NextCycleTime& next = NextCycleTime());

}  // namespace mrqp::loop
