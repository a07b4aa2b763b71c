// Hand controller board: CAN FD setpoint and feedback frames.
#include <catch2/catch.hpp>

#include "test_util.hpp"

#include <cmath>
#include <random>

using namespace fwtest;

namespace {

const mrqp_fw_hand_scale kScale = MRQP_FW_HAND_SCALE_DEFAULT_INIT;

double halfStep(float lsb) {
  return 0.5 * static_cast<double>(lsb) * (1 + 1e-6) + 1e-6;  // + float rounding of the result
}

mrqp_fw_hand_cmd randomCmd(std::mt19937& rng, unsigned count) {
  std::uniform_real_distribution<float> up(-3.2f, 3.2f), uv(-40.0f, 40.0f), ut(-2.0f, 2.0f);
  mrqp_fw_hand_cmd c{};
  c.seq = static_cast<std::uint16_t>(rng());
  c.mode = MRQP_FW_HAND_MODE_POSITION;
  c.first_joint = static_cast<std::uint8_t>(rng() % (MRQP_FW_HAND_MAX_JOINTS - count + 1));
  c.count = static_cast<std::uint8_t>(count);
  for (unsigned j = 0; j < count; ++j) {
    c.joint[j] = {up(rng), uv(rng), ut(rng)};
  }
  return c;
}

}  // namespace

TEST_CASE("hand FD frame lengths and joints per frame", "[firmware_if][hand]") {
  // 5-byte header + 5 bytes per joint + 2 CRC, rounded up to a CAN FD length.
  const unsigned cmd_len[] = {7, 12, 20, 24, 32, 32, 48, 48, 48, 64, 64, 64};
  const unsigned fb_len[] = {12, 16, 20, 24, 32, 48, 48, 48, 64, 64, 64, 64};
  for (unsigned n = 0; n <= 11; ++n) {
    CHECK(mrqp_fw_hand_cmd_len(n) == cmd_len[n]);
    CHECK(mrqp_fw_hand_fb_len(n) == fb_len[n]);
  }
  CHECK(mrqp_fw_hand_cmd_len(12) == 0);
  CHECK(mrqp_fw_hand_fb_len(12) == 0);
  // 11 is the most that fits 64 bytes in both directions.
  CHECK(MRQP_FW_HAND_FD_CMD_HEADER_LEN + 11 * MRQP_FW_HAND_FD_JOINT_LEN + MRQP_FW_HAND_FD_CRC_LEN <= 64u);
  CHECK(MRQP_FW_HAND_FD_CMD_HEADER_LEN + 12 * MRQP_FW_HAND_FD_JOINT_LEN + MRQP_FW_HAND_FD_CRC_LEN > 64u);
  CHECK(MRQP_FW_HAND_FD_FB_HEADER_LEN + 11 * MRQP_FW_HAND_FD_JOINT_LEN + MRQP_FW_HAND_FD_CRC_LEN == 64u);
  CHECK(MRQP_FW_HAND_FD_MAX_JOINTS == 11u);
  CHECK(mrqp_fw_hand_frames_needed(0) == 0);
  CHECK(mrqp_fw_hand_frames_needed(11) == 1);
  CHECK(mrqp_fw_hand_frames_needed(12) == 2);
  CHECK(mrqp_fw_hand_frames_needed(20) == 2);
  CHECK(mrqp_fw_hand_frames_needed(22) == 2);
  CHECK(mrqp_fw_hand_frames_needed(23) == 3);
}

TEST_CASE("hand FD command, byte-exact", "[firmware_if][hand]") {
  // board 2, seq 0x1234, mode position, first joint 3, one joint:
  // p = 1.0 rad -> 10000 = 0x2710; v = -0.02 rad/s -> -1 = 0xFFF; t = 0.5 N m -> 500 = 0x1F4
  mrqp_fw_hand_cmd c{};
  c.seq = 0x1234;
  c.mode = MRQP_FW_HAND_MODE_POSITION;
  c.first_joint = 3;
  c.count = 1;
  c.joint[0] = {1.0f, -0.02f, 0.5f};
  mrqp_fw_frame f{};
  std::uint32_t sat = 99;
  REQUIRE(mrqp_fw_hand_pack_cmd(&kScale, 2, &c, &f, &sat) == MRQP_FW_PACK_OK);
  CHECK(sat == 0);
  CHECK(f.id == 0x122u);
  CHECK(f.flags == (MRQP_FW_FRAME_FD | MRQP_FW_FRAME_BRS));
  REQUIRE(f.len == 12);
  const Bytes head{0x12, 0x34, 0x11, 0x03, 0x01, 0x27, 0x10, 0xFF, 0xF1, 0xF4};
  CHECK(Bytes(f.data, f.data + 10) == head);
  const std::uint16_t crc = crc16Reference(head.data(), head.size());
  CHECK(f.data[10] == (crc >> 8));
  CHECK(f.data[11] == (crc & 0xFF));

  mrqp_fw_hand_cmd d{};
  REQUIRE(mrqp_fw_hand_unpack_cmd(&kScale, &f, 2, &d) == MRQP_FW_OK);
  CHECK(d.seq == 0x1234);
  CHECK(d.mode == MRQP_FW_HAND_MODE_POSITION);
  CHECK(d.first_joint == 3);
  CHECK(d.count == 1);
  CHECK(d.joint[0].position == Approx(1.0f).margin(1e-6));
  CHECK(d.joint[0].velocity == Approx(-0.02f).margin(1e-6));
  CHECK(d.joint[0].torque == Approx(0.5f).margin(1e-6));

  // Zero joints (mode change only): 7 bytes, still an FD frame.
  c.count = 0;
  c.mode = MRQP_FW_HAND_MODE_DISABLED;
  REQUIRE(mrqp_fw_hand_pack_cmd(&kScale, 2, &c, &f, nullptr) == MRQP_FW_PACK_OK);
  CHECK(f.len == 7);
  REQUIRE(mrqp_fw_hand_unpack_cmd(&kScale, &f, 2, &d) == MRQP_FW_OK);
  CHECK(d.count == 0);
  CHECK(d.mode == MRQP_FW_HAND_MODE_DISABLED);
}

TEST_CASE("hand FD feedback, byte-exact", "[firmware_if][hand]") {
  mrqp_fw_hand_fb b{};
  b.cmd_seq_echo = 0xBEEF;
  b.counter = 0x42;
  b.mode = MRQP_FW_HAND_MODE_TORQUE;
  b.status = MRQP_FW_HAND_STATUS_ENABLED | MRQP_FW_HAND_STATUS_LIMIT;
  b.first_joint = 0;
  b.count = 2;
  b.joint[0] = {-1.0f, 0.04f, -0.001f};  // -10000 = D8F0, 2 = 002, -1 = FFF
  b.joint[1] = {0.0f, 0.0f, 2.047f};     // 0000, 000, 2047 = 7FF
  mrqp_fw_frame f{};
  REQUIRE(mrqp_fw_hand_pack_fb(&kScale, 15, &b, &f, nullptr) == MRQP_FW_PACK_OK);
  CHECK(f.id == 0x14Fu);
  REQUIRE(f.len == 20);
  const Bytes body{0xBE, 0xEF, 0x42, 0x12, 0x21, 0x00, 0x02, 0xD8, 0xF0,
                   0x00, 0x2F, 0xFF, 0x00, 0x00, 0x00, 0x07, 0xFF, 0x00};  // 17 used + 1 padding
  CHECK(Bytes(f.data, f.data + 18) == body);
  const std::uint16_t crc = crc16Reference(body.data(), body.size());
  CHECK(f.data[18] == (crc >> 8));
  CHECK(f.data[19] == (crc & 0xFF));

  mrqp_fw_hand_fb d{};
  REQUIRE(mrqp_fw_hand_unpack_fb(&kScale, &f, 15, &d) == MRQP_FW_OK);
  CHECK(d.cmd_seq_echo == 0xBEEF);
  CHECK(d.counter == 0x42);
  CHECK(d.mode == MRQP_FW_HAND_MODE_TORQUE);
  CHECK(d.status == (MRQP_FW_HAND_STATUS_ENABLED | MRQP_FW_HAND_STATUS_LIMIT));
  CHECK(d.count == 2);
  CHECK(d.joint[1].torque == Approx(2.047f));
}

TEST_CASE("hand FD round trips for every joint count stay within half a step", "[firmware_if][hand]") {
  std::mt19937 rng(2024);
  mrqp_fw_frame f{};
  for (int iter = 0; iter < 300; ++iter) {
    for (unsigned n = 0; n <= MRQP_FW_HAND_FD_MAX_JOINTS; ++n) {
      const mrqp_fw_hand_cmd c = randomCmd(rng, n);
      REQUIRE(mrqp_fw_hand_pack_cmd(&kScale, 1, &c, &f, nullptr) == MRQP_FW_PACK_OK);
      REQUIRE(f.len == mrqp_fw_hand_cmd_len(n));
      mrqp_fw_hand_cmd d{};
      REQUIRE(mrqp_fw_hand_unpack_cmd(&kScale, &f, 1, &d) == MRQP_FW_OK);
      REQUIRE(d.seq == c.seq);
      REQUIRE(d.first_joint == c.first_joint);
      for (unsigned j = 0; j < n; ++j) {
        REQUIRE(std::fabs(d.joint[j].position - c.joint[j].position) <= halfStep(kScale.position_lsb));
        REQUIRE(std::fabs(d.joint[j].velocity - c.joint[j].velocity) <= halfStep(kScale.velocity_lsb));
        REQUIRE(std::fabs(d.joint[j].torque - c.joint[j].torque) <= halfStep(kScale.torque_lsb));
      }

      mrqp_fw_hand_fb b{};
      b.cmd_seq_echo = c.seq;
      b.counter = static_cast<std::uint8_t>(iter);
      b.mode = c.mode;
      b.status = MRQP_FW_HAND_STATUS_ENABLED;
      b.first_joint = c.first_joint;
      b.count = c.count;
      for (unsigned j = 0; j < n; ++j) {
        b.joint[j] = c.joint[j];
      }
      REQUIRE(mrqp_fw_hand_pack_fb(&kScale, 1, &b, &f, nullptr) == MRQP_FW_PACK_OK);
      mrqp_fw_hand_fb bd{};
      REQUIRE(mrqp_fw_hand_unpack_fb(&kScale, &f, 1, &bd) == MRQP_FW_OK);
      for (unsigned j = 0; j < n; ++j) {
        REQUIRE(std::fabs(bd.joint[j].torque - b.joint[j].torque) <= halfStep(kScale.torque_lsb));
      }
    }
  }
}

TEST_CASE("hand FD limits: saturation per field and per joint, NaN rejected", "[firmware_if][hand]") {
  mrqp_fw_hand_cmd c{};
  c.mode = MRQP_FW_HAND_MODE_POSITION;
  c.count = 4;
  c.joint[0] = {3.2767f, 40.94f, 2.047f};     // the largest codes: in range
  c.joint[1] = {-3.2767f, -40.94f, -2.047f};  // the smallest codes: in range
  c.joint[2] = {3.3f, 0.0f, 0.0f};            // position beyond
  c.joint[3] = {0.0f, -inff(), 2.1f};         // velocity and torque beyond
  mrqp_fw_frame f{};
  std::uint32_t sat = 0;
  const mrqp_fw_pack_flags flags = mrqp_fw_hand_pack_cmd(&kScale, 0, &c, &f, &sat);
  CHECK(flags == (MRQP_FW_HAND_SAT_POSITION | MRQP_FW_HAND_SAT_VELOCITY | MRQP_FW_HAND_SAT_TORQUE));
  CHECK(sat == 0xCu);
  // Codes: joint 0 7FFF 7FF 7FF, joint 1 8001 801 801, joint 2 7FFF, joint 3 v 801 t 7FF.
  CHECK(Bytes(f.data + 5, f.data + 10) == Bytes{0x7F, 0xFF, 0x7F, 0xF7, 0xFF});
  CHECK(Bytes(f.data + 10, f.data + 15) == Bytes{0x80, 0x01, 0x80, 0x18, 0x01});
  CHECK(Bytes(f.data + 15, f.data + 17) == Bytes{0x7F, 0xFF});
  CHECK(Bytes(f.data + 22, f.data + 25) == Bytes{0x80, 0x17, 0xFF});
  mrqp_fw_hand_cmd d{};
  REQUIRE(mrqp_fw_hand_unpack_cmd(&kScale, &f, 0, &d) == MRQP_FW_OK);
  CHECK(d.joint[2].position == Approx(3.2767f));
  CHECK(d.joint[3].velocity == Approx(-40.94f));
  CHECK(d.joint[3].torque == Approx(2.047f));

  for (int field = 0; field < 3; ++field) {
    mrqp_fw_hand_cmd n = c;
    float* fields[] = {&n.joint[3].position, &n.joint[3].velocity, &n.joint[3].torque};
    *fields[field] = nanf();
    sat = 123;
    CHECK(mrqp_fw_hand_pack_cmd(&kScale, 0, &n, &f, &sat) == MRQP_FW_PACK_ERR_NAN);
    CHECK(isCleared(f));
    CHECK(sat == 0);
  }
  // A NaN beyond `count` is not part of the frame.
  mrqp_fw_hand_cmd tail = c;
  tail.joint[10].position = nanf();
  CHECK_FALSE(mrqp_fw_pack_failed(mrqp_fw_hand_pack_cmd(&kScale, 0, &tail, &f, nullptr)));
}

TEST_CASE("hand FD pack refuses bad arguments and configuration", "[firmware_if][hand]") {
  mrqp_fw_hand_cmd c{};
  c.count = 1;
  mrqp_fw_frame f{};
  CHECK(mrqp_fw_hand_pack_cmd(&kScale, 16, &c, &f, nullptr) == MRQP_FW_PACK_ERR_ARG);
  CHECK(isCleared(f));
  c.count = 12;
  CHECK(mrqp_fw_hand_pack_cmd(&kScale, 0, &c, &f, nullptr) == MRQP_FW_PACK_ERR_ARG);
  c.count = 3;
  c.first_joint = 30;
  CHECK(mrqp_fw_hand_pack_cmd(&kScale, 0, &c, &f, nullptr) == MRQP_FW_PACK_ERR_ARG);
  c.first_joint = 29;
  CHECK(mrqp_fw_hand_pack_cmd(&kScale, 0, &c, &f, nullptr) == MRQP_FW_PACK_OK);
  c.mode = 4;
  CHECK(mrqp_fw_hand_pack_cmd(&kScale, 0, &c, &f, nullptr) == MRQP_FW_PACK_ERR_ARG);
  c.mode = MRQP_FW_HAND_MODE_HOLD;
  mrqp_fw_hand_scale bad = kScale;
  bad.velocity_lsb = 0.0f;
  CHECK(mrqp_fw_hand_scale_valid(&bad) == 0);
  CHECK(mrqp_fw_hand_pack_cmd(&bad, 0, &c, &f, nullptr) == MRQP_FW_PACK_ERR_CONFIG);
  bad = kScale;
  bad.torque_lsb = nanf();
  CHECK(mrqp_fw_hand_pack_cmd(&bad, 0, &c, &f, nullptr) == MRQP_FW_PACK_ERR_CONFIG);
  CHECK(mrqp_fw_hand_pack_cmd(&kScale, 0, nullptr, &f, nullptr) == MRQP_FW_PACK_ERR_ARG);

  mrqp_fw_hand_fb b{};
  b.status = 0x40;  // reserved bit
  CHECK(mrqp_fw_hand_pack_fb(&kScale, 0, &b, &f, nullptr) == MRQP_FW_PACK_ERR_ARG);
  CHECK(isCleared(f));
}

TEST_CASE("hand FD unpack rejects corrupted and malformed frames", "[firmware_if][hand]") {
  std::mt19937 rng(5);
  const mrqp_fw_hand_cmd c = randomCmd(rng, 9);
  mrqp_fw_frame good{};
  REQUIRE(mrqp_fw_hand_pack_cmd(&kScale, 4, &c, &good, nullptr) == MRQP_FW_PACK_OK);
  REQUIRE(good.len == 64);
  mrqp_fw_hand_cmd d{};
  REQUIRE(mrqp_fw_hand_unpack_cmd(&kScale, &good, 4, &d) == MRQP_FW_OK);

  // Every single-bit error is caught (CRC-16 detects all of them).
  for (unsigned bit = 0; bit < 8u * good.len; ++bit) {
    mrqp_fw_frame f = good;
    f.data[bit / 8] = static_cast<std::uint8_t>(f.data[bit / 8] ^ (0x80u >> (bit % 8)));
    REQUIRE(mrqp_fw_hand_unpack_cmd(&kScale, &f, 4, &d) == MRQP_FW_ERR_CRC);
  }
  mrqp_fw_frame f = good;
  f.flags = 0;
  CHECK(mrqp_fw_hand_unpack_cmd(&kScale, &f, 4, &d) == MRQP_FW_ERR_FORMAT);
  f = good;
  f.flags |= MRQP_FW_FRAME_EXT;
  CHECK(mrqp_fw_hand_unpack_cmd(&kScale, &f, 4, &d) == MRQP_FW_ERR_FORMAT);
  CHECK(mrqp_fw_hand_unpack_cmd(&kScale, &good, 5, &d) == MRQP_FW_ERR_ID);
  CHECK(mrqp_fw_hand_unpack_cmd(&kScale, &good, 16, &d) == MRQP_FW_ERR_ID);
  mrqp_fw_hand_fb fb{};
  CHECK(mrqp_fw_hand_unpack_fb(&kScale, &good, 4, &fb) == MRQP_FW_ERR_ID);  // a command is not feedback
  f = good;
  f.len = 48;
  CHECK(mrqp_fw_hand_unpack_cmd(&kScale, &f, 4, &d) == MRQP_FW_ERR_CRC);
  f = good;
  f.len = 6;
  CHECK(mrqp_fw_hand_unpack_cmd(&kScale, &f, 4, &d) == MRQP_FW_ERR_LENGTH);
  // Edits with a correct CRC: the content checks must catch them.
  f = good;
  f.data[2] = static_cast<std::uint8_t>(0x20 | MRQP_FW_HAND_MODE_POSITION);  // version 2
  refreshCrc(f);
  CHECK(mrqp_fw_hand_unpack_cmd(&kScale, &f, 4, &d) == MRQP_FW_ERR_VERSION);
  f = good;
  f.data[2] = 0x15;  // mode 5
  refreshCrc(f);
  CHECK(mrqp_fw_hand_unpack_cmd(&kScale, &f, 4, &d) == MRQP_FW_ERR_RANGE);
  f = good;
  f.data[4] = 12;  // count beyond 11
  refreshCrc(f);
  CHECK(mrqp_fw_hand_unpack_cmd(&kScale, &f, 4, &d) == MRQP_FW_ERR_LENGTH);
  f = good;
  f.data[4] = 5;  // 5 joints need 32 bytes, not 64
  refreshCrc(f);
  CHECK(mrqp_fw_hand_unpack_cmd(&kScale, &f, 4, &d) == MRQP_FW_ERR_LENGTH);
  f = good;
  f.data[3] = 30;  // first 30 + 9 joints > 32
  refreshCrc(f);
  CHECK(mrqp_fw_hand_unpack_cmd(&kScale, &f, 4, &d) == MRQP_FW_ERR_RANGE);
  f = good;
  f.data[5 + 45] = 0x01;  // padding byte
  refreshCrc(f);
  CHECK(mrqp_fw_hand_unpack_cmd(&kScale, &f, 4, &d) == MRQP_FW_ERR_FORMAT);
  f = good;
  f.data[5] = 0x80;  // position code 0x8000 of joint 0 is reserved
  f.data[6] = 0x00;
  refreshCrc(f);
  CHECK(mrqp_fw_hand_unpack_cmd(&kScale, &f, 4, &d) == MRQP_FW_ERR_RANGE);
  f = good;
  f.data[5 + 5 * 8 + 2] = 0x80;  // velocity code 0x800 of joint 8
  f.data[5 + 5 * 8 + 3] = static_cast<std::uint8_t>(f.data[5 + 5 * 8 + 3] & 0x0F);
  refreshCrc(f);
  CHECK(mrqp_fw_hand_unpack_cmd(&kScale, &f, 4, &d) == MRQP_FW_ERR_RANGE);
  mrqp_fw_hand_scale bad = kScale;
  bad.position_lsb = -1.0f;
  CHECK(mrqp_fw_hand_unpack_cmd(&bad, &good, 4, &d) == MRQP_FW_ERR_CONFIG);
  CHECK(mrqp_fw_hand_unpack_cmd(&kScale, nullptr, 4, &d) == MRQP_FW_ERR_NULL);
  CHECK(mrqp_fw_hand_unpack_cmd(&kScale, &good, 4, nullptr) == MRQP_FW_ERR_NULL);

  // Feedback: reserved status bits.
  mrqp_fw_hand_fb b{};
  b.count = 1;
  mrqp_fw_frame g{};
  REQUIRE(mrqp_fw_hand_pack_fb(&kScale, 4, &b, &g, nullptr) == MRQP_FW_PACK_OK);
  g.data[4] = 0x80;
  refreshCrc(g);
  CHECK(mrqp_fw_hand_unpack_fb(&kScale, &g, 4, &fb) == MRQP_FW_ERR_FORMAT);
}
