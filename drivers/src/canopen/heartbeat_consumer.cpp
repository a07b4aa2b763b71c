// mrqp drivers -- CANopen master, heartbeat consumer of one node (see canopen/heartbeat_consumer.hpp).
#include "mrqp/drivers/canopen/heartbeat_consumer.hpp"

namespace mrqp::drivers {

void HeartbeatConsumer::init(bool produces, TimeNs timeout) noexcept {
  produces_ = produces;
  timeout_ = timeout;
  monitoring_ = false;
  state_ = 0xFF;
  last_ = 0;
}

void HeartbeatConsumer::onHeartbeat(mrqp_fw_nmt_state state, TimeNs t) noexcept {
  state_ = static_cast<std::uint8_t>(state);
  last_ = t;
  monitoring_ = produces_;
}

}  // namespace mrqp::drivers
