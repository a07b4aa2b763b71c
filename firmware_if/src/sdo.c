/* mrqp firmware interface -- SDO frames. */
#include "mrqp/firmware_if/sdo.h"

#include <string.h>

#include "internal.h"
#include "mrqp/firmware_if/bytes.h"
#include "mrqp/firmware_if/canopen_ids.h"

const char* mrqp_fw_sdo_abort_str(uint32_t code) {
  switch (code) {
    case MRQP_FW_SDO_ABORT_TOGGLE:
      return "toggle bit not alternated";
    case MRQP_FW_SDO_ABORT_TIMEOUT:
      return "SDO protocol timed out";
    case MRQP_FW_SDO_ABORT_COMMAND:
      return "client/server command specifier not valid or unknown";
    case MRQP_FW_SDO_ABORT_BLOCK_SIZE:
      return "invalid block size";
    case MRQP_FW_SDO_ABORT_SEQUENCE:
      return "invalid sequence number";
    case MRQP_FW_SDO_ABORT_CRC:
      return "CRC error";
    case MRQP_FW_SDO_ABORT_OUT_OF_MEMORY:
      return "out of memory";
    case MRQP_FW_SDO_ABORT_UNSUPPORTED_ACCESS:
      return "unsupported access to an object";
    case MRQP_FW_SDO_ABORT_WRITE_ONLY:
      return "attempt to read a write only object";
    case MRQP_FW_SDO_ABORT_READ_ONLY:
      return "attempt to write a read only object";
    case MRQP_FW_SDO_ABORT_NO_OBJECT:
      return "object does not exist in the object dictionary";
    case MRQP_FW_SDO_ABORT_NOT_MAPPABLE:
      return "object cannot be mapped to the PDO";
    case MRQP_FW_SDO_ABORT_PDO_LENGTH:
      return "the number and length of the objects to be mapped would exceed PDO length";
    case MRQP_FW_SDO_ABORT_PARAM_INCOMPATIBLE:
      return "general parameter incompatibility reason";
    case MRQP_FW_SDO_ABORT_INTERNAL_INCOMPATIBLE:
      return "general internal incompatibility in the device";
    case MRQP_FW_SDO_ABORT_HARDWARE:
      return "access failed due to a hardware error";
    case MRQP_FW_SDO_ABORT_TYPE_LENGTH:
      return "data type does not match, length of service parameter does not match";
    case MRQP_FW_SDO_ABORT_TYPE_LENGTH_HIGH:
      return "data type does not match, length of service parameter too high";
    case MRQP_FW_SDO_ABORT_TYPE_LENGTH_LOW:
      return "data type does not match, length of service parameter too low";
    case MRQP_FW_SDO_ABORT_NO_SUBINDEX:
      return "sub-index does not exist";
    case MRQP_FW_SDO_ABORT_INVALID_VALUE:
      return "invalid value for parameter (download only)";
    case MRQP_FW_SDO_ABORT_VALUE_HIGH:
      return "value of parameter written too high (download only)";
    case MRQP_FW_SDO_ABORT_VALUE_LOW:
      return "value of parameter written too low (download only)";
    case MRQP_FW_SDO_ABORT_MAX_LESS_MIN:
      return "maximum value is less than minimum value";
    case MRQP_FW_SDO_ABORT_NO_RESOURCE:
      return "resource not available: SDO connection";
    case MRQP_FW_SDO_ABORT_GENERAL:
      return "general error";
    case MRQP_FW_SDO_ABORT_STORE:
      return "data cannot be transferred or stored to the application";
    case MRQP_FW_SDO_ABORT_STORE_LOCAL:
      return "data cannot be transferred or stored to the application because of local control";
    case MRQP_FW_SDO_ABORT_STORE_STATE:
      return "data cannot be transferred or stored to the application because of the present device state";
    case MRQP_FW_SDO_ABORT_NO_DICTIONARY:
      return "object dictionary dynamic generation fails or no object dictionary is present";
    case MRQP_FW_SDO_ABORT_NO_DATA:
      return "no data available";
    default:
      break;
  }
  return "unknown SDO abort code";
}

static uint32_t sdo_cob(unsigned node, int from_server) {
  return (from_server ? MRQP_FW_COB_SDO_TX_BASE : MRQP_FW_COB_SDO_RX_BASE) + node;
}

/* Frame with command byte, multiplexer and zero data. */
static void init_mux(mrqp_fw_frame* out, unsigned node, int from_server, uint8_t cmd, uint16_t index,
                     uint8_t subindex) {
  mrqp_fw_frame_init(out, sdo_cob(node, from_server), (uint8_t)MRQP_FW_SDO_LEN, 0u);
  out->data[0] = cmd;
  mrqp_fw_put_u16le(&out->data[1], index);
  out->data[3] = subindex;
}

static mrqp_fw_pack_flags pack_expedited(unsigned node, int from_server, unsigned cs, uint16_t index,
                                         uint8_t subindex, const uint8_t* data, unsigned n,
                                         mrqp_fw_frame* out) {
  if (out == NULL || data == NULL || n < 1u || n > 4u || !mrqp_fw_node_valid(node)) {
    return mrqp_fw_fail(out, MRQP_FW_PACK_ERR_ARG);
  }
  /* cs | n = 4 - size | e = 1 | s = 1 */
  init_mux(out, node, from_server, (uint8_t)((cs << 5) | ((4u - n) << 2) | 0x03u), index, subindex);
  memcpy(&out->data[4], data, n);
  return MRQP_FW_PACK_OK;
}

mrqp_fw_pack_flags mrqp_fw_sdo_pack_download_req(unsigned node, uint16_t index, uint8_t subindex,
                                                 const uint8_t* data, unsigned n, mrqp_fw_frame* out) {
  return pack_expedited(node, 0, MRQP_FW_SDO_CCS_INITIATE_DOWNLOAD, index, subindex, data, n, out);
}

mrqp_fw_pack_flags mrqp_fw_sdo_pack_upload_resp(unsigned node, uint16_t index, uint8_t subindex,
                                                const uint8_t* data, unsigned n, mrqp_fw_frame* out) {
  return pack_expedited(node, 1, MRQP_FW_SDO_SCS_INITIATE_UPLOAD, index, subindex, data, n, out);
}

mrqp_fw_pack_flags mrqp_fw_sdo_pack_download_u32(unsigned node, uint16_t index, uint8_t subindex,
                                                 uint32_t value, unsigned n, mrqp_fw_frame* out) {
  uint8_t bytes[4];
  if (n != 1u && n != 2u && n != 4u) {
    return mrqp_fw_fail(out, MRQP_FW_PACK_ERR_ARG);
  }
  mrqp_fw_put_u32le(bytes, value);
  return mrqp_fw_sdo_pack_download_req(node, index, subindex, bytes, n, out);
}

mrqp_fw_pack_flags mrqp_fw_sdo_pack_download_resp(unsigned node, uint16_t index, uint8_t subindex,
                                                  mrqp_fw_frame* out) {
  if (out == NULL || !mrqp_fw_node_valid(node)) {
    return mrqp_fw_fail(out, MRQP_FW_PACK_ERR_ARG);
  }
  init_mux(out, node, 1, (uint8_t)(MRQP_FW_SDO_SCS_INITIATE_DOWNLOAD << 5), index, subindex);
  return MRQP_FW_PACK_OK;
}

mrqp_fw_pack_flags mrqp_fw_sdo_pack_upload_req(unsigned node, uint16_t index, uint8_t subindex,
                                               mrqp_fw_frame* out) {
  if (out == NULL || !mrqp_fw_node_valid(node)) {
    return mrqp_fw_fail(out, MRQP_FW_PACK_ERR_ARG);
  }
  init_mux(out, node, 0, (uint8_t)(MRQP_FW_SDO_CCS_INITIATE_UPLOAD << 5), index, subindex);
  return MRQP_FW_PACK_OK;
}

mrqp_fw_pack_flags mrqp_fw_sdo_pack_abort(unsigned node, int from_server, uint16_t index, uint8_t subindex,
                                          uint32_t abort_code, mrqp_fw_frame* out) {
  if (out == NULL || !mrqp_fw_node_valid(node)) {
    return mrqp_fw_fail(out, MRQP_FW_PACK_ERR_ARG);
  }
  init_mux(out, node, from_server, (uint8_t)(MRQP_FW_SDO_CS_ABORT << 5), index, subindex);
  mrqp_fw_put_u32le(&out->data[4], abort_code);
  return MRQP_FW_PACK_OK;
}

static mrqp_fw_pack_flags pack_segmented_init(unsigned node, int from_server, unsigned cs, uint16_t index,
                                              uint8_t subindex, uint32_t size, mrqp_fw_frame* out) {
  if (out == NULL || !mrqp_fw_node_valid(node)) {
    return mrqp_fw_fail(out, MRQP_FW_PACK_ERR_ARG);
  }
  /* cs | n = 0 | e = 0 | s = 1, size in bytes 4..7 */
  init_mux(out, node, from_server, (uint8_t)((cs << 5) | 0x01u), index, subindex);
  mrqp_fw_put_u32le(&out->data[4], size);
  return MRQP_FW_PACK_OK;
}

mrqp_fw_pack_flags mrqp_fw_sdo_pack_download_init_segmented(unsigned node, uint16_t index, uint8_t subindex,
                                                            uint32_t size, mrqp_fw_frame* out) {
  return pack_segmented_init(node, 0, MRQP_FW_SDO_CCS_INITIATE_DOWNLOAD, index, subindex, size, out);
}

mrqp_fw_pack_flags mrqp_fw_sdo_pack_upload_resp_segmented(unsigned node, uint16_t index, uint8_t subindex,
                                                          uint32_t size, mrqp_fw_frame* out) {
  return pack_segmented_init(node, 1, MRQP_FW_SDO_SCS_INITIATE_UPLOAD, index, subindex, size, out);
}

mrqp_fw_pack_flags mrqp_fw_sdo_pack_segment(unsigned node, int from_server, unsigned toggle,
                                            const uint8_t* data, unsigned n, int last, mrqp_fw_frame* out) {
  if (out == NULL || (data == NULL && n > 0u) || n > MRQP_FW_SDO_SEGMENT_DATA || toggle > 1u ||
      !mrqp_fw_node_valid(node)) {
    return mrqp_fw_fail(out, MRQP_FW_PACK_ERR_ARG);
  }
  /* cs 0 (download segment / upload segment response) | t | n = 7 - bytes | c */
  mrqp_fw_frame_init(out, sdo_cob(node, from_server), (uint8_t)MRQP_FW_SDO_LEN, 0u);
  out->data[0] = (uint8_t)((toggle << 4) | ((MRQP_FW_SDO_SEGMENT_DATA - n) << 1) | (last ? 1u : 0u));
  if (n > 0u) {
    memcpy(&out->data[1], data, n);
  }
  return MRQP_FW_PACK_OK;
}

static mrqp_fw_pack_flags pack_toggle_only(unsigned node, int from_server, unsigned cs, unsigned toggle,
                                           mrqp_fw_frame* out) {
  if (out == NULL || toggle > 1u || !mrqp_fw_node_valid(node)) {
    return mrqp_fw_fail(out, MRQP_FW_PACK_ERR_ARG);
  }
  mrqp_fw_frame_init(out, sdo_cob(node, from_server), (uint8_t)MRQP_FW_SDO_LEN, 0u);
  out->data[0] = (uint8_t)((cs << 5) | (toggle << 4));
  return MRQP_FW_PACK_OK;
}

mrqp_fw_pack_flags mrqp_fw_sdo_pack_download_seg_resp(unsigned node, unsigned toggle, mrqp_fw_frame* out) {
  return pack_toggle_only(node, 1, MRQP_FW_SDO_SCS_DOWNLOAD_SEGMENT, toggle, out);
}

mrqp_fw_pack_flags mrqp_fw_sdo_pack_upload_seg_req(unsigned node, unsigned toggle, mrqp_fw_frame* out) {
  return pack_toggle_only(node, 0, MRQP_FW_SDO_CCS_UPLOAD_SEGMENT, toggle, out);
}

/* Initiate download request / initiate upload response: expedited or segmented. */
static void decode_initiate(const uint8_t* d, mrqp_fw_sdo_msg* msg) {
  unsigned e = (d[0] >> 1) & 1u;
  unsigned s = d[0] & 1u;
  msg->index = mrqp_fw_get_u16le(&d[1]);
  msg->subindex = d[3];
  msg->size_indicated = (uint8_t)s;
  if (e) {
    msg->expedited = 1u;
    msg->n = (uint8_t)(s ? 4u - ((d[0] >> 2) & 3u) : 4u);
    msg->size = msg->n;
    memcpy(msg->data, &d[4], msg->n);
  } else {
    msg->size = s ? mrqp_fw_get_u32le(&d[4]) : 0u;
  }
}

static void decode_segment(const uint8_t* d, mrqp_fw_sdo_msg* msg) {
  msg->toggle = (uint8_t)((d[0] >> 4) & 1u);
  msg->n = (uint8_t)(MRQP_FW_SDO_SEGMENT_DATA - ((d[0] >> 1) & 7u));
  msg->last = (uint8_t)(d[0] & 1u);
  memcpy(msg->data, &d[1], msg->n);
}

mrqp_fw_err mrqp_fw_sdo_unpack(const mrqp_fw_frame* in, mrqp_fw_sdo_msg* msg) {
  uint8_t node = 0u;
  mrqp_fw_cob kind;
  unsigned cs;
  const uint8_t* d;
  mrqp_fw_err e = mrqp_fw_classic_envelope(in);
  if (e != MRQP_FW_OK) {
    return e;
  }
  if (msg == NULL) {
    return MRQP_FW_ERR_NULL;
  }
  kind = mrqp_fw_cob_decode(in->id, &node);
  if (kind != MRQP_FW_COB_KIND_SDO_TX && kind != MRQP_FW_COB_KIND_SDO_RX) {
    return MRQP_FW_ERR_ID;
  }
  if (in->len != MRQP_FW_SDO_LEN) {
    return MRQP_FW_ERR_LENGTH;
  }
  memset(msg, 0, sizeof(*msg));
  msg->node = node;
  msg->from_server = kind == MRQP_FW_COB_KIND_SDO_TX ? 1u : 0u;
  d = in->data;
  cs = (unsigned)d[0] >> 5;
  if (cs == MRQP_FW_SDO_CS_ABORT) {
    msg->kind = MRQP_FW_SDO_ABORT;
    msg->index = mrqp_fw_get_u16le(&d[1]);
    msg->subindex = d[3];
    msg->abort_code = mrqp_fw_get_u32le(&d[4]);
    return MRQP_FW_OK;
  }
  if (msg->from_server) {
    switch (cs) {
      case MRQP_FW_SDO_SCS_UPLOAD_SEGMENT:
        msg->kind = MRQP_FW_SDO_UPLOAD_SEG_RESP;
        decode_segment(d, msg);
        return MRQP_FW_OK;
      case MRQP_FW_SDO_SCS_DOWNLOAD_SEGMENT:
        msg->kind = MRQP_FW_SDO_DOWNLOAD_SEG_RESP;
        msg->toggle = (uint8_t)((d[0] >> 4) & 1u);
        return MRQP_FW_OK;
      case MRQP_FW_SDO_SCS_INITIATE_UPLOAD:
        msg->kind = MRQP_FW_SDO_UPLOAD_INIT_RESP;
        decode_initiate(d, msg);
        return MRQP_FW_OK;
      case MRQP_FW_SDO_SCS_INITIATE_DOWNLOAD:
        msg->kind = MRQP_FW_SDO_DOWNLOAD_INIT_RESP;
        msg->index = mrqp_fw_get_u16le(&d[1]);
        msg->subindex = d[3];
        return MRQP_FW_OK;
      default:
        return MRQP_FW_ERR_COMMAND;
    }
  }
  switch (cs) {
    case MRQP_FW_SDO_CCS_DOWNLOAD_SEGMENT:
      msg->kind = MRQP_FW_SDO_DOWNLOAD_SEG_REQ;
      decode_segment(d, msg);
      return MRQP_FW_OK;
    case MRQP_FW_SDO_CCS_INITIATE_DOWNLOAD:
      msg->kind = MRQP_FW_SDO_DOWNLOAD_INIT_REQ;
      decode_initiate(d, msg);
      return MRQP_FW_OK;
    case MRQP_FW_SDO_CCS_INITIATE_UPLOAD:
      msg->kind = MRQP_FW_SDO_UPLOAD_INIT_REQ;
      msg->index = mrqp_fw_get_u16le(&d[1]);
      msg->subindex = d[3];
      return MRQP_FW_OK;
    case MRQP_FW_SDO_CCS_UPLOAD_SEGMENT:
      msg->kind = MRQP_FW_SDO_UPLOAD_SEG_REQ;
      msg->toggle = (uint8_t)((d[0] >> 4) & 1u);
      return MRQP_FW_OK;
    default:
      return MRQP_FW_ERR_COMMAND;
  }
}
