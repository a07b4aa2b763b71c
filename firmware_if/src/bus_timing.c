/* mrqp firmware interface -- frame lengths on the wire (see bus_timing.h for the derivation). */
#include "mrqp/firmware_if/bus_timing.h"

#include "mrqp/firmware_if/frame.h"

mrqp_fw_frame_bits mrqp_fw_bits_classic(unsigned n, int worst_case_stuffing) {
  mrqp_fw_frame_bits b;
  uint32_t bytes = n > 8u ? 8u : (uint32_t)n;
  uint32_t stuffable = 34u + 8u * bytes;
  b.nominal_bits = 47u + 8u * bytes + (worst_case_stuffing ? (stuffable - 1u) / 4u : 0u);
  b.data_bits = 0u;
  return b;
}

mrqp_fw_frame_bits mrqp_fw_bits_fd(unsigned n, int brs, int worst_case_stuffing) {
  mrqp_fw_frame_bits b;
  uint32_t len = mrqp_fw_fd_len_round_up(n > 64u ? 64u : n);
  uint32_t crc_bits = len <= 16u ? 17u : 21u;
  uint32_t fixed_stuff = len <= 16u ? 6u : 7u;
  uint32_t arb = 17u;  /* SOF, ID 11, RRS, IDE, FDF, res, BRS */
  uint32_t tail = 13u; /* CRC delimiter, ACK slot, ACK delimiter, EOF 7, intermission 3 */
  uint32_t data = 1u + 4u + 8u * len + 4u + crc_bits + fixed_stuff; /* ESI, DLC, data, stuff count, CRC */
  if (worst_case_stuffing) {
    uint32_t total = (arb + 5u + 8u * len - 1u) / 4u;
    uint32_t in_arb = (arb - 1u) / 4u;
    arb += in_arb;
    data += total - in_arb;
  }
  if (brs) {
    b.nominal_bits = arb + tail;
    b.data_bits = data;
  } else {
    b.nominal_bits = arb + tail + data;
    b.data_bits = 0u;
  }
  return b;
}

uint32_t mrqp_fw_frame_time_ns(mrqp_fw_frame_bits bits, uint32_t nominal_bps, uint32_t data_bps) {
  uint64_t ns;
  if (nominal_bps == 0u || (bits.data_bits != 0u && data_bps == 0u)) {
    return 0xFFFFFFFFu;
  }
  ns = ((uint64_t)bits.nominal_bits * 1000000000u + nominal_bps - 1u) / nominal_bps;
  if (bits.data_bits != 0u) {
    ns += ((uint64_t)bits.data_bits * 1000000000u + data_bps - 1u) / data_bps;
  }
  return ns > 0xFFFFFFFFu ? 0xFFFFFFFFu : (uint32_t)ns;
}
