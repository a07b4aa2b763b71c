/*
 * mrqp firmware interface -- hand controller board: CAN FD setpoint and feedback frames.
 *
 * One hand controller board drives the joints of one hand. Frames are CAN FD with bit-rate switch,
 * big-endian, fields packed MSB first. A frame carries `count` consecutive joints starting at
 * `first`, so a hand with more than MRQP_FW_HAND_FD_MAX_JOINTS joints uses several frames per
 * cycle (same sequence number in each).
 *
 * Command, host -> board, ID 0x120 + board (board 0..15):
 *   byte 0-1   sequence u16 (incremented every cycle by the host)
 *   byte 2     version (high nibble, = 1) | mode (low nibble)
 *   byte 3     first joint index
 *   byte 4     joint count n (0..11)
 *   byte 5..   n joint records, 5 bytes each: position i16 | velocity i12 | torque i12
 *   ...        zero padding up to the CAN FD length
 *   last 2     CRC-16/CCITT-FALSE, MSB first, over every byte before it (padding included)
 *   length     mrqp_fw_fd_len_round_up(5 + 5 n + 2)      (n = 11: 62 -> 64 bytes)
 *
 * Feedback, board -> host, ID 0x140 + board:
 *   byte 0-1   sequence of the last valid command applied (echo) u16
 *   byte 2     feedback counter u8 (incremented by the board every feedback frame)
 *   byte 3     version | mode (the mode the board is in)
 *   byte 4     status (MRQP_FW_HAND_STATUS_*; bits 6-7 reserved, 0)
 *   byte 5     first joint index
 *   byte 6     joint count n (0..11)
 *   byte 7..   n joint records (measured position, velocity, torque), 5 bytes each
 *   last 2     CRC-16/CCITT-FALSE as above; length mrqp_fw_fd_len_round_up(7 + 5 n + 2) (n = 11: 64)
 *
 * Joint record fields are signed fixed point (two's complement) with a configurable LSB:
 * code = round(x / lsb) within +/-(2^(bits-1) - 1); the most negative code (0x8000 / 0x800) is
 * reserved and rejected by unpack. Zero is exact, unlike a [min, max] map.
 * Joints per frame: (64 - 5 - 2) / 5 = 11.4 -> 11 (command), (64 - 7 - 2) / 5 = 11 (feedback).
 */
#ifndef MRQP_FIRMWARE_IF_HAND_FD_FRAME_H
#define MRQP_FIRMWARE_IF_HAND_FD_FRAME_H

#include <stdint.h>

#include "mrqp/firmware_if/frame.h"
#include "mrqp/firmware_if/status.h"

#ifdef __cplusplus
extern "C" {
#endif

#define MRQP_FW_HAND_FD_VERSION 1u
#define MRQP_FW_HAND_FD_CMD_ID_BASE 0x120u
#define MRQP_FW_HAND_FD_FB_ID_BASE 0x140u
#define MRQP_FW_HAND_BOARD_MAX 15u
#define MRQP_FW_HAND_FD_CMD_HEADER_LEN 5u
#define MRQP_FW_HAND_FD_FB_HEADER_LEN 7u
#define MRQP_FW_HAND_FD_JOINT_LEN 5u
#define MRQP_FW_HAND_FD_CRC_LEN 2u
/** Joints per frame (both directions). */
#define MRQP_FW_HAND_FD_MAX_JOINTS 11u
/** Joint indices of one hand: first + count <= 32. */
#define MRQP_FW_HAND_MAX_JOINTS 32u

#define MRQP_FW_HAND_P_BITS 16u
#define MRQP_FW_HAND_V_BITS 12u
#define MRQP_FW_HAND_T_BITS 12u

typedef enum mrqp_fw_hand_mode {
  MRQP_FW_HAND_MODE_DISABLED = 0, /**< power stage off; setpoints ignored */
  MRQP_FW_HAND_MODE_POSITION = 1, /**< board PD on position/velocity + torque feed-forward */
  MRQP_FW_HAND_MODE_TORQUE = 2,   /**< torque only; position/velocity ignored */
  MRQP_FW_HAND_MODE_HOLD = 3      /**< hold the current position; setpoints ignored */
} mrqp_fw_hand_mode;

/* Feedback status bits. */
#define MRQP_FW_HAND_STATUS_ENABLED 0x01u
#define MRQP_FW_HAND_STATUS_FAULT 0x02u
#define MRQP_FW_HAND_STATUS_OVER_TEMPERATURE 0x04u
#define MRQP_FW_HAND_STATUS_COMMAND_TIMEOUT 0x08u /**< no valid command in time: board went to HOLD */
#define MRQP_FW_HAND_STATUS_CRC_ERROR_SEEN 0x10u  /**< a command was dropped for a bad CRC */
#define MRQP_FW_HAND_STATUS_LIMIT 0x20u           /**< a joint is at a position or torque limit */
#define MRQP_FW_HAND_STATUS_RESERVED 0xC0u

/* Saturation bits of the hand pack functions (any joint of the frame). */
#define MRQP_FW_HAND_SAT_POSITION 0x0001u
#define MRQP_FW_HAND_SAT_VELOCITY 0x0002u
#define MRQP_FW_HAND_SAT_TORQUE 0x0004u

/** LSB of each joint field (SI). Each finite and > 0. */
typedef struct mrqp_fw_hand_scale {
  float position_lsb; /**< rad */
  float velocity_lsb; /**< rad/s */
  float torque_lsb;   /**< N m */
} mrqp_fw_hand_scale;

/** 1e-4 rad (+/-3.2767 rad), 0.02 rad/s (+/-40.94 rad/s), 1 mN m (+/-2.047 N m). */
#define MRQP_FW_HAND_SCALE_DEFAULT_INIT \
  { 1.0e-4f, 0.02f, 0.001f }

int mrqp_fw_hand_scale_valid(const mrqp_fw_hand_scale* scale);

typedef struct mrqp_fw_hand_joint {
  float position; /**< rad */
  float velocity; /**< rad/s */
  float torque;   /**< N m */
} mrqp_fw_hand_joint;

typedef struct mrqp_fw_hand_cmd {
  uint16_t seq;
  uint8_t mode; /**< mrqp_fw_hand_mode */
  uint8_t first_joint;
  uint8_t count; /**< 0..MRQP_FW_HAND_FD_MAX_JOINTS */
  mrqp_fw_hand_joint joint[MRQP_FW_HAND_FD_MAX_JOINTS];
} mrqp_fw_hand_cmd;

typedef struct mrqp_fw_hand_fb {
  uint16_t cmd_seq_echo;
  uint8_t counter;
  uint8_t mode;   /**< mrqp_fw_hand_mode */
  uint8_t status; /**< MRQP_FW_HAND_STATUS_* */
  uint8_t first_joint;
  uint8_t count;
  mrqp_fw_hand_joint joint[MRQP_FW_HAND_FD_MAX_JOINTS];
} mrqp_fw_hand_fb;

/** Frame length for n joints (0 if n > 11). */
uint8_t mrqp_fw_hand_cmd_len(unsigned n);
uint8_t mrqp_fw_hand_fb_len(unsigned n);
/** Frames per cycle for a hand of `joints` joints (ceil(joints / 11)). */
unsigned mrqp_fw_hand_frames_needed(unsigned joints);

/**
 * Command frame for `board`. Returns MRQP_FW_HAND_SAT_* bits; `saturated_joints` (optional)
 * gets bit i set when joint[i] had a saturated field. NaN anywhere in joint[0..count): ERR_NAN.
 * Invalid scale: ERR_CONFIG. Board > 15, mode > 3, count > 11, first + count > 32, NULL: ERR_ARG.
 */
mrqp_fw_pack_flags mrqp_fw_hand_pack_cmd(const mrqp_fw_hand_scale* scale, unsigned board,
                                         const mrqp_fw_hand_cmd* cmd, mrqp_fw_frame* out,
                                         uint32_t* saturated_joints);
/**
 * Board side. Checks, in order: NULL, FD frame (ERR_FORMAT), ID (ERR_ID), length >= header
 * (ERR_LENGTH), CRC (ERR_CRC), version (ERR_VERSION), count <= 11 and length equal to
 * mrqp_fw_hand_cmd_len(count) (ERR_LENGTH), mode, first + count, reserved codes (ERR_RANGE),
 * zero padding (ERR_FORMAT). Joints beyond count are zeroed.
 */
mrqp_fw_err mrqp_fw_hand_unpack_cmd(const mrqp_fw_hand_scale* scale, const mrqp_fw_frame* in, unsigned board,
                                    mrqp_fw_hand_cmd* cmd);

/** Board side: feedback frame. Same rules as the command; status reserved bits: ERR_ARG. */
mrqp_fw_pack_flags mrqp_fw_hand_pack_fb(const mrqp_fw_hand_scale* scale, unsigned board,
                                        const mrqp_fw_hand_fb* fb, mrqp_fw_frame* out,
                                        uint32_t* saturated_joints);
/** Host side: as mrqp_fw_hand_unpack_cmd; status reserved bits set: ERR_FORMAT. */
mrqp_fw_err mrqp_fw_hand_unpack_fb(const mrqp_fw_hand_scale* scale, const mrqp_fw_frame* in, unsigned board,
                                   mrqp_fw_hand_fb* fb);

#ifdef __cplusplus
}
#endif

#endif /* MRQP_FIRMWARE_IF_HAND_FD_FRAME_H */
