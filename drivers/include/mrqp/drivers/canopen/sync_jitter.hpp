// mrqp drivers -- CANopen master, the SYNC of one bus as it went out: intervals between
// successive SYNC frames against the cycle period (jitter), and the gaps a drive enforcing a SYNC
// timeout of `timeout_factor` x 0x1006 would take for a lost SYNC (CiA 301 leaves the factor to
// the device; 1.5 is common).
//
// The time of each SYNC is the time of its TX echo where the bus returns the master's own frames
// (the wire time on SimBus, the kernel's time on SocketCAN with receive_own), else the time the
// caller handed to transmit() (on the robot: the loop's absolute deadline, so without echoes the
// figure shows the deadlines, not the wire). restart() forgets the previous SYNC (a new boot).
// Real-time safe, no allocation.
#pragma once

#include <cstdint>

#include "mrqp/drivers/time.hpp"

namespace mrqp::drivers {

struct SyncStats {
  std::uint64_t syncs = 0;          ///< SYNC frames timed
  std::uint64_t intervals = 0;      ///< intervals measured (syncs - 1 per unbroken run)
  TimeNs period = 0;                ///< the nominal interval (cycle period)
  TimeNs min_interval = 0;          ///< shortest interval
  TimeNs max_interval = 0;          ///< longest interval
  TimeNs max_jitter = 0;            ///< largest |interval - period|
  double mean_abs_jitter_ns = 0.0;  ///< mean |interval - period|
  std::uint64_t over_timeout = 0;   ///< intervals longer than timeout_factor x period
  double timeout_factor = 1.5;
};

class SyncJitter {
 public:
  void init(TimeNs period, double timeout_factor) noexcept;
  /// The next SYNC starts a new series (no interval to the previous one).
  void restart() noexcept { have_last_ = false; }
  /// A SYNC went out at `t`.
  void onSync(TimeNs t) noexcept;
  const SyncStats& stats() const noexcept { return stats_; }

 private:
  SyncStats stats_{};
  double sum_abs_ = 0.0;
  bool have_last_ = false;
  TimeNs last_ = 0;
};

}  // namespace mrqp::drivers
