/* mrqp firmware interface -- SYNC. */
#include "mrqp/firmware_if/sync.h"

#include "internal.h"
#include "mrqp/firmware_if/canopen_ids.h"

mrqp_fw_pack_flags mrqp_fw_sync_pack(unsigned counter, mrqp_fw_frame* out) {
  if (out == NULL || counter > MRQP_FW_SYNC_COUNTER_MAX) {
    return mrqp_fw_fail(out, MRQP_FW_PACK_ERR_ARG);
  }
  mrqp_fw_frame_init(out, MRQP_FW_COB_SYNC, counter == 0u ? (uint8_t)0u : (uint8_t)1u, 0u);
  out->data[0] = (uint8_t)counter;
  return MRQP_FW_PACK_OK;
}

mrqp_fw_err mrqp_fw_sync_unpack(const mrqp_fw_frame* in, uint8_t* counter) {
  mrqp_fw_err e = mrqp_fw_classic_envelope(in);
  if (e != MRQP_FW_OK) {
    return e;
  }
  if (counter == NULL) {
    return MRQP_FW_ERR_NULL;
  }
  if (in->id != MRQP_FW_COB_SYNC) {
    return MRQP_FW_ERR_ID;
  }
  if (in->len > 1u) {
    return MRQP_FW_ERR_LENGTH;
  }
  if (in->len == 1u && (in->data[0] < 1u || in->data[0] > MRQP_FW_SYNC_COUNTER_MAX)) {
    return MRQP_FW_ERR_RANGE;
  }
  *counter = in->len == 1u ? in->data[0] : (uint8_t)0u;
  return MRQP_FW_OK;
}

uint8_t mrqp_fw_sync_counter_next(uint8_t counter, uint8_t overflow) {
  if (overflow < 2u || overflow > MRQP_FW_SYNC_COUNTER_MAX) {
    return 0u;
  }
  return (counter >= overflow || counter == 0u) ? (uint8_t)1u : (uint8_t)(counter + 1u);
}
