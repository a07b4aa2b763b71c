/*
 * mrqp firmware interface -- arm drive units (CiA 402) <-> SI.
 *
 *   position  i32 increments         rad   = inc * 2 pi / increments_per_rev
 *   velocity  i32 increments / s     rad/s = inc/s * 2 pi / increments_per_rev
 *   torque    i16 per mille of rated N m   = permille * rated_torque_mNm / 1e6
 *
 * increments_per_rev counts increments per revolution of the JOINT (a motor-side encoder's count
 * times the gear ratio). rated_torque_mNm is the torque, at the joint, that 1000 per mille
 * stands for (for a motor-side drive: motor rated torque 0x6076 times the gear ratio).
 * SI -> wire conversions round to nearest, saturate to the integer range and say so.
 */
#ifndef MRQP_FIRMWARE_IF_ARM_SCALE_H
#define MRQP_FIRMWARE_IF_ARM_SCALE_H

#include <stdint.h>

#include "mrqp/firmware_if/status.h"

#ifdef __cplusplus
extern "C" {
#endif

typedef struct mrqp_fw_arm_scale {
  uint32_t increments_per_rev; /**< > 0 */
  uint32_t rated_torque_mNm;   /**< > 0 */
} mrqp_fw_arm_scale;

/** 2^19 increments per revolution (a 19-bit absolute encoder), 1 N m rated. */
#define MRQP_FW_ARM_SCALE_DEFAULT_INIT \
  { 524288u, 1000u }

/** Non-zero if both factors are positive. */
int mrqp_fw_arm_scale_valid(const mrqp_fw_arm_scale* scale);

mrqp_fw_conv mrqp_fw_arm_position_to_inc(const mrqp_fw_arm_scale* scale, double rad, int32_t* inc);
mrqp_fw_conv mrqp_fw_arm_position_from_inc(const mrqp_fw_arm_scale* scale, int32_t inc, double* rad);
mrqp_fw_conv mrqp_fw_arm_velocity_to_inc(const mrqp_fw_arm_scale* scale, double rad_s, int32_t* inc_s);
mrqp_fw_conv mrqp_fw_arm_velocity_from_inc(const mrqp_fw_arm_scale* scale, int32_t inc_s, double* rad_s);
mrqp_fw_conv mrqp_fw_arm_torque_to_permille(const mrqp_fw_arm_scale* scale, double nm, int16_t* permille);
mrqp_fw_conv mrqp_fw_arm_torque_from_permille(const mrqp_fw_arm_scale* scale, int16_t permille, double* nm);

#ifdef __cplusplus
}
#endif

#endif /* MRQP_FIRMWARE_IF_ARM_SCALE_H */
