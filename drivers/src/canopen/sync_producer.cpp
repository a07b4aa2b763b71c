// mrqp drivers -- CANopen master, SYNC producer of one bus (see canopen/sync_producer.hpp).
#include "mrqp/drivers/canopen/sync_producer.hpp"

#include "mrqp/firmware_if/sync.h"

namespace mrqp::drivers {

void SyncProducer::init(std::uint8_t counter_overflow) noexcept {
  overflow_ = counter_overflow;
  counter_ = 0;
}

void SyncProducer::process(TimeNs, mrqp_fw_frame* out) noexcept {
  if (overflow_ >= 2u) {
    counter_ = mrqp_fw_sync_counter_next(counter_, overflow_);
  }
  (void)mrqp_fw_sync_pack(overflow_ >= 2u ? counter_ : 0u, out);
}

}  // namespace mrqp::drivers
