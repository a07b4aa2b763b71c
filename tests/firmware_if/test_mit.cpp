// Hand drives: MIT-mode impedance frames.
#include <catch2/catch.hpp>

#include "test_util.hpp"

#include <cmath>
#include <random>

using namespace fwtest;

namespace {

const mrqp_fw_mit_ranges kDefault = MRQP_FW_MIT_RANGES_DEFAULT_INIT;

// Largest decoding error of a field that was not saturated: half a step, plus float rounding of
// the decoded value.
double bound(float lo, float hi, unsigned bits) {
  const double step = (static_cast<double>(hi) - lo) / ((1u << bits) - 1u);
  const double mag = std::max(std::fabs(lo), std::fabs(hi));
  return 0.5 * step + 4.0 * mag * 1.2e-7;
}

}  // namespace

TEST_CASE("MIT special commands, byte-exact", "[firmware_if][mit]") {
  mrqp_fw_frame f{};
  REQUIRE(mrqp_fw_mit_pack_special(1, MRQP_FW_MIT_KIND_ENABLE, &f) == MRQP_FW_PACK_OK);
  CHECK(f.id == 1u);
  CHECK(f.flags == 0);
  CHECK(payload(f) == Bytes{0xFF, 0xFF, 0xFF, 0xFF, 0xFF, 0xFF, 0xFF, 0xFC});
  CHECK(mrqp_fw_mit_classify(&f) == MRQP_FW_MIT_KIND_ENABLE);
  REQUIRE(mrqp_fw_mit_pack_special(2, MRQP_FW_MIT_KIND_DISABLE, &f) == MRQP_FW_PACK_OK);
  CHECK(f.id == 2u);
  CHECK(payload(f) == Bytes{0xFF, 0xFF, 0xFF, 0xFF, 0xFF, 0xFF, 0xFF, 0xFD});
  CHECK(mrqp_fw_mit_classify(&f) == MRQP_FW_MIT_KIND_DISABLE);
  REQUIRE(mrqp_fw_mit_pack_special(127, MRQP_FW_MIT_KIND_ZERO, &f) == MRQP_FW_PACK_OK);
  CHECK(payload(f) == Bytes{0xFF, 0xFF, 0xFF, 0xFF, 0xFF, 0xFF, 0xFF, 0xFE});
  CHECK(mrqp_fw_mit_classify(&f) == MRQP_FW_MIT_KIND_ZERO);

  mrqp_fw_mit_cmd cmd{};
  CHECK(mrqp_fw_mit_unpack_cmd(&kDefault, &f, nullptr, &cmd) == MRQP_FW_ERR_COMMAND);
  CHECK(mrqp_fw_mit_pack_special(0, MRQP_FW_MIT_KIND_ENABLE, &f) == MRQP_FW_PACK_ERR_ARG);
  CHECK(isCleared(f));
  CHECK(mrqp_fw_mit_pack_special(1, MRQP_FW_MIT_KIND_COMMAND, &f) == MRQP_FW_PACK_ERR_ARG);
  f = makeFrame(1, {0xFF, 0xFF, 0xFF, 0xFF, 0xFF, 0xFF, 0xFF, 0xFF});
  CHECK(mrqp_fw_mit_classify(&f) == MRQP_FW_MIT_KIND_COMMAND);
  f = makeFrame(1, {0xFF, 0xFF, 0xFF, 0xFF, 0xFF, 0xFF, 0xFF});
  CHECK(mrqp_fw_mit_classify(&f) == MRQP_FW_MIT_KIND_INVALID);
  f = makeFrame(0, {0xFF, 0xFF, 0xFF, 0xFF, 0xFF, 0xFF, 0xFF, 0xFC});
  CHECK(mrqp_fw_mit_classify(&f) == MRQP_FW_MIT_KIND_INVALID);
  CHECK(mrqp_fw_mit_classify(nullptr) == MRQP_FW_MIT_KIND_INVALID);
}

TEST_CASE("MIT command encodings computed by hand", "[firmware_if][mit]") {
  mrqp_fw_frame f{};
  // p = 0   -> (0 + 12.5) / 25 * 65535 = 32767.5 -> 32768 = 0x8000
  // v = 0   -> 65 / 130 * 4095 = 2047.5 -> 2048 = 0x800
  // kp = 100 -> 100 / 500 * 4095 = 819 = 0x333
  // kd = 1   -> 1 / 5 * 4095 = 819 = 0x333
  // t = 0   -> 0x800
  // bits: 8000 | 800 | 333 | 333 | 800 -> 80 00 80 03 33 33 38 00
  mrqp_fw_mit_cmd cmd{0.0f, 0.0f, 100.0f, 1.0f, 0.0f};
  REQUIRE(mrqp_fw_mit_pack_cmd(&kDefault, 3, &cmd, &f) == MRQP_FW_PACK_OK);
  CHECK(f.id == 3u);
  CHECK(f.flags == 0);
  CHECK(payload(f) == Bytes{0x80, 0x00, 0x80, 0x03, 0x33, 0x33, 0x38, 0x00});

  // All minima -> all-zero codes.
  cmd = {-12.5f, -65.0f, 0.0f, 0.0f, -18.0f};
  REQUIRE(mrqp_fw_mit_pack_cmd(&kDefault, 3, &cmd, &f) == MRQP_FW_PACK_OK);
  CHECK(payload(f) == Bytes{0, 0, 0, 0, 0, 0, 0, 0});
  // All maxima -> all-one codes (FF x 8 is not a special command).
  cmd = {12.5f, 65.0f, 500.0f, 5.0f, 18.0f};
  REQUIRE(mrqp_fw_mit_pack_cmd(&kDefault, 3, &cmd, &f) == MRQP_FW_PACK_OK);
  CHECK(payload(f) == Bytes{0xFF, 0xFF, 0xFF, 0xFF, 0xFF, 0xFF, 0xFF, 0xFF});
  CHECK(mrqp_fw_mit_classify(&f) == MRQP_FW_MIT_KIND_COMMAND);

  // p = 12.5 (FFFF), v = -65 (000), kp = 500 (FFF), kd = 0 (000), t = -18 (000):
  // FFFF | 000 | FFF | 000 | 000 -> FF FF 00 0F FF 00 00 00
  cmd = {12.5f, -65.0f, 500.0f, 0.0f, -18.0f};
  REQUIRE(mrqp_fw_mit_pack_cmd(&kDefault, 3, &cmd, &f) == MRQP_FW_PACK_OK);
  CHECK(payload(f) == Bytes{0xFF, 0xFF, 0x00, 0x0F, 0xFF, 0x00, 0x00, 0x00});
}

TEST_CASE("an impedance command never spells a special command", "[firmware_if][mit]") {
  mrqp_fw_frame f{};
  for (std::uint32_t code : {0xFFCu, 0xFFDu, 0xFFEu}) {
    const float t = static_cast<float>(-18.0 + 36.0 * code / 4095.0);
    mrqp_fw_mit_cmd cmd{12.5f, 65.0f, 500.0f, 5.0f, t};
    REQUIRE(mrqp_fw_mit_pack_cmd(&kDefault, 9, &cmd, &f) == MRQP_FW_MIT_ADJ_SPECIAL);
    CHECK(payload(f) == Bytes{0xFF, 0xFF, 0xFF, 0xFF, 0xFF, 0xFF, 0xFF, 0xFB});
    CHECK(mrqp_fw_mit_classify(&f) == MRQP_FW_MIT_KIND_COMMAND);
  }
  // One field below its maximum: no adjustment needed.
  mrqp_fw_mit_cmd cmd{12.5f, 65.0f, 500.0f, 4.9f, static_cast<float>(-18.0 + 36.0 * 0xFFC / 4095.0)};
  CHECK(mrqp_fw_mit_pack_cmd(&kDefault, 9, &cmd, &f) == MRQP_FW_PACK_OK);
}

TEST_CASE("MIT reply, byte-exact", "[firmware_if][mit]") {
  mrqp_fw_frame f{};
  const mrqp_fw_mit_reply r{1, 0.0f, 0.0f, 0.0f};
  REQUIRE(mrqp_fw_mit_pack_reply(&kDefault, &r, &f) == MRQP_FW_PACK_OK);
  CHECK(f.id == 0u);
  CHECK(payload(f) == Bytes{0x01, 0x80, 0x00, 0x80, 0x08, 0x00});
  mrqp_fw_mit_reply d{};
  REQUIRE(mrqp_fw_mit_unpack_reply(&kDefault, &f, &d) == MRQP_FW_OK);
  CHECK(d.motor_id == 1);
  CHECK(std::fabs(d.p) <= bound(-12.5f, 12.5f, 16));
  CHECK(std::fabs(d.v) <= bound(-65.0f, 65.0f, 12));

  // Hand-decoded reply: id 7, p 0xFFFF, v 0x000, t 0xFFF.
  f = makeFrame(0x000, {0x07, 0xFF, 0xFF, 0x00, 0x0F, 0xFF});
  REQUIRE(mrqp_fw_mit_unpack_reply(&kDefault, &f, &d) == MRQP_FW_OK);
  CHECK(d.motor_id == 7);
  CHECK(d.p == Approx(12.5f));
  CHECK(d.v == Approx(-65.0f));
  CHECK(d.t == Approx(18.0f));

  f = makeFrame(0x000, {0x00, 0, 0, 0, 0, 0});
  CHECK(mrqp_fw_mit_unpack_reply(&kDefault, &f, &d) == MRQP_FW_ERR_RANGE);
  f = makeFrame(0x000, {0x80, 0, 0, 0, 0, 0});
  CHECK(mrqp_fw_mit_unpack_reply(&kDefault, &f, &d) == MRQP_FW_ERR_RANGE);
  f = makeFrame(0x001, {0x01, 0, 0, 0, 0, 0});
  CHECK(mrqp_fw_mit_unpack_reply(&kDefault, &f, &d) == MRQP_FW_ERR_ID);
  f = makeFrame(0x000, {0x01, 0, 0, 0, 0, 0, 0, 0});
  CHECK(mrqp_fw_mit_unpack_reply(&kDefault, &f, &d) == MRQP_FW_ERR_LENGTH);
  f = makeFrame(0x000, {0x01, 0, 0, 0, 0, 0}, MRQP_FW_FRAME_FD);
  CHECK(mrqp_fw_mit_unpack_reply(&kDefault, &f, &d) == MRQP_FW_ERR_FORMAT);
}

TEST_CASE("MIT round trips stay within half a step; limits saturate and are flagged", "[firmware_if][mit]") {
  std::mt19937 rng(42);
  std::uniform_real_distribution<float> up(-12.5f, 12.5f), uv(-65.0f, 65.0f), ukp(0.0f, 500.0f),
      ukd(0.0f, 5.0f), ut(-18.0f, 18.0f);
  mrqp_fw_frame f{};
  for (int i = 0; i < 20000; ++i) {
    const mrqp_fw_mit_cmd c{up(rng), uv(rng), ukp(rng), ukd(rng), ut(rng)};
    REQUIRE(mrqp_fw_mit_pack_cmd(&kDefault, 5, &c, &f) == MRQP_FW_PACK_OK);
    mrqp_fw_mit_cmd d{};
    std::uint8_t id = 0;
    REQUIRE(mrqp_fw_mit_unpack_cmd(&kDefault, &f, &id, &d) == MRQP_FW_OK);
    REQUIRE(id == 5);
    REQUIRE(std::fabs(d.p - c.p) <= bound(-12.5f, 12.5f, 16));
    REQUIRE(std::fabs(d.v - c.v) <= bound(-65.0f, 65.0f, 12));
    REQUIRE(std::fabs(d.kp - c.kp) <= bound(0.0f, 500.0f, 12));
    REQUIRE(std::fabs(d.kd - c.kd) <= bound(0.0f, 5.0f, 12));
    REQUIRE(std::fabs(d.t - c.t) <= bound(-18.0f, 18.0f, 12));

    const mrqp_fw_mit_reply r{5, c.p, c.v, c.t};
    REQUIRE(mrqp_fw_mit_pack_reply(&kDefault, &r, &f) == MRQP_FW_PACK_OK);
    mrqp_fw_mit_reply rd{};
    REQUIRE(mrqp_fw_mit_unpack_reply(&kDefault, &f, &rd) == MRQP_FW_OK);
    REQUIRE(std::fabs(rd.t - c.t) <= bound(-18.0f, 18.0f, 12));
  }

  // Decoding every code and re-encoding it gives the code back (the map is consistent).
  for (std::uint32_t code = 0; code < 4096; ++code) {
    f = makeFrame(2, {0x12, 0x34, static_cast<std::uint8_t>(code >> 4),
                      static_cast<std::uint8_t>((code & 0xF) << 4), 0, 0, 0, 0});
    mrqp_fw_mit_cmd d{};
    REQUIRE(mrqp_fw_mit_unpack_cmd(&kDefault, &f, nullptr, &d) == MRQP_FW_OK);
    mrqp_fw_frame g{};
    REQUIRE(mrqp_fw_mit_pack_cmd(&kDefault, 2, &d, &g) == MRQP_FW_PACK_OK);
    REQUIRE(payload(g) == payload(f));
  }

  const double pstep = 25.0 / 65535.0;
  struct Case {
    mrqp_fw_mit_cmd cmd;
    mrqp_fw_pack_flags flags;
  };
  const Case cases[] = {
      {{static_cast<float>(12.5 + 2 * pstep), 0, 0, 0, 0}, MRQP_FW_MIT_SAT_P},
      {{static_cast<float>(12.5 + 0.3 * pstep), 0, 0, 0, 0}, MRQP_FW_PACK_OK},  // within half a step
      {{-13.0f, 0, 0, 0, 0}, MRQP_FW_MIT_SAT_P},
      {{0, 65.1f, 0, 0, 0}, MRQP_FW_MIT_SAT_V},
      {{0, -1000.0f, 0, 0, 0}, MRQP_FW_MIT_SAT_V},
      {{0, 0, -1.0f, 0, 0}, MRQP_FW_MIT_SAT_KP},
      {{0, 0, 501.0f, 0, 0}, MRQP_FW_MIT_SAT_KP},
      {{0, 0, 0, 5.01f, 0}, MRQP_FW_MIT_SAT_KD},
      {{0, 0, 0, 0, -18.1f}, MRQP_FW_MIT_SAT_T},
      {{0, 0, 0, 0, inff()}, MRQP_FW_MIT_SAT_T},
      {{inff(), -inff(), 1e30f, -1e30f, 19.0f},
       MRQP_FW_MIT_SAT_P | MRQP_FW_MIT_SAT_V | MRQP_FW_MIT_SAT_KP | MRQP_FW_MIT_SAT_KD | MRQP_FW_MIT_SAT_T},
  };
  for (const Case& c : cases) {
    REQUIRE(mrqp_fw_mit_pack_cmd(&kDefault, 1, &c.cmd, &f) == c.flags);
    mrqp_fw_mit_cmd d{};
    REQUIRE(mrqp_fw_mit_unpack_cmd(&kDefault, &f, nullptr, &d) == MRQP_FW_OK);
    // Saturated values decode to the nearest end of the range.
    CHECK(d.p >= -12.5f);
    CHECK(d.p <= 12.5f);
    CHECK(d.kp >= 0.0f);
    CHECK(d.kd <= 5.0f);
  }
  mrqp_fw_mit_cmd sat{100.0f, 0, 0, 0, 0};
  REQUIRE(mrqp_fw_mit_pack_cmd(&kDefault, 1, &sat, &f) == MRQP_FW_MIT_SAT_P);
  CHECK(f.data[0] == 0xFF);
  CHECK(f.data[1] == 0xFF);
}

TEST_CASE("MIT: NaN is rejected, bad configuration and ids refused", "[firmware_if][mit]") {
  mrqp_fw_frame f{};
  for (int field = 0; field < 5; ++field) {
    mrqp_fw_mit_cmd c{0, 0, 0, 0, 0};
    float* fields[] = {&c.p, &c.v, &c.kp, &c.kd, &c.t};
    *fields[field] = nanf();
    f.id = 1;
    CHECK(mrqp_fw_mit_pack_cmd(&kDefault, 1, &c, &f) == MRQP_FW_PACK_ERR_NAN);
    CHECK(isCleared(f));
  }
  for (int field = 0; field < 3; ++field) {
    mrqp_fw_mit_reply r{1, 0, 0, 0};
    float* fields[] = {&r.p, &r.v, &r.t};
    *fields[field] = -nanf();
    CHECK(mrqp_fw_mit_pack_reply(&kDefault, &r, &f) == MRQP_FW_PACK_ERR_NAN);
    CHECK(isCleared(f));
  }
  const mrqp_fw_mit_cmd c{0, 0, 0, 0, 0};
  mrqp_fw_mit_ranges bad = kDefault;
  bad.kd_max = bad.kd_min;
  CHECK(mrqp_fw_mit_ranges_valid(&bad) == 0);
  CHECK(mrqp_fw_mit_pack_cmd(&bad, 1, &c, &f) == MRQP_FW_PACK_ERR_CONFIG);
  bad = kDefault;
  bad.p_min = nanf();
  CHECK(mrqp_fw_mit_pack_cmd(&bad, 1, &c, &f) == MRQP_FW_PACK_ERR_CONFIG);
  bad = kDefault;
  bad.t_max = inff();
  CHECK(mrqp_fw_mit_pack_cmd(&bad, 1, &c, &f) == MRQP_FW_PACK_ERR_CONFIG);
  CHECK(mrqp_fw_mit_pack_cmd(nullptr, 1, &c, &f) == MRQP_FW_PACK_ERR_CONFIG);
  CHECK(mrqp_fw_mit_pack_cmd(&kDefault, 0, &c, &f) == MRQP_FW_PACK_ERR_ARG);
  CHECK(mrqp_fw_mit_pack_cmd(&kDefault, 128, &c, &f) == MRQP_FW_PACK_ERR_ARG);
  const mrqp_fw_mit_reply r0{0, 0, 0, 0};
  CHECK(mrqp_fw_mit_pack_reply(&kDefault, &r0, &f) == MRQP_FW_PACK_ERR_ARG);

  REQUIRE(mrqp_fw_mit_pack_cmd(&kDefault, 1, &c, &f) == MRQP_FW_PACK_OK);
  mrqp_fw_mit_cmd d{};
  CHECK(mrqp_fw_mit_unpack_cmd(&bad, &f, nullptr, &d) == MRQP_FW_ERR_CONFIG);
  mrqp_fw_frame g = f;
  g.len = 7;
  CHECK(mrqp_fw_mit_unpack_cmd(&kDefault, &g, nullptr, &d) == MRQP_FW_ERR_LENGTH);
  g = f;
  g.id = 0x80;
  CHECK(mrqp_fw_mit_unpack_cmd(&kDefault, &g, nullptr, &d) == MRQP_FW_ERR_ID);
  g = f;
  g.flags = MRQP_FW_FRAME_EXT;
  CHECK(mrqp_fw_mit_unpack_cmd(&kDefault, &g, nullptr, &d) == MRQP_FW_ERR_FORMAT);
}

TEST_CASE("MIT with custom ranges", "[firmware_if][mit]") {
  // Asymmetric ranges map min to code 0 and max to the top code.
  const mrqp_fw_mit_ranges r{0.0f, 6.0f, -10.0f, 30.0f, 1.0f, 2.0f, 0.0f, 0.1f, -1.0f, 3.0f};
  REQUIRE(mrqp_fw_mit_ranges_valid(&r));
  mrqp_fw_frame f{};
  const mrqp_fw_mit_cmd c{6.0f, -10.0f, 1.0f, 0.1f, -1.0f};
  REQUIRE(mrqp_fw_mit_pack_cmd(&r, 4, &c, &f) == MRQP_FW_PACK_OK);
  CHECK(payload(f) == Bytes{0xFF, 0xFF, 0x00, 0x00, 0x00, 0xFF, 0xF0, 0x00});
}
