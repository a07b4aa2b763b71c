// Wrist force/torque sensor frames.
#include <catch2/catch.hpp>

#include "test_util.hpp"

#include <cmath>
#include <random>

using namespace fwtest;

namespace {
const mrqp_fw_ft_scale kClassic = MRQP_FW_FT_SCALE_CLASSIC_DEFAULT_INIT;  // 50 counts/N, 1000 counts/N m
const mrqp_fw_ft_scale kFd = MRQP_FW_FT_SCALE_FD_DEFAULT_INIT;            // 1e6 counts/N and /N m
}  // namespace

TEST_CASE("force/torque classic pair, byte-exact", "[firmware_if][ft]") {
  // fx 1 N -> 50 = 0x0032, fy -1 N -> -50 = 0xFFCE, fz 655 N -> 32750 = 0x7FEE,
  // mx 1 mN m -> 1, my -32 N m -> -32000 = 0x8300, mz 0.
  mrqp_fw_ft_sample s{{1.0, -1.0, 655.0, 0.001, -32.0, 0.0}, 7, MRQP_FW_FT_STATUS_TARED};
  mrqp_fw_frame f{};
  mrqp_fw_frame m{};
  REQUIRE(mrqp_fw_ft_pack_classic(&kClassic, 0x10, &s, &f, &m) == MRQP_FW_PACK_OK);
  CHECK(f.id == 0x190u);
  CHECK(m.id == 0x290u);
  CHECK(payload(f) == Bytes{0x32, 0x00, 0xCE, 0xFF, 0xEE, 0x7F, 0x07, 0x02});
  CHECK(payload(m) == Bytes{0x01, 0x00, 0x00, 0x83, 0x00, 0x00, 0x07, 0x02});

  mrqp_fw_ft_sample d{};
  REQUIRE(mrqp_fw_ft_unpack_classic(&kClassic, &f, &m, 0x10, &d) == MRQP_FW_OK);
  for (int a = 0; a < 6; ++a) {
    CHECK(d.wrench[a] == Approx(s.wrench[a]).margin(1e-12));
  }
  CHECK(d.seq == 7);
  CHECK(d.status == MRQP_FW_FT_STATUS_TARED);
}

TEST_CASE("force/torque classic: torn pairs are rejected", "[firmware_if][ft]") {
  mrqp_fw_ft_sample s{{1, 2, 3, 0.1, 0.2, 0.3}, 200, 0};
  mrqp_fw_frame f{};
  mrqp_fw_frame m{};
  REQUIRE(mrqp_fw_ft_pack_classic(&kClassic, 1, &s, &f, &m) == MRQP_FW_PACK_OK);
  s.seq = 201;
  mrqp_fw_frame f2{};
  mrqp_fw_frame m2{};
  REQUIRE(mrqp_fw_ft_pack_classic(&kClassic, 1, &s, &f2, &m2) == MRQP_FW_PACK_OK);
  mrqp_fw_ft_sample d{};
  CHECK(mrqp_fw_ft_unpack_classic(&kClassic, &f, &m2, 1, &d) == MRQP_FW_ERR_TORN);
  CHECK(mrqp_fw_ft_unpack_classic(&kClassic, &f2, &m, 1, &d) == MRQP_FW_ERR_TORN);
  CHECK(mrqp_fw_ft_unpack_classic(&kClassic, &f2, &m2, 1, &d) == MRQP_FW_OK);
  CHECK(d.seq == 201);
  // Same sequence, different status: also torn.
  mrqp_fw_frame m3 = m2;
  m3.data[7] = MRQP_FW_FT_STATUS_STALE;
  CHECK(mrqp_fw_ft_unpack_classic(&kClassic, &f2, &m3, 1, &d) == MRQP_FW_ERR_TORN);
  // Two halves of the wrong kind.
  CHECK(mrqp_fw_ft_unpack_classic(&kClassic, &f2, &f2, 1, &d) == MRQP_FW_ERR_ID);
  CHECK(mrqp_fw_ft_unpack_classic(&kClassic, &m2, &f2, 1, &d) == MRQP_FW_ERR_ID);
  mrqp_fw_ft_half h{};
  REQUIRE(mrqp_fw_ft_unpack_half(&kClassic, &m2, 1, &h) == MRQP_FW_OK);
  CHECK(h.moments == 1);
  CHECK(h.value[2] == Approx(0.3));
  CHECK(mrqp_fw_ft_unpack_half(&kClassic, &m2, 2, &h) == MRQP_FW_ERR_ID);
  mrqp_fw_frame bad = m2;
  bad.len = 7;
  CHECK(mrqp_fw_ft_unpack_half(&kClassic, &bad, 1, &h) == MRQP_FW_ERR_LENGTH);
  bad = m2;
  bad.data[7] = 0x80;  // reserved status bit
  CHECK(mrqp_fw_ft_unpack_half(&kClassic, &bad, 1, &h) == MRQP_FW_ERR_FORMAT);
}

TEST_CASE("force/torque classic: limits, saturation, NaN", "[firmware_if][ft]") {
  mrqp_fw_frame f{};
  mrqp_fw_frame m{};
  mrqp_fw_ft_sample d{};
  // i16 limits: 32767 / 50 = 655.34 N; -32768 / 1000 = -32.768 N m.
  mrqp_fw_ft_sample s{{655.34, -655.36, 0, 32.767, -32.768, 0}, 1, 0};
  REQUIRE(mrqp_fw_ft_pack_classic(&kClassic, 1, &s, &f, &m) == MRQP_FW_PACK_OK);
  CHECK(f.data[0] == 0xFF);
  CHECK(f.data[1] == 0x7F);
  CHECK(f.data[2] == 0x00);
  CHECK(f.data[3] == 0x80);
  CHECK(f.data[7] == 0);  // no over-range
  s = {{700.0, 0, -1e9, 0, 40.0, -infd()}, 2, 0};
  const mrqp_fw_pack_flags flags = mrqp_fw_ft_pack_classic(&kClassic, 1, &s, &f, &m);
  CHECK(flags == (MRQP_FW_FT_SAT_FX | MRQP_FW_FT_SAT_FZ | MRQP_FW_FT_SAT_MY | MRQP_FW_FT_SAT_MZ));
  CHECK(f.data[7] == MRQP_FW_FT_STATUS_OVERRANGE);  // announced to the host in both frames
  CHECK(m.data[7] == MRQP_FW_FT_STATUS_OVERRANGE);
  REQUIRE(mrqp_fw_ft_unpack_classic(&kClassic, &f, &m, 1, &d) == MRQP_FW_OK);
  CHECK(d.wrench[0] == Approx(655.34));
  CHECK(d.wrench[2] == Approx(-655.36));
  CHECK(d.wrench[4] == Approx(32.767));
  CHECK(d.wrench[5] == Approx(-32.768));

  // Quantisation error: half a count.
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> uf(-600, 600), um(-30, 30);
  for (int i = 0; i < 5000; ++i) {
    s = {{uf(rng), uf(rng), uf(rng), um(rng), um(rng), um(rng)}, static_cast<std::uint8_t>(i), 0};
    REQUIRE(mrqp_fw_ft_pack_classic(&kClassic, 1, &s, &f, &m) == MRQP_FW_PACK_OK);
    REQUIRE(mrqp_fw_ft_unpack_classic(&kClassic, &f, &m, 1, &d) == MRQP_FW_OK);
    for (int a = 0; a < 3; ++a) {
      REQUIRE(std::fabs(d.wrench[a] - s.wrench[a]) <= 0.5 / 50 + 1e-12);
      REQUIRE(std::fabs(d.wrench[a + 3] - s.wrench[a + 3]) <= 0.5 / 1000 + 1e-12);
    }
  }

  for (int a = 0; a < 6; ++a) {
    s = {{0, 0, 0, 0, 0, 0}, 0, 0};
    s.wrench[a] = nand();
    CHECK(mrqp_fw_ft_pack_classic(&kClassic, 1, &s, &f, &m) == MRQP_FW_PACK_ERR_NAN);
    CHECK(isCleared(f));
    CHECK(isCleared(m));
    CHECK(mrqp_fw_ft_pack_fd(&kFd, 1, &s, &f) == MRQP_FW_PACK_ERR_NAN);
    CHECK(isCleared(f));
  }
  s = {{0, 0, 0, 0, 0, 0}, 0, 0x20};  // reserved status bit
  CHECK(mrqp_fw_ft_pack_classic(&kClassic, 1, &s, &f, &m) == MRQP_FW_PACK_ERR_ARG);
  s.status = 0;
  CHECK(mrqp_fw_ft_pack_classic(&kClassic, 0, &s, &f, &m) == MRQP_FW_PACK_ERR_ARG);
  CHECK(mrqp_fw_ft_pack_classic(&kClassic, 1, &s, &f, &f) == MRQP_FW_PACK_ERR_ARG);
  const mrqp_fw_ft_scale bad{0.0, 1.0};
  CHECK(mrqp_fw_ft_scale_valid(&bad) == 0);
  CHECK(mrqp_fw_ft_pack_classic(&bad, 1, &s, &f, &m) == MRQP_FW_PACK_ERR_CONFIG);
  const mrqp_fw_ft_scale bad2{1.0, nand()};
  CHECK(mrqp_fw_ft_pack_fd(&bad2, 1, &s, &f) == MRQP_FW_PACK_ERR_CONFIG);
}

TEST_CASE("force/torque FD frame, byte-exact and validated", "[firmware_if][ft]") {
  // 1e6 counts per unit: fx 1 N -> 0x000F4240; fy -2.5 N -> -2500000 = 0xFFD9DA60;
  // fz 0; mx 0.000001 -> 1; my -1 -> 0xFFF0BDC0; mz 2147.483647 -> 0x7FFFFFFF.
  mrqp_fw_ft_sample s{{1.0, -2.5, 0.0, 0.000001, -1.0, 2147.483647}, 0xAB, MRQP_FW_FT_STATUS_TEMPERATURE};
  mrqp_fw_frame f{};
  REQUIRE(mrqp_fw_ft_pack_fd(&kFd, 3, &s, &f) == MRQP_FW_PACK_OK);
  CHECK(f.id == 0x183u);
  CHECK(f.flags == (MRQP_FW_FRAME_FD | MRQP_FW_FRAME_BRS));
  REQUIRE(f.len == 32);
  const Bytes body{0x40, 0x42, 0x0F, 0x00, 0x60, 0xDA, 0xD9, 0xFF, 0x00, 0x00, 0x00, 0x00, 0x01, 0x00, 0x00,
                   0x00, 0xC0, 0xBD, 0xF0, 0xFF, 0xFF, 0xFF, 0xFF, 0x7F, 0xAB, 0x04, 0x00, 0x00, 0x00, 0x00};
  CHECK(Bytes(f.data, f.data + 30) == body);
  const std::uint16_t crc = crc16Reference(body.data(), body.size());
  CHECK(f.data[30] == (crc >> 8));
  CHECK(f.data[31] == (crc & 0xFF));

  mrqp_fw_ft_sample d{};
  REQUIRE(mrqp_fw_ft_unpack_fd(&kFd, &f, 3, &d) == MRQP_FW_OK);
  for (int a = 0; a < 6; ++a) {
    CHECK(d.wrench[a] == Approx(s.wrench[a]).margin(1e-9));
  }
  CHECK(d.seq == 0xAB);
  CHECK(d.status == MRQP_FW_FT_STATUS_TEMPERATURE);

  mrqp_fw_frame g = f;
  g.data[5] ^= 0x10;
  CHECK(mrqp_fw_ft_unpack_fd(&kFd, &g, 3, &d) == MRQP_FW_ERR_CRC);
  g = f;
  g.flags = 0;
  CHECK(mrqp_fw_ft_unpack_fd(&kFd, &g, 3, &d) == MRQP_FW_ERR_FORMAT);
  CHECK(mrqp_fw_ft_unpack_fd(&kFd, &f, 4, &d) == MRQP_FW_ERR_ID);
  g = f;
  g.len = 48;
  CHECK(mrqp_fw_ft_unpack_fd(&kFd, &g, 3, &d) == MRQP_FW_ERR_LENGTH);
  g = f;
  g.data[27] = 1;  // padding
  refreshCrc(g);
  CHECK(mrqp_fw_ft_unpack_fd(&kFd, &g, 3, &d) == MRQP_FW_ERR_FORMAT);
  g = f;
  g.data[25] = 0x40;  // reserved status
  refreshCrc(g);
  CHECK(mrqp_fw_ft_unpack_fd(&kFd, &g, 3, &d) == MRQP_FW_ERR_FORMAT);

  // i32 saturation.
  s = {{3000.0, -3000.0, 0, 0, 0, 0}, 1, 0};
  CHECK(mrqp_fw_ft_pack_fd(&kFd, 3, &s, &f) == (MRQP_FW_FT_SAT_FX | MRQP_FW_FT_SAT_FY));
  CHECK(f.data[25] == MRQP_FW_FT_STATUS_OVERRANGE);
  REQUIRE(mrqp_fw_ft_unpack_fd(&kFd, &f, 3, &d) == MRQP_FW_OK);
  CHECK(d.wrench[0] == Approx(2147.483647));
  CHECK(d.wrench[1] == Approx(-2147.483648));
}

TEST_CASE("force/torque tare command", "[firmware_if][ft]") {
  mrqp_fw_frame f{};
  REQUIRE(mrqp_fw_ft_pack_tare(0x10, MRQP_FW_FT_CMD_TARE, &f) == MRQP_FW_PACK_OK);
  CHECK(f.id == 0x210u);
  CHECK(payload(f) == Bytes{0x01, 0xFE});
  std::uint8_t cmd = 9;
  REQUIRE(mrqp_fw_ft_unpack_tare(&f, 0x10, &cmd) == MRQP_FW_OK);
  CHECK(cmd == MRQP_FW_FT_CMD_TARE);
  REQUIRE(mrqp_fw_ft_pack_tare(0x10, MRQP_FW_FT_CMD_CLEAR_TARE, &f) == MRQP_FW_PACK_OK);
  CHECK(payload(f) == Bytes{0x00, 0xFF});
  REQUIRE(mrqp_fw_ft_unpack_tare(&f, 0x10, &cmd) == MRQP_FW_OK);
  CHECK(cmd == MRQP_FW_FT_CMD_CLEAR_TARE);

  CHECK(mrqp_fw_ft_pack_tare(0x10, 2, &f) == MRQP_FW_PACK_ERR_ARG);
  CHECK(isCleared(f));
  mrqp_fw_frame bad = makeFrame(0x210, {0x01, 0xFF});
  CHECK(mrqp_fw_ft_unpack_tare(&bad, 0x10, &cmd) == MRQP_FW_ERR_FORMAT);
  bad = makeFrame(0x210, {0x02, 0xFD});
  CHECK(mrqp_fw_ft_unpack_tare(&bad, 0x10, &cmd) == MRQP_FW_ERR_COMMAND);
  bad = makeFrame(0x211, {0x01, 0xFE});
  CHECK(mrqp_fw_ft_unpack_tare(&bad, 0x10, &cmd) == MRQP_FW_ERR_ID);
  bad = makeFrame(0x210, {0x01, 0xFE, 0x00});
  CHECK(mrqp_fw_ft_unpack_tare(&bad, 0x10, &cmd) == MRQP_FW_ERR_LENGTH);
}
