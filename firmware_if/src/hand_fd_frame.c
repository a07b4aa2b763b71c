/* mrqp firmware interface -- hand controller board CAN FD frames. */
#include "mrqp/firmware_if/hand_fd_frame.h"

#include <string.h>

#include "internal.h"
#include "mrqp/firmware_if/bytes.h"
#include "mrqp/firmware_if/crc.h"
#include "mrqp/firmware_if/saturate.h"

#define FD_FLAGS ((uint8_t)(MRQP_FW_FRAME_FD | MRQP_FW_FRAME_BRS))

static int lsb_ok(float lsb) { return mrqp_fw_isfinite_f(lsb) && lsb > 0.0f; }

int mrqp_fw_hand_scale_valid(const mrqp_fw_hand_scale* s) {
  return s != NULL && lsb_ok(s->position_lsb) && lsb_ok(s->velocity_lsb) && lsb_ok(s->torque_lsb);
}

static uint8_t frame_len(unsigned header, unsigned n) {
  if (n > MRQP_FW_HAND_FD_MAX_JOINTS) {
    return 0u;
  }
  return mrqp_fw_fd_len_round_up(header + MRQP_FW_HAND_FD_JOINT_LEN * n + MRQP_FW_HAND_FD_CRC_LEN);
}

uint8_t mrqp_fw_hand_cmd_len(unsigned n) { return frame_len(MRQP_FW_HAND_FD_CMD_HEADER_LEN, n); }

uint8_t mrqp_fw_hand_fb_len(unsigned n) { return frame_len(MRQP_FW_HAND_FD_FB_HEADER_LEN, n); }

unsigned mrqp_fw_hand_frames_needed(unsigned joints) {
  return (joints + MRQP_FW_HAND_FD_MAX_JOINTS - 1u) / MRQP_FW_HAND_FD_MAX_JOINTS;
}

/* Encodes n joint records at data + offset. Returns error flags (NaN) or saturation flags. */
static mrqp_fw_pack_flags put_joints(const mrqp_fw_hand_scale* s, const mrqp_fw_hand_joint* j, unsigned n,
                                     uint8_t* data, uint32_t* sat_joints) {
  mrqp_fw_pack_flags flags = MRQP_FW_PACK_OK;
  uint32_t joints = 0u;
  unsigned i;
  for (i = 0u; i < n; ++i) {
    int32_t p = 0, v = 0, t = 0;
    mrqp_fw_conv rp =
        mrqp_fw_quantize_fixed((double)j[i].position, (double)s->position_lsb, MRQP_FW_HAND_P_BITS, &p);
    mrqp_fw_conv rv =
        mrqp_fw_quantize_fixed((double)j[i].velocity, (double)s->velocity_lsb, MRQP_FW_HAND_V_BITS, &v);
    mrqp_fw_conv rt =
        mrqp_fw_quantize_fixed((double)j[i].torque, (double)s->torque_lsb, MRQP_FW_HAND_T_BITS, &t);
    unsigned off = MRQP_FW_HAND_FD_JOINT_LEN * 8u * i;
    if (rp == MRQP_FW_CONV_NAN || rv == MRQP_FW_CONV_NAN || rt == MRQP_FW_CONV_NAN) {
      return MRQP_FW_PACK_ERR_NAN;
    }
    if (rp != MRQP_FW_CONV_OK) {
      flags |= MRQP_FW_HAND_SAT_POSITION;
    }
    if (rv != MRQP_FW_CONV_OK) {
      flags |= MRQP_FW_HAND_SAT_VELOCITY;
    }
    if (rt != MRQP_FW_CONV_OK) {
      flags |= MRQP_FW_HAND_SAT_TORQUE;
    }
    if (rp != MRQP_FW_CONV_OK || rv != MRQP_FW_CONV_OK || rt != MRQP_FW_CONV_OK) {
      joints |= (uint32_t)1u << i;
    }
    mrqp_fw_put_bits_be(data, off, MRQP_FW_HAND_P_BITS, (uint32_t)p);
    mrqp_fw_put_bits_be(data, off + 16u, MRQP_FW_HAND_V_BITS, (uint32_t)v);
    mrqp_fw_put_bits_be(data, off + 28u, MRQP_FW_HAND_T_BITS, (uint32_t)t);
  }
  if (sat_joints != NULL) {
    *sat_joints = joints;
  }
  return flags;
}

/* Decodes n joint records; ERR_RANGE on a reserved (most negative) code. */
static mrqp_fw_err get_joints(const mrqp_fw_hand_scale* s, const uint8_t* data, unsigned n,
                              mrqp_fw_hand_joint* j) {
  unsigned i;
  for (i = 0u; i < n; ++i) {
    unsigned off = MRQP_FW_HAND_FD_JOINT_LEN * 8u * i;
    uint32_t p = mrqp_fw_get_bits_be(data, off, MRQP_FW_HAND_P_BITS);
    uint32_t v = mrqp_fw_get_bits_be(data, off + 16u, MRQP_FW_HAND_V_BITS);
    uint32_t t = mrqp_fw_get_bits_be(data, off + 28u, MRQP_FW_HAND_T_BITS);
    if (p == 0x8000u || v == 0x800u || t == 0x800u) {
      return MRQP_FW_ERR_RANGE;
    }
    j[i].position =
        (float)mrqp_fw_dequantize_fixed(mrqp_fw_sign_extend(p, MRQP_FW_HAND_P_BITS), (double)s->position_lsb);
    j[i].velocity =
        (float)mrqp_fw_dequantize_fixed(mrqp_fw_sign_extend(v, MRQP_FW_HAND_V_BITS), (double)s->velocity_lsb);
    j[i].torque =
        (float)mrqp_fw_dequantize_fixed(mrqp_fw_sign_extend(t, MRQP_FW_HAND_T_BITS), (double)s->torque_lsb);
  }
  return MRQP_FW_OK;
}

static void put_crc(mrqp_fw_frame* out) {
  uint16_t crc = mrqp_fw_crc16(out->data, (size_t)out->len - MRQP_FW_HAND_FD_CRC_LEN);
  mrqp_fw_put_u16be(&out->data[out->len - MRQP_FW_HAND_FD_CRC_LEN], crc);
}

static int header_args_ok(unsigned board, unsigned mode, unsigned first, unsigned count) {
  return board <= MRQP_FW_HAND_BOARD_MAX && mode <= MRQP_FW_HAND_MODE_HOLD &&
         count <= MRQP_FW_HAND_FD_MAX_JOINTS && first + count <= MRQP_FW_HAND_MAX_JOINTS;
}

mrqp_fw_pack_flags mrqp_fw_hand_pack_cmd(const mrqp_fw_hand_scale* scale, unsigned board,
                                         const mrqp_fw_hand_cmd* cmd, mrqp_fw_frame* out,
                                         uint32_t* saturated_joints) {
  mrqp_fw_pack_flags flags;
  if (saturated_joints != NULL) {
    *saturated_joints = 0u;
  }
  if (out == NULL || cmd == NULL || !header_args_ok(board, cmd->mode, cmd->first_joint, cmd->count)) {
    return mrqp_fw_fail(out, MRQP_FW_PACK_ERR_ARG);
  }
  if (!mrqp_fw_hand_scale_valid(scale)) {
    return mrqp_fw_fail(out, MRQP_FW_PACK_ERR_CONFIG);
  }
  mrqp_fw_frame_init(out, MRQP_FW_HAND_FD_CMD_ID_BASE + board, mrqp_fw_hand_cmd_len(cmd->count), FD_FLAGS);
  mrqp_fw_put_u16be(&out->data[0], cmd->seq);
  out->data[2] = (uint8_t)((MRQP_FW_HAND_FD_VERSION << 4) | cmd->mode);
  out->data[3] = cmd->first_joint;
  out->data[4] = cmd->count;
  flags =
      put_joints(scale, cmd->joint, cmd->count, &out->data[MRQP_FW_HAND_FD_CMD_HEADER_LEN], saturated_joints);
  if (mrqp_fw_pack_failed(flags)) {
    if (saturated_joints != NULL) {
      *saturated_joints = 0u;
    }
    return mrqp_fw_fail(out, flags);
  }
  put_crc(out);
  return flags;
}

mrqp_fw_pack_flags mrqp_fw_hand_pack_fb(const mrqp_fw_hand_scale* scale, unsigned board,
                                        const mrqp_fw_hand_fb* fb, mrqp_fw_frame* out,
                                        uint32_t* saturated_joints) {
  mrqp_fw_pack_flags flags;
  if (saturated_joints != NULL) {
    *saturated_joints = 0u;
  }
  if (out == NULL || fb == NULL || !header_args_ok(board, fb->mode, fb->first_joint, fb->count) ||
      (fb->status & MRQP_FW_HAND_STATUS_RESERVED) != 0u) {
    return mrqp_fw_fail(out, MRQP_FW_PACK_ERR_ARG);
  }
  if (!mrqp_fw_hand_scale_valid(scale)) {
    return mrqp_fw_fail(out, MRQP_FW_PACK_ERR_CONFIG);
  }
  mrqp_fw_frame_init(out, MRQP_FW_HAND_FD_FB_ID_BASE + board, mrqp_fw_hand_fb_len(fb->count), FD_FLAGS);
  mrqp_fw_put_u16be(&out->data[0], fb->cmd_seq_echo);
  out->data[2] = fb->counter;
  out->data[3] = (uint8_t)((MRQP_FW_HAND_FD_VERSION << 4) | fb->mode);
  out->data[4] = fb->status;
  out->data[5] = fb->first_joint;
  out->data[6] = fb->count;
  flags =
      put_joints(scale, fb->joint, fb->count, &out->data[MRQP_FW_HAND_FD_FB_HEADER_LEN], saturated_joints);
  if (mrqp_fw_pack_failed(flags)) {
    if (saturated_joints != NULL) {
      *saturated_joints = 0u;
    }
    return mrqp_fw_fail(out, flags);
  }
  put_crc(out);
  return flags;
}

/*
 * Common checks: envelope, CRC, version (byte `ver_at`), count (byte `count_at`) and length,
 * zero padding. On success *count holds the joint count.
 */
static mrqp_fw_err check_frame(const mrqp_fw_hand_scale* scale, const mrqp_fw_frame* in, uint32_t id,
                               unsigned header, unsigned ver_at, unsigned count_at, unsigned* count) {
  unsigned n;
  unsigned i;
  unsigned used;
  if (in == NULL || count == NULL) {
    return MRQP_FW_ERR_NULL;
  }
  if ((in->flags & (MRQP_FW_FRAME_EXT | MRQP_FW_FRAME_RTR)) != 0u || (in->flags & MRQP_FW_FRAME_FD) == 0u) {
    return MRQP_FW_ERR_FORMAT;
  }
  if (in->id != id) {
    return MRQP_FW_ERR_ID;
  }
  if (in->len < header + MRQP_FW_HAND_FD_CRC_LEN || in->len > MRQP_FW_CAN_FD_MAX_LEN) {
    return MRQP_FW_ERR_LENGTH;
  }
  if (mrqp_fw_crc16(in->data, in->len) != 0u) { /* residue of data + appended CRC */
    return MRQP_FW_ERR_CRC;
  }
  if ((in->data[ver_at] >> 4) != MRQP_FW_HAND_FD_VERSION) {
    return MRQP_FW_ERR_VERSION;
  }
  n = in->data[count_at];
  if (n > MRQP_FW_HAND_FD_MAX_JOINTS || in->len != frame_len(header, n)) {
    return MRQP_FW_ERR_LENGTH;
  }
  if (!mrqp_fw_hand_scale_valid(scale)) {
    return MRQP_FW_ERR_CONFIG;
  }
  used = header + MRQP_FW_HAND_FD_JOINT_LEN * n;
  for (i = used; i + MRQP_FW_HAND_FD_CRC_LEN < in->len; ++i) {
    if (in->data[i] != 0u) {
      return MRQP_FW_ERR_FORMAT;
    }
  }
  *count = n;
  return MRQP_FW_OK;
}

mrqp_fw_err mrqp_fw_hand_unpack_cmd(const mrqp_fw_hand_scale* scale, const mrqp_fw_frame* in, unsigned board,
                                    mrqp_fw_hand_cmd* cmd) {
  unsigned n = 0u;
  unsigned mode;
  unsigned first;
  mrqp_fw_err e;
  if (cmd == NULL) {
    return MRQP_FW_ERR_NULL;
  }
  if (board > MRQP_FW_HAND_BOARD_MAX) {
    return MRQP_FW_ERR_ID;
  }
  e = check_frame(scale, in, MRQP_FW_HAND_FD_CMD_ID_BASE + board, MRQP_FW_HAND_FD_CMD_HEADER_LEN, 2u, 4u, &n);
  if (e != MRQP_FW_OK) {
    return e;
  }
  mode = in->data[2] & 0x0Fu;
  first = in->data[3];
  if (mode > MRQP_FW_HAND_MODE_HOLD || first + n > MRQP_FW_HAND_MAX_JOINTS) {
    return MRQP_FW_ERR_RANGE;
  }
  memset(cmd, 0, sizeof(*cmd));
  e = get_joints(scale, &in->data[MRQP_FW_HAND_FD_CMD_HEADER_LEN], n, cmd->joint);
  if (e != MRQP_FW_OK) {
    memset(cmd, 0, sizeof(*cmd));
    return e;
  }
  cmd->seq = mrqp_fw_get_u16be(&in->data[0]);
  cmd->mode = (uint8_t)mode;
  cmd->first_joint = (uint8_t)first;
  cmd->count = (uint8_t)n;
  return MRQP_FW_OK;
}

mrqp_fw_err mrqp_fw_hand_unpack_fb(const mrqp_fw_hand_scale* scale, const mrqp_fw_frame* in, unsigned board,
                                   mrqp_fw_hand_fb* fb) {
  unsigned n = 0u;
  unsigned mode;
  unsigned first;
  mrqp_fw_err e;
  if (fb == NULL) {
    return MRQP_FW_ERR_NULL;
  }
  if (board > MRQP_FW_HAND_BOARD_MAX) {
    return MRQP_FW_ERR_ID;
  }
  e = check_frame(scale, in, MRQP_FW_HAND_FD_FB_ID_BASE + board, MRQP_FW_HAND_FD_FB_HEADER_LEN, 3u, 6u, &n);
  if (e != MRQP_FW_OK) {
    return e;
  }
  if ((in->data[4] & MRQP_FW_HAND_STATUS_RESERVED) != 0u) {
    return MRQP_FW_ERR_FORMAT;
  }
  mode = in->data[3] & 0x0Fu;
  first = in->data[5];
  if (mode > MRQP_FW_HAND_MODE_HOLD || first + n > MRQP_FW_HAND_MAX_JOINTS) {
    return MRQP_FW_ERR_RANGE;
  }
  memset(fb, 0, sizeof(*fb));
  e = get_joints(scale, &in->data[MRQP_FW_HAND_FD_FB_HEADER_LEN], n, fb->joint);
  if (e != MRQP_FW_OK) {
    memset(fb, 0, sizeof(*fb));
    return e;
  }
  fb->cmd_seq_echo = mrqp_fw_get_u16be(&in->data[0]);
  fb->counter = in->data[2];
  fb->mode = (uint8_t)mode;
  fb->status = in->data[4];
  fb->first_joint = (uint8_t)first;
  fb->count = (uint8_t)n;
  return MRQP_FW_OK;
}
