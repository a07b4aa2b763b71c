/*
 * mrqp firmware interface -- SDO client transfer helper (expedited and segmented), no allocation.
 *
 * One transfer at a time per server. The caller owns the buffer and the timing: it sends the frame
 * written to `out` whenever a call returns MRQP_FW_SDO_STEP_SEND or MRQP_FW_SDO_STEP_ABORT_SEND,
 * feeds every frame received on 0x580 + node to mrqp_fw_sdo_client_on_frame, and calls
 * mrqp_fw_sdo_client_timeout when the server stays silent too long (CiA 301 leaves the time to
 * the application; 100 ms is common).
 *
 *   upload (read):    start -> [upload init req] -> expedited resp -> DONE
 *                                                -> segmented resp -> [seg req t=0] -> seg resp
 *                                                   -> [seg req t=1] -> ... -> last seg -> DONE
 *   download (write): start -> [init req: expedited if <= 4 bytes, else segmented with size]
 *                     -> init resp -> [seg t=0] -> seg resp -> ... -> last seg resp -> DONE
 */
#ifndef MRQP_FIRMWARE_IF_SDO_CLIENT_H
#define MRQP_FIRMWARE_IF_SDO_CLIENT_H

#include <stdint.h>

#include "mrqp/firmware_if/frame.h"
#include "mrqp/firmware_if/sdo.h"

#ifdef __cplusplus
extern "C" {
#endif

typedef enum mrqp_fw_sdo_step {
  MRQP_FW_SDO_STEP_SEND = 0,   /**< send `out`, then wait for the server */
  MRQP_FW_SDO_STEP_DONE,       /**< transfer complete (nothing to send) */
  MRQP_FW_SDO_STEP_ABORT_SEND, /**< the client aborts: send `out` (abort frame); see abort_code */
  MRQP_FW_SDO_STEP_ABORTED,    /**< the server aborted; see abort_code (nothing to send) */
  MRQP_FW_SDO_STEP_IGNORED,    /**< the frame is not for this transfer (other node, not SDO, idle) */
  MRQP_FW_SDO_STEP_ERROR       /**< invalid call (NULL, node, zero-length buffer, busy/idle) */
} mrqp_fw_sdo_step;

typedef enum mrqp_fw_sdo_client_state {
  MRQP_FW_SDO_CLIENT_IDLE = 0,
  MRQP_FW_SDO_CLIENT_UPLOAD_INIT,
  MRQP_FW_SDO_CLIENT_UPLOAD_SEG,
  MRQP_FW_SDO_CLIENT_DOWNLOAD_INIT,
  MRQP_FW_SDO_CLIENT_DOWNLOAD_SEG
} mrqp_fw_sdo_client_state;

/** Transfer state. Zero-initialise (or call mrqp_fw_sdo_client_reset) before first use. */
typedef struct mrqp_fw_sdo_client {
  mrqp_fw_sdo_client_state state;
  uint8_t node;
  uint16_t index;
  uint8_t subindex;
  uint8_t toggle;
  uint8_t* rx;         /**< upload destination (caller-owned) */
  const uint8_t* tx;   /**< download source (caller-owned) */
  uint32_t capacity;   /**< upload: capacity of rx; download: bytes to write */
  uint32_t size;       /**< upload: announced size (0 = not indicated) */
  uint32_t count;      /**< bytes transferred so far (upload: bytes in rx when DONE) */
  uint32_t abort_code; /**< after ABORT_SEND / ABORTED */
} mrqp_fw_sdo_client;

void mrqp_fw_sdo_client_reset(mrqp_fw_sdo_client* c);

/** Starts reading node:index:subindex into buf[0..capacity). */
mrqp_fw_sdo_step mrqp_fw_sdo_client_start_upload(mrqp_fw_sdo_client* c, unsigned node, uint16_t index,
                                                 uint8_t subindex, uint8_t* buf, uint32_t capacity,
                                                 mrqp_fw_frame* out);
/** Starts writing data[0..n) (n >= 1) to node:index:subindex. */
mrqp_fw_sdo_step mrqp_fw_sdo_client_start_download(mrqp_fw_sdo_client* c, unsigned node, uint16_t index,
                                                   uint8_t subindex, const uint8_t* data, uint32_t n,
                                                   mrqp_fw_frame* out);
/**
 * Feeds a received frame. Protocol violations by the server (wrong index, toggle, command,
 * size beyond capacity) make the client abort with the matching CiA 301 code (ABORT_SEND).
 */
mrqp_fw_sdo_step mrqp_fw_sdo_client_on_frame(mrqp_fw_sdo_client* c, const mrqp_fw_frame* in,
                                             mrqp_fw_frame* out);
/** The server timed out: abort frame 0x05040000 in out (ABORT_SEND), or ERROR when idle. */
mrqp_fw_sdo_step mrqp_fw_sdo_client_timeout(mrqp_fw_sdo_client* c, mrqp_fw_frame* out);

#ifdef __cplusplus
}
#endif

#endif /* MRQP_FIRMWARE_IF_SDO_CLIENT_H */
