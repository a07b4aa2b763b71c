/* mrqp firmware interface -- helpers private to the implementation (not installed). */
#ifndef MRQP_FIRMWARE_IF_SRC_INTERNAL_H
#define MRQP_FIRMWARE_IF_SRC_INTERNAL_H

#include <stddef.h>

#include "mrqp/firmware_if/frame.h"
#include "mrqp/firmware_if/status.h"

/* Clears `out` (if any) and returns the error flags: a failed pack never leaves a valid frame. */
static inline mrqp_fw_pack_flags mrqp_fw_fail(mrqp_fw_frame* out, mrqp_fw_pack_flags flags) {
  mrqp_fw_frame_clear(out);
  return flags;
}

/* Envelope check of a classic frame whose id is taken from the frame itself. */
static inline mrqp_fw_err mrqp_fw_classic_envelope(const mrqp_fw_frame* in) {
  if (in == NULL) {
    return MRQP_FW_ERR_NULL;
  }
  if ((in->flags & (MRQP_FW_FRAME_EXT | MRQP_FW_FRAME_RTR | MRQP_FW_FRAME_FD)) != 0u) {
    return MRQP_FW_ERR_FORMAT;
  }
  if (in->id > MRQP_FW_CAN_SFF_MAX) {
    return MRQP_FW_ERR_ID;
  }
  if (in->len > MRQP_FW_CAN_CLASSIC_MAX_LEN) {
    return MRQP_FW_ERR_LENGTH;
  }
  return MRQP_FW_OK;
}

#endif
