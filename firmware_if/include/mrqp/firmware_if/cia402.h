/*
 * mrqp firmware interface -- CiA 402 drive profile: power state machine, controlword,
 * statusword, modes of operation.
 *
 * Statusword (0x6041) state coding, bits 6 5 3 2 1 0 (x = don't care):
 *   Not ready to switch on   0 x 0 0 0 0   mask 0x004F value 0x0000
 *   Switch on disabled       1 x 0 0 0 0   mask 0x004F value 0x0040
 *   Ready to switch on       0 1 0 0 0 1   mask 0x006F value 0x0021
 *   Switched on              0 1 0 0 1 1   mask 0x006F value 0x0023
 *   Operation enabled        0 1 0 1 1 1   mask 0x006F value 0x0027
 *   Quick stop active        0 0 0 1 1 1   mask 0x006F value 0x0007
 *   Fault reaction active    0 x 1 1 1 1   mask 0x004F value 0x000F
 *   Fault                    0 x 1 0 0 0   mask 0x004F value 0x0008
 *
 * Controlword (0x6040) commands, bits 7 3 2 1 0 (fault reset, enable operation, quick stop
 * (active low), enable voltage, switch on):
 *   Shutdown                 0 x 1 1 0   -> transitions 2, 6, 8        canonical 0x0006
 *   Switch on                0 0 1 1 1   -> transition 3               canonical 0x0007
 *   Switch on + enable op.   0 1 1 1 1   -> transitions 3 + 4          canonical 0x000F
 *   Disable voltage          0 x x 0 x   -> transitions 7, 9, 10, 12   canonical 0x0000
 *   Quick stop               0 x 0 1 x   -> transitions 7, 10, 11      canonical 0x0002
 *   Disable operation        0 0 1 1 1   -> transition 5               canonical 0x0007
 *   Enable operation         0 1 1 1 1   -> transitions 4, 16          canonical 0x000F
 *   Fault reset              0 -> 1 x x x x (rising edge) -> transition 15  canonical 0x0080
 * Outside the Fault state bit 7 is ignored (bits 3..0 decide).
 */
#ifndef MRQP_FIRMWARE_IF_CIA402_H
#define MRQP_FIRMWARE_IF_CIA402_H

#include <stdint.h>

#ifdef __cplusplus
extern "C" {
#endif

/* ---- statusword bits ---- */
#define MRQP_FW_SW_READY_TO_SWITCH_ON 0x0001u
#define MRQP_FW_SW_SWITCHED_ON 0x0002u
#define MRQP_FW_SW_OPERATION_ENABLED 0x0004u
#define MRQP_FW_SW_FAULT 0x0008u
#define MRQP_FW_SW_VOLTAGE_ENABLED 0x0010u
#define MRQP_FW_SW_QUICK_STOP 0x0020u /**< 0 = quick stop active */
#define MRQP_FW_SW_SWITCH_ON_DISABLED 0x0040u
#define MRQP_FW_SW_WARNING 0x0080u
#define MRQP_FW_SW_REMOTE 0x0200u
#define MRQP_FW_SW_TARGET_REACHED 0x0400u
#define MRQP_FW_SW_INTERNAL_LIMIT 0x0800u
#define MRQP_FW_SW_CS_FOLLOWS_COMMAND 0x1000u  /**< CSP/CST: drive follows the command value */
#define MRQP_FW_SW_CSP_FOLLOWING_ERROR 0x2000u /**< CSP: following error */
/** Bits that code the state. */
#define MRQP_FW_SW_STATE_BITS 0x006Fu

/* ---- controlword bits ---- */
#define MRQP_FW_CW_SWITCH_ON 0x0001u
#define MRQP_FW_CW_ENABLE_VOLTAGE 0x0002u
#define MRQP_FW_CW_QUICK_STOP 0x0004u /**< 0 = quick stop */
#define MRQP_FW_CW_ENABLE_OPERATION 0x0008u
#define MRQP_FW_CW_FAULT_RESET 0x0080u
#define MRQP_FW_CW_HALT 0x0100u
/** Bits that carry state-machine commands. */
#define MRQP_FW_CW_COMMAND_BITS 0x008Fu

/* ---- canonical command words ---- */
#define MRQP_FW_CW_SHUTDOWN 0x0006u
#define MRQP_FW_CW_SWITCH_ON_CMD 0x0007u
#define MRQP_FW_CW_DISABLE_OPERATION 0x0007u
#define MRQP_FW_CW_ENABLE_OPERATION_CMD 0x000Fu
#define MRQP_FW_CW_DISABLE_VOLTAGE 0x0000u
#define MRQP_FW_CW_QUICK_STOP_CMD 0x0002u
#define MRQP_FW_CW_FAULT_RESET_CMD 0x0080u

/* ---- modes of operation (0x6060 / 0x6061, i8) ---- */
#define MRQP_FW_MODE_NONE 0
#define MRQP_FW_MODE_PROFILE_POSITION 1
#define MRQP_FW_MODE_PROFILE_VELOCITY 3
#define MRQP_FW_MODE_PROFILE_TORQUE 4
#define MRQP_FW_MODE_HOMING 6
#define MRQP_FW_MODE_CSP 8  /**< cyclic synchronous position */
#define MRQP_FW_MODE_CSV 9  /**< cyclic synchronous velocity */
#define MRQP_FW_MODE_CST 10 /**< cyclic synchronous torque */

/** The power states. UNKNOWN is a statusword that matches no state (a broken device). */
typedef enum mrqp_fw_cia402_state {
  MRQP_FW_CIA402_NOT_READY_TO_SWITCH_ON = 0,
  MRQP_FW_CIA402_SWITCH_ON_DISABLED,
  MRQP_FW_CIA402_READY_TO_SWITCH_ON,
  MRQP_FW_CIA402_SWITCHED_ON,
  MRQP_FW_CIA402_OPERATION_ENABLED,
  MRQP_FW_CIA402_QUICK_STOP_ACTIVE,
  MRQP_FW_CIA402_FAULT_REACTION_ACTIVE,
  MRQP_FW_CIA402_FAULT,
  MRQP_FW_CIA402_UNKNOWN
} mrqp_fw_cia402_state;

/** Device-control commands decoded from a controlword. */
typedef enum mrqp_fw_cia402_cmd {
  MRQP_FW_CIA402_CMD_DISABLE_VOLTAGE = 0, /**< bits x x 0 x */
  MRQP_FW_CIA402_CMD_QUICK_STOP,          /**< bits x 0 1 x */
  MRQP_FW_CIA402_CMD_SHUTDOWN,            /**< bits x 1 1 0 */
  MRQP_FW_CIA402_CMD_SWITCH_ON,           /**< bits 0 1 1 1 (= disable operation) */
  MRQP_FW_CIA402_CMD_ENABLE_OPERATION,    /**< bits 1 1 1 1 (= switch on + enable operation) */
  MRQP_FW_CIA402_CMD_FAULT_RESET          /**< bit 7 rising edge (only meaningful in Fault) */
} mrqp_fw_cia402_cmd;

/** Internal events of the drive (automatic transitions). */
typedef enum mrqp_fw_cia402_event {
  MRQP_FW_CIA402_EV_INIT_COMPLETE = 0,   /**< transition 1: self-test done */
  MRQP_FW_CIA402_EV_FAULT,               /**< transition 13: fault detected (any state but FRA/Fault) */
  MRQP_FW_CIA402_EV_FAULT_REACTION_DONE, /**< transition 14 */
  MRQP_FW_CIA402_EV_QUICK_STOP_DONE      /**< transition 12 for quick-stop option codes 1..4 */
} mrqp_fw_cia402_event;

/** State coded by a statusword (mask table above); UNKNOWN if none matches. */
mrqp_fw_cia402_state mrqp_fw_cia402_decode_statusword(uint16_t statusword);
/**
 * Drive side: statusword for `state`: the state bits take their canonical values (the table
 * values above, don't-care bits 0), the other bits come from `other_bits`.
 */
uint16_t mrqp_fw_cia402_statusword(mrqp_fw_cia402_state state, uint16_t other_bits);
/** Name of a state ("unknown" for UNKNOWN or out-of-range values). */
const char* mrqp_fw_cia402_state_str(mrqp_fw_cia402_state state);

/** Command coded by bits 3..0 of a controlword (bit 7 is not looked at). */
mrqp_fw_cia402_cmd mrqp_fw_cia402_decode_command(uint16_t controlword);
/** Canonical controlword of a command (only the command bits set). */
uint16_t mrqp_fw_cia402_controlword(mrqp_fw_cia402_cmd cmd);

/**
 * Drive side: the state after receiving `controlword` in `state`; `previous_controlword` is the
 * last one received (for the fault-reset rising edge). Transition 16 (quick stop active ->
 * operation enabled) is allowed, as for quick-stop option codes 5..8. If `transition` is not NULL
 * it receives the CiA 402 transition number taken (0 when the state does not change; 34 for the
 * combined 3 + 4). NOT_READY_TO_SWITCH_ON and FAULT_REACTION_ACTIVE ignore the controlword;
 * UNKNOWN stays UNKNOWN.
 */
mrqp_fw_cia402_state mrqp_fw_cia402_drive_next(mrqp_fw_cia402_state state, uint16_t controlword,
                                               uint16_t previous_controlword, unsigned* transition);
/** Drive side: automatic transitions (1, 13, 14, 12). Events that do not apply leave the state. */
mrqp_fw_cia402_state mrqp_fw_cia402_drive_event(mrqp_fw_cia402_state state, mrqp_fw_cia402_event event,
                                                unsigned* transition);

/**
 * Master side: the next controlword (command bits only; OR in halt and mode bits yourself) that
 * moves a drive reported in `current` towards `target`, one transition per call. Targets:
 * SWITCH_ON_DISABLED, READY_TO_SWITCH_ON, SWITCHED_ON, OPERATION_ENABLED, QUICK_STOP_ACTIVE.
 * From Fault it produces a fault-reset rising edge (0x0000 first if previous_controlword already
 * had bit 7 set). From Quick stop active it goes down through Switch on disabled (it never relies
 * on transition 16). Unreachable or transient states yield Disable voltage (the safe command).
 */
uint16_t mrqp_fw_cia402_master_controlword(mrqp_fw_cia402_state current, mrqp_fw_cia402_state target,
                                           uint16_t previous_controlword);

/** Non-zero for CSP and CST, the two modes of this contract. */
int mrqp_fw_cia402_mode_supported(int mode);

#ifdef __cplusplus
}
#endif

#endif /* MRQP_FIRMWARE_IF_CIA402_H */
