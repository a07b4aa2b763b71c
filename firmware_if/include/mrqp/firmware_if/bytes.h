/*
 * mrqp firmware interface -- byte order and bit-field helpers (header-only, static inline).
 *
 * CANopen (arm bus, force/torque sensor) is little-endian. The hand bus (MIT frames, hand FD
 * frames) is big-endian with fields packed MSB first across byte boundaries.
 */
#ifndef MRQP_FIRMWARE_IF_BYTES_H
#define MRQP_FIRMWARE_IF_BYTES_H

#include <stdint.h>

#ifdef __cplusplus
extern "C" {
#endif

static inline void mrqp_fw_put_u16le(uint8_t* p, uint16_t v) {
  p[0] = (uint8_t)(v & 0xFFu);
  p[1] = (uint8_t)((v >> 8) & 0xFFu);
}

static inline void mrqp_fw_put_u32le(uint8_t* p, uint32_t v) {
  p[0] = (uint8_t)(v & 0xFFu);
  p[1] = (uint8_t)((v >> 8) & 0xFFu);
  p[2] = (uint8_t)((v >> 16) & 0xFFu);
  p[3] = (uint8_t)((v >> 24) & 0xFFu);
}

static inline void mrqp_fw_put_u16be(uint8_t* p, uint16_t v) {
  p[0] = (uint8_t)((v >> 8) & 0xFFu);
  p[1] = (uint8_t)(v & 0xFFu);
}

static inline uint16_t mrqp_fw_get_u16le(const uint8_t* p) {
  return (uint16_t)((unsigned)p[0] | ((unsigned)p[1] << 8));
}

static inline uint32_t mrqp_fw_get_u32le(const uint8_t* p) {
  return (uint32_t)p[0] | ((uint32_t)p[1] << 8) | ((uint32_t)p[2] << 16) | ((uint32_t)p[3] << 24);
}

static inline uint16_t mrqp_fw_get_u16be(const uint8_t* p) {
  return (uint16_t)(((unsigned)p[0] << 8) | (unsigned)p[1]);
}

/** Two's complement reinterpretation without implementation-defined conversions. */
static inline int16_t mrqp_fw_u16_to_i16(uint16_t v) {
  return (v & 0x8000u) ? (int16_t)(-(int32_t)(uint16_t)(~v) - 1) : (int16_t)v;
}

static inline int32_t mrqp_fw_u32_to_i32(uint32_t v) {
  return (v & 0x80000000u) ? (int32_t)(-(int32_t)(~v & 0x7FFFFFFFu) - 1) : (int32_t)v;
}

/** Sign-extends the low `bits` bits of v (1 <= bits <= 32). */
static inline int32_t mrqp_fw_sign_extend(uint32_t v, unsigned bits) {
  uint32_t sign = (uint32_t)1u << (bits - 1u);
  uint32_t mask = (bits >= 32u) ? 0xFFFFFFFFu : (((uint32_t)1u << bits) - 1u);
  v &= mask;
  return (v & sign) ? mrqp_fw_u32_to_i32(v | ~mask) : (int32_t)v;
}

/**
 * Writes the low `nbits` bits of `value` into `buf` starting at bit `offset`, MSB first
 * (bit 0 of the stream is the MSB of buf[0]). Other bits of buf are unchanged.
 */
static inline void mrqp_fw_put_bits_be(uint8_t* buf, unsigned offset, unsigned nbits, uint32_t value) {
  unsigned i;
  for (i = 0u; i < nbits; ++i) {
    unsigned pos = offset + i;
    uint8_t mask = (uint8_t)(0x80u >> (pos & 7u));
    if ((value >> (nbits - 1u - i)) & 1u) {
      buf[pos >> 3] = (uint8_t)(buf[pos >> 3] | mask);
    } else {
      buf[pos >> 3] = (uint8_t)(buf[pos >> 3] & (uint8_t)~mask);
    }
  }
}

/** Reads `nbits` (<= 32) bits starting at bit `offset`, MSB first. */
static inline uint32_t mrqp_fw_get_bits_be(const uint8_t* buf, unsigned offset, unsigned nbits) {
  uint32_t v = 0u;
  unsigned i;
  for (i = 0u; i < nbits; ++i) {
    unsigned pos = offset + i;
    v = (v << 1) | (((unsigned)buf[pos >> 3] >> (7u - (pos & 7u))) & 1u);
  }
  return v;
}

#ifdef __cplusplus
}
#endif

#endif /* MRQP_FIRMWARE_IF_BYTES_H */
