// IMU sample frames (CAN FD, 24 bytes): byte-exact frames worked out by hand, round trips at the
// limits of every channel, the quaternion norm check, and every rejected frame.
#include <catch2/catch.hpp>

#include "test_util.hpp"

#include <cmath>
#include <limits>
#include <random>
#include <utility>

using namespace fwtest;

namespace {
const mrqp_fw_imu_scale kScale = MRQP_FW_IMU_SCALE_DEFAULT_INIT;  // 1000 counts per rad/s, 200 per m/s^2

mrqp_fw_imu_sample sample(double qw, double qx, double qy, double qz) {
  mrqp_fw_imu_sample s{};
  s.orientation[0] = qw;
  s.orientation[1] = qx;
  s.orientation[2] = qy;
  s.orientation[3] = qz;
  return s;
}
}  // namespace

TEST_CASE("IMU frame, byte-exact", "[firmware_if][imu]") {
  // q = (0.6, 0, 0.8, 0): 0.6 * 32767 = 19660.2 -> 0x4CCC, 0.8 * 32767 = 26213.6 -> 0x6666.
  // rate (1, -0.5, 0.001) rad/s -> 1000 = 0x03E8, -500 = 0xFE0C, 1.
  // specific force (0, 0, 9.81) m/s^2 -> 0, 0, 1962 = 0x07AA. seq 0x2A, status ALIGNING.
  mrqp_fw_imu_sample s = sample(0.6, 0.0, 0.8, 0.0);
  s.angular_velocity[0] = 1.0;
  s.angular_velocity[1] = -0.5;
  s.angular_velocity[2] = 0.001;
  s.specific_force[2] = 9.81;
  s.seq = 0x2A;
  s.status = MRQP_FW_IMU_STATUS_ALIGNING;
  mrqp_fw_frame f{};
  REQUIRE(mrqp_fw_imu_pack(&kScale, 0x21, &s, &f) == MRQP_FW_PACK_OK);
  CHECK(f.id == 0x1A1u);
  CHECK(f.flags == (MRQP_FW_FRAME_FD | MRQP_FW_FRAME_BRS));
  Bytes expect{0xCC, 0x4C, 0x00, 0x00, 0x66, 0x66, 0x00, 0x00,  // quaternion
               0xE8, 0x03, 0x0C, 0xFE, 0x01, 0x00,              // angular rate
               0x00, 0x00, 0x00, 0x00, 0xAA, 0x07,              // specific force
               0x2A, 0x02};                                     // seq, status
  const std::uint16_t crc = crc16Reference(expect.data(), expect.size());
  expect.push_back(static_cast<std::uint8_t>(crc >> 8));
  expect.push_back(static_cast<std::uint8_t>(crc & 0xFFu));
  CHECK(payload(f) == expect);

  mrqp_fw_imu_sample d{};
  REQUIRE(mrqp_fw_imu_unpack(&kScale, &f, 0x21, &d) == MRQP_FW_OK);
  CHECK(d.orientation[0] == Approx(19660.0 / 32767.0).margin(1e-15));
  CHECK(d.orientation[2] == Approx(26214.0 / 32767.0).margin(1e-15));
  CHECK(d.angular_velocity[1] == -0.5);
  CHECK(d.specific_force[2] == Approx(9.81).margin(1e-12));
  CHECK(d.seq == 0x2A);
  CHECK(d.status == MRQP_FW_IMU_STATUS_ALIGNING);
}

TEST_CASE("IMU frame: limits of every channel and saturation", "[firmware_if][imu]") {
  mrqp_fw_frame f{};
  mrqp_fw_imu_sample d{};
  // The ends of the i16 ranges: 32.767 rad/s, -32.767 rad/s, 163.835 m/s^2; q component 1.
  mrqp_fw_imu_sample s = sample(1.0, 0.0, 0.0, 0.0);
  s.angular_velocity[0] = 32.767;
  s.angular_velocity[1] = -32.767;
  s.angular_velocity[2] = 32.7674;  // rounds to 32767: not saturated
  s.specific_force[0] = 32767.0 / 200.0;
  s.specific_force[1] = -32767.0 / 200.0;
  REQUIRE(mrqp_fw_imu_pack(&kScale, 1, &s, &f) == MRQP_FW_PACK_OK);
  CHECK(f.data[0] == 0xFF);
  CHECK(f.data[1] == 0x7F);
  CHECK((f.data[21] & MRQP_FW_IMU_STATUS_OVERRANGE) == 0u);
  REQUIRE(mrqp_fw_imu_unpack(&kScale, &f, 1, &d) == MRQP_FW_OK);
  CHECK(d.orientation[0] == 1.0);
  CHECK(d.angular_velocity[0] == Approx(32.767).margin(1e-12));
  CHECK(d.angular_velocity[1] == Approx(-32.767).margin(1e-12));
  CHECK(d.specific_force[0] == Approx(163.835).margin(1e-12));
  CHECK(d.specific_force[1] == Approx(-163.835).margin(1e-12));

  // Half a step beyond each end saturates, flags the channel and sets OVERRANGE.
  s.angular_velocity[0] = 32.7676;
  s.angular_velocity[1] = -std::numeric_limits<double>::infinity();
  s.angular_velocity[2] = 0.0;
  s.specific_force[0] = 0.0;
  s.specific_force[1] = 0.0;
  s.specific_force[2] = -164.0;
  const mrqp_fw_pack_flags pf = mrqp_fw_imu_pack(&kScale, 1, &s, &f);
  CHECK(pf == (MRQP_FW_IMU_SAT_WX | MRQP_FW_IMU_SAT_WY | MRQP_FW_IMU_SAT_AZ));
  CHECK((f.data[21] & MRQP_FW_IMU_STATUS_OVERRANGE) != 0u);
  REQUIRE(mrqp_fw_imu_unpack(&kScale, &f, 1, &d) == MRQP_FW_OK);
  CHECK(d.angular_velocity[0] == Approx(32.767).margin(1e-12));
  CHECK(d.angular_velocity[1] == Approx(-32.767).margin(1e-12));  // -32768 is never sent
  CHECK(d.specific_force[2] == Approx(-163.835).margin(1e-12));

  // A quaternion component above 1 by more than half a step saturates (and is flagged) without
  // touching the status byte (the orientation is not a measured range).
  s = sample(1.00002, 0.0, 0.0, 0.0);
  CHECK(mrqp_fw_imu_pack(&kScale, 1, &s, &f) == MRQP_FW_IMU_SAT_QW);
  CHECK((f.data[21] & MRQP_FW_IMU_STATUS_OVERRANGE) == 0u);
  s = sample(0.0, 0.0, 0.0, -1.0);
  CHECK(mrqp_fw_imu_pack(&kScale, 1, &s, &f) == MRQP_FW_PACK_OK);
  REQUIRE(mrqp_fw_imu_unpack(&kScale, &f, 1, &d) == MRQP_FW_OK);
  CHECK(d.orientation[3] == -1.0);
}

TEST_CASE("IMU frame: random round trips stay within half a step", "[firmware_if][imu]") {
  std::mt19937 rng(7);
  std::normal_distribution<double> n01(0.0, 1.0);
  std::uniform_real_distribution<double> rate(-32.7, 32.7);
  std::uniform_real_distribution<double> force(-163.8, 163.8);
  const mrqp_fw_imu_scale coarse{500.0, 100.0};
  for (const mrqp_fw_imu_scale& sc : {kScale, coarse}) {
    for (int k = 0; k < 2000; ++k) {
      double q[4];
      double norm = 0.0;
      for (double& c : q) {
        c = n01(rng);
        norm += c * c;
      }
      norm = std::sqrt(norm);
      mrqp_fw_imu_sample s = sample(q[0] / norm, q[1] / norm, q[2] / norm, q[3] / norm);
      for (int a = 0; a < 3; ++a) {
        s.angular_velocity[a] = rate(rng);  // within the range of both scales
        s.specific_force[a] = force(rng);
      }
      s.seq = static_cast<std::uint8_t>(k);
      mrqp_fw_frame f{};
      REQUIRE(mrqp_fw_imu_pack(&sc, 0x7F, &s, &f) == MRQP_FW_PACK_OK);
      mrqp_fw_imu_sample d{};
      REQUIRE(mrqp_fw_imu_unpack(&sc, &f, 0x7F, &d) == MRQP_FW_OK);
      for (int a = 0; a < 4; ++a) {
        CHECK(std::fabs(d.orientation[a] - s.orientation[a]) <= 0.5 / 32767.0 + 1e-15);
      }
      for (int a = 0; a < 3; ++a) {
        CHECK(std::fabs(d.angular_velocity[a] - s.angular_velocity[a]) <= 0.5 / sc.counts_per_rad_s + 1e-12);
        CHECK(std::fabs(d.specific_force[a] - s.specific_force[a]) <= 0.5 / sc.counts_per_mps2 + 1e-12);
      }
      CHECK(d.seq == s.seq);
    }
  }
}

TEST_CASE("IMU frame: corrupt and foreign frames are rejected", "[firmware_if][imu]") {
  mrqp_fw_imu_sample s = sample(0.5, 0.5, 0.5, 0.5);
  s.seq = 9;
  mrqp_fw_frame good{};
  REQUIRE(mrqp_fw_imu_pack(&kScale, 5, &s, &good) == MRQP_FW_PACK_OK);
  mrqp_fw_imu_sample d{};
  CHECK(mrqp_fw_imu_unpack(&kScale, &good, 5, &d) == MRQP_FW_OK);
  CHECK(mrqp_fw_imu_unpack(&kScale, &good, 6, &d) == MRQP_FW_ERR_ID);
  CHECK(mrqp_fw_imu_unpack(&kScale, &good, 0, &d) == MRQP_FW_ERR_ID);
  CHECK(mrqp_fw_imu_unpack(&kScale, nullptr, 5, &d) == MRQP_FW_ERR_NULL);
  CHECK(mrqp_fw_imu_unpack(&kScale, &good, 5, nullptr) == MRQP_FW_ERR_NULL);
  const mrqp_fw_imu_scale bad_scale{0.0, 200.0};
  CHECK(mrqp_fw_imu_unpack(&bad_scale, &good, 5, &d) == MRQP_FW_ERR_CONFIG);

  for (unsigned byte = 0; byte < MRQP_FW_IMU_FD_LEN; ++byte) {
    mrqp_fw_frame f = good;
    f.data[byte] ^= 0x10;  // one flipped bit anywhere: the CRC catches it
    CHECK(mrqp_fw_imu_unpack(&kScale, &f, 5, &d) == MRQP_FW_ERR_CRC);
  }
  mrqp_fw_frame f = good;
  f.flags = 0;  // classic
  CHECK(mrqp_fw_imu_unpack(&kScale, &f, 5, &d) == MRQP_FW_ERR_FORMAT);
  f = good;
  f.len = 32;
  CHECK(mrqp_fw_imu_unpack(&kScale, &f, 5, &d) == MRQP_FW_ERR_LENGTH);
  f = good;
  f.data[21] = 0x20;  // reserved status bit, CRC made right
  refreshCrc(f);
  CHECK(mrqp_fw_imu_unpack(&kScale, &f, 5, &d) == MRQP_FW_ERR_FORMAT);
  f = good;
  f.data[0] = 0x00;  // qw = -32768: reserved
  f.data[1] = 0x80;
  refreshCrc(f);
  CHECK(mrqp_fw_imu_unpack(&kScale, &f, 5, &d) == MRQP_FW_ERR_RANGE);

  // The norm check: |q| = 1.0099 and 0.9901 are accepted, 1.0101 and 0.9899 are not.
  for (const auto& [c, ok] :
       {std::pair<double, bool>{1.0099, true}, {1.0101, false}, {0.9899, false}, {0.9901, true}}) {
    f = good;
    // A component above 1 cannot be coded: q = (c, c, 0, 0) / sqrt(2) has norm c.
    const double w = c / std::sqrt(2.0);
    const auto cw = static_cast<std::int16_t>(std::lround(w * 32767.0));
    std::uint8_t* p = f.data;
    p[0] = static_cast<std::uint8_t>(static_cast<std::uint16_t>(cw) & 0xFFu);
    p[1] = static_cast<std::uint8_t>(static_cast<std::uint16_t>(cw) >> 8);
    p[2] = p[0];
    p[3] = p[1];
    for (int b = 4; b < 8; ++b) {
      p[b] = 0;
    }
    refreshCrc(f);
    CHECK((mrqp_fw_imu_unpack(&kScale, &f, 5, &d) == MRQP_FW_OK) == ok);
  }

  // Pack refuses NaN, reserved status bits, bad nodes and scales, and leaves a cleared frame.
  mrqp_fw_frame out{};
  mrqp_fw_imu_sample n = s;
  n.orientation[1] = nand();
  CHECK(mrqp_fw_imu_pack(&kScale, 5, &n, &out) == MRQP_FW_PACK_ERR_NAN);
  CHECK(isCleared(out));
  n = s;
  n.specific_force[2] = nand();
  CHECK(mrqp_fw_imu_pack(&kScale, 5, &n, &out) == MRQP_FW_PACK_ERR_NAN);
  CHECK(isCleared(out));
  n = s;
  n.status = 0x80;
  CHECK(mrqp_fw_imu_pack(&kScale, 5, &n, &out) == MRQP_FW_PACK_ERR_ARG);
  CHECK(mrqp_fw_imu_pack(&kScale, 128, &s, &out) == MRQP_FW_PACK_ERR_ARG);
  CHECK(mrqp_fw_imu_pack(&bad_scale, 5, &s, &out) == MRQP_FW_PACK_ERR_CONFIG);
  CHECK(isCleared(out));
  CHECK(mrqp_fw_imu_pack(&kScale, 5, &s, nullptr) == MRQP_FW_PACK_ERR_ARG);
}
