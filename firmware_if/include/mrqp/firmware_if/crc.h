/*
 * mrqp firmware interface -- CRC-16/CCITT-FALSE (own table-driven implementation).
 *
 * Parameters (Rocksoft model): width 16, poly 0x1021, init 0xFFFF, refin false, refout false,
 * xorout 0x0000, check ("123456789") 0x29B1, residue 0x0000.
 * The CRC is appended MSB first; then the CRC computed over data + appended CRC is 0x0000.
 * The 256-entry table is const (read-only data, no state).
 */
#ifndef MRQP_FIRMWARE_IF_CRC_H
#define MRQP_FIRMWARE_IF_CRC_H

#include <stddef.h>
#include <stdint.h>

#ifdef __cplusplus
extern "C" {
#endif

#define MRQP_FW_CRC16_INIT 0xFFFFu
#define MRQP_FW_CRC16_POLY 0x1021u
#define MRQP_FW_CRC16_CHECK 0x29B1u

/** Continues a CRC over n more bytes (start with MRQP_FW_CRC16_INIT). data may be NULL if n is 0. */
uint16_t mrqp_fw_crc16_update(uint16_t crc, const uint8_t* data, size_t n);
/** CRC-16/CCITT-FALSE of n bytes. */
uint16_t mrqp_fw_crc16(const uint8_t* data, size_t n);

#ifdef __cplusplus
}
#endif

#endif /* MRQP_FIRMWARE_IF_CRC_H */
