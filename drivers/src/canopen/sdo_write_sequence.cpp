// mrqp drivers -- CANopen master, the SDO write sequence of one node: the real-time part
// (see canopen/sdo_write_sequence.hpp).
#include "mrqp/drivers/canopen/sdo_write_sequence.hpp"

namespace mrqp::drivers {

void SdoWriteSequence::restart() noexcept {
  step_ = 0;
  mrqp_fw_sdo_client_reset(&client_);
  busy_ = false;
  read_value_ = 0;
  tolerated_ = 0;
  tolerated_index_ = 0;
  tolerated_subindex_ = 0;
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
  mrqp_fw_sdo_step first = MRQP_FW_SDO_STEP_ERROR;
  if (w.access == SdoAccess::ReadCheck) {
    data_.fill(0);
    first = mrqp_fw_sdo_client_start_upload(&client_, node_, w.index, w.subindex, data_.data(),
                                            static_cast<std::uint32_t>(data_.size()), out);
  } else {
    for (unsigned k = 0; k < 4; ++k) {
      data_[k] = static_cast<std::uint8_t>((w.value >> (8u * k)) & 0xFFu);
    }
    first =
        mrqp_fw_sdo_client_start_download(&client_, node_, w.index, w.subindex, data_.data(), w.size, out);
  }
  if (first != MRQP_FW_SDO_STEP_SEND) {
    return Step::Failed;
  }
  busy_ = true;
  sent_at_ = now;
  return Step::Send;
}

SdoWriteSequence::Step SdoWriteSequence::onFrame(const mrqp_fw_frame& f, mrqp_fw_frame* out) noexcept {
  if (!busy_) {
    return Step::Unexpected;
  }
  const SdoWrite& w = writes_[step_];
  switch (mrqp_fw_sdo_client_on_frame(&client_, &f, out)) {
    case MRQP_FW_SDO_STEP_DONE:
      busy_ = false;
      if (w.access == SdoAccess::ReadCheck) {
        std::uint32_t v = 0;
        for (std::uint32_t k = 0; k < client_.count && k < 4u; ++k) {
          v |= static_cast<std::uint32_t>(data_[k]) << (8u * k);
        }
        read_value_ = v;
        if ((v & w.mask) != (w.value & w.mask)) {
          return Step::Mismatch;
        }
      }
      ++step_;
      return Step::Done;
    case MRQP_FW_SDO_STEP_SEND:
      return Step::Send;
    case MRQP_FW_SDO_STEP_ABORTED:
      busy_ = false;
      if (w.access == SdoAccess::WriteUnlessAbsent && client_.abort_code == MRQP_FW_SDO_ABORT_NO_OBJECT) {
        ++tolerated_;
        tolerated_index_ = w.index;
        tolerated_subindex_ = w.subindex;
        ++step_;
        return Step::Done;
      }
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
