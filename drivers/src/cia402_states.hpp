// mrqp drivers -- the CiA 402 state tests the arm master's enable, recovery and safe-exit logic
// share (internal header).
#pragma once

#include "mrqp/firmware_if/cia402.h"

namespace mrqp::drivers::detail {

/// Fault, fault reaction or a statusword that decodes to no state.
inline bool cia402FaultState(mrqp_fw_cia402_state s) noexcept {
  return s == MRQP_FW_CIA402_FAULT || s == MRQP_FW_CIA402_FAULT_REACTION_ACTIVE ||
         s == MRQP_FW_CIA402_UNKNOWN;
}

/// Whether a drive in state s has got where target asked: switch-on-disabled is also reached from
/// not-ready (the drive passes through it), a quick stop also by switch-on-disabled (where the
/// quick stop ends).
inline bool cia402StateReached(mrqp_fw_cia402_state target, mrqp_fw_cia402_state s) noexcept {
  switch (target) {
    case MRQP_FW_CIA402_SWITCH_ON_DISABLED:
      return s == MRQP_FW_CIA402_SWITCH_ON_DISABLED || s == MRQP_FW_CIA402_NOT_READY_TO_SWITCH_ON;
    case MRQP_FW_CIA402_QUICK_STOP_ACTIVE:
      return s == MRQP_FW_CIA402_QUICK_STOP_ACTIVE || s == MRQP_FW_CIA402_SWITCH_ON_DISABLED;
    default:
      return s == target;
  }
}

}  // namespace mrqp::drivers::detail
