/* mrqp firmware interface -- wrist force/torque sensor frames. */
#include "mrqp/firmware_if/ft_sensor.h"

#include <string.h>

#include "internal.h"
#include "mrqp/firmware_if/bytes.h"
#include "mrqp/firmware_if/canopen_ids.h"
#include "mrqp/firmware_if/crc.h"
#include "mrqp/firmware_if/saturate.h"

#define FD_SEQ_AT 24u
#define FD_STATUS_AT 25u
#define FD_CRC_AT 30u

int mrqp_fw_ft_scale_valid(const mrqp_fw_ft_scale* s) {
  return s != NULL && mrqp_fw_isfinite_d(s->counts_per_n) && s->counts_per_n > 0.0 &&
         mrqp_fw_isfinite_d(s->counts_per_nm) && s->counts_per_nm > 0.0;
}

static double axis_scale(const mrqp_fw_ft_scale* s, unsigned axis) {
  return axis < 3u ? s->counts_per_n : s->counts_per_nm;
}

/* Quantises the six channels into counts[] within [lo, hi]. Returns flags (NaN error or sat bits). */
static mrqp_fw_pack_flags quantize6(const mrqp_fw_ft_scale* scale, const double w[6], int64_t lo, int64_t hi,
                                    int64_t counts[6]) {
  mrqp_fw_pack_flags flags = MRQP_FW_PACK_OK;
  unsigned a;
  for (a = 0u; a < 6u; ++a) {
    mrqp_fw_conv r;
    if (mrqp_fw_isnan_d(w[a])) {
      return MRQP_FW_PACK_ERR_NAN;
    }
    r = mrqp_fw_quantize_int(w[a] * axis_scale(scale, a), lo, hi, &counts[a]);
    if (r == MRQP_FW_CONV_NAN) { /* inf * scale cannot be NaN; kept for safety */
      return MRQP_FW_PACK_ERR_NAN;
    }
    if (r != MRQP_FW_CONV_OK) {
      flags |= (mrqp_fw_pack_flags)1u << a;
    }
  }
  return flags;
}

static mrqp_fw_pack_flags check_pack_args(const mrqp_fw_ft_scale* scale, unsigned node,
                                          const mrqp_fw_ft_sample* s) {
  if (s == NULL || !mrqp_fw_node_valid(node) || (s->status & MRQP_FW_FT_STATUS_RESERVED) != 0u) {
    return MRQP_FW_PACK_ERR_ARG;
  }
  if (!mrqp_fw_ft_scale_valid(scale)) {
    return MRQP_FW_PACK_ERR_CONFIG;
  }
  return MRQP_FW_PACK_OK;
}

mrqp_fw_pack_flags mrqp_fw_ft_pack_classic(const mrqp_fw_ft_scale* scale, unsigned node,
                                           const mrqp_fw_ft_sample* s, mrqp_fw_frame* forces,
                                           mrqp_fw_frame* moments) {
  int64_t c[6];
  mrqp_fw_pack_flags flags;
  uint8_t status;
  unsigned a;
  if (forces == NULL || moments == NULL || forces == moments) {
    mrqp_fw_frame_clear(forces);
    mrqp_fw_frame_clear(moments);
    return MRQP_FW_PACK_ERR_ARG;
  }
  flags = check_pack_args(scale, node, s);
  if (flags == MRQP_FW_PACK_OK) {
    flags = quantize6(scale, s->wrench, INT16_MIN, INT16_MAX, c);
  }
  if (mrqp_fw_pack_failed(flags)) {
    mrqp_fw_frame_clear(moments);
    return mrqp_fw_fail(forces, flags);
  }
  status = (uint8_t)(s->status | (flags != 0u ? MRQP_FW_FT_STATUS_OVERRANGE : 0u));
  mrqp_fw_frame_init(forces, MRQP_FW_COB_TPDO1_BASE + node, (uint8_t)MRQP_FW_FT_CLASSIC_LEN, 0u);
  mrqp_fw_frame_init(moments, MRQP_FW_COB_TPDO2_BASE + node, (uint8_t)MRQP_FW_FT_CLASSIC_LEN, 0u);
  for (a = 0u; a < 3u; ++a) {
    mrqp_fw_put_u16le(&forces->data[2u * a], (uint16_t)(int16_t)c[a]);
    mrqp_fw_put_u16le(&moments->data[2u * a], (uint16_t)(int16_t)c[a + 3u]);
  }
  forces->data[6] = s->seq;
  forces->data[7] = status;
  moments->data[6] = s->seq;
  moments->data[7] = status;
  return flags;
}

mrqp_fw_err mrqp_fw_ft_unpack_half(const mrqp_fw_ft_scale* scale, const mrqp_fw_frame* in, unsigned node,
                                   mrqp_fw_ft_half* half) {
  unsigned a;
  int is_moments;
  mrqp_fw_err e = mrqp_fw_classic_envelope(in);
  if (e != MRQP_FW_OK) {
    return e;
  }
  if (half == NULL) {
    return MRQP_FW_ERR_NULL;
  }
  if (!mrqp_fw_node_valid(node)) {
    return MRQP_FW_ERR_ID;
  }
  if (in->id == MRQP_FW_COB_TPDO1_BASE + node) {
    is_moments = 0;
  } else if (in->id == MRQP_FW_COB_TPDO2_BASE + node) {
    is_moments = 1;
  } else {
    return MRQP_FW_ERR_ID;
  }
  if (in->len != MRQP_FW_FT_CLASSIC_LEN) {
    return MRQP_FW_ERR_LENGTH;
  }
  if ((in->data[7] & MRQP_FW_FT_STATUS_RESERVED) != 0u) {
    return MRQP_FW_ERR_FORMAT;
  }
  if (!mrqp_fw_ft_scale_valid(scale)) {
    return MRQP_FW_ERR_CONFIG;
  }
  half->moments = is_moments;
  for (a = 0u; a < 3u; ++a) {
    double k = is_moments ? scale->counts_per_nm : scale->counts_per_n;
    half->value[a] = (double)mrqp_fw_u16_to_i16(mrqp_fw_get_u16le(&in->data[2u * a])) / k;
  }
  half->seq = in->data[6];
  half->status = in->data[7];
  return MRQP_FW_OK;
}

mrqp_fw_err mrqp_fw_ft_join(const mrqp_fw_ft_half* forces, const mrqp_fw_ft_half* moments,
                            mrqp_fw_ft_sample* s) {
  unsigned a;
  if (forces == NULL || moments == NULL || s == NULL) {
    return MRQP_FW_ERR_NULL;
  }
  if (forces->moments != 0 || moments->moments == 0) {
    return MRQP_FW_ERR_ID;
  }
  if (forces->seq != moments->seq || forces->status != moments->status) {
    return MRQP_FW_ERR_TORN;
  }
  for (a = 0u; a < 3u; ++a) {
    s->wrench[a] = forces->value[a];
    s->wrench[a + 3u] = moments->value[a];
  }
  s->seq = forces->seq;
  s->status = forces->status;
  return MRQP_FW_OK;
}

mrqp_fw_err mrqp_fw_ft_unpack_classic(const mrqp_fw_ft_scale* scale, const mrqp_fw_frame* forces,
                                      const mrqp_fw_frame* moments, unsigned node, mrqp_fw_ft_sample* s) {
  mrqp_fw_ft_half f;
  mrqp_fw_ft_half m;
  mrqp_fw_err e = mrqp_fw_ft_unpack_half(scale, forces, node, &f);
  if (e != MRQP_FW_OK) {
    return e;
  }
  e = mrqp_fw_ft_unpack_half(scale, moments, node, &m);
  if (e != MRQP_FW_OK) {
    return e;
  }
  return mrqp_fw_ft_join(&f, &m, s);
}

mrqp_fw_pack_flags mrqp_fw_ft_pack_fd(const mrqp_fw_ft_scale* scale, unsigned node,
                                      const mrqp_fw_ft_sample* s, mrqp_fw_frame* out) {
  int64_t c[6];
  mrqp_fw_pack_flags flags;
  unsigned a;
  if (out == NULL) {
    return MRQP_FW_PACK_ERR_ARG;
  }
  flags = check_pack_args(scale, node, s);
  if (flags == MRQP_FW_PACK_OK) {
    flags = quantize6(scale, s->wrench, INT32_MIN, INT32_MAX, c);
  }
  if (mrqp_fw_pack_failed(flags)) {
    return mrqp_fw_fail(out, flags);
  }
  mrqp_fw_frame_init(out, MRQP_FW_COB_TPDO1_BASE + node, (uint8_t)MRQP_FW_FT_FD_LEN,
                     (uint8_t)(MRQP_FW_FRAME_FD | MRQP_FW_FRAME_BRS));
  for (a = 0u; a < 6u; ++a) {
    mrqp_fw_put_u32le(&out->data[4u * a], (uint32_t)(int32_t)c[a]);
  }
  out->data[FD_SEQ_AT] = s->seq;
  out->data[FD_STATUS_AT] = (uint8_t)(s->status | (flags != 0u ? MRQP_FW_FT_STATUS_OVERRANGE : 0u));
  mrqp_fw_put_u16be(&out->data[FD_CRC_AT], mrqp_fw_crc16(out->data, FD_CRC_AT));
  return flags;
}

mrqp_fw_err mrqp_fw_ft_unpack_fd(const mrqp_fw_ft_scale* scale, const mrqp_fw_frame* in, unsigned node,
                                 mrqp_fw_ft_sample* s) {
  unsigned a;
  mrqp_fw_err e;
  if (in == NULL || s == NULL) {
    return MRQP_FW_ERR_NULL;
  }
  if (!mrqp_fw_node_valid(node)) {
    return MRQP_FW_ERR_ID;
  }
  e = mrqp_fw_frame_expect(in, MRQP_FW_COB_TPDO1_BASE + node, MRQP_FW_FT_FD_LEN, 1);
  if (e != MRQP_FW_OK) {
    return e;
  }
  if (mrqp_fw_crc16(in->data, MRQP_FW_FT_FD_LEN) != 0u) {
    return MRQP_FW_ERR_CRC;
  }
  for (a = FD_STATUS_AT + 1u; a < FD_CRC_AT; ++a) {
    if (in->data[a] != 0u) {
      return MRQP_FW_ERR_FORMAT;
    }
  }
  if ((in->data[FD_STATUS_AT] & MRQP_FW_FT_STATUS_RESERVED) != 0u) {
    return MRQP_FW_ERR_FORMAT;
  }
  if (!mrqp_fw_ft_scale_valid(scale)) {
    return MRQP_FW_ERR_CONFIG;
  }
  for (a = 0u; a < 6u; ++a) {
    s->wrench[a] = (double)mrqp_fw_u32_to_i32(mrqp_fw_get_u32le(&in->data[4u * a])) / axis_scale(scale, a);
  }
  s->seq = in->data[FD_SEQ_AT];
  s->status = in->data[FD_STATUS_AT];
  return MRQP_FW_OK;
}

mrqp_fw_pack_flags mrqp_fw_ft_pack_tare(unsigned node, unsigned command, mrqp_fw_frame* out) {
  if (out == NULL || !mrqp_fw_node_valid(node) ||
      (command != MRQP_FW_FT_CMD_TARE && command != MRQP_FW_FT_CMD_CLEAR_TARE)) {
    return mrqp_fw_fail(out, MRQP_FW_PACK_ERR_ARG);
  }
  mrqp_fw_frame_init(out, MRQP_FW_COB_RPDO1_BASE + node, (uint8_t)MRQP_FW_FT_TARE_LEN, 0u);
  out->data[0] = (uint8_t)command;
  out->data[1] = (uint8_t)(command ^ 0xFFu);
  return MRQP_FW_PACK_OK;
}

mrqp_fw_err mrqp_fw_ft_unpack_tare(const mrqp_fw_frame* in, unsigned node, uint8_t* command) {
  mrqp_fw_err e;
  if (in == NULL || command == NULL) {
    return MRQP_FW_ERR_NULL;
  }
  if (!mrqp_fw_node_valid(node)) {
    return MRQP_FW_ERR_ID;
  }
  e = mrqp_fw_frame_expect(in, MRQP_FW_COB_RPDO1_BASE + node, MRQP_FW_FT_TARE_LEN, 0);
  if (e != MRQP_FW_OK) {
    return e;
  }
  if (((unsigned)in->data[0] ^ (unsigned)in->data[1]) != 0xFFu) {
    return MRQP_FW_ERR_FORMAT;
  }
  if (in->data[0] != MRQP_FW_FT_CMD_TARE && in->data[0] != MRQP_FW_FT_CMD_CLEAR_TARE) {
    return MRQP_FW_ERR_COMMAND;
  }
  *command = in->data[0];
  return MRQP_FW_OK;
}
