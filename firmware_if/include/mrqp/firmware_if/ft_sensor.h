/*
 * mrqp firmware interface -- wrist 6-axis force/torque sensor (a CANopen-style node on the arm bus).
 *
 * The sensor samples all six channels when it receives SYNC and then transmits, little-endian:
 *
 * Classic variant (two frames per sample):
 *   forces   0x180 + node (TPDO1), DLC 8:  fx i16 | fy i16 | fz i16 | seq u8 | status u8
 *   moments  0x280 + node (TPDO2), DLC 8:  mx i16 | my i16 | mz i16 | seq u8 | status u8
 *   Both frames of one sample carry the same seq and status; a mismatch reveals a torn pair
 *   (one frame lost or reordered) and the pair is rejected (MRQP_FW_ERR_TORN).
 * FD variant (one frame per sample):
 *   0x180 + node (TPDO1), CAN FD, 32 bytes: fx fy fz mx my mz i32 (bytes 0-23) | seq u8 (24) |
 *   status u8 (25) | zero (26-29) | CRC-16/CCITT-FALSE MSB first over bytes 0-29 (30-31)
 * Tare command, master -> sensor:
 *   0x200 + node (RPDO1), DLC 2: command u8 | command XOR 0xFF (guards against a stray frame)
 *
 * Scaling: counts = round(N * counts_per_N) for forces, round(N m * counts_per_Nm) for moments.
 * seq increments by one per SYNC (wraps at 255). The status byte: MRQP_FW_FT_STATUS_*.
 */
#ifndef MRQP_FIRMWARE_IF_FT_SENSOR_H
#define MRQP_FIRMWARE_IF_FT_SENSOR_H

#include <stdint.h>

#include "mrqp/firmware_if/frame.h"
#include "mrqp/firmware_if/status.h"

#ifdef __cplusplus
extern "C" {
#endif

#define MRQP_FW_FT_CLASSIC_LEN 8u
#define MRQP_FW_FT_FD_LEN 32u
#define MRQP_FW_FT_TARE_LEN 2u

/* Status bits. */
#define MRQP_FW_FT_STATUS_OVERRANGE 0x01u   /**< a channel saturated (gauge or wire range) */
#define MRQP_FW_FT_STATUS_TARED 0x02u       /**< a tare offset is applied */
#define MRQP_FW_FT_STATUS_TEMPERATURE 0x04u /**< temperature outside the calibrated range */
#define MRQP_FW_FT_STATUS_FAULT 0x08u       /**< sensor fault: values not trustworthy */
#define MRQP_FW_FT_STATUS_STALE 0x10u       /**< no new sample for this SYNC (values repeated) */
#define MRQP_FW_FT_STATUS_RESERVED 0xE0u

/* Tare commands. */
#define MRQP_FW_FT_CMD_CLEAR_TARE 0x00u
#define MRQP_FW_FT_CMD_TARE 0x01u

/* Saturation bits: one per axis, in the order fx fy fz mx my mz. */
#define MRQP_FW_FT_SAT_FX 0x0001u
#define MRQP_FW_FT_SAT_FY 0x0002u
#define MRQP_FW_FT_SAT_FZ 0x0004u
#define MRQP_FW_FT_SAT_MX 0x0008u
#define MRQP_FW_FT_SAT_MY 0x0010u
#define MRQP_FW_FT_SAT_MZ 0x0020u

/** Counts per SI unit, each finite and > 0. */
typedef struct mrqp_fw_ft_scale {
  double counts_per_n;  /**< force channels */
  double counts_per_nm; /**< moment channels */
} mrqp_fw_ft_scale;

/** Classic i16 frames: 0.02 N (+/-655 N) and 1 mN m (+/-32.8 N m) resolution. */
#define MRQP_FW_FT_SCALE_CLASSIC_DEFAULT_INIT \
  { 50.0, 1000.0 }
/** FD i32 frame: 1 uN (+/-2147 N) and 1 uN m (+/-2147 N m) resolution. */
#define MRQP_FW_FT_SCALE_FD_DEFAULT_INIT \
  { 1.0e6, 1.0e6 }

int mrqp_fw_ft_scale_valid(const mrqp_fw_ft_scale* scale);

/** One sample in SI: wrench[0..2] force (N), wrench[3..5] moment (N m), sensor frame. */
typedef struct mrqp_fw_ft_sample {
  double wrench[6];
  uint8_t seq;
  uint8_t status;
} mrqp_fw_ft_sample;

/** One classic frame decoded on its own (forces or moments). */
typedef struct mrqp_fw_ft_half {
  int moments;     /**< 0: forces frame, 1: moments frame */
  double value[3]; /**< N or N m */
  uint8_t seq;
  uint8_t status;
} mrqp_fw_ft_half;

/**
 * Sensor side: the two classic frames of one sample. Saturation bits MRQP_FW_FT_SAT_*; a saturated
 * channel also sets MRQP_FW_FT_STATUS_OVERRANGE in the transmitted status. NaN: ERR_NAN. Reserved
 * status bits, invalid node or NULL: ERR_ARG. Invalid scale: ERR_CONFIG.
 */
mrqp_fw_pack_flags mrqp_fw_ft_pack_classic(const mrqp_fw_ft_scale* scale, unsigned node,
                                           const mrqp_fw_ft_sample* s, mrqp_fw_frame* forces,
                                           mrqp_fw_frame* moments);
/** Host side: one classic frame (forces on TPDO1, moments on TPDO2 of `node`). */
mrqp_fw_err mrqp_fw_ft_unpack_half(const mrqp_fw_ft_scale* scale, const mrqp_fw_frame* in, unsigned node,
                                   mrqp_fw_ft_half* half);
/** Host side: joins a forces half and a moments half; ERR_TORN if seq or status differ. */
mrqp_fw_err mrqp_fw_ft_join(const mrqp_fw_ft_half* forces, const mrqp_fw_ft_half* moments,
                            mrqp_fw_ft_sample* s);
/** Host side: unpack_half on both + join. */
mrqp_fw_err mrqp_fw_ft_unpack_classic(const mrqp_fw_ft_scale* scale, const mrqp_fw_frame* forces,
                                      const mrqp_fw_frame* moments, unsigned node, mrqp_fw_ft_sample* s);

/** Sensor side: the FD frame. Same flags as mrqp_fw_ft_pack_classic (i32 range). */
mrqp_fw_pack_flags mrqp_fw_ft_pack_fd(const mrqp_fw_ft_scale* scale, unsigned node,
                                      const mrqp_fw_ft_sample* s, mrqp_fw_frame* out);
/** Host side: FD flag, ID, length 32, CRC, zero padding, reserved status bits (ERR_FORMAT). */
mrqp_fw_err mrqp_fw_ft_unpack_fd(const mrqp_fw_ft_scale* scale, const mrqp_fw_frame* in, unsigned node,
                                 mrqp_fw_ft_sample* s);

/** Master side: tare command (MRQP_FW_FT_CMD_TARE / _CLEAR_TARE). */
mrqp_fw_pack_flags mrqp_fw_ft_pack_tare(unsigned node, unsigned command, mrqp_fw_frame* out);
/** Sensor side: ERR_FORMAT if the check byte is not the complement, ERR_COMMAND if unknown. */
mrqp_fw_err mrqp_fw_ft_unpack_tare(const mrqp_fw_frame* in, unsigned node, uint8_t* command);

#ifdef __cplusplus
}
#endif

#endif /* MRQP_FIRMWARE_IF_FT_SENSOR_H */
