// The arm driver's wire output and fault reports, recorded: six scenarios (two buses with SYNC
// counter and master heartbeat through enable, setpoints, a drive fault, quick stop, a drive
// powered off and on, a restart; reset communication; no reset; an SDO abort; a two-frame
// transmit queue; a boot timeout) run on SimBus against the fake drives, every frame on every bus
// and every cycle's phase and fault flags written as text, and compared with the recording in
// tests/drivers/data/arm_wire.txt made by an earlier implementation of the master, with and
// without the masters receiving their own frames (TX echo). With
// MRQP_RECORD_ARM_WIRE=1 in the environment the test writes the recording instead.
#include <catch2/catch.hpp>

#include <mrqp/drivers/arm_driver.hpp>

#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <functional>
#include <iterator>
#include <sstream>
#include <string>
#include <vector>

#include "arm_rig.hpp"

using namespace mrqp::drivers;

namespace {

std::string hex(std::uint32_t v) {
  char b[16];
  std::snprintf(b, sizeof b, "%X", v);
  return b;
}

/// Runs `cycles` cycles with `program(rig, k)` as the hook; appends the cycle records and then
/// every bus's wire log to `out`.
void run(const std::string& name, drvtest::ArmRig& rig, int cycles,
         const std::function<void(drvtest::ArmRig&, int)>& program, std::ostringstream& out) {
  out << "== " << name << "\n";
  for (int k = 0; k < cycles; ++k) {
    rig.hook = [&program, k](drvtest::ArmRig& r) { program(r, k); };
    const FaultReport& rep = rig.cycle();
    out << "cycle " << k << " " << armPhaseStr(rig.arm->phase()) << " flags " << hex(rep.flags);
    for (std::size_t i = 0; i < rep.device_count; ++i) {
      const DeviceFaults& d = rep.devices[i];
      out << " | " << hex(d.flags) << " m" << d.missed_cycles << " e" << d.emcy_count << " c"
          << d.corrupt_frames << " q" << d.tx_queue_full << " a" << hex(d.sdo_abort_code) << "@"
          << hex(d.sdo_index) << "." << unsigned(d.sdo_subindex);
    }
    for (std::size_t i = 0; i < rig.arm->driveCount(); ++i) {
      const ArmDriveState& s = rig.arm->drive(i);
      out << " ; " << s.position_inc << " " << s.statusword << " " << unsigned(s.nmt_state) << " "
          << s.controlword;
    }
    out << "\n";
  }
  rig.flush();
  for (std::size_t b = 0; b < rig.logs.size(); ++b) {
    for (const WireEvent& e : rig.logs[b]->events) {
      out << "bus " << b << " t " << e.start << " n " << e.node << " o " << static_cast<int>(e.outcome) << " "
          << drvtest::frameStr(e.frame) << "\n";
    }
  }
}

ArmConfig baseConfig() {
  ArmConfig c;
  c.tpdo_rtr_allowed = true;  // the recording predates TPDO COB-IDs with bit 30 (no RTR)
  c.cycle_period = milliseconds(1);
  return c;
}

/// `echo`: the masters receive their own frames (TX echo); the wire output must not change.
std::string recordAll(bool echo) {
  std::ostringstream out;
  {
    ArmConfig c = baseConfig();
    c.master_node = 0x7F;
    c.master_heartbeat_ms = 20;
    c.drive_consumer_ms = 60;
    c.producer_heartbeat_ms = 20;
    c.heartbeat_timeout = milliseconds(60);
    c.sync_counter_overflow = 10;
    ArmDriveConfig csp;
    csp.position_min = -2.0;
    csp.position_max = 2.0;
    ArmDriveConfig cst = csp;
    cst.mode = MRQP_FW_MODE_CST;
    cst.torque_limit = 40.0;
    c.drives = {csp, cst, csp};
    drvtest::ArmRig rig({{0, 1}, {0, 2}, {1, 5}}, c, 64, {100, -200, 3000}, echo);
    REQUIRE(rig.arm != nullptr);
    rig.arm->start(rig.t);
    run(
        "two buses", rig, 620,
        [](drvtest::ArmRig& r, int k) {
          if (k == 40 || k == 150) {
            r.arm->requestEnable(r.t);
          }
          if (k >= 40 && k < 250) {
            (void)r.arm->setPosition(0, 0.5 * std::sin(0.05 * k));
            (void)r.arm->setTorque(0, 0.25);
            (void)r.arm->setTorque(1, 5.0 * std::cos(0.05 * k));
            (void)r.arm->setPosition(2, k == 120 ? 9.0 : -0.3);  // once beyond the limit
          }
          if (k == 100) {
            r.fakes[0]->injectFault(0x2310, 0x03);
          }
          if (k == 250) {
            r.arm->requestQuickStop(r.t);
          }
          if (k == 280) {
            r.arm->requestDisable(r.t);
          }
          if (k == 320) {
            r.fakes[2]->power(false);
          }
          if (k == 400) {
            r.fakes[2]->power(true);
          }
          if (k == 450) {
            r.arm->start(r.t);
          }
        },
        out);
  }
  {
    ArmConfig c = baseConfig();
    c.reset = NmtReset::Communication;
    c.tpdo2 = false;
    c.write_cycle_period = false;
    drvtest::ArmRig rig({{0, 3}, {0, 4}}, c, 64, {}, echo);
    REQUIRE(rig.arm != nullptr);
    rig.arm->start(rig.t);
    run(
        "reset communication", rig, 120,
        [](drvtest::ArmRig& r, int k) {
          if (k == 60) {
            r.arm->requestEnable(r.t);
          }
        },
        out);
  }
  {
    ArmConfig c = baseConfig();
    c.reset = NmtReset::None;
    c.produce_sync = false;
    drvtest::ArmRig rig({{0, 7}}, c, 64, {}, echo);
    REQUIRE(rig.arm != nullptr);
    rig.arm->start(rig.t);
    run(
        "no reset, no SYNC", rig, 200, [](drvtest::ArmRig&, int) {}, out);
  }
  {
    ArmConfig c = baseConfig();
    drvtest::ArmRig rig({{0, 1}, {0, 2}}, c, 64, {}, echo);
    REQUIRE(rig.arm != nullptr);
    rig.fakes[1]->abortOnWrite(0x1A00, 0, 0x06090030u);
    rig.arm->start(rig.t);
    run(
        "SDO abort", rig, 60, [](drvtest::ArmRig&, int) {}, out);
  }
  {
    ArmConfig c = baseConfig();
    drvtest::ArmRig rig({{0, 1}, {0, 2}, {0, 3}, {0, 4}}, c, 2, {}, echo);
    REQUIRE(rig.arm != nullptr);
    rig.arm->start(rig.t);
    run(
        "two-frame queue", rig, 300,
        [](drvtest::ArmRig& r, int k) {
          if (k == 200) {
            r.arm->requestEnable(r.t);
          }
        },
        out);
  }
  {
    ArmConfig c = baseConfig();
    c.boot_timeout = milliseconds(30);
    drvtest::ArmRig rig({{0, 1}, {0, 2}}, c, 64, {}, echo);
    REQUIRE(rig.arm != nullptr);
    rig.fakes[1]->power(false);
    rig.arm->start(rig.t);
    run(
        "boot timeout", rig, 50, [](drvtest::ArmRig&, int) {}, out);
  }
  return out.str();
}

}  // namespace

TEST_CASE("drivers: arm master: wire output and fault reports as recorded", "[drivers][arm]") {
  const std::string path = std::string(MRQP_DRIVERS_TEST_DATA) + "/arm_wire.txt";
  const std::string now = recordAll(false);
  const char* record = std::getenv("MRQP_RECORD_ARM_WIRE");
  if (record != nullptr && std::string(record) == "1") {
    std::ofstream(path) << now;
    WARN("recorded " << path);
    return;
  }
  std::ifstream in(path);
  REQUIRE(in.good());
  const std::string before((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  REQUIRE(before.size() > 100000u);
  if (before != now) {
    // The first line that differs.
    std::istringstream a(before);
    std::istringstream b(now);
    std::string la;
    std::string lb;
    int line = 0;
    while (std::getline(a, la) && std::getline(b, lb)) {
      ++line;
      if (la != lb) {
        break;
      }
    }
    FAIL("line " << line << ": recorded \"" << la << "\", now \"" << lb << "\"");
  }
  // With TX echoes the master waits for the reset's echo instead of its send time: the same output.
  CHECK(recordAll(true) == before);
}
