// Arm drives: default PDO mapping, byte-exact PDOs, SI scaling with saturation.
#include <catch2/catch.hpp>

#include "test_util.hpp"

#include <cmath>
#include <random>

using namespace fwtest;

namespace {
const double kPi = 3.14159265358979323846;
}

TEST_CASE("default PDO mapping entries fill the PDO lengths exactly", "[firmware_if][arm]") {
  std::uint32_t e[4] = {};
  REQUIRE(mrqp_fw_arm_pdo_mapping(MRQP_FW_ARM_RPDO1, e) == 3);
  CHECK(e[0] == 0x60400010u);
  CHECK(e[1] == 0x607A0020u);
  CHECK(e[2] == 0x60710010u);
  REQUIRE(mrqp_fw_arm_pdo_mapping(MRQP_FW_ARM_TPDO1, e) == 3);
  CHECK(e[0] == 0x60410010u);
  CHECK(e[1] == 0x60640020u);
  CHECK(e[2] == 0x60770010u);
  REQUIRE(mrqp_fw_arm_pdo_mapping(MRQP_FW_ARM_TPDO2, e) == 3);
  CHECK(e[0] == 0x606C0020u);
  CHECK(e[1] == 0x603F0010u);
  CHECK(e[2] == 0x60610008u);
  CHECK(mrqp_fw_arm_pdo_mapping(outOfRangeEnum<mrqp_fw_arm_pdo>(7), e) == 0);

  const struct {
    mrqp_fw_arm_pdo pdo;
    unsigned len;
  } pdos[] = {{MRQP_FW_ARM_RPDO1, MRQP_FW_ARM_RPDO1_LEN},
              {MRQP_FW_ARM_TPDO1, MRQP_FW_ARM_TPDO1_LEN},
              {MRQP_FW_ARM_TPDO2, MRQP_FW_ARM_TPDO2_LEN}};
  for (const auto& p : pdos) {
    const unsigned n = mrqp_fw_arm_pdo_mapping(p.pdo, e);
    unsigned bits = 0;
    for (unsigned i = 0; i < n; ++i) {
      bits += e[i] & 0xFFu;
    }
    CHECK(bits == 8 * p.len);
  }
}

TEST_CASE("arm PDOs, byte-exact", "[firmware_if][arm]") {
  mrqp_fw_frame f{};
  const mrqp_fw_arm_rpdo1 r{0x000F, 0x12345678, -2};
  REQUIRE(mrqp_fw_arm_pack_rpdo1(1, &r, &f) == MRQP_FW_PACK_OK);
  CHECK(f.id == 0x201u);
  CHECK(f.flags == 0);
  CHECK(payload(f) == Bytes{0x0F, 0x00, 0x78, 0x56, 0x34, 0x12, 0xFE, 0xFF});

  const mrqp_fw_arm_tpdo1 t1{0x1237, -1, 1000};
  REQUIRE(mrqp_fw_arm_pack_tpdo1(2, &t1, &f) == MRQP_FW_PACK_OK);
  CHECK(f.id == 0x182u);
  CHECK(payload(f) == Bytes{0x37, 0x12, 0xFF, 0xFF, 0xFF, 0xFF, 0xE8, 0x03});

  const mrqp_fw_arm_tpdo2 t2{-100000, 0x8611, MRQP_FW_MODE_CSP};
  REQUIRE(mrqp_fw_arm_pack_tpdo2(3, &t2, &f) == MRQP_FW_PACK_OK);
  CHECK(f.id == 0x283u);
  CHECK(payload(f) == Bytes{0x60, 0x79, 0xFE, 0xFF, 0x11, 0x86, 0x08});
}

TEST_CASE("arm PDOs round-trip at the integer limits and reject bad frames", "[firmware_if][arm]") {
  mrqp_fw_frame f{};
  for (std::int32_t pos : {INT32_MIN, -1, 0, 1, INT32_MAX}) {
    for (std::int16_t tq : {static_cast<std::int16_t>(INT16_MIN), static_cast<std::int16_t>(0),
                            static_cast<std::int16_t>(INT16_MAX)}) {
      const mrqp_fw_arm_rpdo1 r{0xFFFF, pos, tq};
      REQUIRE(mrqp_fw_arm_pack_rpdo1(127, &r, &f) == MRQP_FW_PACK_OK);
      mrqp_fw_arm_rpdo1 rr{};
      REQUIRE(mrqp_fw_arm_unpack_rpdo1(&f, 127, &rr) == MRQP_FW_OK);
      CHECK(rr.controlword == 0xFFFF);
      CHECK(rr.target_position == pos);
      CHECK(rr.target_torque == tq);

      const mrqp_fw_arm_tpdo1 t{0x0027, pos, tq};
      REQUIRE(mrqp_fw_arm_pack_tpdo1(127, &t, &f) == MRQP_FW_PACK_OK);
      mrqp_fw_arm_tpdo1 tt{};
      REQUIRE(mrqp_fw_arm_unpack_tpdo1(&f, 127, &tt) == MRQP_FW_OK);
      CHECK(tt.position_actual == pos);
      CHECK(tt.torque_actual == tq);
    }
    for (std::int8_t mode :
         {static_cast<std::int8_t>(-128), static_cast<std::int8_t>(10), static_cast<std::int8_t>(127)}) {
      const mrqp_fw_arm_tpdo2 t{pos, 0xFFFF, mode};
      REQUIRE(mrqp_fw_arm_pack_tpdo2(1, &t, &f) == MRQP_FW_PACK_OK);
      mrqp_fw_arm_tpdo2 tt{};
      REQUIRE(mrqp_fw_arm_unpack_tpdo2(&f, 1, &tt) == MRQP_FW_OK);
      CHECK(tt.velocity_actual == pos);
      CHECK(tt.error_code == 0xFFFF);
      CHECK(tt.mode_display == mode);
    }
  }
  const mrqp_fw_arm_tpdo1 t{0x0027, 5, 5};
  REQUIRE(mrqp_fw_arm_pack_tpdo1(4, &t, &f) == MRQP_FW_PACK_OK);
  mrqp_fw_arm_tpdo1 tt{};
  CHECK(mrqp_fw_arm_unpack_tpdo1(&f, 5, &tt) == MRQP_FW_ERR_ID);
  CHECK(mrqp_fw_arm_unpack_tpdo1(&f, 0, &tt) == MRQP_FW_ERR_ID);
  mrqp_fw_frame g = f;
  g.len = 7;
  CHECK(mrqp_fw_arm_unpack_tpdo1(&g, 4, &tt) == MRQP_FW_ERR_LENGTH);
  g = f;
  g.flags = MRQP_FW_FRAME_FD;
  CHECK(mrqp_fw_arm_unpack_tpdo1(&g, 4, &tt) == MRQP_FW_ERR_FORMAT);
  g = f;
  g.flags = MRQP_FW_FRAME_RTR;
  CHECK(mrqp_fw_arm_unpack_tpdo1(&g, 4, &tt) == MRQP_FW_ERR_FORMAT);
  mrqp_fw_arm_tpdo2 t2{};
  CHECK(mrqp_fw_arm_unpack_tpdo2(&f, 4, &t2) == MRQP_FW_ERR_ID);  // a TPDO1 is not a TPDO2
  mrqp_fw_arm_rpdo1 r{};
  CHECK(mrqp_fw_arm_unpack_rpdo1(&f, 4, &r) == MRQP_FW_ERR_ID);
  CHECK(mrqp_fw_arm_pack_tpdo1(0, &t, &f) == MRQP_FW_PACK_ERR_ARG);
  CHECK(isCleared(f));
  CHECK(mrqp_fw_arm_pack_tpdo1(1, nullptr, &f) == MRQP_FW_PACK_ERR_ARG);
}

TEST_CASE("arm scaling: position and velocity in increments", "[firmware_if][arm][scale]") {
  const mrqp_fw_arm_scale s = MRQP_FW_ARM_SCALE_DEFAULT_INIT;  // 2^19 increments / rev
  std::int32_t inc = 0;
  CHECK(mrqp_fw_arm_position_to_inc(&s, kPi, &inc) == MRQP_FW_CONV_OK);
  CHECK(inc == 262144);
  CHECK(mrqp_fw_arm_position_to_inc(&s, -kPi / 2, &inc) == MRQP_FW_CONV_OK);
  CHECK(inc == -131072);
  CHECK(mrqp_fw_arm_velocity_to_inc(&s, 2 * kPi, &inc) == MRQP_FW_CONV_OK);
  CHECK(inc == 524288);
  double rad = 0;
  CHECK(mrqp_fw_arm_position_from_inc(&s, 524288, &rad) == MRQP_FW_CONV_OK);
  CHECK(rad == Approx(2 * kPi).epsilon(1e-15));
  CHECK(mrqp_fw_arm_velocity_from_inc(&s, -262144, &rad) == MRQP_FW_CONV_OK);
  CHECK(rad == Approx(-kPi).epsilon(1e-15));

  // Limits: INT32_MAX increments is 4096 rev - 1 increment; saturation starts half an increment
  // beyond.
  const double lsb = 2 * kPi / 524288.0;
  const double max_rad = 2147483647.0 * lsb;
  CHECK(mrqp_fw_arm_position_to_inc(&s, max_rad, &inc) == MRQP_FW_CONV_OK);
  CHECK(inc == INT32_MAX);
  CHECK(mrqp_fw_arm_position_to_inc(&s, max_rad + 0.4 * lsb, &inc) == MRQP_FW_CONV_OK);
  CHECK(inc == INT32_MAX);
  CHECK(mrqp_fw_arm_position_to_inc(&s, max_rad + lsb, &inc) == MRQP_FW_CONV_SAT_HIGH);
  CHECK(inc == INT32_MAX);
  CHECK(mrqp_fw_arm_position_to_inc(&s, -max_rad - lsb, &inc) == MRQP_FW_CONV_OK);
  CHECK(inc == INT32_MIN);
  CHECK(mrqp_fw_arm_position_to_inc(&s, -max_rad - 3 * lsb, &inc) == MRQP_FW_CONV_SAT_LOW);
  CHECK(inc == INT32_MIN);
  CHECK(mrqp_fw_arm_velocity_to_inc(&s, infd(), &inc) == MRQP_FW_CONV_SAT_HIGH);
  CHECK(inc == INT32_MAX);
  inc = 77;
  CHECK(mrqp_fw_arm_position_to_inc(&s, nand(), &inc) == MRQP_FW_CONV_NAN);
  CHECK(inc == 77);
  CHECK(mrqp_fw_arm_velocity_to_inc(&s, nand(), &inc) == MRQP_FW_CONV_NAN);

  // Quantisation error: at most half an increment.
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> u(-100.0, 100.0);
  for (int i = 0; i < 10000; ++i) {
    const double x = u(rng);
    REQUIRE(mrqp_fw_arm_position_to_inc(&s, x, &inc) == MRQP_FW_CONV_OK);
    REQUIRE(mrqp_fw_arm_position_from_inc(&s, inc, &rad) == MRQP_FW_CONV_OK);
    REQUIRE(std::fabs(rad - x) <= 0.5 * lsb * (1 + 1e-9));
  }

  const mrqp_fw_arm_scale bad{0, 1000};
  CHECK(mrqp_fw_arm_scale_valid(&bad) == 0);
  CHECK(mrqp_fw_arm_position_to_inc(&bad, 1.0, &inc) == MRQP_FW_CONV_BAD_SCALE);
  CHECK(mrqp_fw_arm_position_from_inc(&bad, 1, &rad) == MRQP_FW_CONV_BAD_SCALE);
  CHECK(mrqp_fw_arm_position_to_inc(nullptr, 1.0, &inc) == MRQP_FW_CONV_BAD_SCALE);
}

TEST_CASE("arm scaling: torque in per mille of rated torque", "[firmware_if][arm][scale]") {
  const mrqp_fw_arm_scale s{524288u, 2500u};  // rated 2.5 N m
  std::int16_t pm = 0;
  CHECK(mrqp_fw_arm_torque_to_permille(&s, 2.5, &pm) == MRQP_FW_CONV_OK);
  CHECK(pm == 1000);
  CHECK(mrqp_fw_arm_torque_to_permille(&s, -0.0025, &pm) == MRQP_FW_CONV_OK);
  CHECK(pm == -1);
  CHECK(mrqp_fw_arm_torque_to_permille(&s, 0.00125, &pm) == MRQP_FW_CONV_OK);
  CHECK(pm == 1);  // 0.5 per mille rounds away from zero
  // i16 range: +/-32.767 x rated.
  CHECK(mrqp_fw_arm_torque_to_permille(&s, 32767 * 0.0025, &pm) == MRQP_FW_CONV_OK);
  CHECK(pm == 32767);
  CHECK(mrqp_fw_arm_torque_to_permille(&s, 32768 * 0.0025, &pm) == MRQP_FW_CONV_SAT_HIGH);
  CHECK(pm == 32767);
  CHECK(mrqp_fw_arm_torque_to_permille(&s, -32768 * 0.0025, &pm) == MRQP_FW_CONV_OK);
  CHECK(pm == -32768);
  CHECK(mrqp_fw_arm_torque_to_permille(&s, -32769 * 0.0025, &pm) == MRQP_FW_CONV_SAT_LOW);
  CHECK(pm == -32768);
  pm = 5;
  CHECK(mrqp_fw_arm_torque_to_permille(&s, nand(), &pm) == MRQP_FW_CONV_NAN);
  CHECK(pm == 5);
  double nm = 0;
  CHECK(mrqp_fw_arm_torque_from_permille(&s, -400, &nm) == MRQP_FW_CONV_OK);
  CHECK(nm == Approx(-1.0));
  const mrqp_fw_arm_scale bad{524288u, 0u};
  CHECK(mrqp_fw_arm_torque_to_permille(&bad, 1.0, &pm) == MRQP_FW_CONV_BAD_SCALE);
  CHECK(mrqp_fw_arm_torque_from_permille(&bad, 1, &nm) == MRQP_FW_CONV_BAD_SCALE);
}

TEST_CASE("RPDO1 from SI: saturation flagged, NaN rejected", "[firmware_if][arm]") {
  const mrqp_fw_arm_scale s = MRQP_FW_ARM_SCALE_DEFAULT_INIT;  // rated 1 N m
  mrqp_fw_frame f{};
  REQUIRE(mrqp_fw_arm_pack_rpdo1_si(&s, 6, 0x000F, kPi, -0.5, &f) == MRQP_FW_PACK_OK);
  CHECK(f.id == 0x206u);
  // 262144 = 0x00040000, -500 = 0xFE0C
  CHECK(payload(f) == Bytes{0x0F, 0x00, 0x00, 0x00, 0x04, 0x00, 0x0C, 0xFE});

  CHECK(mrqp_fw_arm_pack_rpdo1_si(&s, 6, 0x000F, 1e6, 0.0, &f) == MRQP_FW_ARM_SAT_POSITION);
  mrqp_fw_arm_rpdo1 r{};
  REQUIRE(mrqp_fw_arm_unpack_rpdo1(&f, 6, &r) == MRQP_FW_OK);
  CHECK(r.target_position == INT32_MAX);
  CHECK(mrqp_fw_arm_pack_rpdo1_si(&s, 6, 0x000F, 0.0, -40.0, &f) == MRQP_FW_ARM_SAT_TORQUE);
  REQUIRE(mrqp_fw_arm_unpack_rpdo1(&f, 6, &r) == MRQP_FW_OK);
  CHECK(r.target_torque == INT16_MIN);
  CHECK(mrqp_fw_arm_pack_rpdo1_si(&s, 6, 0x000F, -1e6, 40.0, &f) ==
        (MRQP_FW_ARM_SAT_POSITION | MRQP_FW_ARM_SAT_TORQUE));

  CHECK(mrqp_fw_arm_pack_rpdo1_si(&s, 6, 0x000F, nand(), 0.0, &f) == MRQP_FW_PACK_ERR_NAN);
  CHECK(isCleared(f));
  CHECK(mrqp_fw_arm_pack_rpdo1_si(&s, 6, 0x000F, 0.0, nand(), &f) == MRQP_FW_PACK_ERR_NAN);
  CHECK(isCleared(f));
  const mrqp_fw_arm_scale bad{0, 0};
  CHECK(mrqp_fw_arm_pack_rpdo1_si(&bad, 6, 0x000F, 0.0, 0.0, &f) == MRQP_FW_PACK_ERR_CONFIG);
  CHECK(mrqp_fw_arm_pack_rpdo1_si(&s, 0, 0x000F, 0.0, 0.0, &f) == MRQP_FW_PACK_ERR_ARG);
  CHECK(isCleared(f));
}
