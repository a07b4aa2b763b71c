/*
 * mrqp firmware interface -- CANopen emergency (EMCY) object (CiA 301, codes from CiA 402).
 *
 * COB-ID 0x080 + node, DLC 8:
 *   byte 0-1  emergency error code, u16 little-endian
 *   byte 2    error register (object 0x1001)
 *   byte 3-7  manufacturer-specific error field
 * Error code 0x0000 ("error reset / no error") announces that the device left the error state.
 */
#ifndef MRQP_FIRMWARE_IF_EMCY_H
#define MRQP_FIRMWARE_IF_EMCY_H

#include <stdint.h>

#include "mrqp/firmware_if/frame.h"
#include "mrqp/firmware_if/status.h"

#ifdef __cplusplus
extern "C" {
#endif

#define MRQP_FW_EMCY_LEN 8u
#define MRQP_FW_EMCY_MANUFACTURER_LEN 5u

/* Emergency error codes (CiA 301 table, CiA 402 drive additions). */
#define MRQP_FW_EMCY_NO_ERROR 0x0000u
#define MRQP_FW_EMCY_GENERIC 0x1000u
#define MRQP_FW_EMCY_CURRENT 0x2000u
#define MRQP_FW_EMCY_CONTINUOUS_OVER_CURRENT 0x2310u
#define MRQP_FW_EMCY_VOLTAGE 0x3000u
#define MRQP_FW_EMCY_DC_LINK_OVER_VOLTAGE 0x3210u
#define MRQP_FW_EMCY_DC_LINK_UNDER_VOLTAGE 0x3220u
#define MRQP_FW_EMCY_TEMPERATURE 0x4000u
#define MRQP_FW_EMCY_DEVICE_OVER_TEMPERATURE 0x4210u
#define MRQP_FW_EMCY_DEVICE_HARDWARE 0x5000u
#define MRQP_FW_EMCY_DEVICE_SOFTWARE 0x6000u
#define MRQP_FW_EMCY_ADDITIONAL_MODULES 0x7000u
#define MRQP_FW_EMCY_SENSOR 0x7300u
#define MRQP_FW_EMCY_INCREMENTAL_SENSOR_1 0x7305u
#define MRQP_FW_EMCY_MONITORING 0x8000u
#define MRQP_FW_EMCY_COMMUNICATION 0x8100u
#define MRQP_FW_EMCY_CAN_OVERRUN 0x8110u
#define MRQP_FW_EMCY_CAN_ERROR_PASSIVE 0x8120u
#define MRQP_FW_EMCY_HEARTBEAT_ERROR 0x8130u
#define MRQP_FW_EMCY_BUS_OFF_RECOVERED 0x8140u
#define MRQP_FW_EMCY_PDO_LENGTH_ERROR 0x8210u
#define MRQP_FW_EMCY_PDO_LENGTH_EXCEEDED 0x8220u
#define MRQP_FW_EMCY_RPDO_TIMEOUT 0x8250u
#define MRQP_FW_EMCY_FOLLOWING_ERROR 0x8611u
#define MRQP_FW_EMCY_EXTERNAL 0x9000u
#define MRQP_FW_EMCY_DEVICE_SPECIFIC 0xFF00u

/* Error register (0x1001) bits. */
#define MRQP_FW_ERRREG_GENERIC 0x01u
#define MRQP_FW_ERRREG_CURRENT 0x02u
#define MRQP_FW_ERRREG_VOLTAGE 0x04u
#define MRQP_FW_ERRREG_TEMPERATURE 0x08u
#define MRQP_FW_ERRREG_COMMUNICATION 0x10u
#define MRQP_FW_ERRREG_DEVICE_PROFILE 0x20u
#define MRQP_FW_ERRREG_RESERVED 0x40u
#define MRQP_FW_ERRREG_MANUFACTURER 0x80u

typedef struct mrqp_fw_emcy {
  uint16_t error_code;
  uint8_t error_register;
  uint8_t manufacturer[MRQP_FW_EMCY_MANUFACTURER_LEN];
} mrqp_fw_emcy;

/** EMCY frame of `node` (1..127). ERR_ARG for invalid node or NULL. */
mrqp_fw_pack_flags mrqp_fw_emcy_pack(unsigned node, const mrqp_fw_emcy* emcy, mrqp_fw_frame* out);
/**
 * Validates id 0x081..0x0FF (ERR_ID; 0x080 is SYNC), classic, DLC 8; a non-zero error code with
 * an error register lacking the generic bit is accepted (devices differ), the reserved bit 6 of
 * the error register must be 0 (ERR_FORMAT).
 */
mrqp_fw_err mrqp_fw_emcy_unpack(const mrqp_fw_frame* in, uint8_t* node, mrqp_fw_emcy* emcy);
/** Name of a known error code; otherwise the name of its class (top hex digit), never NULL. */
const char* mrqp_fw_emcy_code_str(uint16_t code);

#ifdef __cplusplus
}
#endif

#endif /* MRQP_FIRMWARE_IF_EMCY_H */
