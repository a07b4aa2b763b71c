// mrqp-drive-emu's configuration sets the emulated drive's watch of the master (docs/drivers.md,
// "Bringing up a vendor's drive"): heartbeat_consumer, rpdo_timeout_ms (0x1400:05) and
// abort_connection_option (0x6007) read from the profile with FILE:LINE: FIELD errors; the
// emulated drive then reacts as configured when the master's RPDOs stop (observed on the drive's
// CiA 402 and NMT states), and a master that writes 0x1400:05 itself (ArmConfig::rpdo_timeout_ms,
// the scene's hardware.robots[].rpdo_timeout) arms the same reaction on a drive configured
// without one; a drive that nobody gave a deadline stays enabled.
#include <catch2/catch.hpp>
#include <emu_sim.hpp>
#include <mrqp/drivers/arm_driver.hpp>
#include <mrqp/drivers/bus_router.hpp>
#include <mrqp/drivers/sim_bus.hpp>

#include <cstdio>
#include <memory>
#include <string>
#include <utility>
#include <vector>

#include "emu_bench.hpp"
#include "emu_config_file.hpp"

using namespace mrqp::drivers;
using namespace mrqp::drive_emu;
using drive_emu_test::Bench;
using drive_emu_test::writeConfigFile;

namespace {

EmuConfig load(const std::string& text, std::string* err) {
  const std::string file = "drive_emu_switches.yaml";
  writeConfigFile(file, text);
  EmuConfig c;
  const bool ok = loadConfig(file, &c, err);
  std::remove(file.c_str());
  if (!ok) c.nodes.clear();
  return c;
}

}  // namespace

TEST_CASE("drive emulator: the profile's watch of the master from YAML, and its errors", "[drive_emu]") {
  std::string err;
  const EmuConfig c = load(
      "nodes: [1]\n"
      "profile: {base: strict, heartbeat_consumer: true, rpdo_timeout_ms: 20, abort_connection_option: 2}\n",
      &err);
  INFO(err);
  REQUIRE(c.nodes.size() == 1u);
  CHECK(c.profile.heartbeat_consumer);
  CHECK(c.profile.rpdo_timeout_ms == 20u);
  CHECK(c.profile.abort_connection_option == 2u);
  CHECK(c.profile.tpdo_count == 2u);  // the rest from the base
  const std::string text = describeConfig(c);
  CHECK(text.find("heartbeat consumer (0x1016) watched; RPDO timeout (0x1400:05) 20 ms; 0x6007 = 2") !=
        std::string::npos);
  // The defaults (lenient): nothing watched, 0x6007 = 1.
  const EmuConfig d = load("nodes: [1]\n", &err);
  REQUIRE(d.nodes.size() == 1u);
  CHECK(describeConfig(d).find("heartbeat consumer (0x1016) not watched; RPDO timeout (0x1400:05) off; "
                               "0x6007 = 1") != std::string::npos);

  const std::vector<std::pair<std::string, std::string>> cases = {
      {"nodes: [1]\nprofile: {abort_connection_option: 4}\n",
       ":2: profile.abort_connection_option: expected an integer in [0, 3], got 4"},
      {"nodes: [1]\nprofile: {rpdo_timeout_ms: 65536}\n",
       ":2: profile.rpdo_timeout_ms: expected an integer in [0, 65535], got 65536"},
      {"nodes: [1]\nprofile:\n  heartbeat_consumer: maybe\n", ":3: profile.heartbeat_consumer: "},
  };
  for (const auto& [text_in, expected] : cases) {
    INFO(text_in);
    const EmuConfig bad = load(text_in, &err);
    CHECK(bad.nodes.empty());
    CHECK(err.rfind("drive_emu_switches.yaml" + expected, 0) == 0u);
  }
  // Command-line values go through the same limits.
  EmuConfig v = c;
  v.profile.abort_connection_option = 7;
  CHECK_FALSE(validateConfig(v, "command line", &err));
  CHECK(err.rfind("command line: profile: ", 0) == 0u);
}

TEST_CASE("drive emulator: an RPDO deadline from the profile or from the master stops the drive",
          "[drive_emu]") {
  std::string err;
  SECTION("from the profile: 0x6007 = 2, disable voltage") {
    Bench b(load("nodes: [1]\nprofile: {rpdo_timeout_ms: 20, abort_connection_option: 2}\n", &err), 0);
    REQUIRE(b.arm != nullptr);
    REQUIRE(b.bootAndEnable(5));  // then the master stops cycling
    b.silence(10);
    CHECK(b.emu->emulator().state(0) == MRQP_FW_CIA402_OPERATION_ENABLED);  // within its deadline
    b.silence(60);
    CHECK(b.emu->emulator().state(0) == MRQP_FW_CIA402_SWITCH_ON_DISABLED);
    CHECK(b.emu->emulator().nmt(0) == MRQP_FW_NMT_STATE_OPERATIONAL);  // the NMT state is unchanged
  }
  SECTION("from the master's write of 0x1400:05: 0x6007 = 3, quick stop") {
    Bench b(load("nodes: [1]\nprofile: {abort_connection_option: 3}\n", &err), 20);
    REQUIRE(b.arm != nullptr);
    REQUIRE(b.bootAndEnable(5));  // then the master stops cycling
    b.silence(60);
    CHECK(b.emu->emulator().state(0) == MRQP_FW_CIA402_QUICK_STOP_ACTIVE);
  }
  SECTION("no deadline anywhere: the drive stays enabled") {
    Bench b(load("nodes: [1]\nprofile: {abort_connection_option: 3}\n", &err), 0);
    REQUIRE(b.arm != nullptr);
    REQUIRE(b.bootAndEnable(5));  // then the master stops cycling
    b.silence(60);
    CHECK(b.emu->emulator().state(0) == MRQP_FW_CIA402_OPERATION_ENABLED);
  }
}
