// Per-phase times of a cycle (docs/loop.md, "Devices without a scene"): a cycle is cut into
// phases (e.g. read, estimate, update, solve, write) by laps of the monotonic clock, and each
// phase keeps its count, total and largest time. Fixed size, no allocation: real-time safe.
#pragma once

#include <mrqp/drivers/time.hpp>

#include <algorithm>
#include <array>
#include <cstddef>
#include <cstdint>

namespace mrqp::loop {

template <std::size_t N>
class PhaseTimes {
 public:
  /// The cycle's first phase starts now.
  void begin() noexcept { mark_ = drivers::monotonicNow(); }
  /// Phase `p` ends now (and the next one starts).
  void lap(std::size_t p) noexcept {
    const drivers::TimeNs t = drivers::monotonicNow();
    add(p, t - mark_);
    mark_ = t;
  }
  /// Records one duration of phase `p` (what lap() does with the clock's).
  void add(std::size_t p, drivers::TimeNs ns) noexcept {
    if (p >= N) return;
    ++count_[p];
    total_[p] += ns;
    max_[p] = std::max(max_[p], ns);
  }
  std::uint64_t count(std::size_t p) const noexcept { return p < N ? count_[p] : 0u; }
  drivers::TimeNs max(std::size_t p) const noexcept { return p < N ? max_[p] : 0; }
  /// The mean time of phase `p`, ns (0 before any).
  double mean(std::size_t p) const noexcept {
    return p < N && count_[p] > 0u ? static_cast<double>(total_[p]) / static_cast<double>(count_[p]) : 0.0;
  }

 private:
  drivers::TimeNs mark_ = 0;
  std::array<std::uint64_t, N> count_{};
  std::array<drivers::TimeNs, N> total_{};
  std::array<drivers::TimeNs, N> max_{};
};

}  // namespace mrqp::loop
