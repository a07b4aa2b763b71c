/* mrqp firmware interface -- CANopen COB-IDs. */
#include "mrqp/firmware_if/canopen_ids.h"

#include <stddef.h>

static const uint32_t per_node_base[] = {
    /* indexed by mrqp_fw_cob from MRQP_FW_COB_KIND_EMCY */
    MRQP_FW_COB_EMCY_BASE,  MRQP_FW_COB_TPDO1_BASE,  MRQP_FW_COB_RPDO1_BASE,  MRQP_FW_COB_TPDO2_BASE,
    MRQP_FW_COB_RPDO2_BASE, MRQP_FW_COB_TPDO3_BASE,  MRQP_FW_COB_RPDO3_BASE,  MRQP_FW_COB_TPDO4_BASE,
    MRQP_FW_COB_RPDO4_BASE, MRQP_FW_COB_SDO_TX_BASE, MRQP_FW_COB_SDO_RX_BASE, MRQP_FW_COB_HEARTBEAT_BASE,
};

uint32_t mrqp_fw_cob_id(mrqp_fw_cob kind, unsigned node) {
  if (kind == MRQP_FW_COB_KIND_NMT) {
    return MRQP_FW_COB_NMT;
  }
  if (kind == MRQP_FW_COB_KIND_SYNC) {
    return MRQP_FW_COB_SYNC;
  }
  if (kind < MRQP_FW_COB_KIND_EMCY || kind > MRQP_FW_COB_KIND_HEARTBEAT || !mrqp_fw_node_valid(node)) {
    return 0xFFFFFFFFu;
  }
  return per_node_base[(unsigned)kind - (unsigned)MRQP_FW_COB_KIND_EMCY] + node;
}

mrqp_fw_cob mrqp_fw_cob_decode(uint32_t id, uint8_t* node) {
  uint32_t base = id & 0x780u;
  uint32_t n = id & 0x7Fu;
  unsigned k;
  if (node != NULL) {
    *node = 0u;
  }
  if (id == MRQP_FW_COB_NMT) {
    return MRQP_FW_COB_KIND_NMT;
  }
  if (id == MRQP_FW_COB_SYNC) {
    return MRQP_FW_COB_KIND_SYNC;
  }
  if (id > 0x7FFu || n == 0u) {
    return MRQP_FW_COB_KIND_UNKNOWN;
  }
  for (k = 0u; k < sizeof(per_node_base) / sizeof(per_node_base[0]); ++k) {
    if (per_node_base[k] == base) {
      if (node != NULL) {
        *node = (uint8_t)n;
      }
      return (mrqp_fw_cob)((unsigned)MRQP_FW_COB_KIND_EMCY + k);
    }
  }
  return MRQP_FW_COB_KIND_UNKNOWN;
}

uint32_t mrqp_fw_cob_tpdo(unsigned n, unsigned node) {
  if (n < 1u || n > 4u || !mrqp_fw_node_valid(node)) {
    return 0xFFFFFFFFu;
  }
  return MRQP_FW_COB_TPDO1_BASE + 0x100u * (n - 1u) + node;
}

uint32_t mrqp_fw_cob_rpdo(unsigned n, unsigned node) {
  if (n < 1u || n > 4u || !mrqp_fw_node_valid(node)) {
    return 0xFFFFFFFFu;
  }
  return MRQP_FW_COB_RPDO1_BASE + 0x100u * (n - 1u) + node;
}
