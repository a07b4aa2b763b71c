// A set of devices booted and stopped like the controller's (see device_set.hpp).
#include "loop/device_set.hpp"

#include <algorithm>
#include <utility>

namespace mrqp::loop {

DeviceSet::DeviceSet(std::vector<drivers::BusRouter*> routers, std::vector<drivers::Device*> devices)
    : routers_(std::move(routers)), devices_(std::move(devices)) {
  for (drivers::Device* d : devices_) {
    if (auto* arm = dynamic_cast<drivers::ArmDriver*>(d)) arms_.push_back(arm);
  }
}

void DeviceSet::startDevices(drivers::TimeNs now) noexcept {
  for (drivers::Device* d : devices_) d->start(now);
}

bool DeviceSet::bootCycle(drivers::TimeNs now) noexcept {
  ++boot_cycle_;
  for (drivers::BusRouter* r : routers_) r->poll(now);
  bool all_ready = true;
  for (drivers::Device* d : devices_) {
    boot_flags_ |= d->update(now).flags;
    all_ready = all_ready && d->ready();
  }
  const bool all_booted = std::all_of(arms_.begin(), arms_.end(), [](const drivers::ArmDriver* a) {
    return a->phase() == drivers::ArmPhase::Running;
  });
  if (all_booted && enable_after_ < 0) {
    enable_after_ = boot_cycle_;
    for (drivers::Device* d : devices_) d->requestEnable(now);
  }
  for (drivers::Device* d : devices_) {
    if (auto* jd = dynamic_cast<drivers::JointDevice*>(d)) {
      // Until enabled, hold every joint where it is.
      for (std::size_t j = 0; j < jd->jointCount(); ++j) {
        const drivers::JointFeedback fb = jd->joint(j);
        if (!fb.valid) continue;
        drivers::JointCommand c;
        c.position = fb.position;
        (void)jd->setJoint(j, c);
      }
    }
    (void)d->transmit(now);
  }
  return all_ready;
}

bool DeviceSet::bootFailed() const noexcept {
  return std::any_of(arms_.begin(), arms_.end(),
                     [](const drivers::ArmDriver* a) { return a->phase() == drivers::ArmPhase::Failed; });
}

void DeviceSet::requestSafeExit(drivers::TimeNs now) noexcept {
  exit_cycle_ = 0;
  for (drivers::Device* d : devices_) {
    if (auto* arm = dynamic_cast<drivers::ArmDriver*>(d)) {
      arm->setSafeState(true);
      arm->requestSafeExit(now);
    } else {
      d->requestDisable(now);
    }
  }
}

bool DeviceSet::exitCycle(drivers::TimeNs now) noexcept {
  for (drivers::BusRouter* r : routers_) r->poll(now);
  for (drivers::Device* d : devices_) exit_flags_ |= d->update(now).flags;
  for (drivers::Device* d : devices_) (void)d->transmit(now);
  ++exit_cycle_;
  return exitDone() && exit_cycle_ >= 3;
}

bool DeviceSet::exitDone() const noexcept {
  return std::all_of(arms_.begin(), arms_.end(),
                     [](const drivers::ArmDriver* a) { return a->safeExitDone(); });
}

LifecycleResult bootDevices(DeviceSet& set, drivers::TimeNs& now, drivers::TimeNs period, double timeout_s,
                            const NextCycleTime& next, const StopRequested& stop) {
  set.startDevices(now);
  LifecycleResult res = runDeviceCycles(
      now, period, timeout_s, next, [&](drivers::TimeNs t) { return set.bootCycle(t); },
      [](drivers::TimeNs) {}, [&] { return set.bootFailed() || (stop && stop()); });
  res.flags = set.bootFlags();
  return res;
}

LifecycleResult exitDevices(DeviceSet& set, drivers::TimeNs& now, drivers::TimeNs period, double timeout_s,
                            const NextCycleTime& next) {
  set.requestSafeExit(now);
  LifecycleResult res = runDeviceCycles(
      now, period, timeout_s, next, [&](drivers::TimeNs t) { return set.exitCycle(t); },
      [](drivers::TimeNs) {}, [] { return false; });
  res.flags = set.exitFlags();
  return res;
}

}  // namespace mrqp::loop
