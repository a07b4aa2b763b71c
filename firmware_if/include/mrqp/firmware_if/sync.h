/*
 * mrqp firmware interface -- CANopen SYNC (CiA 301).
 *
 * COB-ID 0x080. DLC 0 (no counter) or DLC 1 with a counter 1..240 (object 0x1019 > 1).
 * Synchronous PDOs (transmission type 1) and the force/torque sensor sample on SYNC reception.
 */
#ifndef MRQP_FIRMWARE_IF_SYNC_H
#define MRQP_FIRMWARE_IF_SYNC_H

#include <stdint.h>

#include "mrqp/firmware_if/frame.h"
#include "mrqp/firmware_if/status.h"

#ifdef __cplusplus
extern "C" {
#endif

#define MRQP_FW_SYNC_COUNTER_MAX 240u

/** SYNC frame: counter 0 = no counter (DLC 0), 1..240 = DLC 1. ERR_ARG for counter > 240. */
mrqp_fw_pack_flags mrqp_fw_sync_pack(unsigned counter, mrqp_fw_frame* out);
/** Validates id, classic, DLC 0 or 1, counter 1..240 (ERR_RANGE). *counter = 0 without counter. */
mrqp_fw_err mrqp_fw_sync_unpack(const mrqp_fw_frame* in, uint8_t* counter);
/** Next SYNC counter after `counter` (1..overflow, then 1 again); 0 if overflow is not 2..240. */
uint8_t mrqp_fw_sync_counter_next(uint8_t counter, uint8_t overflow);

#ifdef __cplusplus
}
#endif

#endif /* MRQP_FIRMWARE_IF_SYNC_H */
