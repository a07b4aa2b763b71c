// candump -L lines and their decoding, checked against frames packed by firmware_if and against
// hand-written log lines in the format can-utils prints.
#include <catch2/catch.hpp>

#include <cstdio>
#include <string>

#include "candump_log.hpp"
#include "frame_decoder.hpp"
#include "mrqp/firmware_if/arm_pdo.h"
#include "mrqp/firmware_if/nmt.h"

using mrqp::tools::DecodeCounters;
using mrqp::tools::DeviceMap;
using mrqp::tools::LogFrame;
using mrqp::tools::TraceRow;

namespace {

std::string toLogLine(double t, const char* iface, const mrqp_fw_frame& f) {
  char head[64];
  std::snprintf(head, sizeof head, "(%.6f) %s %03X#", t, iface, static_cast<unsigned>(f.id));
  std::string s = head;
  for (unsigned k = 0; k < f.len; ++k) {
    char b[3];
    std::snprintf(b, sizeof b, "%02X", f.data[k]);
    s += b;
  }
  return s;
}

double field(const std::vector<TraceRow>& rows, const std::string& name) {
  for (const auto& r : rows)
    if (r.field == name) return r.value;
  FAIL("no field " << name);
  return 0.0;
}

}  // namespace

TEST_CASE("candump -L lines parse: classic, FD, remote, error frames", "[candecode]") {
  LogFrame f;
  std::string err;
  REQUIRE(mrqp::tools::parseCandumpLine("(1700000000.123456) vcan0 123#DEADBEEF", f, err));
  CHECK(f.time == Approx(1700000000.123456));
  CHECK(f.iface == "vcan0");
  CHECK(f.frame.id == 0x123);
  CHECK(f.frame.len == 4);
  CHECK(f.frame.data[0] == 0xDE);
  CHECK(f.frame.data[3] == 0xEF);
  REQUIRE(mrqp::tools::parseCandumpLine("(0.5) can1 080#", f, err));
  CHECK(f.frame.id == 0x80);
  CHECK(f.frame.len == 0);
  REQUIRE(mrqp::tools::parseCandumpLine("(0.5) can1 120##1000102030405060708090A0B", f, err));
  CHECK((f.frame.flags & MRQP_FW_FRAME_FD) != 0);
  CHECK((f.frame.flags & MRQP_FW_FRAME_BRS) != 0);
  CHECK(f.frame.len == 12);
  REQUIRE(mrqp::tools::parseCandumpLine("(0.5) can1 123#R", f, err));
  CHECK(f.remote);
  REQUIRE(mrqp::tools::parseCandumpLine("(0.5) can0 20000080#0000000000000000", f, err));
  CHECK(f.error_frame);

  CHECK_FALSE(mrqp::tools::parseCandumpLine("vcan0 123#00", f, err));
  CHECK(err.find("timestamp") != std::string::npos);
  CHECK_FALSE(mrqp::tools::parseCandumpLine("(1.0) vcan0 12#00", f, err));
  CHECK(err.find("identifier") != std::string::npos);
  CHECK_FALSE(mrqp::tools::parseCandumpLine("(1.0) vcan0 123#0", f, err));
  CHECK(err.find("odd") != std::string::npos);
  CHECK_FALSE(mrqp::tools::parseCandumpLine("(1.0) vcan0 123#001122334455667788", f, err));
  CHECK(err.find("length") != std::string::npos);
  CHECK_FALSE(mrqp::tools::parseCandumpLine("(1.0) vcan0 123#ZZ", f, err));
}

TEST_CASE("an arm RPDO packed by firmware_if decodes back from its log line", "[candecode]") {
  DeviceMap map;
  map.arm_nodes = {3};
  mrqp_fw_arm_rpdo1 p{0x000F, 262144, -250};  // half a turn at 524288 increments/rev, -0.25 of rated torque
  mrqp_fw_frame frame;
  REQUIRE(mrqp_fw_arm_pack_rpdo1(3, &p, &frame) == 0);
  LogFrame f;
  std::string err;
  REQUIRE(mrqp::tools::parseCandumpLine(toLogLine(2.0, "vcan0", frame), f, err));
  std::vector<TraceRow> rows;
  DecodeCounters c;
  mrqp::tools::decodeFrame(map, f, rows, c);
  CHECK(c.decoded == 1);
  REQUIRE_FALSE(rows.empty());
  CHECK(rows[0].device == "arm3");
  CHECK(rows[0].message == "rpdo1");
  CHECK(field(rows, "controlword") == 0x000F);
  CHECK(field(rows, "target_position_rad") == Approx(3.14159265358979).epsilon(1e-9));
  CHECK(field(rows, "target_torque_nm") == Approx(-0.25));
}

TEST_CASE("SYNC, heartbeat and a foreign EMCY decode; malformed and unknown frames are counted",
          "[candecode]") {
  DeviceMap map;
  map.arm_nodes = {1, 2};
  DecodeCounters c;
  std::vector<TraceRow> rows;
  LogFrame f;
  std::string err;
  const char* lines[] = {
      "(1.0) vcan0 080#",                  // SYNC
      "(1.0) vcan0 701#05",                // heartbeat node 1 operational
      "(1.1) vcan0 082#1023010000000000",  // EMCY node 2: 0x2310 continuous over-current
      "(1.2) vcan0 181#0700",              // TPDO1 of arm 1 with a wrong length -> malformed
      "(1.3) vcan0 7FF#00",                // nothing mrqp uses -> unknown
  };
  for (const char* l : lines) {
    REQUIRE(mrqp::tools::parseCandumpLine(l, f, err));
    mrqp::tools::decodeFrame(map, f, rows, c);
  }
  CHECK(c.frames == 5);
  CHECK(c.decoded == 3);
  CHECK(c.malformed == 1);
  CHECK(c.unknown == 1);
  CHECK(field(rows, "state") == MRQP_FW_NMT_STATE_OPERATIONAL);
  CHECK(field(rows, "error_code") == 0x2310);
}
