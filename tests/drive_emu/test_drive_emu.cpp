// The ArmDriver against mrqp-drive-emu's emulator on a SimBus: boot, enable, closed-loop CSP
// tracking by the joint model, heartbeat loss, YAML errors (every value checked for type, finiteness
// and range: the hostile inputs of a fuzzing campaign among them), the vendor profile.
#include <catch2/catch.hpp>
#include <emu_sim.hpp>
#include <mrqp/drivers/arm_driver.hpp>
#include <mrqp/drivers/bus_router.hpp>
#include <mrqp/drivers/sim_bus.hpp>

#include <cmath>
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

EmuConfig threeNodes() {
  EmuConfig c;
  for (std::uint8_t n = 1; n <= 3; ++n) {
    EmuNode e;
    e.node = n;
    e.scale.rated_torque_mNm = 10000;  // 10 N m rated
    c.nodes.push_back(e);
  }
  return c;
}

}  // namespace

TEST_CASE("drive emulator: boot, enable and closed-loop CSP tracking", "[drive_emu]") {
  Bench b(threeNodes());
  REQUIRE(b.arm != nullptr);
  REQUIRE(b.bootAndEnable());
  CHECK((b.flags & fault::kBootFailed) == 0u);
  // A sine per joint; the drive's PD loop and the joint model must follow it.
  double worst = 0.0;
  for (int k = 0; k < 1500; ++k) {
    const double time = static_cast<double>(k) * 2e-3;
    for (std::size_t j = 0; j < 3; ++j) {
      const double target = 0.3 * std::sin(2.0 * M_PI * 0.5 * time + static_cast<double>(j));
      REQUIRE(b.arm->setPosition(j, target) == SetpointResult::Ok);
    }
    const FaultReport& r = b.cycle();
    REQUIRE((r.flags & (fault::kHeartbeatLost | fault::kFeedbackMissing | fault::kDeviceFault)) == 0u);
    if (k > 250) {
      for (std::size_t j = 0; j < 3; ++j) {
        const double prev = 0.3 * std::sin(2.0 * M_PI * 0.5 * (time - 4e-3) + static_cast<double>(j));
        worst = std::max(worst, std::fabs(b.arm->drive(j).position - prev));
      }
    }
  }
  CHECK(worst < 0.05);  // rad, a few cycles of lag at 1 rad/s
  // The joint model moved (not a drive that copies the setpoint).
  CHECK(std::fabs(b.emu->emulator().position(0)) > 0.01);
  CHECK(b.emu->emulator().stats().syncs > 1500);
}

TEST_CASE("drive emulator: a stopped heartbeat is reported within the consumer timeout", "[drive_emu]") {
  EmuConfig c = threeNodes();
  c.nodes[1].faults.heartbeat_stop_at = milliseconds(1500);
  Bench b(c);
  REQUIRE(b.arm != nullptr);
  REQUIRE(b.bootAndEnable());
  REQUIRE(b.t < milliseconds(1500));
  TimeNs detected = -1;
  while (b.t < milliseconds(3000) && detected < 0) {
    const TimeNs now = b.t;
    const FaultReport& r = b.cycle();
    if (r.has(fault::kHeartbeatLost)) {
      detected = now;
    }
  }
  REQUIRE(detected > 0);
  CHECK(detected >= milliseconds(1500));
  CHECK(detected <= milliseconds(1500) + b.config.heartbeat_timeout + milliseconds(5));
}

TEST_CASE("drive emulator: an EMCY puts the drive in Fault and the driver sees it", "[drive_emu]") {
  EmuConfig c = threeNodes();
  c.nodes[2].faults.emcy_at = milliseconds(1200);
  Bench b(c);
  REQUIRE(b.bootAndEnable());
  bool emcy = false;
  bool fault_state = false;
  while (b.t < milliseconds(1600)) {
    const FaultReport& r = b.cycle();
    emcy = emcy || r.has(fault::kEmcy);
    fault_state = fault_state || r.has(fault::kDeviceFault);
  }
  CHECK(emcy);
  CHECK(fault_state);
}

TEST_CASE("drive emulator: YAML configuration and its errors", "[drive_emu]") {
  const std::string good = "drive_emu_good.yaml";
  writeConfigFile(
      good,
      "interface: vcan0\nincrements_per_rev: 131072\nrated_torque: 5\n"
      "joint: {inertia: 0.1, damping: 0.2, torque_limit: 30}\n"
      "nodes:\n  - 1\n  - {node: 2, inertia: 0.2, faults: {stop_heartbeat_at: 2.5, emcy_at: 1, emcy_code: "
      "0x3210}}\n"
      "faults: {drop_fraction: 0.01, corrupt_fraction: 0.02}\n");
  EmuConfig c;
  std::string err;
  REQUIRE(loadConfig(good, &c, &err));
  REQUIRE(c.nodes.size() == 2);
  CHECK(c.nodes[0].scale.increments_per_rev == 131072u);
  CHECK(c.nodes[0].scale.rated_torque_mNm == 5000u);
  CHECK(c.nodes[1].joint.inertia == Approx(0.2));
  CHECK(c.nodes[0].joint.inertia == Approx(0.1));
  CHECK(c.nodes[1].faults.heartbeat_stop_at == milliseconds(2500));
  CHECK(c.nodes[1].faults.emcy_code == 0x3210);
  CHECK(c.corrupt_fraction == Approx(0.02));
  REQUIRE(applyFaultSwitch("saturate", "1@0.5", &c, &err));
  CHECK(c.nodes[0].faults.saturate_at == milliseconds(500));
  CHECK_FALSE(applyFaultSwitch("emcy", "9@1", &c, &err));
  CHECK(err.find("node 9") != std::string::npos);

  const std::string bad = "drive_emu_bad.yaml";
  writeConfigFile(bad, "nodes:\n  - {node: 3, inertia: -1}\n");
  // Errors are "FILE:LINE: FIELD: message", as for every YAML file of mrqp (control/scene/yaml_reader).
  CHECK_FALSE(loadConfig(bad, &c, &err));
  CHECK(err == bad + ":2: nodes[0].inertia: expected a number in (0, 1000000], got -1");
  writeConfigFile(bad, "nodes:\n  - {node: 3, damping: abc}\n");
  CHECK_FALSE(loadConfig(bad, &c, &err));
  CHECK(err == bad + ":2: nodes[0].damping: expected a number, got \"abc\"");
  writeConfigFile(bad, "nodes: [1, 1]\n");
  CHECK_FALSE(loadConfig(bad, &c, &err));
  CHECK(err == bad + ":1: nodes[1]: node id 1 appears twice (first at line 1)");
  writeConfigFile(bad, "interface: vcan0\nnodes: [1]\njiont: {inertia: 1}\n");
  CHECK_FALSE(loadConfig(bad, &c, &err));
  CHECK(err == bad + ":3: jiont: unknown key");
  writeConfigFile(bad, "nodes: [1, 200]\n");
  CHECK_FALSE(loadConfig(bad, &c, &err));
  CHECK(err == bad + ":1: nodes[1]: expected an integer in [1, 127], got 200");
  writeConfigFile(bad, "nodes: [1]\nfaults: {drop_fraction: 1.5}\n");
  CHECK_FALSE(loadConfig(bad, &c, &err));
  CHECK(err == bad + ":2: faults.drop_fraction: expected a fraction in [0, 1], got 1.5");
  writeConfigFile(bad, "nodes:\n  - {node: 2}\n  - {inertia: 1}\n");
  CHECK_FALSE(loadConfig(bad, &c, &err));
  CHECK(err == bad + ":3: nodes[1]: missing required field 'node'");
  std::remove(good.c_str());
  std::remove(bad.c_str());
}

TEST_CASE("drive emulator: hostile configurations are refused with FILE:LINE: FIELD, never a crash",
          "[drive_emu]") {
  const std::string bad = "drive_emu_hostile.yaml";
  // Each: the file, then the exact error (limits of drive_emu.hpp, limits::).
  const std::vector<std::pair<std::string, std::string>> cases = {
      {"nodes: [1]\njoint: 1\n", ":2: joint: expected a map, got 1"},
      {"nodes: [1]\nstep_ms: 1e-6\n", ":2: step_ms: expected a number in [0.01, 100], got 1e-6"},
      {"nodes:\n  - {node: 1, faults: {emcy_at: 1e300}}\n",
       ":2: nodes[0].faults.emcy_at: expected a number in [0, 1000000], got 1e300"},
      {"nodes: [1]\nboot_delay_ms: .nan\n", ":2: boot_delay_ms: expected a finite number, got .nan"},
      {"nodes: [1]\nrated_torque: 4294968\n",
       ":2: rated_torque: expected a number in [0.001, 4294967.295], got 4294968"},
      {"nodes: [1]\nduration: 1e400\n", ":2: duration: expected a finite number, got 1e400"},
      {"nodes: [1]\nboot_delay_ms: -1\n", ":2: boot_delay_ms: expected a number in [0, 60000], got -1"},
      {"nodes:\n  - {node: 1, initial_position: 1e9}\n",
       ":2: nodes[0].initial_position: expected a number in [-1000, 1000], got 1e9"},
      {"nodes: [1]\nprofile: picky\n",
       ":2: profile: expected lenient, strict or a map of switches, got \"picky\""},
      {"nodes: [1]\nprofile: {tpdo_count: 5}\n",
       ":2: profile.tpdo_count: expected an integer in [1, 4], got 5"},
      {"nodes: [1]\nprofile: {sync_timeout_factor: 0.5}\n",
       ":2: profile.sync_timeout_factor: expected 0 (no SYNC timeout) or a factor in [1, 100], got 0.5"},
      {"nodes: [1]\nprofile: {vendor_id: 0x100000000}\n",
       ":2: profile.vendor_id: expected an integer in [0, 4294967295], got \"0x100000000\""},
      {"nodes: 1\n", ":1: nodes: expected a list, got 1"},
      {"[]\n", ":1: (top level): expected a map, got a list of 0"},
  };
  for (const auto& [text, expected] : cases) {
    writeConfigFile(bad, text);
    EmuConfig c;
    std::string err;
    INFO(text);
    CHECK_FALSE(loadConfig(bad, &c, &err));
    CHECK(err == bad + expected);
  }
  // Command-line overrides go through the same limits.
  EmuConfig c = threeNodes();
  std::string err;
  c.duration_s = 1e300;
  CHECK_FALSE(validateConfig(c, "command line", &err));
  CHECK(err == "command line: duration: must be in [0, 1e6] s");
  c = threeNodes();
  CHECK_FALSE(applyFaultSwitch("emcy", "1@1e300", &c, &err));
  CHECK(err == "--emcy 1@1e300: bad time: expected seconds in [0, 1e6]");
  std::remove(bad.c_str());
}

TEST_CASE("drive emulator: the vendor profile from YAML, and a strict drive booted by the master",
          "[drive_emu]") {
  const std::string file = "drive_emu_profile.yaml";
  writeConfigFile(file,
                  "nodes: [1, 2]\nrated_torque: 10\n"
                  "profile: {base: strict, tpdo_count: 3, vendor_id: 0x1234, comm_error_behaviour: 2}\n");
  EmuConfig c;
  std::string err;
  REQUIRE(loadConfig(file, &c, &err));
  const auto strict = mrqp::emulation::VendorProfile::strict();
  CHECK(c.profile.tpdo_count == 3u);
  CHECK(c.profile.vendor_id == 0x1234u);
  CHECK(c.profile.comm_error_behaviour == 2u);
  CHECK(c.profile.rtr_check == strict.rtr_check);
  CHECK(c.profile.sync_timeout_factor == strict.sync_timeout_factor);
  CHECK(c.profile.statusword_bits);
  const std::string text = describeConfig(c);
  CHECK(text.find("3 TPDO(s)") != std::string::npos);
  CHECK(text.find("SYNC timeout 1.5 x 0x1006 (0x1029:01 = 2)") != std::string::npos);
  CHECK(text.find("node 2: 524288 increments/rev, rated 10 N m") != std::string::npos);
  std::remove(file.c_str());

  // The master boots the strict emulated drives (TPDO3/4 absent: 2 aborts tolerated), streams.
  EmuConfig e = threeNodes();
  e.profile = strict;
  Bench b(e);
  REQUIRE(b.arm != nullptr);
  REQUIRE(b.bootAndEnable());
  for (int k = 0; k < 100; ++k) {
    const FaultReport& r = b.cycle();
    REQUIRE(r.flags == 0u);
  }
  for (std::size_t j = 0; j < 3; ++j) {
    CHECK(b.arm->faults().devices[j].tolerated_aborts == 2u);
  }
  // A SYNC gap of 4 cycles: each drive reports EMCY 0x8100 and leaves Operational.
  b.t += 4 * b.config.cycle_period;
  for (int k = 0; k < 20; ++k) b.cycle();
  for (std::size_t j = 0; j < 3; ++j) {
    CHECK(b.emu->emulator().commErrors(j) == 1u);
    CHECK(b.emu->emulator().nmt(j) == MRQP_FW_NMT_STATE_PRE_OPERATIONAL);
    CHECK(b.arm->faults().devices[j].emcy_code == 0x8100);
  }
  CHECK(b.arm->requestRecovery(b.t) == 3u);
  for (int k = 0; k < 200 && !b.arm->ready(); ++k) b.cycle();
  CHECK(b.arm->ready());
  // Safe exit: every emulated drive stopped and pre-operational.
  b.arm->requestSafeExit(b.t);
  for (int k = 0; k < 200 && !b.arm->safeExitDone(); ++k) b.cycle();
  b.cycle();
  CHECK(b.arm->safeExitDone());
  for (std::size_t j = 0; j < 3; ++j) {
    CHECK(b.emu->emulator().state(j) == MRQP_FW_CIA402_SWITCH_ON_DISABLED);
    CHECK(b.emu->emulator().nmt(j) == MRQP_FW_NMT_STATE_PRE_OPERATIONAL);
  }
}

TEST_CASE("drive emulator: corrupted frames are counted by the driver", "[drive_emu]") {
  EmuConfig faulty = threeNodes();
  faulty.corrupt_fraction = 0.05;  // of every frame the emulator sends, boot included
  faulty.seed = 7;
  Bench f(faulty);
  f.arm->start(f.t);
  std::uint64_t corrupt = 0;
  for (int k = 0; k < 1500; ++k) {
    const FaultReport& r = f.cycle();
    for (std::size_t j = 0; j < r.device_count; ++j) {
      corrupt += (r.devices[j].flags & fault::kCorruptFrame) != 0u ? 1u : 0u;
    }
  }
  CHECK(f.emu->emulator().stats().corrupted > 0u);
  CHECK(corrupt > 0u);
}
