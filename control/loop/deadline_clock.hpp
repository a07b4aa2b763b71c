// Absolute deadlines for the loop (docs/loop.md, "Real time"): wait() sleeps until the next
// deadline with clock_nanosleep(TIMER_ABSTIME) on CLOCK_MONOTONIC. A cycle that ends after its
// deadline is an overrun: counted, and the schedule moves on to the first deadline still ahead
// (lateness is never accumulated into the following cycles). Real-time safe.
#pragma once

#include <mrqp/drivers/time.hpp>

#include <cstdint>

namespace mrqp::loop {

class DeadlineClock {
 public:
  explicit DeadlineClock(drivers::TimeNs period) noexcept : period_(period) {}
  /// The first deadline is one period from now; returns now.
  drivers::TimeNs start() noexcept;
  /// Sleeps until the next deadline and returns it (the cycle's time).
  drivers::TimeNs wait() noexcept;
  std::uint64_t overruns() const noexcept { return overruns_; }
  std::uint64_t skipped() const noexcept { return skipped_; }
  drivers::TimeNs worstLateness() const noexcept { return worst_late_; }

 private:
  drivers::TimeNs period_;
  drivers::TimeNs next_ = 0;
  std::uint64_t overruns_ = 0;
  std::uint64_t skipped_ = 0;
  drivers::TimeNs worst_late_ = 0;
};

}  // namespace mrqp::loop
