// mrqp drivers -- time base of the drivers: signed 64-bit nanoseconds.
//
// Every driver entry point takes the current time as an argument instead of reading a clock, so
// the same code runs on the real clock (CLOCK_MONOTONIC, see monotonicNow()) and on the
// simulated clock of the in-process bus (SimBus::now()), and tests are deterministic.
#pragma once

#include <cstdint>

namespace mrqp::drivers {

/// Nanoseconds on the caller's monotonic clock.
using TimeNs = std::int64_t;

constexpr TimeNs microseconds(std::int64_t us) noexcept { return us * 1000; }
constexpr TimeNs milliseconds(std::int64_t ms) noexcept { return ms * 1000000; }
constexpr TimeNs seconds(std::int64_t s) noexcept { return s * 1000000000; }

/// Period in nanoseconds of a cycle rate in Hz (rounded to the nearest nanosecond).
constexpr TimeNs periodOfHz(double hz) noexcept { return hz > 0.0 ? static_cast<TimeNs>(1e9 / hz + 0.5) : 0; }

/// CLOCK_MONOTONIC in nanoseconds (real-time safe: a vDSO call, no allocation).
TimeNs monotonicNow() noexcept;

}  // namespace mrqp::drivers
