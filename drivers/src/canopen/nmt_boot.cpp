// mrqp drivers -- CANopen master, NMT boot of one node (see canopen/nmt_boot.hpp).
#include "mrqp/drivers/canopen/nmt_boot.hpp"

#include "mrqp/firmware_if/nmt.h"

namespace mrqp::drivers {

namespace {
mrqp_fw_nmt_cmd bootCommand(NmtReset reset) noexcept {
  return reset == NmtReset::Node            ? MRQP_FW_NMT_RESET_NODE
         : reset == NmtReset::Communication ? MRQP_FW_NMT_RESET_COMM
                                            : MRQP_FW_NMT_ENTER_PREOP;
}
}  // namespace

void NmtBoot::init(std::uint8_t node, NmtReset reset, TimeNs boot_timeout) noexcept {
  node_ = node;
  reset_ = reset;
  boot_timeout_ = boot_timeout;
  begun_ = false;
  booted_ = false;
  sent_ = false;
  echoed_ = false;
}

void NmtBoot::begin(TimeNs now, mrqp_fw_frame* out) noexcept {
  begun_ = true;
  booted_ = reset_ == NmtReset::None;
  sent_ = false;
  echoed_ = false;
  commanded_ = now;
  (void)mrqp_fw_nmt_pack(bootCommand(reset_), node_, out);
}

void NmtBoot::startRemote(TimeNs now, mrqp_fw_frame* out) noexcept {
  commanded_ = now;
  (void)mrqp_fw_nmt_pack(MRQP_FW_NMT_START, node_, out);
}

void NmtBoot::sent(TimeNs now) noexcept {
  if (waiting() && !sent_) {
    sent_ = true;
    sent_at_ = now;
  }
}

bool NmtBoot::onOwnCommand(const mrqp_fw_frame& f) noexcept {
  mrqp_fw_nmt_cmd cmd;
  std::uint8_t target = 0;
  if (!waiting() || mrqp_fw_nmt_unpack(&f, &cmd, &target) != MRQP_FW_OK || cmd != bootCommand(reset_) ||
      (target != node_ && target != 0u)) {
    return false;
  }
  echoed_ = true;
  return true;
}

bool NmtBoot::onBootUp(TimeNs t) noexcept {
  if (!waiting()) {
    return false;
  }
  // Only an answer to the command on the bus: received after its echo, or (without echoes)
  // not received before the command was handed to the bus.
  if (echo_ ? !echoed_ : !sent_ || t < sent_at_) {
    return false;
  }
  booted_ = true;
  return true;
}

bool NmtBoot::process(TimeNs now) const noexcept { return waiting() && now - commanded_ > boot_timeout_; }

}  // namespace mrqp::drivers
