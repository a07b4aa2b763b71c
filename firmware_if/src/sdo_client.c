/* mrqp firmware interface -- SDO client transfer helper. */
#include "mrqp/firmware_if/sdo_client.h"

#include <string.h>

#include "internal.h"
#include "mrqp/firmware_if/canopen_ids.h"

void mrqp_fw_sdo_client_reset(mrqp_fw_sdo_client* c) {
  if (c != NULL) {
    memset(c, 0, sizeof(*c));
    c->state = MRQP_FW_SDO_CLIENT_IDLE;
  }
}

/* The client gives up: abort frame in out, back to idle. */
static mrqp_fw_sdo_step client_abort(mrqp_fw_sdo_client* c, uint32_t code, mrqp_fw_frame* out) {
  c->abort_code = code;
  c->state = MRQP_FW_SDO_CLIENT_IDLE;
  (void)mrqp_fw_sdo_pack_abort(c->node, 0, c->index, c->subindex, code, out);
  return MRQP_FW_SDO_STEP_ABORT_SEND;
}

static mrqp_fw_sdo_step done(mrqp_fw_sdo_client* c, mrqp_fw_frame* out) {
  c->state = MRQP_FW_SDO_CLIENT_IDLE;
  mrqp_fw_frame_clear(out);
  return MRQP_FW_SDO_STEP_DONE;
}

static void start(mrqp_fw_sdo_client* c, unsigned node, uint16_t index, uint8_t subindex) {
  mrqp_fw_sdo_client_reset(c);
  c->node = (uint8_t)node;
  c->index = index;
  c->subindex = subindex;
}

mrqp_fw_sdo_step mrqp_fw_sdo_client_start_upload(mrqp_fw_sdo_client* c, unsigned node, uint16_t index,
                                                 uint8_t subindex, uint8_t* buf, uint32_t capacity,
                                                 mrqp_fw_frame* out) {
  if (c == NULL || out == NULL || buf == NULL || capacity == 0u || !mrqp_fw_node_valid(node) ||
      c->state != MRQP_FW_SDO_CLIENT_IDLE) {
    mrqp_fw_frame_clear(out);
    return MRQP_FW_SDO_STEP_ERROR;
  }
  start(c, node, index, subindex);
  c->rx = buf;
  c->capacity = capacity;
  c->state = MRQP_FW_SDO_CLIENT_UPLOAD_INIT;
  (void)mrqp_fw_sdo_pack_upload_req(node, index, subindex, out);
  return MRQP_FW_SDO_STEP_SEND;
}

mrqp_fw_sdo_step mrqp_fw_sdo_client_start_download(mrqp_fw_sdo_client* c, unsigned node, uint16_t index,
                                                   uint8_t subindex, const uint8_t* data, uint32_t n,
                                                   mrqp_fw_frame* out) {
  if (c == NULL || out == NULL || data == NULL || n == 0u || !mrqp_fw_node_valid(node) ||
      c->state != MRQP_FW_SDO_CLIENT_IDLE) {
    mrqp_fw_frame_clear(out);
    return MRQP_FW_SDO_STEP_ERROR;
  }
  start(c, node, index, subindex);
  c->tx = data;
  c->capacity = n;
  c->state = MRQP_FW_SDO_CLIENT_DOWNLOAD_INIT;
  if (n <= 4u) {
    (void)mrqp_fw_sdo_pack_download_req(node, index, subindex, data, (unsigned)n, out);
  } else {
    (void)mrqp_fw_sdo_pack_download_init_segmented(node, index, subindex, n, out);
  }
  return MRQP_FW_SDO_STEP_SEND;
}

/* Next download segment (toggle c->toggle) from c->count. */
static mrqp_fw_sdo_step send_segment(mrqp_fw_sdo_client* c, mrqp_fw_frame* out) {
  uint32_t left = c->capacity - c->count;
  unsigned n = left > MRQP_FW_SDO_SEGMENT_DATA ? MRQP_FW_SDO_SEGMENT_DATA : (unsigned)left;
  int last = left <= MRQP_FW_SDO_SEGMENT_DATA;
  (void)mrqp_fw_sdo_pack_segment(c->node, 0, c->toggle, c->tx + c->count, n, last, out);
  c->count += n;
  return MRQP_FW_SDO_STEP_SEND;
}

static int same_mux(const mrqp_fw_sdo_client* c, const mrqp_fw_sdo_msg* m) {
  return m->index == c->index && m->subindex == c->subindex;
}

mrqp_fw_sdo_step mrqp_fw_sdo_client_on_frame(mrqp_fw_sdo_client* c, const mrqp_fw_frame* in,
                                             mrqp_fw_frame* out) {
  mrqp_fw_sdo_msg m;
  mrqp_fw_err e;
  if (c == NULL || in == NULL || out == NULL) {
    return MRQP_FW_SDO_STEP_ERROR;
  }
  if (c->state == MRQP_FW_SDO_CLIENT_IDLE || in->id != MRQP_FW_COB_SDO_TX_BASE + c->node ||
      (in->flags & (MRQP_FW_FRAME_EXT | MRQP_FW_FRAME_RTR | MRQP_FW_FRAME_FD)) != 0u) {
    return MRQP_FW_SDO_STEP_IGNORED;
  }
  e = mrqp_fw_sdo_unpack(in, &m);
  if (e == MRQP_FW_ERR_COMMAND) {
    return client_abort(c, MRQP_FW_SDO_ABORT_COMMAND, out);
  }
  if (e != MRQP_FW_OK) {
    return client_abort(c, MRQP_FW_SDO_ABORT_GENERAL, out);
  }
  if (m.kind == MRQP_FW_SDO_ABORT) {
    c->abort_code = m.abort_code;
    c->state = MRQP_FW_SDO_CLIENT_IDLE;
    mrqp_fw_frame_clear(out);
    return MRQP_FW_SDO_STEP_ABORTED;
  }
  switch (c->state) {
    case MRQP_FW_SDO_CLIENT_UPLOAD_INIT:
      if (m.kind != MRQP_FW_SDO_UPLOAD_INIT_RESP) {
        break;
      }
      if (!same_mux(c, &m)) {
        return client_abort(c, MRQP_FW_SDO_ABORT_GENERAL, out);
      }
      if (m.expedited) {
        if (m.n > c->capacity) {
          return client_abort(c, MRQP_FW_SDO_ABORT_OUT_OF_MEMORY, out);
        }
        memcpy(c->rx, m.data, m.n);
        c->count = m.n;
        c->size = m.n;
        return done(c, out);
      }
      if (m.size_indicated && m.size > c->capacity) {
        return client_abort(c, MRQP_FW_SDO_ABORT_OUT_OF_MEMORY, out);
      }
      c->size = m.size_indicated ? m.size : 0u;
      c->toggle = 0u;
      c->state = MRQP_FW_SDO_CLIENT_UPLOAD_SEG;
      (void)mrqp_fw_sdo_pack_upload_seg_req(c->node, c->toggle, out);
      return MRQP_FW_SDO_STEP_SEND;

    case MRQP_FW_SDO_CLIENT_UPLOAD_SEG:
      if (m.kind != MRQP_FW_SDO_UPLOAD_SEG_RESP) {
        break;
      }
      if (m.toggle != c->toggle) {
        return client_abort(c, MRQP_FW_SDO_ABORT_TOGGLE, out);
      }
      if (m.n > c->capacity - c->count) {
        return client_abort(c, MRQP_FW_SDO_ABORT_OUT_OF_MEMORY, out);
      }
      memcpy(c->rx + c->count, m.data, m.n);
      c->count += m.n;
      if (m.last) {
        if (c->size != 0u && c->count != c->size) {
          return client_abort(c, MRQP_FW_SDO_ABORT_TYPE_LENGTH, out);
        }
        return done(c, out);
      }
      c->toggle ^= 1u;
      (void)mrqp_fw_sdo_pack_upload_seg_req(c->node, c->toggle, out);
      return MRQP_FW_SDO_STEP_SEND;

    case MRQP_FW_SDO_CLIENT_DOWNLOAD_INIT:
      if (m.kind != MRQP_FW_SDO_DOWNLOAD_INIT_RESP) {
        break;
      }
      if (!same_mux(c, &m)) {
        return client_abort(c, MRQP_FW_SDO_ABORT_GENERAL, out);
      }
      if (c->capacity <= 4u) {
        c->count = c->capacity;
        return done(c, out);
      }
      c->toggle = 0u;
      c->count = 0u;
      c->state = MRQP_FW_SDO_CLIENT_DOWNLOAD_SEG;
      return send_segment(c, out);

    case MRQP_FW_SDO_CLIENT_DOWNLOAD_SEG:
      if (m.kind != MRQP_FW_SDO_DOWNLOAD_SEG_RESP) {
        break;
      }
      if (m.toggle != c->toggle) {
        return client_abort(c, MRQP_FW_SDO_ABORT_TOGGLE, out);
      }
      if (c->count >= c->capacity) {
        return done(c, out);
      }
      c->toggle ^= 1u;
      return send_segment(c, out);

    case MRQP_FW_SDO_CLIENT_IDLE:
      return MRQP_FW_SDO_STEP_IGNORED;
  }
  /* A valid SDO frame that does not fit the transfer state. */
  return client_abort(c, MRQP_FW_SDO_ABORT_COMMAND, out);
}

mrqp_fw_sdo_step mrqp_fw_sdo_client_timeout(mrqp_fw_sdo_client* c, mrqp_fw_frame* out) {
  if (c == NULL || out == NULL || c->state == MRQP_FW_SDO_CLIENT_IDLE) {
    mrqp_fw_frame_clear(out);
    return MRQP_FW_SDO_STEP_ERROR;
  }
  return client_abort(c, MRQP_FW_SDO_ABORT_TIMEOUT, out);
}
