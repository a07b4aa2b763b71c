/*
 * mrqp firmware interface -- CANopen (CiA 301) predefined connection set: COB-IDs.
 *
 * Node ids are 1..127. Every COB-ID is an 11-bit identifier: function code base + node id.
 */
#ifndef MRQP_FIRMWARE_IF_CANOPEN_IDS_H
#define MRQP_FIRMWARE_IF_CANOPEN_IDS_H

#include <stdint.h>

#ifdef __cplusplus
extern "C" {
#endif

#define MRQP_FW_NODE_ID_MIN 1u
#define MRQP_FW_NODE_ID_MAX 127u

#define MRQP_FW_COB_NMT 0x000u        /**< NMT module control (master -> all) */
#define MRQP_FW_COB_SYNC 0x080u       /**< SYNC (no node id) */
#define MRQP_FW_COB_EMCY_BASE 0x080u  /**< EMCY: 0x080 + node */
#define MRQP_FW_COB_TPDO1_BASE 0x180u /**< device -> master */
#define MRQP_FW_COB_RPDO1_BASE 0x200u /**< master -> device */
#define MRQP_FW_COB_TPDO2_BASE 0x280u
#define MRQP_FW_COB_RPDO2_BASE 0x300u
#define MRQP_FW_COB_TPDO3_BASE 0x380u
#define MRQP_FW_COB_RPDO3_BASE 0x400u
#define MRQP_FW_COB_TPDO4_BASE 0x480u
#define MRQP_FW_COB_RPDO4_BASE 0x500u
#define MRQP_FW_COB_SDO_TX_BASE 0x580u /**< server (device) -> client (master) */
#define MRQP_FW_COB_SDO_RX_BASE 0x600u /**< client (master) -> server (device) */
#define MRQP_FW_COB_HEARTBEAT_BASE 0x700u

/** Communication object kinds of the predefined connection set. */
typedef enum mrqp_fw_cob {
  MRQP_FW_COB_KIND_NMT = 0,
  MRQP_FW_COB_KIND_SYNC,
  MRQP_FW_COB_KIND_EMCY,
  MRQP_FW_COB_KIND_TPDO1,
  MRQP_FW_COB_KIND_RPDO1,
  MRQP_FW_COB_KIND_TPDO2,
  MRQP_FW_COB_KIND_RPDO2,
  MRQP_FW_COB_KIND_TPDO3,
  MRQP_FW_COB_KIND_RPDO3,
  MRQP_FW_COB_KIND_TPDO4,
  MRQP_FW_COB_KIND_RPDO4,
  MRQP_FW_COB_KIND_SDO_TX,
  MRQP_FW_COB_KIND_SDO_RX,
  MRQP_FW_COB_KIND_HEARTBEAT,
  MRQP_FW_COB_KIND_UNKNOWN
} mrqp_fw_cob;

/** Non-zero for a node id in 1..127. */
static inline int mrqp_fw_node_valid(unsigned node) {
  return node >= MRQP_FW_NODE_ID_MIN && node <= MRQP_FW_NODE_ID_MAX;
}

/**
 * COB-ID of `kind` for `node`. NMT and SYNC ignore the node. Returns 0xFFFFFFFF for an invalid
 * node (of a per-node object) or kind.
 */
uint32_t mrqp_fw_cob_id(mrqp_fw_cob kind, unsigned node);

/**
 * Splits an 11-bit identifier into kind and node (node 0 for NMT/SYNC).
 * Returns MRQP_FW_COB_KIND_UNKNOWN (node 0) for identifiers outside the predefined set
 * (e.g. 0x080 + 0 is SYNC, 0x180 + 0 is unknown).
 */
mrqp_fw_cob mrqp_fw_cob_decode(uint32_t id, uint8_t* node);

/** PDO COB-IDs, n = 1..4 (0xFFFFFFFF for an invalid n or node). */
uint32_t mrqp_fw_cob_tpdo(unsigned n, unsigned node);
uint32_t mrqp_fw_cob_rpdo(unsigned n, unsigned node);

#ifdef __cplusplus
}
#endif

#endif /* MRQP_FIRMWARE_IF_CANOPEN_IDS_H */
