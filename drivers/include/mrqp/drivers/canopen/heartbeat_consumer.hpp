// mrqp drivers -- CANopen master, heartbeat consumer of one node (CiA 301 0x1016 on the master's
// side): the node's last NMT state and when it was heard, and whether it has gone silent.
//
// Monitoring starts with the first heartbeat after restart() (when the node produces heartbeats
// at all); process(now) is true while the last heartbeat is older than the consumer time.
// Real-time safe, no allocation.
#pragma once

#include <cstdint>

#include "mrqp/drivers/time.hpp"
#include "mrqp/firmware_if/nmt.h"

namespace mrqp::drivers {

class HeartbeatConsumer {
 public:
  /// `produces`: the node was configured to send heartbeats; `timeout`: the consumer time.
  void init(bool produces, TimeNs timeout) noexcept;
  /// Forget the node's heartbeats (a new boot).
  void restart() noexcept { monitoring_ = false; }
  /// A heartbeat (or boot-up, state 0) of the node received at `t`.
  void onHeartbeat(mrqp_fw_nmt_state state, TimeNs t) noexcept;
  /// True when the node is monitored and silent for longer than the consumer time.
  bool process(TimeNs now) const noexcept { return monitoring_ && now - last_ > timeout_; }

  bool monitoring() const noexcept { return monitoring_; }
  /// Last reported state (0xFF: none yet).
  std::uint8_t state() const noexcept { return state_; }
  TimeNs last() const noexcept { return last_; }

 private:
  bool produces_ = false;
  TimeNs timeout_ = 0;
  bool monitoring_ = false;
  std::uint8_t state_ = 0xFF;
  TimeNs last_ = 0;
};

}  // namespace mrqp::drivers
