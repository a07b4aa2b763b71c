// What mrqp-stream watches while it streams and prints at the end (README.md, "mrqp-stream"): per
// drive the largest tracking error, the heartbeat loss (and its time), the first faults of each
// kind in order, the failed cycles and their flags, the time of the cycle's read and write
// phases. Capacities are fixed at construction; note() and the per-cycle calls are real-time safe
// (no allocation, no printing), the print calls are not.
#pragma once

#include <mrqp/drivers/arm_driver.hpp>

#include "loop/phase_times.hpp"

#include <cstdint>
#include <vector>

namespace mrqp::stream {

class StreamMonitor {
 public:
  /// `expect_hb_drive`: index of the drive whose heartbeat loss is the point of the run (-1: none).
  StreamMonitor(std::size_t drives, double max_error, int expect_hb_drive);

  /// Copies the faults first seen in `r` into the fault events (every cycle, boot included).
  void note(const drivers::FaultReport& r) noexcept;
  /// Checks one streaming cycle `k` (after the arm driver's update): heartbeat loss, hard faults,
  /// the tracking error against what was sent the cycle before; `since_start` times the loss.
  void check(long k, drivers::TimeNs since_start, const drivers::FaultReport& r,
             const drivers::ArmDriver& arm) noexcept;
  /// The position sent to drive j this cycle.
  void sent(std::size_t j, double q) noexcept { sent_[j] = q; }
  /// The cycle's phases: read (poll + update), then write (setpoints + transmit), timed by laps.
  enum Phase : std::size_t { kRead = 0, kWrite, kPhases };
  loop::PhaseTimes<kPhases>& phases() noexcept { return phases_; }
  void flags(std::uint32_t f) noexcept { all_flags_ |= f; }
  void nextCycle() noexcept { ++cycle_; }

  std::uint32_t allFlags() const noexcept { return all_flags_; }
  std::uint64_t failedCycles() const noexcept { return fail_cycles_; }
  std::uint32_t failFlags() const noexcept { return fail_flags_; }
  bool heartbeatLost(std::size_t j) const noexcept { return hb_lost_at_[j] >= 0; }

  void printEvents() const;
  void printPhases() const;
  /// One line per drive: max error, the drivers' counters (from `faults`), heartbeat loss.
  void printDrives(const drivers::ArmConfig& cfg, const std::vector<drivers::DeviceFaults>& faults) const;
  /// The heartbeat-loss line of drive j (detected at, wall time, timeout).
  void printHeartbeatLoss(std::size_t j, int node, int timeout_ms) const;

 private:
  struct Event {
    long cycle = 0;
    std::size_t drive = 0;
    drivers::DeviceFaults faults;
  };
  double max_error_;
  int hb_drive_;
  long cycle_ = 0;
  std::vector<double> sent_, max_err_, hb_lost_wall_;
  std::vector<std::uint64_t> hb_lost_;
  std::vector<drivers::TimeNs> hb_lost_at_;
  std::vector<std::uint32_t> reported_;
  std::vector<Event> events_;
  std::size_t event_count_ = 0;
  std::uint64_t fail_cycles_ = 0;
  std::uint32_t fail_flags_ = 0;
  std::uint32_t all_flags_ = 0;
  loop::PhaseTimes<kPhases> phases_;
};

}  // namespace mrqp::stream
