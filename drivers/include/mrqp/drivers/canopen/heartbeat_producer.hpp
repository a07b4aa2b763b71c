// mrqp drivers -- CANopen master, the master's own heartbeat (CiA 301 0x1017 on the master's
// side), which the drives consume (their 0x1016) to notice a master that has stopped.
// Real-time safe, no allocation.
#pragma once

#include <cstdint>

#include "mrqp/drivers/time.hpp"
#include "mrqp/firmware_if/frame.h"

namespace mrqp::drivers {

class HeartbeatProducer {
 public:
  /// `node` 0: no heartbeat. `period_ms` 0 is taken as 1 ms.
  void init(std::uint8_t node, std::uint16_t period_ms) noexcept;
  /// The next heartbeat is due at `now`.
  void restart(TimeNs now) noexcept { next_ = now; }
  /// True when a heartbeat (state operational) is due at `now`: the frame in `out`, and the next
  /// one is scheduled a whole number of periods later.
  bool process(TimeNs now, mrqp_fw_frame* out) noexcept;

 private:
  std::uint8_t node_ = 0;
  TimeNs period_ = 0;
  TimeNs next_ = 0;
};

}  // namespace mrqp::drivers
