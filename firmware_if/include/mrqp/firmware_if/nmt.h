/*
 * mrqp firmware interface -- CANopen NMT module control and heartbeat (CiA 301).
 *
 * NMT command: COB-ID 0x000, DLC 2: [command specifier, node id (0 = all nodes)].
 * Heartbeat / boot-up: COB-ID 0x700 + node, DLC 1: [NMT state] (bit 7, the node-guarding toggle
 * bit, is always 0 in a heartbeat).
 */
#ifndef MRQP_FIRMWARE_IF_NMT_H
#define MRQP_FIRMWARE_IF_NMT_H

#include <stdint.h>

#include "mrqp/firmware_if/frame.h"
#include "mrqp/firmware_if/status.h"

#ifdef __cplusplus
extern "C" {
#endif

#define MRQP_FW_NMT_LEN 2u
#define MRQP_FW_HEARTBEAT_LEN 1u
/** NMT "all nodes" address. */
#define MRQP_FW_NMT_ALL_NODES 0u

typedef enum mrqp_fw_nmt_cmd {
  MRQP_FW_NMT_START = 0x01,       /**< -> operational */
  MRQP_FW_NMT_STOP = 0x02,        /**< -> stopped */
  MRQP_FW_NMT_ENTER_PREOP = 0x80, /**< -> pre-operational */
  MRQP_FW_NMT_RESET_NODE = 0x81,  /**< application reset -> initialisation */
  MRQP_FW_NMT_RESET_COMM = 0x82   /**< communication reset -> initialisation */
} mrqp_fw_nmt_cmd;

/** NMT states as carried by the heartbeat byte. */
typedef enum mrqp_fw_nmt_state {
  MRQP_FW_NMT_STATE_BOOTUP = 0x00, /**< initialisation; the boot-up message carries 0x00 */
  MRQP_FW_NMT_STATE_STOPPED = 0x04,
  MRQP_FW_NMT_STATE_OPERATIONAL = 0x05,
  MRQP_FW_NMT_STATE_PRE_OPERATIONAL = 0x7F
} mrqp_fw_nmt_state;

/** Non-zero if cmd is one of the five NMT command specifiers. */
int mrqp_fw_nmt_cmd_valid(unsigned cmd);
/** Non-zero if state is one of the four heartbeat state codes. */
int mrqp_fw_nmt_state_valid(unsigned state);

/** NMT command frame; node 0 addresses all nodes. ERR_ARG for an unknown cmd or node > 127. */
mrqp_fw_pack_flags mrqp_fw_nmt_pack(mrqp_fw_nmt_cmd cmd, unsigned node, mrqp_fw_frame* out);
/** Validates id 0x000, classic, DLC 2, known command (ERR_COMMAND), node <= 127 (ERR_RANGE). */
mrqp_fw_err mrqp_fw_nmt_unpack(const mrqp_fw_frame* in, mrqp_fw_nmt_cmd* cmd, uint8_t* node);
/** Non-zero if an NMT command for `target` (0 = all) addresses the node `self`. */
int mrqp_fw_nmt_addresses(uint8_t target, uint8_t self);

/**
 * Drive side: NMT state after `cmd`. Reset node / reset communication go to BOOTUP
 * (initialisation) from any state; the node then sends its boot-up message and enters
 * pre-operational on its own (mrqp_fw_nmt_boot_complete). In BOOTUP other commands are ignored.
 */
mrqp_fw_nmt_state mrqp_fw_nmt_next_state(mrqp_fw_nmt_state state, mrqp_fw_nmt_cmd cmd);
/** Drive side: the automatic transition at the end of initialisation (-> pre-operational). */
mrqp_fw_nmt_state mrqp_fw_nmt_boot_complete(mrqp_fw_nmt_state state);

/** Heartbeat (or boot-up, state BOOTUP) frame of `node`. ERR_ARG for invalid node or state. */
mrqp_fw_pack_flags mrqp_fw_heartbeat_pack(unsigned node, mrqp_fw_nmt_state state, mrqp_fw_frame* out);
/** Validates id 0x701..0x77F, classic, DLC 1, known state code (ERR_COMMAND). */
mrqp_fw_err mrqp_fw_heartbeat_unpack(const mrqp_fw_frame* in, uint8_t* node, mrqp_fw_nmt_state* state);

#ifdef __cplusplus
}
#endif

#endif /* MRQP_FIRMWARE_IF_NMT_H */
