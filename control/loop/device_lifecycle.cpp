// The devices' boot and safe exit (see device_lifecycle.hpp).
#include "loop/device_lifecycle.hpp"

#include <cmath>

namespace mrqp::loop {

namespace {

/// Runs `step` once per cycle until it returns true or `timeout_s` has passed.
template <class Step>
LifecycleResult runCycles(drivers::TimeNs& now, drivers::TimeNs period, EmulatedRig* rig, double timeout_s,
                          const NextCycleTime& next, Step step) {
  LifecycleResult res;
  const long limit = std::max(1L, std::lround(timeout_s * 1e9 / static_cast<double>(period)));
  for (; res.cycles < limit && !res.done; ++res.cycles) {
    res.done = step(now);
    if (rig != nullptr) rig->advanceTo(now + period);
    now = next ? next() : now + period;
  }
  return res;
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
