// Absolute deadlines (see deadline_clock.hpp).
#include "loop/deadline_clock.hpp"

#include <time.h>

namespace mrqp::loop {

namespace {
timespec toTimespec(drivers::TimeNs t) noexcept {
  timespec ts;
  ts.tv_sec = static_cast<time_t>(t / 1000000000);
  ts.tv_nsec = static_cast<long>(t % 1000000000);
  return ts;
}
}  // namespace

drivers::TimeNs DeadlineClock::start() noexcept {
  const drivers::TimeNs now = drivers::monotonicNow();
  next_ = now;
  return now;
}

drivers::TimeNs DeadlineClock::wait() noexcept {
  next_ += period_;
  drivers::TimeNs now = drivers::monotonicNow();
  if (now > next_) {
    // Overrun: the previous cycle ended after this deadline. Start now, on the grid, without
    // trying to catch up the missed cycles.
    ++overruns_;
    const drivers::TimeNs late = now - next_;
    if (late > worst_late_) worst_late_ = late;
    const drivers::TimeNs missed = late / period_;
    skipped_ += static_cast<std::uint64_t>(missed);
    next_ += missed * period_;
    return now;
  }
  const timespec ts = toTimespec(next_);
  while (clock_nanosleep(CLOCK_MONOTONIC, TIMER_ABSTIME, &ts, nullptr) != 0) {}
  now = drivers::monotonicNow();
  if (now - next_ > worst_late_) worst_late_ = now - next_;
  return next_;
}

}  // namespace mrqp::loop
