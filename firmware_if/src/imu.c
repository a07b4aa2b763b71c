/* mrqp firmware interface -- IMU sample frame (CAN FD). See imu.h. */
#include "mrqp/firmware_if/imu.h"

#include <string.h>

#include "internal.h"
#include "mrqp/firmware_if/bytes.h"
#include "mrqp/firmware_if/canopen_ids.h"
#include "mrqp/firmware_if/crc.h"
#include "mrqp/firmware_if/saturate.h"

#define IMU_QUAT_AT 0u
#define IMU_RATE_AT 8u
#define IMU_FORCE_AT 14u
#define IMU_SEQ_AT 20u
#define IMU_STATUS_AT 21u
#define IMU_CRC_AT 22u
#define IMU_RATE_SAT_MASK (MRQP_FW_IMU_SAT_WX | MRQP_FW_IMU_SAT_WY | MRQP_FW_IMU_SAT_WZ)
#define IMU_FORCE_SAT_MASK (MRQP_FW_IMU_SAT_AX | MRQP_FW_IMU_SAT_AY | MRQP_FW_IMU_SAT_AZ)

int mrqp_fw_imu_scale_valid(const mrqp_fw_imu_scale* s) {
  return s != NULL && mrqp_fw_isfinite_d(s->counts_per_rad_s) && s->counts_per_rad_s > 0.0 &&
         mrqp_fw_isfinite_d(s->counts_per_mps2) && s->counts_per_mps2 > 0.0;
}

/* One i16 channel: value * k rounded into [-32767, 32767] at data[at]; sets `bit` when saturated. */
static mrqp_fw_pack_flags put_channel(double value, double k, uint8_t* data, mrqp_fw_pack_flags bit) {
  int64_t code = 0;
  const mrqp_fw_conv r = mrqp_fw_quantize_int(value * k, -32767, 32767, &code);
  if (r == MRQP_FW_CONV_NAN) {
    return MRQP_FW_PACK_ERR_NAN;
  }
  mrqp_fw_put_u16le(data, (uint16_t)(int16_t)code);
  return r == MRQP_FW_CONV_OK ? MRQP_FW_PACK_OK : bit;
}

mrqp_fw_pack_flags mrqp_fw_imu_pack(const mrqp_fw_imu_scale* scale, unsigned node,
                                    const mrqp_fw_imu_sample* s, mrqp_fw_frame* out) {
  mrqp_fw_pack_flags flags = MRQP_FW_PACK_OK;
  unsigned a;
  if (out == NULL) {
    return MRQP_FW_PACK_ERR_ARG;
  }
  if (s == NULL || !mrqp_fw_node_valid(node) || (s->status & MRQP_FW_IMU_STATUS_RESERVED) != 0u) {
    return mrqp_fw_fail(out, MRQP_FW_PACK_ERR_ARG);
  }
  if (!mrqp_fw_imu_scale_valid(scale)) {
    return mrqp_fw_fail(out, MRQP_FW_PACK_ERR_CONFIG);
  }
  for (a = 0u; a < 4u; ++a) {
    if (mrqp_fw_isnan_d(s->orientation[a])) {
      return mrqp_fw_fail(out, MRQP_FW_PACK_ERR_NAN);
    }
  }
  for (a = 0u; a < 3u; ++a) {
    if (mrqp_fw_isnan_d(s->angular_velocity[a]) || mrqp_fw_isnan_d(s->specific_force[a])) {
      return mrqp_fw_fail(out, MRQP_FW_PACK_ERR_NAN);
    }
  }
  mrqp_fw_frame_init(out, MRQP_FW_COB_TPDO1_BASE + node, (uint8_t)MRQP_FW_IMU_FD_LEN,
                     (uint8_t)(MRQP_FW_FRAME_FD | MRQP_FW_FRAME_BRS));
  for (a = 0u; a < 4u; ++a) {
    flags |= put_channel(s->orientation[a], MRQP_FW_IMU_QUAT_COUNTS, &out->data[IMU_QUAT_AT + 2u * a],
                         (mrqp_fw_pack_flags)MRQP_FW_IMU_SAT_QW << a);
  }
  for (a = 0u; a < 3u; ++a) {
    flags |= put_channel(s->angular_velocity[a], scale->counts_per_rad_s, &out->data[IMU_RATE_AT + 2u * a],
                         (mrqp_fw_pack_flags)MRQP_FW_IMU_SAT_WX << a);
    flags |= put_channel(s->specific_force[a], scale->counts_per_mps2, &out->data[IMU_FORCE_AT + 2u * a],
                         (mrqp_fw_pack_flags)MRQP_FW_IMU_SAT_AX << a);
  }
  out->data[IMU_SEQ_AT] = s->seq;
  out->data[IMU_STATUS_AT] = (uint8_t)(s->status | ((flags & (IMU_RATE_SAT_MASK | IMU_FORCE_SAT_MASK)) != 0u
                                                        ? MRQP_FW_IMU_STATUS_OVERRANGE
                                                        : 0u));
  mrqp_fw_put_u16be(&out->data[IMU_CRC_AT], mrqp_fw_crc16(out->data, IMU_CRC_AT));
  return flags;
}

mrqp_fw_err mrqp_fw_imu_unpack(const mrqp_fw_imu_scale* scale, const mrqp_fw_frame* in, unsigned node,
                               mrqp_fw_imu_sample* s) {
  unsigned a;
  double norm2 = 0.0;
  double q[4];
  mrqp_fw_err e;
  if (in == NULL || s == NULL) {
    return MRQP_FW_ERR_NULL;
  }
  if (!mrqp_fw_node_valid(node)) {
    return MRQP_FW_ERR_ID;
  }
  e = mrqp_fw_frame_expect(in, MRQP_FW_COB_TPDO1_BASE + node, MRQP_FW_IMU_FD_LEN, 1);
  if (e != MRQP_FW_OK) {
    return e;
  }
  if (mrqp_fw_crc16(in->data, MRQP_FW_IMU_FD_LEN) != 0u) {
    return MRQP_FW_ERR_CRC;
  }
  if ((in->data[IMU_STATUS_AT] & MRQP_FW_IMU_STATUS_RESERVED) != 0u) {
    return MRQP_FW_ERR_FORMAT;
  }
  if (!mrqp_fw_imu_scale_valid(scale)) {
    return MRQP_FW_ERR_CONFIG;
  }
  for (a = 0u; a < 4u; ++a) {
    const int16_t code = mrqp_fw_u16_to_i16(mrqp_fw_get_u16le(&in->data[IMU_QUAT_AT + 2u * a]));
    if (code == INT16_MIN) {
      return MRQP_FW_ERR_RANGE;
    }
    q[a] = (double)code / MRQP_FW_IMU_QUAT_COUNTS;
    norm2 += q[a] * q[a];
  }
  /* | |q| - 1 | <= tol  <=>  (1 - tol)^2 <= |q|^2 <= (1 + tol)^2 (no libm in firmware_if). */
  if (norm2 < (1.0 - MRQP_FW_IMU_NORM_TOLERANCE) * (1.0 - MRQP_FW_IMU_NORM_TOLERANCE) ||
      norm2 > (1.0 + MRQP_FW_IMU_NORM_TOLERANCE) * (1.0 + MRQP_FW_IMU_NORM_TOLERANCE)) {
    return MRQP_FW_ERR_RANGE;
  }
  memcpy(s->orientation, q, sizeof q);
  for (a = 0u; a < 3u; ++a) {
    s->angular_velocity[a] = (double)mrqp_fw_u16_to_i16(mrqp_fw_get_u16le(&in->data[IMU_RATE_AT + 2u * a])) /
                             scale->counts_per_rad_s;
    s->specific_force[a] = (double)mrqp_fw_u16_to_i16(mrqp_fw_get_u16le(&in->data[IMU_FORCE_AT + 2u * a])) /
                           scale->counts_per_mps2;
  }
  s->seq = in->data[IMU_SEQ_AT];
  s->status = in->data[IMU_STATUS_AT];
  return MRQP_FW_OK;
}
