// mrqp drivers -- CANopen master, faults in words (see canopen/canopen_text.hpp). Setup side:
// nmtStateStr() aside, everything here allocates.
#include "mrqp/drivers/canopen/canopen_text.hpp"

#include <cstdio>

#include "mrqp/firmware_if/emcy.h"
#include "mrqp/firmware_if/nmt.h"
#include "mrqp/firmware_if/sdo.h"

namespace mrqp::drivers {

const char* nmtStateStr(std::uint8_t state) noexcept {
  switch (state) {
    case MRQP_FW_NMT_STATE_BOOTUP:
      return "boot-up";
    case MRQP_FW_NMT_STATE_STOPPED:
      return "stopped";
    case MRQP_FW_NMT_STATE_OPERATIONAL:
      return "operational";
    case MRQP_FW_NMT_STATE_PRE_OPERATIONAL:
      return "pre-operational";
    case 0xFF:
      return "none";
    default:
      return "invalid";
  }
}

std::string describeSdoAbort(std::uint32_t code, std::uint16_t index, std::uint8_t subindex,
                             std::uint8_t node, const char* what) {
  char buf[96];
  std::snprintf(buf, sizeof buf, "SDO abort 0x%08X (", static_cast<unsigned>(code));
  std::string out = buf;
  out += mrqp_fw_sdo_abort_str(code);
  std::snprintf(buf, sizeof buf, ") %s 0x%04X:%02X of node %u", what, static_cast<unsigned>(index),
                static_cast<unsigned>(subindex), static_cast<unsigned>(node));
  out += buf;
  return out;
}

std::string describeEmcy(std::uint16_t code, std::uint8_t error_register, std::uint8_t node) {
  char buf[96];
  std::snprintf(buf, sizeof buf, "EMCY 0x%04X (", static_cast<unsigned>(code));
  std::string out = buf;
  out += mrqp_fw_emcy_code_str(code);
  std::snprintf(buf, sizeof buf, ") register 0x%02X from node %u", static_cast<unsigned>(error_register),
                static_cast<unsigned>(node));
  out += buf;
  return out;
}

std::string describeCheckMismatch(std::uint16_t index, std::uint8_t subindex, std::uint8_t node,
                                  std::uint32_t expected, std::uint32_t actual, std::uint32_t mask) {
  char buf[160];
  std::snprintf(buf, sizeof buf,
                "0x%04X:%02X of node %u is 0x%08X, the configuration expects 0x%08X (mask 0x%08X)",
                static_cast<unsigned>(index), static_cast<unsigned>(subindex), static_cast<unsigned>(node),
                static_cast<unsigned>(actual), static_cast<unsigned>(expected), static_cast<unsigned>(mask));
  return buf;
}

}  // namespace mrqp::drivers
