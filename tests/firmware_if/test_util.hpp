// Helpers shared by the firmware_if tests.
#pragma once

#include <mrqp/firmware_if/firmware_if.h>

#include <cstddef>
#include <cstdint>
#include <limits>
#include <vector>

namespace fwtest {

using Bytes = std::vector<std::uint8_t>;

inline Bytes payload(const mrqp_fw_frame& f) { return Bytes(f.data, f.data + f.len); }

inline mrqp_fw_frame makeFrame(std::uint32_t id, const Bytes& data, std::uint8_t flags = 0) {
  mrqp_fw_frame f{};
  f.id = id;
  f.len = static_cast<std::uint8_t>(data.size());
  f.flags = flags;
  for (std::size_t i = 0; i < data.size(); ++i) {
    f.data[i] = data[i];
  }
  return f;
}

// A cleared frame: what every failed pack must leave behind.
inline bool isCleared(const mrqp_fw_frame& f) {
  if (f.id != MRQP_FW_ID_INVALID || f.len != 0 || f.flags != 0) {
    return false;
  }
  for (std::uint8_t b : f.data) {
    if (b != 0) {
      return false;
    }
  }
  return true;
}

// Bit-by-bit CRC-16/CCITT-FALSE straight from the definition (independent of the table code).
inline std::uint16_t crc16Reference(const std::uint8_t* data, std::size_t n) {
  std::uint16_t crc = 0xFFFF;
  for (std::size_t i = 0; i < n; ++i) {
    for (int bit = 7; bit >= 0; --bit) {
      const bool in = ((data[i] >> bit) & 1u) != 0;
      const bool top = (crc & 0x8000u) != 0;
      crc = static_cast<std::uint16_t>(crc << 1);
      if (in != top) {
        crc = static_cast<std::uint16_t>(crc ^ 0x1021u);
      }
    }
  }
  return crc;
}

// Recomputes the trailing MSB-first CRC-16 of a frame after a deliberate edit.
inline void refreshCrc(mrqp_fw_frame& f) {
  const std::uint16_t crc = crc16Reference(f.data, static_cast<std::size_t>(f.len) - 2u);
  f.data[f.len - 2] = static_cast<std::uint8_t>(crc >> 8);
  f.data[f.len - 1] = static_cast<std::uint8_t>(crc & 0xFFu);
}

// An enumeration value outside the enumerators (what a corrupt caller or frame could hand over),
// made at run time so that the conversion is not a constant the compiler rejects.
template <class Enum>
inline Enum outOfRangeEnum(int value) {
  volatile int v = value;
  return static_cast<Enum>(static_cast<int>(v));
}

inline float nanf() { return std::numeric_limits<float>::quiet_NaN(); }
inline double nand() { return std::numeric_limits<double>::quiet_NaN(); }
inline float inff() { return std::numeric_limits<float>::infinity(); }
inline double infd() { return std::numeric_limits<double>::infinity(); }

}  // namespace fwtest
