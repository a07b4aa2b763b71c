/*
 * mrqp firmware interface -- result codes shared by every message.
 *
 * Plain C99, no dependencies beyond <stdint.h>. Included by the drive firmware and by the host.
 *
 * Conventions used by every header of this folder:
 *  - every pack function returns a mrqp_fw_pack_flags bitmask: the low 16 bits say which fields
 *    were saturated (clamped to their wire range; the bit numbers are defined per message), the
 *    high 8 bits are errors. If an error bit is set the output frame is NOT a valid message: it is
 *    cleared to id MRQP_FW_ID_INVALID, length 0 (a NaN input is never encoded as a value).
 *  - every unpack function validates identifier, format, length, CRC and field ranges and returns
 *    a mrqp_fw_err code; the output is only meaningful when it returns MRQP_FW_OK.
 *  - values are rounded to the nearest code (ties away from zero). A value is "saturated" when
 *    that nearest code lies outside the field's range (it is more than half a quantisation step
 *    beyond an end, or infinite); it is then clamped to that end and flagged. Hence: an unflagged
 *    value always decodes to within half a step of the input.
 */
#ifndef MRQP_FIRMWARE_IF_STATUS_H
#define MRQP_FIRMWARE_IF_STATUS_H

#include <stdint.h>

#ifdef __cplusplus
extern "C" {
#endif

/** Version of the wire contract described by these headers (see docs/protocol.md). */
#define MRQP_FW_PROTOCOL_VERSION 1u

/** Error codes returned by unpack / validation functions. */
typedef enum mrqp_fw_err {
  MRQP_FW_OK = 0,
  MRQP_FW_ERR_NULL = 1,   /**< a required pointer argument is NULL */
  MRQP_FW_ERR_ID = 2,     /**< the CAN identifier does not belong to this message / node */
  MRQP_FW_ERR_FORMAT = 3, /**< classic/FD/extended/remote mismatch, non-zero padding or reserved bits */
  MRQP_FW_ERR_LENGTH = 4, /**< wrong data length */
  MRQP_FW_ERR_CRC = 5,    /**< application CRC mismatch */
  MRQP_FW_ERR_RANGE = 6,  /**< a field holds a value outside its allowed range (reserved code, count, node) */
  MRQP_FW_ERR_COMMAND = 7, /**< unknown or unsupported command specifier / command / state code */
  MRQP_FW_ERR_VERSION = 8, /**< unsupported protocol version in the frame */
  MRQP_FW_ERR_CONFIG = 9,  /**< invalid scaling or range configuration passed by the caller */
  MRQP_FW_ERR_TORN = 10    /**< two frames of one sample carry different sequence/status: torn pair */
} mrqp_fw_err;

/** A static, human-readable name of an error code (never NULL). */
const char* mrqp_fw_err_str(mrqp_fw_err err);

/** Result of a pack function: saturation bits (low 16) and error bits (high 8). */
typedef uint32_t mrqp_fw_pack_flags;

#define MRQP_FW_PACK_OK 0x00000000u
/** Mask of the per-message saturation / adjustment bits. */
#define MRQP_FW_PACK_SAT_MASK 0x0000FFFFu
/** A NaN input: the frame was not produced. */
#define MRQP_FW_PACK_ERR_NAN 0x01000000u
/** An invalid argument (NULL pointer, node id, count, mode, size...): the frame was not produced. */
#define MRQP_FW_PACK_ERR_ARG 0x02000000u
/** An invalid scaling/range configuration: the frame was not produced. */
#define MRQP_FW_PACK_ERR_CONFIG 0x04000000u
/** Mask of all error bits. */
#define MRQP_FW_PACK_ERR_MASK 0xFF000000u

/** Non-zero when the pack failed (no valid frame was produced). */
static inline int mrqp_fw_pack_failed(mrqp_fw_pack_flags flags) {
  return (flags & MRQP_FW_PACK_ERR_MASK) != 0u;
}

/** Result of a scalar SI <-> wire-integer conversion. */
typedef enum mrqp_fw_conv {
  MRQP_FW_CONV_OK = 0,       /**< in range (rounded to the nearest code) */
  MRQP_FW_CONV_SAT_LOW = 1,  /**< below the range: the output holds the lowest code */
  MRQP_FW_CONV_SAT_HIGH = 2, /**< above the range: the output holds the highest code */
  MRQP_FW_CONV_NAN = 3,      /**< NaN input: the output was not written */
  MRQP_FW_CONV_BAD_SCALE = 4 /**< invalid scale: the output was not written */
} mrqp_fw_conv;

#ifdef __cplusplus
}
#endif

#endif /* MRQP_FIRMWARE_IF_STATUS_H */
