/*
 * mrqp firmware interface -- inertial measurement unit (IMU): one CAN FD frame per sample.
 *
 * The IMU of a floating-base robot (on its torso or pelvis) runs its own attitude filter and
 * samples when it receives SYNC, like the F/T sensor, then transmits one frame, little-endian:
 *
 *   0x180 + node (TPDO1 of its own node id), CAN FD with bit-rate switch, 24 bytes:
 *     bytes 0-7    orientation quaternion qw qx qy qz  i16, 32767 = 1 (the sensor frame in the
 *                  world frame, w >= 0 not required); code -32768 is reserved
 *     bytes 8-13   angular rate wx wy wz               i16, counts_per_rad_s (sensor frame)
 *     bytes 14-19  specific force ax ay az              i16, counts_per_mps2 (sensor frame; at rest
 *                  it is -g expressed in the sensor frame, i.e. +9.81 m/s^2 "up")
 *     byte 20      seq u8 (incremented per SYNC, wraps at 255)
 *     byte 21      status u8 (MRQP_FW_IMU_STATUS_*; bits 5-7 reserved, 0)
 *     bytes 22-23  CRC-16/CCITT-FALSE, MSB first, over bytes 0-21
 *
 * Why CAN FD and one frame: the 21 bytes of a sample need three classic frames; at 1 kHz that is
 * 3 x 111..135 bit times = 0.33..0.41 ms of every 1 ms cycle on a 1 Mbit/s bus (a third of the bus
 * the drives share) and a three-way reassembly with torn-sample detection. One 24-byte FD frame
 * at 1/5 Mbit/s takes 75.8..89.6 us, is atomic (no torn sample) and carries its own CRC.
 *
 * Scaling: the quaternion's wire unit is fixed (1/32767: 3.1e-5, an attitude resolution of about
 * 6e-5 rad); unpack rejects a quaternion whose norm is off by more than MRQP_FW_IMU_NORM_TOLERANCE
 * (quantisation alone moves it by less than 1e-4). The default scale: 1000 counts per rad/s
 * (+/-32.767 rad/s = +/-1877 deg/s, 1 mrad/s resolution) and 200 counts per m/s^2 (+/-163.8 m/s^2
 * = +/-16.7 g, 5 mm/s^2 resolution), the ranges of common MEMS IMUs (+/-2000 deg/s is reduced to
 * +/-1877 deg/s; a robot's torso does not turn faster). A saturated rate or force channel sets
 * MRQP_FW_IMU_STATUS_OVERRANGE in the transmitted status.
 */
#ifndef MRQP_FIRMWARE_IF_IMU_H
#define MRQP_FIRMWARE_IF_IMU_H

#include <stdint.h>

#include "mrqp/firmware_if/frame.h"
#include "mrqp/firmware_if/status.h"

#ifdef __cplusplus
extern "C" {
#endif

#define MRQP_FW_IMU_FD_LEN 24u
/** Wire counts of a quaternion component equal to 1. */
#define MRQP_FW_IMU_QUAT_COUNTS 32767.0
/** Largest accepted | |q| - 1 | of a decoded quaternion. */
#define MRQP_FW_IMU_NORM_TOLERANCE 0.01

/* Status bits. */
#define MRQP_FW_IMU_STATUS_OVERRANGE 0x01u   /**< a rate or force channel saturated */
#define MRQP_FW_IMU_STATUS_ALIGNING 0x02u    /**< attitude filter not converged: orientation not valid */
#define MRQP_FW_IMU_STATUS_TEMPERATURE 0x04u /**< temperature outside the calibrated range */
#define MRQP_FW_IMU_STATUS_FAULT 0x08u       /**< sensor fault: values not trustworthy */
#define MRQP_FW_IMU_STATUS_STALE 0x10u       /**< no new sample for this SYNC (values repeated) */
#define MRQP_FW_IMU_STATUS_RESERVED 0xE0u

/* Saturation bits, in the order of the frame. */
#define MRQP_FW_IMU_SAT_QW 0x0001u
#define MRQP_FW_IMU_SAT_QX 0x0002u
#define MRQP_FW_IMU_SAT_QY 0x0004u
#define MRQP_FW_IMU_SAT_QZ 0x0008u
#define MRQP_FW_IMU_SAT_WX 0x0010u
#define MRQP_FW_IMU_SAT_WY 0x0020u
#define MRQP_FW_IMU_SAT_WZ 0x0040u
#define MRQP_FW_IMU_SAT_AX 0x0080u
#define MRQP_FW_IMU_SAT_AY 0x0100u
#define MRQP_FW_IMU_SAT_AZ 0x0200u

/** Counts per SI unit, each finite and > 0. */
typedef struct mrqp_fw_imu_scale {
  double counts_per_rad_s; /**< angular rate */
  double counts_per_mps2;  /**< specific force */
} mrqp_fw_imu_scale;

#define MRQP_FW_IMU_SCALE_DEFAULT_INIT \
  { 1000.0, 200.0 }

int mrqp_fw_imu_scale_valid(const mrqp_fw_imu_scale* scale);

/** One sample in SI units. */
typedef struct mrqp_fw_imu_sample {
  double orientation[4];      /**< w x y z */
  double angular_velocity[3]; /**< rad/s */
  double specific_force[3];   /**< m/s^2 */
  uint8_t seq;
  uint8_t status;
} mrqp_fw_imu_sample;

/**
 * Sensor side: the FD frame. Saturation bits MRQP_FW_IMU_SAT_*; a saturated rate or force channel
 * also sets MRQP_FW_IMU_STATUS_OVERRANGE in the transmitted status. NaN: ERR_NAN. Reserved status
 * bits, invalid node or NULL: ERR_ARG. Invalid scale: ERR_CONFIG.
 */
mrqp_fw_pack_flags mrqp_fw_imu_pack(const mrqp_fw_imu_scale* scale, unsigned node,
                                    const mrqp_fw_imu_sample* s, mrqp_fw_frame* out);
/**
 * Host side: ERR_FORMAT (not FD, reserved status bits), ERR_ID, ERR_LENGTH (not 24 bytes), ERR_CRC,
 * ERR_RANGE (a quaternion code -32768 or a norm off by more than MRQP_FW_IMU_NORM_TOLERANCE),
 * ERR_CONFIG (scale).
 */
mrqp_fw_err mrqp_fw_imu_unpack(const mrqp_fw_imu_scale* scale, const mrqp_fw_frame* in, unsigned node,
                               mrqp_fw_imu_sample* s);

#ifdef __cplusplus
}
#endif

#endif /* MRQP_FIRMWARE_IF_IMU_H */
