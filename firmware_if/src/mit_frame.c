/* mrqp firmware interface -- MIT-mode impedance frames. */
#include "mrqp/firmware_if/mit_frame.h"

#include "internal.h"
#include "mrqp/firmware_if/bytes.h"
#include "mrqp/firmware_if/saturate.h"

/* Bit offsets in the command / reply bit streams. */
#define CMD_P_OFF 0u
#define CMD_V_OFF 16u
#define CMD_KP_OFF 28u
#define CMD_KD_OFF 40u
#define CMD_T_OFF 52u
#define REPLY_P_OFF 8u
#define REPLY_V_OFF 24u
#define REPLY_T_OFF 36u

#define SPECIAL_ENABLE 0xFCu
#define SPECIAL_DISABLE 0xFDu
#define SPECIAL_ZERO 0xFEu

static int range_ok(float lo, float hi) {
  return mrqp_fw_isfinite_f(lo) && mrqp_fw_isfinite_f(hi) && lo < hi;
}

int mrqp_fw_mit_ranges_valid(const mrqp_fw_mit_ranges* r) {
  return r != NULL && range_ok(r->p_min, r->p_max) && range_ok(r->v_min, r->v_max) &&
         range_ok(r->kp_min, r->kp_max) && range_ok(r->kd_min, r->kd_max) && range_ok(r->t_min, r->t_max);
}

static int motor_id_ok(unsigned id) {
  return id >= MRQP_FW_MIT_MOTOR_ID_MIN && id <= MRQP_FW_MIT_MOTOR_ID_MAX;
}

/* Quantises one field; sets `sat_bit` in *flags when saturated. Returns 0 on NaN. */
static int field(float x, float lo, float hi, unsigned bits, uint32_t* code, mrqp_fw_pack_flags sat_bit,
                 mrqp_fw_pack_flags* flags) {
  mrqp_fw_conv r = mrqp_fw_quantize_linear((double)x, (double)lo, (double)hi, bits, code);
  if (r == MRQP_FW_CONV_NAN || r == MRQP_FW_CONV_BAD_SCALE) {
    return 0;
  }
  if (r != MRQP_FW_CONV_OK) {
    *flags |= sat_bit;
  }
  return 1;
}

static float unfield(uint32_t code, float lo, float hi, unsigned bits) {
  return (float)mrqp_fw_dequantize_linear(code, (double)lo, (double)hi, bits);
}

mrqp_fw_pack_flags mrqp_fw_mit_pack_cmd(const mrqp_fw_mit_ranges* r, unsigned motor_id,
                                        const mrqp_fw_mit_cmd* cmd, mrqp_fw_frame* out) {
  mrqp_fw_pack_flags flags = MRQP_FW_PACK_OK;
  uint32_t p = 0u, v = 0u, kp = 0u, kd = 0u, t = 0u;
  if (out == NULL || cmd == NULL || !motor_id_ok(motor_id)) {
    return mrqp_fw_fail(out, MRQP_FW_PACK_ERR_ARG);
  }
  if (!mrqp_fw_mit_ranges_valid(r)) {
    return mrqp_fw_fail(out, MRQP_FW_PACK_ERR_CONFIG);
  }
  if (!field(cmd->p, r->p_min, r->p_max, MRQP_FW_MIT_P_BITS, &p, MRQP_FW_MIT_SAT_P, &flags) ||
      !field(cmd->v, r->v_min, r->v_max, MRQP_FW_MIT_V_BITS, &v, MRQP_FW_MIT_SAT_V, &flags) ||
      !field(cmd->kp, r->kp_min, r->kp_max, MRQP_FW_MIT_KP_BITS, &kp, MRQP_FW_MIT_SAT_KP, &flags) ||
      !field(cmd->kd, r->kd_min, r->kd_max, MRQP_FW_MIT_KD_BITS, &kd, MRQP_FW_MIT_SAT_KD, &flags) ||
      !field(cmd->t, r->t_min, r->t_max, MRQP_FW_MIT_T_BITS, &t, MRQP_FW_MIT_SAT_T, &flags)) {
    return mrqp_fw_fail(out, MRQP_FW_PACK_ERR_NAN);
  }
  /* Never spell FF FF FF FF FF FF FF FC..FE with an impedance command. */
  if (p == 0xFFFFu && v == 0xFFFu && kp == 0xFFFu && kd == 0xFFFu && t >= 0xFFCu && t <= 0xFFEu) {
    t = 0xFFBu;
    flags |= MRQP_FW_MIT_ADJ_SPECIAL;
  }
  mrqp_fw_frame_init(out, (uint32_t)motor_id, (uint8_t)MRQP_FW_MIT_CMD_LEN, 0u);
  mrqp_fw_put_bits_be(out->data, CMD_P_OFF, MRQP_FW_MIT_P_BITS, p);
  mrqp_fw_put_bits_be(out->data, CMD_V_OFF, MRQP_FW_MIT_V_BITS, v);
  mrqp_fw_put_bits_be(out->data, CMD_KP_OFF, MRQP_FW_MIT_KP_BITS, kp);
  mrqp_fw_put_bits_be(out->data, CMD_KD_OFF, MRQP_FW_MIT_KD_BITS, kd);
  mrqp_fw_put_bits_be(out->data, CMD_T_OFF, MRQP_FW_MIT_T_BITS, t);
  return flags;
}

mrqp_fw_pack_flags mrqp_fw_mit_pack_special(unsigned motor_id, mrqp_fw_mit_kind kind, mrqp_fw_frame* out) {
  uint8_t last;
  unsigned i;
  switch (kind) {
    case MRQP_FW_MIT_KIND_ENABLE:
      last = SPECIAL_ENABLE;
      break;
    case MRQP_FW_MIT_KIND_DISABLE:
      last = SPECIAL_DISABLE;
      break;
    case MRQP_FW_MIT_KIND_ZERO:
      last = SPECIAL_ZERO;
      break;
    case MRQP_FW_MIT_KIND_COMMAND:
    case MRQP_FW_MIT_KIND_INVALID:
    default:
      return mrqp_fw_fail(out, MRQP_FW_PACK_ERR_ARG);
  }
  if (out == NULL || !motor_id_ok(motor_id)) {
    return mrqp_fw_fail(out, MRQP_FW_PACK_ERR_ARG);
  }
  mrqp_fw_frame_init(out, (uint32_t)motor_id, (uint8_t)MRQP_FW_MIT_CMD_LEN, 0u);
  for (i = 0u; i < 7u; ++i) {
    out->data[i] = 0xFFu;
  }
  out->data[7] = last;
  return MRQP_FW_PACK_OK;
}

mrqp_fw_mit_kind mrqp_fw_mit_classify(const mrqp_fw_frame* in) {
  unsigned i;
  if (mrqp_fw_classic_envelope(in) != MRQP_FW_OK || !motor_id_ok(in->id) || in->len != MRQP_FW_MIT_CMD_LEN) {
    return MRQP_FW_MIT_KIND_INVALID;
  }
  for (i = 0u; i < 7u; ++i) {
    if (in->data[i] != 0xFFu) {
      return MRQP_FW_MIT_KIND_COMMAND;
    }
  }
  switch (in->data[7]) {
    case SPECIAL_ENABLE:
      return MRQP_FW_MIT_KIND_ENABLE;
    case SPECIAL_DISABLE:
      return MRQP_FW_MIT_KIND_DISABLE;
    case SPECIAL_ZERO:
      return MRQP_FW_MIT_KIND_ZERO;
    default:
      break;
  }
  return MRQP_FW_MIT_KIND_COMMAND;
}

mrqp_fw_err mrqp_fw_mit_unpack_cmd(const mrqp_fw_mit_ranges* r, const mrqp_fw_frame* in, uint8_t* motor_id,
                                   mrqp_fw_mit_cmd* cmd) {
  mrqp_fw_err e = mrqp_fw_classic_envelope(in);
  if (e != MRQP_FW_OK) {
    return e;
  }
  if (cmd == NULL) {
    return MRQP_FW_ERR_NULL;
  }
  if (!motor_id_ok(in->id)) {
    return MRQP_FW_ERR_ID;
  }
  if (in->len != MRQP_FW_MIT_CMD_LEN) {
    return MRQP_FW_ERR_LENGTH;
  }
  if (mrqp_fw_mit_classify(in) != MRQP_FW_MIT_KIND_COMMAND) {
    return MRQP_FW_ERR_COMMAND;
  }
  if (!mrqp_fw_mit_ranges_valid(r)) {
    return MRQP_FW_ERR_CONFIG;
  }
  cmd->p = unfield(mrqp_fw_get_bits_be(in->data, CMD_P_OFF, MRQP_FW_MIT_P_BITS), r->p_min, r->p_max,
                   MRQP_FW_MIT_P_BITS);
  cmd->v = unfield(mrqp_fw_get_bits_be(in->data, CMD_V_OFF, MRQP_FW_MIT_V_BITS), r->v_min, r->v_max,
                   MRQP_FW_MIT_V_BITS);
  cmd->kp = unfield(mrqp_fw_get_bits_be(in->data, CMD_KP_OFF, MRQP_FW_MIT_KP_BITS), r->kp_min, r->kp_max,
                    MRQP_FW_MIT_KP_BITS);
  cmd->kd = unfield(mrqp_fw_get_bits_be(in->data, CMD_KD_OFF, MRQP_FW_MIT_KD_BITS), r->kd_min, r->kd_max,
                    MRQP_FW_MIT_KD_BITS);
  cmd->t = unfield(mrqp_fw_get_bits_be(in->data, CMD_T_OFF, MRQP_FW_MIT_T_BITS), r->t_min, r->t_max,
                   MRQP_FW_MIT_T_BITS);
  if (motor_id != NULL) {
    *motor_id = (uint8_t)in->id;
  }
  return MRQP_FW_OK;
}

mrqp_fw_pack_flags mrqp_fw_mit_pack_reply(const mrqp_fw_mit_ranges* r, const mrqp_fw_mit_reply* reply,
                                          mrqp_fw_frame* out) {
  mrqp_fw_pack_flags flags = MRQP_FW_PACK_OK;
  uint32_t p = 0u, v = 0u, t = 0u;
  if (out == NULL || reply == NULL || !motor_id_ok(reply->motor_id)) {
    return mrqp_fw_fail(out, MRQP_FW_PACK_ERR_ARG);
  }
  if (!mrqp_fw_mit_ranges_valid(r)) {
    return mrqp_fw_fail(out, MRQP_FW_PACK_ERR_CONFIG);
  }
  if (!field(reply->p, r->p_min, r->p_max, MRQP_FW_MIT_P_BITS, &p, MRQP_FW_MIT_SAT_P, &flags) ||
      !field(reply->v, r->v_min, r->v_max, MRQP_FW_MIT_V_BITS, &v, MRQP_FW_MIT_SAT_V, &flags) ||
      !field(reply->t, r->t_min, r->t_max, MRQP_FW_MIT_T_BITS, &t, MRQP_FW_MIT_SAT_T, &flags)) {
    return mrqp_fw_fail(out, MRQP_FW_PACK_ERR_NAN);
  }
  mrqp_fw_frame_init(out, MRQP_FW_MIT_MASTER_ID, (uint8_t)MRQP_FW_MIT_REPLY_LEN, 0u);
  out->data[0] = reply->motor_id;
  mrqp_fw_put_bits_be(out->data, REPLY_P_OFF, MRQP_FW_MIT_P_BITS, p);
  mrqp_fw_put_bits_be(out->data, REPLY_V_OFF, MRQP_FW_MIT_V_BITS, v);
  mrqp_fw_put_bits_be(out->data, REPLY_T_OFF, MRQP_FW_MIT_T_BITS, t);
  return flags;
}

mrqp_fw_err mrqp_fw_mit_unpack_reply(const mrqp_fw_mit_ranges* r, const mrqp_fw_frame* in,
                                     mrqp_fw_mit_reply* reply) {
  mrqp_fw_err e = mrqp_fw_frame_expect(in, MRQP_FW_MIT_MASTER_ID, MRQP_FW_MIT_REPLY_LEN, 0);
  if (e != MRQP_FW_OK) {
    return e;
  }
  if (reply == NULL) {
    return MRQP_FW_ERR_NULL;
  }
  if (!motor_id_ok(in->data[0])) {
    return MRQP_FW_ERR_RANGE;
  }
  if (!mrqp_fw_mit_ranges_valid(r)) {
    return MRQP_FW_ERR_CONFIG;
  }
  reply->motor_id = in->data[0];
  reply->p = unfield(mrqp_fw_get_bits_be(in->data, REPLY_P_OFF, MRQP_FW_MIT_P_BITS), r->p_min, r->p_max,
                     MRQP_FW_MIT_P_BITS);
  reply->v = unfield(mrqp_fw_get_bits_be(in->data, REPLY_V_OFF, MRQP_FW_MIT_V_BITS), r->v_min, r->v_max,
                     MRQP_FW_MIT_V_BITS);
  reply->t = unfield(mrqp_fw_get_bits_be(in->data, REPLY_T_OFF, MRQP_FW_MIT_T_BITS), r->t_min, r->t_max,
                     MRQP_FW_MIT_T_BITS);
  return MRQP_FW_OK;
}
