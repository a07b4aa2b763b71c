// candump -L lines and their decoding, checked against frames packed by firmware_if and against
// hand-written log lines in the format can-utils prints.
#include <catch2/catch.hpp>

#include <sys/wait.h>

#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <iterator>
#include <limits>
#include <sstream>
#include <string>

#include "candump_log.hpp"
#include "csv_writer.hpp"
#include "frame_decoder.hpp"
#include "line_reader.hpp"
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
  CHECK(field(rows, "state") == static_cast<double>(MRQP_FW_NMT_STATE_OPERATIONAL));
  CHECK(field(rows, "error_code") == 0x2310);
}

// ---- hostile input (docs/robustness.md) ----------------------------------------------------------

TEST_CASE("candump lines: timestamps are digits only, identifiers within their width",
          "[candecode][robustness]") {
  LogFrame f;
  std::string err;
  for (const char* bad : {"(nan) can0 123#", "(inf) can0 123#", "(-1.0) can0 123#", "(1e999) can0 123#",
                          "(0x10) can0 123#", "(1.) can0 123#", "(.5) can0 123#", "( 1.5) can0 123#",
                          "(1234567890123.5) can0 123#", "(1.1234567890) can0 123#"}) {
    INFO(bad);
    CHECK_FALSE(mrqp::tools::parseCandumpLine(bad, f, err));
    CHECK(err.find("bad timestamp") == 0);
  }
  REQUIRE(mrqp::tools::parseCandumpLine("(123456789012.123456789) can0 123#", f, err));
  CHECK(f.time == Approx(123456789012.123456789));

  CHECK_FALSE(mrqp::tools::parseCandumpLine("(1.0) can0 800#00", f, err));
  CHECK(err == "identifier '800' is above 0x7FF, the largest 11-bit identifier");
  CHECK_FALSE(mrqp::tools::parseCandumpLine("(1.0) can0 FFF#00", f, err));
  REQUIRE(mrqp::tools::parseCandumpLine("(1.0) can0 7FF#00", f, err));
  CHECK(f.frame.id == 0x7FFu);
  CHECK_FALSE(mrqp::tools::parseCandumpLine("(1.0) can0 40000000#00", f, err));
  CHECK(err == "identifier '40000000' has bits above the 29-bit identifier and the error flag");
  REQUIRE(mrqp::tools::parseCandumpLine("(1.0) can0 3FFFFFFF#00", f, err));
  CHECK(f.error_frame);
}

TEST_CASE("CSV rows: RFC 4180 quoting of interface names, no NaN", "[candecode][robustness]") {
  CHECK(mrqp::tools::csvField("can0") == "can0");
  CHECK(mrqp::tools::csvField("a,b") == "\"a,b\"");
  CHECK(mrqp::tools::csvField("say \"hi\"") == "\"say \"\"hi\"\"\"");
  CHECK(mrqp::tools::csvField("cr\rlf\n") == "\"cr\rlf\n\"");

  LogFrame f;
  std::string err;
  REQUIRE(mrqp::tools::parseCandumpLine("(1.5) a,\"b 080#07", f, err));
  CHECK(f.iface == "a,\"b");
  DeviceMap map;
  std::vector<TraceRow> rows;
  DecodeCounters counters;
  mrqp::tools::decodeFrame(map, f, rows, counters);
  REQUIRE(rows.size() == 1);
  std::ostringstream out;
  mrqp::tools::writeTraceRow(out, rows[0], true);
  CHECK(out.str() == "1.500000,\"a,\"\"b\",bus,sync,counter,7\n");

  TraceRow nan_row{std::numeric_limits<double>::quiet_NaN(), "can0", "x", "m", "f",
                   std::numeric_limits<double>::infinity()};
  std::ostringstream out2;
  mrqp::tools::writeTraceRow(out2, nan_row, false);
  CHECK(out2.str() == ",can0,m,f,\n");
}

TEST_CASE("line reader: bounded lines, binary input stops", "[candecode][robustness]") {
  std::istringstream in("one\r\n" + std::string(2000, 'x') + "\nthree\n" + std::string("a\0b\n", 4) +
                        "after\n");
  mrqp::tools::LineReader reader(in);
  std::string line;
  CHECK(reader.next(line) == mrqp::tools::LineStatus::Line);
  CHECK(line == "one");
  CHECK(reader.next(line) == mrqp::tools::LineStatus::TooLong);
  CHECK(reader.next(line) == mrqp::tools::LineStatus::Line);
  CHECK(line == "three");
  CHECK(reader.lineNumber() == 3);
  CHECK(reader.next(line) == mrqp::tools::LineStatus::Binary);
  CHECK(reader.lineNumber() == 4);
  std::istringstream empty("");
  mrqp::tools::LineReader none(empty);
  CHECK(none.next(line) == mrqp::tools::LineStatus::End);
}

namespace {

// Runs mrqp-candecode on `input` (a path), stdout and stderr into files; returns the exit status.
int runCandecode(const std::string& input, std::string* err_text = nullptr) {
  const std::string out = "candecode_test_out.csv", err = "candecode_test_err.txt";
  const std::string cmd =
      std::string(MRQP_CANDECODE_EXE) + " --arm 1 '" + input + "' > " + out + " 2> " + err;
  const int status = std::system(cmd.c_str());
  if (err_text != nullptr) {
    std::ifstream e(err);
    *err_text = std::string(std::istreambuf_iterator<char>(e), {});
  }
  std::remove(out.c_str());
  std::remove(err.c_str());
  return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
}

void writeFile(const std::string& path, const std::string& text) {
  std::ofstream f(path, std::ios::binary);
  f << text;
}

}  // namespace

TEST_CASE("mrqp-candecode: success means frames were read", "[candecode][robustness]") {
  if (std::string(MRQP_CANDECODE_EXE).empty()) {
    WARN("mrqp-candecode is not run in this build (cross build or no tools)");
    return;
  }
  std::string err;
  CHECK(runCandecode("/dev/zero", &err) == 1);
  CHECK(err.find("/dev/zero:1: a NUL byte: binary data, not a candump -L log") != std::string::npos);

  writeFile("candecode_empty.log", "");
  CHECK(runCandecode("candecode_empty.log", &err) == 1);
  CHECK(err.find("no frame read") != std::string::npos);

  writeFile("candecode_garbage.log", "hello\nworld\n");
  CHECK(runCandecode("candecode_garbage.log", &err) == 1);
  CHECK(err.find("candecode_garbage.log:1: expected '(' and a timestamp") != std::string::npos);

  writeFile("candecode_good.log", "(1.000000) can0 080#\n(1.001000) can0 701#05\n");
  CHECK(runCandecode("candecode_good.log") == 0);

  writeFile("candecode_mixed.log", "(1.000000) can0 080#\n(nan) can0 080#\n");
  CHECK(runCandecode("candecode_mixed.log") == 3);
  CHECK(runCandecode("/nonexistent/x.log", &err) == 1);
  CHECK(err.find("cannot open /nonexistent/x.log") != std::string::npos);
  for (const char* f :
       {"candecode_empty.log", "candecode_garbage.log", "candecode_good.log", "candecode_mixed.log"})
    std::remove(f);
}
