// CRC, byte/bit helpers, saturation and quantisation, CAN FD lengths, bus timing.
#include <catch2/catch.hpp>

#include "test_util.hpp"

#include <cmath>
#include <cstring>
#include <random>
#include <string>

using namespace fwtest;

TEST_CASE("CRC-16/CCITT-FALSE matches the published check value", "[firmware_if][crc]") {
  const char* check = "123456789";
  const auto* p = reinterpret_cast<const std::uint8_t*>(check);
  CHECK(mrqp_fw_crc16(p, 9) == 0x29B1);
  CHECK(MRQP_FW_CRC16_CHECK == 0x29B1u);
  CHECK(crc16Reference(p, 9) == 0x29B1);
  CHECK(mrqp_fw_crc16(nullptr, 0) == 0xFFFF);  // init value, no xorout
}

TEST_CASE("CRC-16 table code equals the bitwise definition; residue and incremental use",
          "[firmware_if][crc]") {
  std::mt19937 rng(1234);
  std::uniform_int_distribution<int> byte(0, 255);
  for (std::size_t n = 0; n <= 70; ++n) {
    Bytes buf(n + 2);
    for (std::size_t i = 0; i < n; ++i) {
      buf[i] = static_cast<std::uint8_t>(byte(rng));
    }
    const std::uint16_t crc = mrqp_fw_crc16(buf.data(), n);
    REQUIRE(crc == crc16Reference(buf.data(), n));
    // Split in two calls.
    const std::size_t k = n / 3;
    CHECK(mrqp_fw_crc16_update(mrqp_fw_crc16(buf.data(), k), buf.data() + k, n - k) == crc);
    // Appended MSB first, the CRC over data + CRC is zero.
    buf[n] = static_cast<std::uint8_t>(crc >> 8);
    buf[n + 1] = static_cast<std::uint8_t>(crc & 0xFF);
    CHECK(mrqp_fw_crc16(buf.data(), n + 2) == 0);
  }
}

TEST_CASE("byte order helpers", "[firmware_if][bytes]") {
  std::uint8_t b[4] = {0, 0, 0, 0};
  mrqp_fw_put_u16le(b, 0x1234);
  CHECK(b[0] == 0x34);
  CHECK(b[1] == 0x12);
  CHECK(mrqp_fw_get_u16le(b) == 0x1234);
  mrqp_fw_put_u16be(b, 0x1234);
  CHECK(b[0] == 0x12);
  CHECK(b[1] == 0x34);
  CHECK(mrqp_fw_get_u16be(b) == 0x1234);
  mrqp_fw_put_u32le(b, 0xA1B2C3D4u);
  CHECK(b[0] == 0xD4);
  CHECK(b[3] == 0xA1);
  CHECK(mrqp_fw_get_u32le(b) == 0xA1B2C3D4u);

  CHECK(mrqp_fw_u16_to_i16(0x8000) == -32768);
  CHECK(mrqp_fw_u16_to_i16(0xFFFF) == -1);
  CHECK(mrqp_fw_u16_to_i16(0x7FFF) == 32767);
  CHECK(mrqp_fw_u32_to_i32(0x80000000u) == std::numeric_limits<std::int32_t>::min());
  CHECK(mrqp_fw_u32_to_i32(0xFFFFFFFFu) == -1);
  CHECK(mrqp_fw_u32_to_i32(0x7FFFFFFFu) == std::numeric_limits<std::int32_t>::max());
  for (std::uint32_t v = 0; v < 0x10000u; ++v) {
    REQUIRE(mrqp_fw_u16_to_i16(static_cast<std::uint16_t>(v)) == static_cast<std::int16_t>(v));
  }
  CHECK(mrqp_fw_sign_extend(0x800, 12) == -2048);
  CHECK(mrqp_fw_sign_extend(0x7FF, 12) == 2047);
  CHECK(mrqp_fw_sign_extend(0xFFF, 12) == -1);
  CHECK(mrqp_fw_sign_extend(0xFFFFF7FF, 12) == 2047);  // high bits are ignored
  CHECK(mrqp_fw_sign_extend(0x80000000u, 32) == std::numeric_limits<std::int32_t>::min());
}

TEST_CASE("big-endian bit fields round-trip at any offset and leave other bits alone",
          "[firmware_if][bytes]") {
  std::mt19937 rng(99);
  for (int iter = 0; iter < 2000; ++iter) {
    const unsigned nbits = 1u + static_cast<unsigned>(rng() % 32u);
    const unsigned offset = static_cast<unsigned>(rng() % (512u - nbits));
    const std::uint32_t mask = nbits == 32 ? 0xFFFFFFFFu : ((1u << nbits) - 1u);
    const std::uint32_t value = static_cast<std::uint32_t>(rng()) & mask;
    std::uint8_t buf[64];
    std::uint8_t before[64];
    for (auto& x : buf) {
      x = static_cast<std::uint8_t>(rng());
    }
    std::memcpy(before, buf, sizeof(buf));
    mrqp_fw_put_bits_be(buf, offset, nbits, value);
    REQUIRE(mrqp_fw_get_bits_be(buf, offset, nbits) == value);
    for (unsigned pos = 0; pos < 512; ++pos) {
      if (pos >= offset && pos < offset + nbits) {
        continue;
      }
      const unsigned a = (static_cast<unsigned>(buf[pos / 8]) >> (7 - pos % 8)) & 1u;
      const unsigned b = (static_cast<unsigned>(before[pos / 8]) >> (7 - pos % 8)) & 1u;
      REQUIRE(a == b);
    }
  }
  // Hand example: 0xABC at bit 4 of a zero buffer -> 0x0A 0xBC.
  std::uint8_t b2[2] = {0, 0};
  mrqp_fw_put_bits_be(b2, 4, 12, 0xABC);
  CHECK(b2[0] == 0x0A);
  CHECK(b2[1] == 0xBC);
}

TEST_CASE("NaN and finiteness tests look at the bits", "[firmware_if][saturate]") {
  CHECK(mrqp_fw_isnan_d(nand()));
  CHECK(mrqp_fw_isnan_d(-nand()));
  CHECK(mrqp_fw_isnan_d(std::numeric_limits<double>::signaling_NaN()));
  CHECK_FALSE(mrqp_fw_isnan_d(infd()));
  CHECK_FALSE(mrqp_fw_isnan_d(0.0));
  CHECK(mrqp_fw_isnan_f(nanf()));
  CHECK(mrqp_fw_isnan_f(std::numeric_limits<float>::signaling_NaN()));
  CHECK_FALSE(mrqp_fw_isnan_f(-inff()));
  CHECK_FALSE(mrqp_fw_isfinite_d(infd()));
  CHECK_FALSE(mrqp_fw_isfinite_d(nand()));
  CHECK(mrqp_fw_isfinite_d(std::numeric_limits<double>::max()));
  CHECK_FALSE(mrqp_fw_isfinite_f(inff()));
  CHECK(mrqp_fw_isfinite_f(std::numeric_limits<float>::denorm_min()));
}

TEST_CASE("integer quantisation: rounding, closed range, saturation, NaN", "[firmware_if][saturate]") {
  std::int64_t v = 42;
  CHECK(mrqp_fw_quantize_int(2.5, -10, 10, &v) == MRQP_FW_CONV_OK);
  CHECK(v == 3);
  CHECK(mrqp_fw_quantize_int(-2.5, -10, 10, &v) == MRQP_FW_CONV_OK);
  CHECK(v == -3);
  CHECK(mrqp_fw_quantize_int(2.4999, -10, 10, &v) == MRQP_FW_CONV_OK);
  CHECK(v == 2);
  CHECK(mrqp_fw_quantize_int(0.49999999999999994, -10, 10, &v) == MRQP_FW_CONV_OK);
  CHECK(v == 0);
  CHECK(mrqp_fw_quantize_int(10.0, -10, 10, &v) == MRQP_FW_CONV_OK);  // the end is in range
  CHECK(v == 10);
  CHECK(mrqp_fw_quantize_int(10.49, -10, 10, &v) == MRQP_FW_CONV_OK);  // nearest code 10: in range
  CHECK(v == 10);
  CHECK(mrqp_fw_quantize_int(10.5, -10, 10, &v) == MRQP_FW_CONV_SAT_HIGH);  // nearest code 11
  CHECK(v == 10);
  CHECK(mrqp_fw_quantize_int(-10.49, -10, 10, &v) == MRQP_FW_CONV_OK);
  CHECK(v == -10);
  CHECK(mrqp_fw_quantize_int(-10.0, -10, 10, &v) == MRQP_FW_CONV_OK);
  CHECK(mrqp_fw_quantize_int(-10.5, -10, 10, &v) == MRQP_FW_CONV_SAT_LOW);
  CHECK(v == -10);
  CHECK(mrqp_fw_quantize_int(infd(), -10, 10, &v) == MRQP_FW_CONV_SAT_HIGH);
  CHECK(mrqp_fw_quantize_int(-infd(), -10, 10, &v) == MRQP_FW_CONV_SAT_LOW);
  v = 42;
  CHECK(mrqp_fw_quantize_int(nand(), -10, 10, &v) == MRQP_FW_CONV_NAN);
  CHECK(v == 42);  // untouched
  CHECK(mrqp_fw_quantize_int(2147483647.0, INT32_MIN, INT32_MAX, &v) == MRQP_FW_CONV_OK);
  CHECK(v == 2147483647);
  CHECK(mrqp_fw_quantize_int(2147483647.4, INT32_MIN, INT32_MAX, &v) == MRQP_FW_CONV_OK);
  CHECK(v == 2147483647);
  CHECK(mrqp_fw_quantize_int(2147483647.5, INT32_MIN, INT32_MAX, &v) == MRQP_FW_CONV_SAT_HIGH);
  CHECK(mrqp_fw_quantize_int(-2147483648.5, INT32_MIN, INT32_MAX, &v) == MRQP_FW_CONV_SAT_LOW);
  CHECK(mrqp_fw_quantize_int(-2147483648.0, INT32_MIN, INT32_MAX, &v) == MRQP_FW_CONV_OK);
  CHECK(v == INT32_MIN);
  CHECK(mrqp_fw_quantize_int(1e300, INT32_MIN, INT32_MAX, &v) == MRQP_FW_CONV_SAT_HIGH);
  CHECK(v == INT32_MAX);
}

TEST_CASE("linear [min,max] quantisation", "[firmware_if][saturate]") {
  std::uint32_t c = 7;
  CHECK(mrqp_fw_quantize_linear(-1.0, -1.0, 1.0, 12, &c) == MRQP_FW_CONV_OK);
  CHECK(c == 0);
  CHECK(mrqp_fw_quantize_linear(1.0, -1.0, 1.0, 12, &c) == MRQP_FW_CONV_OK);
  CHECK(c == 4095);
  CHECK(mrqp_fw_quantize_linear(0.0, -1.0, 1.0, 12, &c) == MRQP_FW_CONV_OK);
  CHECK(c == 2048);  // 2047.5 rounds away from zero
  const double step = 2.0 / 4095.0;
  CHECK(mrqp_fw_quantize_linear(1.0 + 0.4 * step, -1.0, 1.0, 12, &c) == MRQP_FW_CONV_OK);
  CHECK(c == 4095);
  CHECK(mrqp_fw_quantize_linear(1.0 + 0.6 * step, -1.0, 1.0, 12, &c) == MRQP_FW_CONV_SAT_HIGH);
  CHECK(c == 4095);
  CHECK(mrqp_fw_quantize_linear(infd(), -1.0, 1.0, 12, &c) == MRQP_FW_CONV_SAT_HIGH);
  CHECK(mrqp_fw_quantize_linear(-1e308, -1.0, 1.0, 12, &c) == MRQP_FW_CONV_SAT_LOW);
  CHECK(c == 0);
  CHECK(mrqp_fw_quantize_linear(-3.0, -1.0, 1.0, 12, &c) == MRQP_FW_CONV_SAT_LOW);
  CHECK(c == 0);
  c = 7;
  CHECK(mrqp_fw_quantize_linear(nand(), -1.0, 1.0, 12, &c) == MRQP_FW_CONV_NAN);
  CHECK(mrqp_fw_quantize_linear(0.0, 1.0, 1.0, 12, &c) == MRQP_FW_CONV_BAD_SCALE);
  CHECK(mrqp_fw_quantize_linear(0.0, 1.0, -1.0, 12, &c) == MRQP_FW_CONV_BAD_SCALE);
  CHECK(mrqp_fw_quantize_linear(0.0, nand(), 1.0, 12, &c) == MRQP_FW_CONV_BAD_SCALE);
  CHECK(mrqp_fw_quantize_linear(0.0, -infd(), 1.0, 12, &c) == MRQP_FW_CONV_BAD_SCALE);
  CHECK(mrqp_fw_quantize_linear(0.0, -1.0, 1.0, 0, &c) == MRQP_FW_CONV_BAD_SCALE);
  CHECK(c == 7);
  CHECK(mrqp_fw_quantize_linear(1.0, -1.0, 1.0, 32, &c) == MRQP_FW_CONV_OK);
  CHECK(c == 0xFFFFFFFFu);
  CHECK(mrqp_fw_dequantize_linear(4095, -1.0, 1.0, 12) == Approx(1.0));
  CHECK(mrqp_fw_dequantize_linear(0, -1.0, 1.0, 12) == -1.0);
}

TEST_CASE("signed fixed point never produces the reserved most-negative code", "[firmware_if][saturate]") {
  std::int32_t c = 0;
  CHECK(mrqp_fw_quantize_fixed(-1e9, 1.0, 12, &c) == MRQP_FW_CONV_SAT_LOW);
  CHECK(c == -2047);
  CHECK(mrqp_fw_quantize_fixed(1e9, 1.0, 12, &c) == MRQP_FW_CONV_SAT_HIGH);
  CHECK(c == 2047);
  CHECK(mrqp_fw_quantize_fixed(-2047.0, 1.0, 12, &c) == MRQP_FW_CONV_OK);
  CHECK(mrqp_fw_quantize_fixed(-2047.4, 1.0, 12, &c) == MRQP_FW_CONV_OK);
  CHECK(c == -2047);
  CHECK(mrqp_fw_quantize_fixed(-2047.5, 1.0, 12, &c) == MRQP_FW_CONV_SAT_LOW);
  CHECK(c == -2047);
  CHECK(mrqp_fw_quantize_fixed(0.0, 0.5, 16, &c) == MRQP_FW_CONV_OK);
  CHECK(c == 0);
  CHECK(mrqp_fw_quantize_fixed(1.25, 0.5, 16, &c) == MRQP_FW_CONV_OK);
  CHECK(c == 3);  // 2.5 -> 3
  CHECK(mrqp_fw_quantize_fixed(1.0, 0.0, 16, &c) == MRQP_FW_CONV_BAD_SCALE);
  CHECK(mrqp_fw_quantize_fixed(1.0, -1.0, 16, &c) == MRQP_FW_CONV_BAD_SCALE);
  CHECK(mrqp_fw_quantize_fixed(1.0, infd(), 16, &c) == MRQP_FW_CONV_BAD_SCALE);
  CHECK(mrqp_fw_quantize_fixed(nand(), 1.0, 16, &c) == MRQP_FW_CONV_NAN);
}

TEST_CASE("CAN FD lengths and DLC codes", "[firmware_if][frame]") {
  const unsigned valid[] = {0, 1, 2, 3, 4, 5, 6, 7, 8, 12, 16, 20, 24, 32, 48, 64};
  for (unsigned dlc = 0; dlc < 16; ++dlc) {
    CHECK(mrqp_fw_fd_dlc_to_len(static_cast<std::uint8_t>(dlc)) == valid[dlc]);
    CHECK(mrqp_fw_fd_len_to_dlc(static_cast<std::uint8_t>(valid[dlc])) == dlc);
    CHECK(mrqp_fw_fd_len_valid(valid[dlc]));
  }
  CHECK(mrqp_fw_fd_dlc_to_len(16) == 0);
  CHECK(mrqp_fw_fd_len_to_dlc(9) == 0xFF);
  CHECK_FALSE(mrqp_fw_fd_len_valid(9));
  CHECK_FALSE(mrqp_fw_fd_len_valid(63));
  CHECK_FALSE(mrqp_fw_fd_len_valid(65));
  CHECK(mrqp_fw_fd_len_round_up(8) == 8);
  CHECK(mrqp_fw_fd_len_round_up(9) == 12);
  CHECK(mrqp_fw_fd_len_round_up(33) == 48);
  CHECK(mrqp_fw_fd_len_round_up(62) == 64);
  CHECK(mrqp_fw_fd_len_round_up(65) == 0);
}

TEST_CASE("frame envelope checks", "[firmware_if][frame]") {
  mrqp_fw_frame f = makeFrame(0x123, {1, 2, 3});
  CHECK(mrqp_fw_frame_expect(&f, 0x123, 3, 0) == MRQP_FW_OK);
  CHECK(mrqp_fw_frame_expect(&f, 0x124, 3, 0) == MRQP_FW_ERR_ID);
  CHECK(mrqp_fw_frame_expect(&f, 0x123, 4, 0) == MRQP_FW_ERR_LENGTH);
  CHECK(mrqp_fw_frame_expect(&f, 0x123, 3, 1) == MRQP_FW_ERR_FORMAT);
  CHECK(mrqp_fw_frame_expect(nullptr, 0x123, 3, 0) == MRQP_FW_ERR_NULL);
  f.flags = MRQP_FW_FRAME_EXT;
  CHECK(mrqp_fw_frame_expect(&f, 0x123, 3, 0) == MRQP_FW_ERR_FORMAT);
  f.flags = MRQP_FW_FRAME_RTR;
  CHECK(mrqp_fw_frame_expect(&f, 0x123, 3, 0) == MRQP_FW_ERR_FORMAT);
  mrqp_fw_frame_clear(&f);
  CHECK(isCleared(f));
  mrqp_fw_frame_clear(nullptr);  // tolerated
}

TEST_CASE("every error code has a name", "[firmware_if][status]") {
  for (int e = MRQP_FW_OK; e <= MRQP_FW_ERR_TORN; ++e) {
    const std::string s = mrqp_fw_err_str(static_cast<mrqp_fw_err>(e));
    CHECK_FALSE(s.empty());
    CHECK(s != "unknown error code");
  }
  CHECK(std::string(mrqp_fw_err_str(outOfRangeEnum<mrqp_fw_err>(99))) == "unknown error code");
  CHECK(mrqp_fw_pack_failed(MRQP_FW_PACK_ERR_NAN));
  CHECK_FALSE(mrqp_fw_pack_failed(0x0000FFFFu));
}

TEST_CASE("frame lengths on the wire (design card figures)", "[firmware_if][bus]") {
  // Classic 8-byte data frame: 111 bits, 135 with worst-case stuffing.
  CHECK(mrqp_fw_bits_classic(8, 0).nominal_bits == 111u);
  CHECK(mrqp_fw_bits_classic(8, 1).nominal_bits == 135u);
  CHECK(mrqp_fw_bits_classic(0, 0).nominal_bits == 47u);
  CHECK(mrqp_fw_bits_classic(0, 1).nominal_bits == 55u);
  CHECK(mrqp_fw_bits_classic(6, 0).nominal_bits == 95u);
  CHECK(mrqp_fw_bits_classic(6, 1).nominal_bits == 115u);
  CHECK(mrqp_fw_bits_classic(8, 0).data_bits == 0u);
  // 111 us .. 135 us at 1 Mbit/s: 7407 .. 9009 frames/s.
  CHECK(mrqp_fw_frame_time_ns(mrqp_fw_bits_classic(8, 0), 1000000u, 0u) == 111000u);
  CHECK(mrqp_fw_frame_time_ns(mrqp_fw_bits_classic(8, 1), 1000000u, 0u) == 135000u);

  // CAN FD 64 bytes with BRS: 30 nominal + 549 data bits unstuffed.
  const mrqp_fw_frame_bits fd64 = mrqp_fw_bits_fd(64, 1, 0);
  CHECK(fd64.nominal_bits == 30u);
  CHECK(fd64.data_bits == 549u);
  CHECK(mrqp_fw_frame_time_ns(fd64, 1000000u, 5000000u) == 139800u);
  const mrqp_fw_frame_bits fd64w = mrqp_fw_bits_fd(64, 1, 1);
  CHECK(fd64w.nominal_bits == 34u);
  CHECK(fd64w.data_bits == 678u);
  CHECK(mrqp_fw_frame_time_ns(fd64w, 1000000u, 5000000u) == 169600u);
  // 8 bytes FD: CRC-17 and 6 fixed stuff bits.
  const mrqp_fw_frame_bits fd8 = mrqp_fw_bits_fd(8, 1, 0);
  CHECK(fd8.data_bits == 1u + 4u + 64u + 4u + 17u + 6u);
  // 32 bytes (force/torque FD frame): CRC-21.
  CHECK(mrqp_fw_bits_fd(32, 1, 0).data_bits == 1u + 4u + 256u + 4u + 21u + 7u);
  // Without BRS everything is nominal; lengths round up to valid FD lengths.
  CHECK(mrqp_fw_bits_fd(62, 0, 0).nominal_bits == 30u + 549u);
  CHECK(mrqp_fw_bits_fd(62, 0, 0).data_bits == 0u);
  CHECK(mrqp_fw_frame_time_ns(fd64, 0u, 5000000u) == 0xFFFFFFFFu);
}
