// The cycle runner of the devices' boot and safe exit (docs/loop.md, "Safety"): one step per
// cycle until the step reports done, a stop is asked for or the time limit has passed. Shared by
// the controller's lifecycle (device_lifecycle.hpp) and a plain set of devices (device_set.hpp).
// Not real time (runs outside the control cycle).
#pragma once

#include <mrqp/drivers/time.hpp>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <functional>

namespace mrqp::loop {

/// Returns the time of the next cycle (may wait for it).
using NextCycleTime = std::function<drivers::TimeNs()>;

struct LifecycleResult {
  bool done = false;        ///< every device ready (boot) / stopped (exit)
  long cycles = 0;          ///< cycles run
  std::uint32_t flags = 0;  ///< fault flags seen meanwhile (drivers::fault::)
};

/// Runs `step(now)` (true: done) once per cycle, then `after(now)` (e.g. a simulated rig runs to
/// the next cycle), then takes the next cycle time from `next` (when given, else now + period),
/// until done, `stop()` is true or `timeout_s` has passed; `now` is advanced cycle by cycle.
template <class Step, class After, class Stop>
LifecycleResult runDeviceCycles(drivers::TimeNs& now, drivers::TimeNs period, double timeout_s,
                                const NextCycleTime& next, Step step, After after, Stop stop) {
  LifecycleResult res;
  const long limit = std::max(1L, std::lround(timeout_s * 1e9 / static_cast<double>(period)));
  for (; res.cycles < limit && !res.done; ++res.cycles) {
    res.done = step(now);
    after(now);
    now = next ? next() : now + period;
    if (!res.done && stop()) {
      ++res.cycles;
      break;
    }
  }
  return res;
}

}  // namespace mrqp::loop
