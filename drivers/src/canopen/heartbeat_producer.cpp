// mrqp drivers -- CANopen master, the master's heartbeat (see canopen/heartbeat_producer.hpp).
#include "mrqp/drivers/canopen/heartbeat_producer.hpp"

#include "mrqp/firmware_if/nmt.h"

namespace mrqp::drivers {

void HeartbeatProducer::init(std::uint8_t node, std::uint16_t period_ms) noexcept {
  node_ = node;
  period_ = milliseconds(period_ms > 0u ? period_ms : 1);
  next_ = 0;
}

bool HeartbeatProducer::process(TimeNs now, mrqp_fw_frame* out) noexcept {
  if (node_ == 0u || now < next_) {
    return false;
  }
  (void)mrqp_fw_heartbeat_pack(node_, MRQP_FW_NMT_STATE_OPERATIONAL, out);
  while (next_ <= now) {
    next_ += period_;
  }
  return true;
}

}  // namespace mrqp::drivers
