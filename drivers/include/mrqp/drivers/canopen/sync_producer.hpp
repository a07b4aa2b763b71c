// mrqp drivers -- CANopen master, SYNC producer of one bus (CiA 301 0x1005 / 0x1019): one SYNC
// per control cycle, with a counter 1..overflow when the counter overflow value is 2..240.
// Real-time safe, no allocation.
#pragma once

#include <cstdint>

#include "mrqp/drivers/time.hpp"
#include "mrqp/firmware_if/frame.h"

namespace mrqp::drivers {

class SyncProducer {
 public:
  /// `counter_overflow`: 0 for SYNC without a counter, 2..240 for a counter.
  void init(std::uint8_t counter_overflow) noexcept;
  /// The counter starts again at 1 with the next SYNC.
  void restart() noexcept { counter_ = 0; }
  /// This cycle's SYNC in `out` (the counter moves on whether or not the frame gets sent).
  void process(TimeNs now, mrqp_fw_frame* out) noexcept;
  std::uint8_t counter() const noexcept { return counter_; }

 private:
  std::uint8_t overflow_ = 0;
  std::uint8_t counter_ = 0;
};

}  // namespace mrqp::drivers
