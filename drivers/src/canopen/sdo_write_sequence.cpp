// mrqp drivers -- CANopen master, the SDO write sequence of one node: the real-time part
// (see canopen/sdo_write_sequence.hpp).
#include "mrqp/drivers/canopen/sdo_write_sequence.hpp"

namespace mrqp::drivers {

void SdoWriteSequence::restart() noexcept {
  step_ = 0;
  mrqp_fw_sdo_client_reset(&client_);
  busy_ = false;
}

SdoWriteSequence::Step SdoWriteSequence::process(TimeNs now, bool start, mrqp_fw_frame* out) noexcept {
  if (busy_) {
    if (now - sent_at_ <= timeout_) {
      return Step::Idle;
    }
    busy_ = false;
    const bool send = mrqp_fw_sdo_client_timeout(&client_, out) == MRQP_FW_SDO_STEP_ABORT_SEND;
    client_.abort_code = MRQP_FW_SDO_ABORT_TIMEOUT;
    return send ? Step::FailedSend : Step::Failed;
  }
  if (!start || done()) {
    return Step::Idle;
  }
  const SdoWrite& w = writes_[step_];
  for (unsigned k = 0; k < 4; ++k) {
    data_[k] = static_cast<std::uint8_t>((w.value >> (8u * k)) & 0xFFu);
  }
  if (mrqp_fw_sdo_client_start_download(&client_, node_, w.index, w.subindex, data_.data(), w.size, out) !=
      MRQP_FW_SDO_STEP_SEND) {
    return Step::Failed;
  }
  busy_ = true;
  sent_at_ = now;
  return Step::Send;
}

SdoWriteSequence::Step SdoWriteSequence::on_frame(const mrqp_fw_frame& f, mrqp_fw_frame* out) noexcept {
  if (!busy_) {
    return Step::Unexpected;
  }
  switch (mrqp_fw_sdo_client_on_frame(&client_, &f, out)) {
    case MRQP_FW_SDO_STEP_DONE:
      busy_ = false;
      ++step_;
      return Step::Done;
    case MRQP_FW_SDO_STEP_SEND:
      return Step::Send;
    case MRQP_FW_SDO_STEP_ABORTED:
      busy_ = false;
      return Step::Failed;
    case MRQP_FW_SDO_STEP_ABORT_SEND:
      busy_ = false;
      return Step::FailedSend;
    case MRQP_FW_SDO_STEP_IGNORED:
    case MRQP_FW_SDO_STEP_ERROR:
      break;
  }
  return Step::Unexpected;
}

}  // namespace mrqp::drivers
