/*
 * mrqp firmware interface -- the fixed default PDO mapping of the arm drives (little-endian).
 *
 *   RPDO1  0x200 + node  DLC 8  controlword u16 (0x6040) | target position i32 (0x607A) | target torque i16 (0x6071)
 *   TPDO1  0x180 + node  DLC 8  statusword u16 (0x6041)  | position actual i32 (0x6064) | torque actual i16 (0x6077)
 *   TPDO2  0x280 + node  DLC 7  velocity actual i32 (0x606C) | error code u16 (0x603F) | mode display i8 (0x6061)
 *
 * All three are synchronous: RPDO1 is applied and TPDO1/TPDO2 are sampled at the next SYNC
 * (transmission type 1). In CSP the drive ignores the target torque; in CST it ignores the
 * target position (both are always sent so one mapping serves both modes).
 */
#ifndef MRQP_FIRMWARE_IF_ARM_PDO_H
#define MRQP_FIRMWARE_IF_ARM_PDO_H

#include <stdint.h>

#include "mrqp/firmware_if/arm_scale.h"
#include "mrqp/firmware_if/frame.h"
#include "mrqp/firmware_if/status.h"

#ifdef __cplusplus
extern "C" {
#endif

#define MRQP_FW_ARM_RPDO1_LEN 8u
#define MRQP_FW_ARM_TPDO1_LEN 8u
#define MRQP_FW_ARM_TPDO2_LEN 7u

/** PDO mapping entry: index << 16 | subindex << 8 | length in bits. */
#define MRQP_FW_PDO_MAP_ENTRY(index, sub, bits) \
  ((((uint32_t)(index)) << 16) | (((uint32_t)(sub)) << 8) | ((uint32_t)(bits)))
/** Transmission type "synchronous, every SYNC" (PDO communication parameter sub-index 2). */
#define MRQP_FW_PDO_TRANSMISSION_SYNC 1u

typedef enum mrqp_fw_arm_pdo { MRQP_FW_ARM_RPDO1 = 0, MRQP_FW_ARM_TPDO1, MRQP_FW_ARM_TPDO2 } mrqp_fw_arm_pdo;

/**
 * Mapping of a PDO (to write to 0x1600 / 0x1A00 / 0x1A01 by SDO at start-up): fills entries[0..n)
 * and returns n (3), or 0 for an unknown pdo. The mapped bits add up to 8 x the PDO's DLC.
 */
unsigned mrqp_fw_arm_pdo_mapping(mrqp_fw_arm_pdo pdo, uint32_t entries[4]);

/* Saturation bits of mrqp_fw_arm_pack_rpdo1_si. */
#define MRQP_FW_ARM_SAT_POSITION 0x0001u
#define MRQP_FW_ARM_SAT_TORQUE 0x0002u

typedef struct mrqp_fw_arm_rpdo1 {
  uint16_t controlword;
  int32_t target_position; /**< increments */
  int16_t target_torque;   /**< per mille */
} mrqp_fw_arm_rpdo1;

typedef struct mrqp_fw_arm_tpdo1 {
  uint16_t statusword;
  int32_t position_actual; /**< increments */
  int16_t torque_actual;   /**< per mille */
} mrqp_fw_arm_tpdo1;

typedef struct mrqp_fw_arm_tpdo2 {
  int32_t velocity_actual; /**< increments / s */
  uint16_t error_code;     /**< 0x603F, an EMCY code (0 = no error) */
  int8_t mode_display;     /**< 0x6061 */
} mrqp_fw_arm_tpdo2;

/* Raw (wire-unit) pack/unpack. Pack: ERR_ARG for NULL or node outside 1..127. Unpack: classic,
 * COB-ID of `node` (ERR_ID), exact DLC (ERR_LENGTH). */
mrqp_fw_pack_flags mrqp_fw_arm_pack_rpdo1(unsigned node, const mrqp_fw_arm_rpdo1* pdo, mrqp_fw_frame* out);
mrqp_fw_err mrqp_fw_arm_unpack_rpdo1(const mrqp_fw_frame* in, unsigned node, mrqp_fw_arm_rpdo1* pdo);
mrqp_fw_pack_flags mrqp_fw_arm_pack_tpdo1(unsigned node, const mrqp_fw_arm_tpdo1* pdo, mrqp_fw_frame* out);
mrqp_fw_err mrqp_fw_arm_unpack_tpdo1(const mrqp_fw_frame* in, unsigned node, mrqp_fw_arm_tpdo1* pdo);
mrqp_fw_pack_flags mrqp_fw_arm_pack_tpdo2(unsigned node, const mrqp_fw_arm_tpdo2* pdo, mrqp_fw_frame* out);
mrqp_fw_err mrqp_fw_arm_unpack_tpdo2(const mrqp_fw_frame* in, unsigned node, mrqp_fw_arm_tpdo2* pdo);

/**
 * Master: RPDO1 from SI setpoints. Saturation: MRQP_FW_ARM_SAT_POSITION / _TORQUE.
 * NaN position or torque: ERR_NAN (no frame). Invalid scale: ERR_CONFIG.
 */
mrqp_fw_pack_flags mrqp_fw_arm_pack_rpdo1_si(const mrqp_fw_arm_scale* scale, unsigned node,
                                             uint16_t controlword, double position_rad, double torque_nm,
                                             mrqp_fw_frame* out);

#ifdef __cplusplus
}
#endif

#endif /* MRQP_FIRMWARE_IF_ARM_PDO_H */
