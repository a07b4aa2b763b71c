/* mrqp firmware interface -- CiA 402 power state machine. */
#include "mrqp/firmware_if/cia402.h"

#include <stddef.h>

mrqp_fw_cia402_state mrqp_fw_cia402_decode_statusword(uint16_t sw) {
  switch (sw & 0x004Fu) {
    case 0x0000u:
      return MRQP_FW_CIA402_NOT_READY_TO_SWITCH_ON;
    case 0x0040u:
      return MRQP_FW_CIA402_SWITCH_ON_DISABLED;
    case 0x000Fu:
      return MRQP_FW_CIA402_FAULT_REACTION_ACTIVE;
    case 0x0008u:
      return MRQP_FW_CIA402_FAULT;
    default:
      break;
  }
  switch (sw & 0x006Fu) {
    case 0x0021u:
      return MRQP_FW_CIA402_READY_TO_SWITCH_ON;
    case 0x0023u:
      return MRQP_FW_CIA402_SWITCHED_ON;
    case 0x0027u:
      return MRQP_FW_CIA402_OPERATION_ENABLED;
    case 0x0007u:
      return MRQP_FW_CIA402_QUICK_STOP_ACTIVE;
    default:
      break;
  }
  return MRQP_FW_CIA402_UNKNOWN;
}

uint16_t mrqp_fw_cia402_statusword(mrqp_fw_cia402_state state, uint16_t other_bits) {
  uint16_t mask = 0x006Fu;
  uint16_t value;
  switch (state) {
    case MRQP_FW_CIA402_NOT_READY_TO_SWITCH_ON:
      value = 0x0000u;
      break;
    case MRQP_FW_CIA402_SWITCH_ON_DISABLED:
      value = 0x0040u;
      break;
    case MRQP_FW_CIA402_READY_TO_SWITCH_ON:
      value = 0x0021u;
      break;
    case MRQP_FW_CIA402_SWITCHED_ON:
      value = 0x0023u;
      break;
    case MRQP_FW_CIA402_OPERATION_ENABLED:
      value = 0x0027u;
      break;
    case MRQP_FW_CIA402_QUICK_STOP_ACTIVE:
      value = 0x0007u;
      break;
    case MRQP_FW_CIA402_FAULT_REACTION_ACTIVE:
      value = 0x000Fu;
      break;
    case MRQP_FW_CIA402_FAULT:
      value = 0x0008u;
      break;
    case MRQP_FW_CIA402_UNKNOWN:
    default:
      return other_bits;
  }
  return (uint16_t)((other_bits & (uint16_t)~mask) | value);
}

const char* mrqp_fw_cia402_state_str(mrqp_fw_cia402_state state) {
  switch (state) {
    case MRQP_FW_CIA402_NOT_READY_TO_SWITCH_ON:
      return "not ready to switch on";
    case MRQP_FW_CIA402_SWITCH_ON_DISABLED:
      return "switch on disabled";
    case MRQP_FW_CIA402_READY_TO_SWITCH_ON:
      return "ready to switch on";
    case MRQP_FW_CIA402_SWITCHED_ON:
      return "switched on";
    case MRQP_FW_CIA402_OPERATION_ENABLED:
      return "operation enabled";
    case MRQP_FW_CIA402_QUICK_STOP_ACTIVE:
      return "quick stop active";
    case MRQP_FW_CIA402_FAULT_REACTION_ACTIVE:
      return "fault reaction active";
    case MRQP_FW_CIA402_FAULT:
      return "fault";
    case MRQP_FW_CIA402_UNKNOWN:
      break;
  }
  return "unknown";
}

mrqp_fw_cia402_cmd mrqp_fw_cia402_decode_command(uint16_t cw) {
  if ((cw & MRQP_FW_CW_ENABLE_VOLTAGE) == 0u) {
    return MRQP_FW_CIA402_CMD_DISABLE_VOLTAGE;
  }
  if ((cw & MRQP_FW_CW_QUICK_STOP) == 0u) {
    return MRQP_FW_CIA402_CMD_QUICK_STOP;
  }
  if ((cw & MRQP_FW_CW_SWITCH_ON) == 0u) {
    return MRQP_FW_CIA402_CMD_SHUTDOWN;
  }
  if ((cw & MRQP_FW_CW_ENABLE_OPERATION) == 0u) {
    return MRQP_FW_CIA402_CMD_SWITCH_ON;
  }
  return MRQP_FW_CIA402_CMD_ENABLE_OPERATION;
}

uint16_t mrqp_fw_cia402_controlword(mrqp_fw_cia402_cmd cmd) {
  switch (cmd) {
    case MRQP_FW_CIA402_CMD_DISABLE_VOLTAGE:
      return MRQP_FW_CW_DISABLE_VOLTAGE;
    case MRQP_FW_CIA402_CMD_QUICK_STOP:
      return MRQP_FW_CW_QUICK_STOP_CMD;
    case MRQP_FW_CIA402_CMD_SHUTDOWN:
      return MRQP_FW_CW_SHUTDOWN;
    case MRQP_FW_CIA402_CMD_SWITCH_ON:
      return MRQP_FW_CW_SWITCH_ON_CMD;
    case MRQP_FW_CIA402_CMD_ENABLE_OPERATION:
      return MRQP_FW_CW_ENABLE_OPERATION_CMD;
    case MRQP_FW_CIA402_CMD_FAULT_RESET:
      return MRQP_FW_CW_FAULT_RESET_CMD;
  }
  return MRQP_FW_CW_DISABLE_VOLTAGE;
}

static mrqp_fw_cia402_state go(mrqp_fw_cia402_state next, unsigned number, unsigned* transition) {
  if (transition != NULL) {
    *transition = number;
  }
  return next;
}

mrqp_fw_cia402_state mrqp_fw_cia402_drive_next(mrqp_fw_cia402_state state, uint16_t cw, uint16_t previous_cw,
                                               unsigned* transition) {
  mrqp_fw_cia402_cmd cmd = mrqp_fw_cia402_decode_command(cw);
  switch (state) {
    case MRQP_FW_CIA402_SWITCH_ON_DISABLED:
      if (cmd == MRQP_FW_CIA402_CMD_SHUTDOWN) {
        return go(MRQP_FW_CIA402_READY_TO_SWITCH_ON, 2u, transition);
      }
      break;
    case MRQP_FW_CIA402_READY_TO_SWITCH_ON:
      if (cmd == MRQP_FW_CIA402_CMD_SWITCH_ON) {
        return go(MRQP_FW_CIA402_SWITCHED_ON, 3u, transition);
      }
      if (cmd == MRQP_FW_CIA402_CMD_ENABLE_OPERATION) {
        return go(MRQP_FW_CIA402_OPERATION_ENABLED, 34u, transition);
      }
      if (cmd == MRQP_FW_CIA402_CMD_DISABLE_VOLTAGE || cmd == MRQP_FW_CIA402_CMD_QUICK_STOP) {
        return go(MRQP_FW_CIA402_SWITCH_ON_DISABLED, 7u, transition);
      }
      break;
    case MRQP_FW_CIA402_SWITCHED_ON:
      if (cmd == MRQP_FW_CIA402_CMD_ENABLE_OPERATION) {
        return go(MRQP_FW_CIA402_OPERATION_ENABLED, 4u, transition);
      }
      if (cmd == MRQP_FW_CIA402_CMD_SHUTDOWN) {
        return go(MRQP_FW_CIA402_READY_TO_SWITCH_ON, 6u, transition);
      }
      if (cmd == MRQP_FW_CIA402_CMD_DISABLE_VOLTAGE || cmd == MRQP_FW_CIA402_CMD_QUICK_STOP) {
        return go(MRQP_FW_CIA402_SWITCH_ON_DISABLED, 10u, transition);
      }
      break;
    case MRQP_FW_CIA402_OPERATION_ENABLED:
      if (cmd == MRQP_FW_CIA402_CMD_SWITCH_ON) { /* = disable operation */
        return go(MRQP_FW_CIA402_SWITCHED_ON, 5u, transition);
      }
      if (cmd == MRQP_FW_CIA402_CMD_SHUTDOWN) {
        return go(MRQP_FW_CIA402_READY_TO_SWITCH_ON, 8u, transition);
      }
      if (cmd == MRQP_FW_CIA402_CMD_DISABLE_VOLTAGE) {
        return go(MRQP_FW_CIA402_SWITCH_ON_DISABLED, 9u, transition);
      }
      if (cmd == MRQP_FW_CIA402_CMD_QUICK_STOP) {
        return go(MRQP_FW_CIA402_QUICK_STOP_ACTIVE, 11u, transition);
      }
      break;
    case MRQP_FW_CIA402_QUICK_STOP_ACTIVE:
      if (cmd == MRQP_FW_CIA402_CMD_DISABLE_VOLTAGE) {
        return go(MRQP_FW_CIA402_SWITCH_ON_DISABLED, 12u, transition);
      }
      if (cmd == MRQP_FW_CIA402_CMD_ENABLE_OPERATION) {
        return go(MRQP_FW_CIA402_OPERATION_ENABLED, 16u, transition);
      }
      break;
    case MRQP_FW_CIA402_FAULT:
      if ((cw & MRQP_FW_CW_FAULT_RESET) != 0u && (previous_cw & MRQP_FW_CW_FAULT_RESET) == 0u) {
        return go(MRQP_FW_CIA402_SWITCH_ON_DISABLED, 15u, transition);
      }
      break;
    case MRQP_FW_CIA402_NOT_READY_TO_SWITCH_ON:
    case MRQP_FW_CIA402_FAULT_REACTION_ACTIVE:
    case MRQP_FW_CIA402_UNKNOWN:
      break;
  }
  return go(state, 0u, transition);
}

mrqp_fw_cia402_state mrqp_fw_cia402_drive_event(mrqp_fw_cia402_state state, mrqp_fw_cia402_event event,
                                                unsigned* transition) {
  switch (event) {
    case MRQP_FW_CIA402_EV_INIT_COMPLETE:
      if (state == MRQP_FW_CIA402_NOT_READY_TO_SWITCH_ON) {
        return go(MRQP_FW_CIA402_SWITCH_ON_DISABLED, 1u, transition);
      }
      break;
    case MRQP_FW_CIA402_EV_FAULT:
      if (state != MRQP_FW_CIA402_FAULT_REACTION_ACTIVE && state != MRQP_FW_CIA402_FAULT &&
          state != MRQP_FW_CIA402_UNKNOWN) {
        return go(MRQP_FW_CIA402_FAULT_REACTION_ACTIVE, 13u, transition);
      }
      break;
    case MRQP_FW_CIA402_EV_FAULT_REACTION_DONE:
      if (state == MRQP_FW_CIA402_FAULT_REACTION_ACTIVE) {
        return go(MRQP_FW_CIA402_FAULT, 14u, transition);
      }
      break;
    case MRQP_FW_CIA402_EV_QUICK_STOP_DONE:
      if (state == MRQP_FW_CIA402_QUICK_STOP_ACTIVE) {
        return go(MRQP_FW_CIA402_SWITCH_ON_DISABLED, 12u, transition);
      }
      break;
  }
  return go(state, 0u, transition);
}

/* Rank along the enabling path; -1 for states off the path. */
static int path_rank(mrqp_fw_cia402_state s) {
  switch (s) {
    case MRQP_FW_CIA402_SWITCH_ON_DISABLED:
      return 0;
    case MRQP_FW_CIA402_READY_TO_SWITCH_ON:
      return 1;
    case MRQP_FW_CIA402_SWITCHED_ON:
      return 2;
    case MRQP_FW_CIA402_OPERATION_ENABLED:
      return 3;
    default:
      return -1;
  }
}

uint16_t mrqp_fw_cia402_master_controlword(mrqp_fw_cia402_state current, mrqp_fw_cia402_state target,
                                           uint16_t previous_controlword) {
  int cur;
  int tgt;
  if (current == MRQP_FW_CIA402_FAULT) {
    /* A rising edge of bit 7: drop it first if it is still set. */
    return (previous_controlword & MRQP_FW_CW_FAULT_RESET) != 0u ? MRQP_FW_CW_DISABLE_VOLTAGE
                                                                 : MRQP_FW_CW_FAULT_RESET_CMD;
  }
  if (target == MRQP_FW_CIA402_QUICK_STOP_ACTIVE) {
    /* From Operation enabled -> Quick stop active; elsewhere the same command leads to Switch
     * on disabled, the nearest safe state. */
    return MRQP_FW_CW_QUICK_STOP_CMD;
  }
  cur = path_rank(current);
  tgt = path_rank(target);
  if (cur < 0 || tgt < 0) {
    /* Not ready, fault reaction, quick stop active, unknown, or an unsupported target. */
    return MRQP_FW_CW_DISABLE_VOLTAGE;
  }
  if (tgt == 0) {
    return MRQP_FW_CW_DISABLE_VOLTAGE;
  }
  if (tgt == 1) {
    return MRQP_FW_CW_SHUTDOWN; /* 2 from SOD, 6 from SO, 8 from OE */
  }
  if (tgt == 2) {
    /* Up: SOD -> RTSO (shutdown) -> SO (switch on). Down from OE: disable operation. */
    return cur == 0 ? MRQP_FW_CW_SHUTDOWN : MRQP_FW_CW_SWITCH_ON_CMD;
  }
  /* tgt == 3: Operation enabled, one transition at a time. */
  switch (cur) {
    case 0:
      return MRQP_FW_CW_SHUTDOWN;
    case 1:
      return MRQP_FW_CW_SWITCH_ON_CMD;
    default:
      return MRQP_FW_CW_ENABLE_OPERATION_CMD;
  }
}

int mrqp_fw_cia402_mode_supported(int mode) { return mode == MRQP_FW_MODE_CSP || mode == MRQP_FW_MODE_CST; }
