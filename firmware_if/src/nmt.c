/* mrqp firmware interface -- NMT module control and heartbeat. */
#include "mrqp/firmware_if/nmt.h"

#include "internal.h"
#include "mrqp/firmware_if/canopen_ids.h"

int mrqp_fw_nmt_cmd_valid(unsigned cmd) {
  return cmd == MRQP_FW_NMT_START || cmd == MRQP_FW_NMT_STOP || cmd == MRQP_FW_NMT_ENTER_PREOP ||
         cmd == MRQP_FW_NMT_RESET_NODE || cmd == MRQP_FW_NMT_RESET_COMM;
}

int mrqp_fw_nmt_state_valid(unsigned state) {
  return state == MRQP_FW_NMT_STATE_BOOTUP || state == MRQP_FW_NMT_STATE_STOPPED ||
         state == MRQP_FW_NMT_STATE_OPERATIONAL || state == MRQP_FW_NMT_STATE_PRE_OPERATIONAL;
}

mrqp_fw_pack_flags mrqp_fw_nmt_pack(mrqp_fw_nmt_cmd cmd, unsigned node, mrqp_fw_frame* out) {
  if (out == NULL || !mrqp_fw_nmt_cmd_valid((unsigned)cmd) || node > MRQP_FW_NODE_ID_MAX) {
    return mrqp_fw_fail(out, MRQP_FW_PACK_ERR_ARG);
  }
  mrqp_fw_frame_init(out, MRQP_FW_COB_NMT, (uint8_t)MRQP_FW_NMT_LEN, 0u);
  out->data[0] = (uint8_t)cmd;
  out->data[1] = (uint8_t)node;
  return MRQP_FW_PACK_OK;
}

mrqp_fw_err mrqp_fw_nmt_unpack(const mrqp_fw_frame* in, mrqp_fw_nmt_cmd* cmd, uint8_t* node) {
  mrqp_fw_err e = mrqp_fw_frame_expect(in, MRQP_FW_COB_NMT, MRQP_FW_NMT_LEN, 0);
  if (e != MRQP_FW_OK) {
    return e;
  }
  if (cmd == NULL || node == NULL) {
    return MRQP_FW_ERR_NULL;
  }
  if (!mrqp_fw_nmt_cmd_valid(in->data[0])) {
    return MRQP_FW_ERR_COMMAND;
  }
  if (in->data[1] > MRQP_FW_NODE_ID_MAX) {
    return MRQP_FW_ERR_RANGE;
  }
  *cmd = (mrqp_fw_nmt_cmd)in->data[0];
  *node = in->data[1];
  return MRQP_FW_OK;
}

int mrqp_fw_nmt_addresses(uint8_t target, uint8_t self) {
  return target == MRQP_FW_NMT_ALL_NODES || target == self;
}

mrqp_fw_nmt_state mrqp_fw_nmt_next_state(mrqp_fw_nmt_state state, mrqp_fw_nmt_cmd cmd) {
  if (cmd == MRQP_FW_NMT_RESET_NODE || cmd == MRQP_FW_NMT_RESET_COMM) {
    return MRQP_FW_NMT_STATE_BOOTUP;
  }
  if (state == MRQP_FW_NMT_STATE_BOOTUP || !mrqp_fw_nmt_state_valid((unsigned)state)) {
    return state;
  }
  switch (cmd) {
    case MRQP_FW_NMT_START:
      return MRQP_FW_NMT_STATE_OPERATIONAL;
    case MRQP_FW_NMT_STOP:
      return MRQP_FW_NMT_STATE_STOPPED;
    case MRQP_FW_NMT_ENTER_PREOP:
      return MRQP_FW_NMT_STATE_PRE_OPERATIONAL;
    case MRQP_FW_NMT_RESET_NODE:
    case MRQP_FW_NMT_RESET_COMM:
      break;
  }
  return state;
}

mrqp_fw_nmt_state mrqp_fw_nmt_boot_complete(mrqp_fw_nmt_state state) {
  return state == MRQP_FW_NMT_STATE_BOOTUP ? MRQP_FW_NMT_STATE_PRE_OPERATIONAL : state;
}

mrqp_fw_pack_flags mrqp_fw_heartbeat_pack(unsigned node, mrqp_fw_nmt_state state, mrqp_fw_frame* out) {
  if (out == NULL || !mrqp_fw_node_valid(node) || !mrqp_fw_nmt_state_valid((unsigned)state)) {
    return mrqp_fw_fail(out, MRQP_FW_PACK_ERR_ARG);
  }
  mrqp_fw_frame_init(out, MRQP_FW_COB_HEARTBEAT_BASE + node, (uint8_t)MRQP_FW_HEARTBEAT_LEN, 0u);
  out->data[0] = (uint8_t)state;
  return MRQP_FW_PACK_OK;
}

mrqp_fw_err mrqp_fw_heartbeat_unpack(const mrqp_fw_frame* in, uint8_t* node, mrqp_fw_nmt_state* state) {
  uint8_t n = 0u;
  mrqp_fw_err e = mrqp_fw_classic_envelope(in);
  if (e != MRQP_FW_OK) {
    return e;
  }
  if (node == NULL || state == NULL) {
    return MRQP_FW_ERR_NULL;
  }
  if (mrqp_fw_cob_decode(in->id, &n) != MRQP_FW_COB_KIND_HEARTBEAT) {
    return MRQP_FW_ERR_ID;
  }
  if (in->len != MRQP_FW_HEARTBEAT_LEN) {
    return MRQP_FW_ERR_LENGTH;
  }
  if (!mrqp_fw_nmt_state_valid(in->data[0])) {
    return MRQP_FW_ERR_COMMAND;
  }
  *node = n;
  *state = (mrqp_fw_nmt_state)in->data[0];
  return MRQP_FW_OK;
}
