// mrqp drivers -- CANopen master, the SDO write sequence of one node: set-up (allocates).
#include <utility>

#include "mrqp/drivers/canopen/sdo_write_sequence.hpp"

namespace mrqp::drivers {

void SdoWriteSequence::init(std::uint8_t node, std::vector<SdoWrite> writes, TimeNs sdo_timeout) {
  node_ = node;
  writes_ = std::move(writes);
  timeout_ = sdo_timeout;
  restart();
}

}  // namespace mrqp::drivers
