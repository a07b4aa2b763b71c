/*
 * mrqp firmware interface -- the CAN frame as seen by this contract, and CAN FD lengths.
 *
 * The contract only uses 11-bit identifiers and data frames; a frame flagged extended or remote is
 * rejected by every unpack function. Drivers copy their bus frame (SocketCAN can_frame/canfd_frame,
 * an MCU's mailbox) into this struct; it carries no pointer and no state.
 */
#ifndef MRQP_FIRMWARE_IF_FRAME_H
#define MRQP_FIRMWARE_IF_FRAME_H

#include <stdint.h>

#include "mrqp/firmware_if/status.h"

#ifdef __cplusplus
extern "C" {
#endif

#define MRQP_FW_CAN_CLASSIC_MAX_LEN 8u
#define MRQP_FW_CAN_FD_MAX_LEN 64u
/** Largest 11-bit identifier. */
#define MRQP_FW_CAN_SFF_MAX 0x7FFu
/** Identifier of a cleared frame (a failed pack): not a valid 11-bit identifier. */
#define MRQP_FW_ID_INVALID 0xFFFFFFFFu

#define MRQP_FW_FRAME_FD 0x01u  /**< CAN FD frame (FDF set) */
#define MRQP_FW_FRAME_BRS 0x02u /**< CAN FD bit-rate switch */
#define MRQP_FW_FRAME_EXT 0x04u /**< 29-bit identifier: never used by this contract */
#define MRQP_FW_FRAME_RTR 0x08u /**< remote request: never used by this contract */

typedef struct mrqp_fw_frame {
  uint32_t id;      /**< 11-bit identifier (or MRQP_FW_ID_INVALID) */
  uint8_t len;      /**< data length in bytes: 0..8 classic, a valid FD length for FD frames */
  uint8_t flags;    /**< MRQP_FW_FRAME_* */
  uint8_t data[64]; /**< payload; bytes beyond len are zero in frames produced by this library */
} mrqp_fw_frame;

/** Clears a frame: id MRQP_FW_ID_INVALID, len 0, flags 0, data zero. NULL is ignored. */
void mrqp_fw_frame_clear(mrqp_fw_frame* frame);

/** Sets id, len, flags and zeroes the data. */
void mrqp_fw_frame_init(mrqp_fw_frame* frame, uint32_t id, uint8_t len, uint8_t flags);

/**
 * Checks the envelope of a received frame: not NULL (ERR_NULL), neither extended nor remote and
 * FD flag equal to `fd` (ERR_FORMAT), identifier equal to `id` (ERR_ID), length equal to `len`
 * (ERR_LENGTH).
 */
mrqp_fw_err mrqp_fw_frame_expect(const mrqp_fw_frame* frame, uint32_t id, unsigned len, int fd);

/** Non-zero if n is a length a CAN FD frame can carry (0..8, 12, 16, 20, 24, 32, 48, 64). */
int mrqp_fw_fd_len_valid(unsigned n);
/** Smallest valid CAN FD length >= n, or 0 if n > 64. */
uint8_t mrqp_fw_fd_len_round_up(unsigned n);
/** CAN FD DLC code (0..15) -> length in bytes; 0 for a DLC > 15. */
uint8_t mrqp_fw_fd_dlc_to_len(uint8_t dlc);
/** Valid CAN FD length -> DLC code; 0xFF for an invalid length. */
uint8_t mrqp_fw_fd_len_to_dlc(uint8_t len);

#ifdef __cplusplus
}
#endif

#endif /* MRQP_FIRMWARE_IF_FRAME_H */
