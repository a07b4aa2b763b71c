// The devices' boot and safe exit (see device_lifecycle.hpp).
#include "loop/device_lifecycle.hpp"

namespace mrqp::loop {

namespace {

/// Runs `step` once per cycle until it returns true or `timeout_s` has passed.
template <class Step>
LifecycleResult runCycles(drivers::TimeNs& now, drivers::TimeNs period, EmulatedRig* rig, double timeout_s,
                          const NextCycleTime& next, Step step) {
  return runDeviceCycles(
      now, period, timeout_s, next, step,
      [rig, period](drivers::TimeNs t) {
        if (rig != nullptr) rig->advanceTo(t + period);
      },
      [] { return false; });
}

}  // namespace

LifecycleResult bootDevices(Controller& controller, drivers::TimeNs& now, drivers::TimeNs period,
                            EmulatedRig* rig, double timeout_s, const NextCycleTime& next) {
  controller.startDevices(now);
  LifecycleResult res = runCycles(now, period, rig, timeout_s, next,
                                  [&](drivers::TimeNs t) { return controller.bootCycle(t); });
  res.flags = controller.bootFlags();
  return res;
}

LifecycleResult exitDevices(Controller& controller, drivers::TimeNs& now, drivers::TimeNs period,
                            EmulatedRig* rig, double timeout_s, const NextCycleTime& next) {
  controller.requestSafeExit(now);
  LifecycleResult res = runCycles(now, period, rig, timeout_s, next,
                                  [&](drivers::TimeNs t) { return controller.exitCycle(t); });
  res.flags = controller.exitFlags();
  return res;
}

}  // namespace mrqp::loop
