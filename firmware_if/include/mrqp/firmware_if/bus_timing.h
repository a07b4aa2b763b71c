/*
 * mrqp firmware interface -- length of a frame on the wire, for bus-load budgets.
 *
 * Classic CAN, 11-bit identifier, n data bytes:
 *   SOF 1 + ID 11 + RTR 1 + IDE 1 + r0 1 + DLC 4 + data 8n + CRC 15 + CRC delim 1 + ACK 2
 *   + EOF 7 + intermission 3 = 47 + 8n bits (n = 8: 111).
 *   Bit stuffing applies from SOF to the end of the CRC (34 + 8n bits); at worst one stuff bit
 *   per 4 bits after the first: floor((34 + 8n - 1) / 4) (n = 8: 24, total 135).
 * CAN FD, 11-bit identifier, n data bytes (a valid FD length):
 *   nominal (arbitration) rate: SOF 1 + ID 11 + RRS 1 + IDE 1 + FDF 1 + res 1 + BRS 1 = 17,
 *     and CRC delim 1 + ACK 2 + EOF 7 + intermission 3 = 13: 30 bits;
 *   data rate (if BRS): ESI 1 + DLC 4 + data 8n + stuff count 4 + CRC 17 (n <= 16) or 21
 *     + fixed stuff bits 6 (CRC-17) or 7 (CRC-21);
 *   dynamic stuffing (SOF .. end of data, 22 + 8n bits): at worst floor((22 + 8n - 1) / 4),
 *     of which at most 4 fall in the 17 arbitration bits.
 *   (The rate switches at the sample points of BRS and of the CRC delimiter; counting those two
 *   bits whole at one rate is within one bit time.)
 */
#ifndef MRQP_FIRMWARE_IF_BUS_TIMING_H
#define MRQP_FIRMWARE_IF_BUS_TIMING_H

#include <stdint.h>

#ifdef __cplusplus
extern "C" {
#endif

typedef struct mrqp_fw_frame_bits {
  uint32_t nominal_bits; /**< bits sent at the nominal (arbitration) rate */
  uint32_t data_bits;    /**< bits sent at the data rate (0 for classic or FD without BRS) */
} mrqp_fw_frame_bits;

/** Classic frame of n <= 8 bytes; worst_case_stuffing selects the maximum stuff-bit count. */
mrqp_fw_frame_bits mrqp_fw_bits_classic(unsigned n, int worst_case_stuffing);
/** CAN FD frame of n bytes (rounded up to a valid FD length, at most 64). */
mrqp_fw_frame_bits mrqp_fw_bits_fd(unsigned n, int brs, int worst_case_stuffing);
/** Duration in nanoseconds (rounded up) at the given rates (bit/s, > 0). */
uint32_t mrqp_fw_frame_time_ns(mrqp_fw_frame_bits bits, uint32_t nominal_bps, uint32_t data_bps);

#ifdef __cplusplus
}
#endif

#endif /* MRQP_FIRMWARE_IF_BUS_TIMING_H */
