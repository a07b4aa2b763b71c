/*
 * mrqp firmware interface -- hand drives: the compact "MIT mode" impedance frames (classic CAN).
 *
 * Command, master -> motor, CAN ID = motor id (1..127), DLC 8, big-endian bit stream:
 *   p 16 | v 12 | kp 12 | kd 12 | t 12                              (64 bits)
 *   byte 0 p[15:8]   byte 1 p[7:0]   byte 2 v[11:4]   byte 3 v[3:0] kp[11:8]
 *   byte 4 kp[7:0]   byte 5 kd[11:4] byte 6 kd[3:0] t[11:8]         byte 7 t[7:0]
 * Motor torque = kp (p_set - p) + kd (v_set - v) + t_ff.
 *
 * Reply, motor -> master, CAN ID MRQP_FW_MIT_MASTER_ID (0x000), DLC 6:
 *   byte 0 motor id | p 16 | v 12 | t 12   (bytes 1..5 big-endian bit stream)
 *
 * Special commands, DLC 8, CAN ID = motor id:
 *   FF FF FF FF FF FF FF FC  enter motor mode (enable)
 *   FF FF FF FF FF FF FF FD  exit motor mode (disable)
 *   FF FF FF FF FF FF FF FE  set the current position as zero
 *
 * Each field maps [min, max] linearly onto its unsigned codes (mrqp_fw_quantize_linear); the
 * ranges are configuration shared by both ends. An impedance command whose bytes would spell a
 * special command (p, v, kp, kd all at their maximum and t code 0xFFC..0xFFE) is never emitted:
 * the torque code is lowered to 0xFFB and MRQP_FW_MIT_ADJ_SPECIAL is reported.
 * The hand bus is not a CANopen bus (ID 0x000 is the master's reply address here).
 */
#ifndef MRQP_FIRMWARE_IF_MIT_FRAME_H
#define MRQP_FIRMWARE_IF_MIT_FRAME_H

#include <stdint.h>

#include "mrqp/firmware_if/frame.h"
#include "mrqp/firmware_if/status.h"

#ifdef __cplusplus
extern "C" {
#endif

#define MRQP_FW_MIT_CMD_LEN 8u
#define MRQP_FW_MIT_REPLY_LEN 6u
#define MRQP_FW_MIT_MASTER_ID 0x000u
#define MRQP_FW_MIT_MOTOR_ID_MIN 1u
#define MRQP_FW_MIT_MOTOR_ID_MAX 127u

#define MRQP_FW_MIT_P_BITS 16u
#define MRQP_FW_MIT_V_BITS 12u
#define MRQP_FW_MIT_KP_BITS 12u
#define MRQP_FW_MIT_KD_BITS 12u
#define MRQP_FW_MIT_T_BITS 12u

/* Saturation / adjustment bits of the MIT pack functions. */
#define MRQP_FW_MIT_SAT_P 0x0001u
#define MRQP_FW_MIT_SAT_V 0x0002u
#define MRQP_FW_MIT_SAT_KP 0x0004u
#define MRQP_FW_MIT_SAT_KD 0x0008u
#define MRQP_FW_MIT_SAT_T 0x0010u
/** The torque code was lowered so that the command does not spell a special command. */
#define MRQP_FW_MIT_ADJ_SPECIAL 0x0020u

/** Physical range of each field (SI: rad, rad/s, N m/rad, N m s/rad, N m). min < max, finite. */
typedef struct mrqp_fw_mit_ranges {
  float p_min, p_max;
  float v_min, v_max;
  float kp_min, kp_max;
  float kd_min, kd_max;
  float t_min, t_max;
} mrqp_fw_mit_ranges;

/** Typical defaults: p +/-12.5 rad, v +/-65 rad/s, kp 0..500, kd 0..5, t +/-18 N m. */
#define MRQP_FW_MIT_RANGES_DEFAULT_INIT \
  { -12.5f, 12.5f, -65.0f, 65.0f, 0.0f, 500.0f, 0.0f, 5.0f, -18.0f, 18.0f }

/** Non-zero if every min < max and all are finite. */
int mrqp_fw_mit_ranges_valid(const mrqp_fw_mit_ranges* ranges);

typedef struct mrqp_fw_mit_cmd {
  float p;  /**< position setpoint, rad */
  float v;  /**< velocity setpoint, rad/s */
  float kp; /**< stiffness, N m / rad */
  float kd; /**< damping, N m s / rad */
  float t;  /**< feed-forward torque, N m */
} mrqp_fw_mit_cmd;

typedef struct mrqp_fw_mit_reply {
  uint8_t motor_id;
  float p; /**< rad */
  float v; /**< rad/s */
  float t; /**< N m */
} mrqp_fw_mit_reply;

/** What a frame sent to a motor is. */
typedef enum mrqp_fw_mit_kind {
  MRQP_FW_MIT_KIND_COMMAND = 0, /**< an impedance command */
  MRQP_FW_MIT_KIND_ENABLE,
  MRQP_FW_MIT_KIND_DISABLE,
  MRQP_FW_MIT_KIND_ZERO,
  MRQP_FW_MIT_KIND_INVALID /**< not a valid motor frame (NULL, format, id, length) */
} mrqp_fw_mit_kind;

/**
 * Command frame for `motor_id`. Saturation bits MRQP_FW_MIT_SAT_*, MRQP_FW_MIT_ADJ_SPECIAL.
 * NaN in any field: ERR_NAN (no frame). Invalid ranges: ERR_CONFIG. Invalid id / NULL: ERR_ARG.
 */
mrqp_fw_pack_flags mrqp_fw_mit_pack_cmd(const mrqp_fw_mit_ranges* ranges, unsigned motor_id,
                                        const mrqp_fw_mit_cmd* cmd, mrqp_fw_frame* out);
/** Special command (kind ENABLE, DISABLE or ZERO) for `motor_id`; ERR_ARG otherwise. */
mrqp_fw_pack_flags mrqp_fw_mit_pack_special(unsigned motor_id, mrqp_fw_mit_kind kind, mrqp_fw_frame* out);
/** Motor side: what a received frame is (envelope: classic, id 1..127, DLC 8). */
mrqp_fw_mit_kind mrqp_fw_mit_classify(const mrqp_fw_frame* in);
/**
 * Motor side: decodes an impedance command. ERR_COMMAND for a special command, ERR_ID for an id
 * outside 1..127, ERR_CONFIG for invalid ranges. *motor_id (optional, may be NULL) gets the id.
 */
mrqp_fw_err mrqp_fw_mit_unpack_cmd(const mrqp_fw_mit_ranges* ranges, const mrqp_fw_frame* in,
                                   uint8_t* motor_id, mrqp_fw_mit_cmd* cmd);

/** Motor side: reply frame. Saturation bits MRQP_FW_MIT_SAT_P, _V, _T; NaN: ERR_NAN. */
mrqp_fw_pack_flags mrqp_fw_mit_pack_reply(const mrqp_fw_mit_ranges* ranges, const mrqp_fw_mit_reply* reply,
                                          mrqp_fw_frame* out);
/** Master: decodes a reply (classic, ID 0x000, DLC 6, motor id 1..127 else ERR_RANGE). */
mrqp_fw_err mrqp_fw_mit_unpack_reply(const mrqp_fw_mit_ranges* ranges, const mrqp_fw_frame* in,
                                     mrqp_fw_mit_reply* reply);

#ifdef __cplusplus
}
#endif

#endif /* MRQP_FIRMWARE_IF_MIT_FRAME_H */
