// The emulated CiA 402 drive's own watch of the master (vendor_profile.hpp): the heartbeat
// consumer of 0x1016:1 and the RPDO timeout of 0x1400:05, each a communication error with its
// EMCY (0x8130, 0x8250, hand-encoded here from CiA 301: code little-endian, error register
// generic | communication = 0x11) and the CiA 402 reaction of 0x6007 (abort connection option
// code: 1 fault, 2 disable voltage, 3 quick stop), on a SimBus against the arm master. The master
// "stops" by no longer cycling (its heartbeat, SYNC and RPDOs end with it); the times are read off
// the wire. Both watches are off by default: the same runs then leave the drive as it was.
#include <catch2/catch.hpp>

#include <mrqp/drivers/faults.hpp>

#include <string>
#include <vector>

#include "arm_rig.hpp"

using mrqp::drivers::ArmConfig;
using mrqp::drivers::milliseconds;
using mrqp::drivers::TimeNs;
using mrqp::emulation::VendorProfile;

namespace {

constexpr std::uint8_t kMasterNode = 100;

ArmConfig watchedConfig() {
  ArmConfig cfg;
  cfg.cycle_period = milliseconds(1);
  cfg.master_node = kMasterNode;  // the master's heartbeat, written to the drive's 0x1016:1
  cfg.master_heartbeat_ms = 100;
  cfg.drive_consumer_ms = 300;
  return cfg;
}

/// Boots and enables the one drive of the rig; then `cycles` running cycles.
void bootAndEnable(drvtest::ArmRig& rig, int cycles) {
  REQUIRE(rig.error.empty());
  rig.boot();
  REQUIRE(rig.arm->phase() == mrqp::drivers::ArmPhase::Running);
  rig.arm->requestEnable(rig.t);
  for (int k = 0; k < 50 && !rig.arm->allEnabled(); ++k) rig.cycle();
  REQUIRE(rig.arm->allEnabled());
  for (int k = 0; k < cycles; ++k) rig.cycle();
  rig.flush();
}

/// End of the last delivered frame with identifier `id` on bus 0.
TimeNs lastFrameEnd(const drvtest::ArmRig& rig, std::uint32_t id) {
  TimeNs end = -1;
  for (const auto& e : rig.logs[0]->events) {
    if (e.outcome == mrqp::drivers::WireOutcome::Delivered && e.frame.id == id) end = e.end;
  }
  return end;
}

/// Start times of delivered frames `text` on bus 0 from `from` on.
std::vector<TimeNs> startsOf(const drvtest::ArmRig& rig, const std::string& text, TimeNs from) {
  std::vector<TimeNs> at;
  for (const auto& e : rig.logs[0]->events) {
    if (e.outcome == mrqp::drivers::WireOutcome::Delivered && e.start >= from &&
        drvtest::frameStr(e.frame) == text) {
      at.push_back(e.start);
    }
  }
  return at;
}

}  // namespace

TEST_CASE("emulated drive: heartbeat consumer of the master (0x1016), EMCY 0x8130 and its reaction",
          "[drivers][emulation][vendor]") {
  for (const bool on : {true, false}) {
    INFO((on ? "heartbeat consumer on" : "heartbeat consumer off (default)"));
    VendorProfile p = VendorProfile::lenient();
    p.heartbeat_consumer = on;
    p.abort_connection_option = 1;  // fault
    drvtest::ArmRig rig({{0, 1}}, watchedConfig(), 64, {}, false, milliseconds(2), p);
    bootAndEnable(rig, 200);
    std::uint32_t consumer = 0;
    REQUIRE(rig.fakes[0]->od(0x1016, 1, &consumer));
    CHECK(consumer == ((static_cast<std::uint32_t>(kMasterNode) << 16) | 300u));

    // The master stops: no cycle any more, the bus runs on for 600 ms.
    const TimeNs stop = rig.t;
    const TimeNs last_hb = lastFrameEnd(rig, 0x700u + kMasterNode);
    REQUIRE(last_hb > 0);
    rig.buses[0]->advanceTo(stop + milliseconds(600));
    const std::vector<TimeNs> emcy = startsOf(rig, "081#3081110000000000", stop);
    if (!on) {
      CHECK(emcy.empty());
      CHECK(rig.fakes[0]->nmt() == MRQP_FW_NMT_STATE_OPERATIONAL);
      CHECK(rig.fakes[0]->state() == MRQP_FW_CIA402_OPERATION_ENABLED);
      continue;
    }
    // One EMCY 0x8130 right after the consumer time (300 ms) from the last heartbeat heard.
    REQUIRE(emcy.size() == 1u);
    CHECK(emcy[0] > last_hb + milliseconds(300) - 200000);
    CHECK(emcy[0] < last_hb + milliseconds(300) + 200000);
    // 0x1029:01 = 0: pre-operational; 0x6007 = 1: the power stage faults.
    CHECK(rig.fakes[0]->nmt() == MRQP_FW_NMT_STATE_PRE_OPERATIONAL);
    CHECK(rig.fakes[0]->state() == MRQP_FW_CIA402_FAULT);

    // The master is back: its update sees the EMCY, the state and the Fault; a recovery (NMT
    // start, fault reset, enable) brings the drive back, and the EMCY is reset.
    rig.t = stop + milliseconds(600);
    const mrqp::drivers::FaultReport& rep = rig.cycle();
    CHECK((rep.flags & mrqp::drivers::fault::kEmcy) != 0u);
    CHECK(mrqp::drivers::describeDeviceFaults(rep.devices[0]).find("0x8130") != std::string::npos);
    bool recovered = false;
    for (int k = 0; k < 1000 && !recovered; ++k) {
      if (rig.arm->needsRecovery(0)) (void)rig.arm->requestRecovery(rig.t);
      rig.cycle();
      recovered = rig.arm->ready() && rig.arm->faults().devices[0].recoveries == 1u;
    }
    CHECK(recovered);
    CHECK(rig.fakes[0]->state() == MRQP_FW_CIA402_OPERATION_ENABLED);
    CHECK(startsOf(rig, "081#0000000000000000", stop).size() == 1u);
  }
}

TEST_CASE("emulated drive: RPDO timeout (0x1400:05), EMCY 0x8250 and the reaction of 0x6007",
          "[drivers][emulation][vendor]") {
  struct Case {
    std::uint16_t timeout_ms;
    std::uint8_t option;
    mrqp_fw_cia402_state after;
  };
  for (const Case c :
       {Case{5, 1, MRQP_FW_CIA402_FAULT}, Case{5, 2, MRQP_FW_CIA402_SWITCH_ON_DISABLED},
        Case{5, 3, MRQP_FW_CIA402_QUICK_STOP_ACTIVE}, Case{0, 1, MRQP_FW_CIA402_OPERATION_ENABLED}}) {
    INFO("timeout " << c.timeout_ms << " ms, 0x6007 = " << int(c.option));
    VendorProfile p = VendorProfile::lenient();
    p.rpdo_timeout_ms = c.timeout_ms;
    p.abort_connection_option = c.option;
    ArmConfig cfg;
    cfg.cycle_period = milliseconds(1);
    drvtest::ArmRig rig({{0, 1}}, cfg, 64, {}, false, milliseconds(2), p);
    bootAndEnable(rig, 50);
    std::uint32_t v = 0;
    REQUIRE(rig.fakes[0]->od(0x1400, 5, &v));
    CHECK(v == c.timeout_ms);
    std::uint32_t option = 0;
    REQUIRE(rig.fakes[0]->od(0x6007, 0, &option));
    CHECK(option == c.option);
    // Running with RPDOs every millisecond: no timeout.
    CHECK(startsOf(rig, "081#5082110000000000", 0).empty());

    const TimeNs stop = rig.t;
    const TimeNs last_rpdo = lastFrameEnd(rig, 0x201);
    REQUIRE(last_rpdo > 0);
    rig.buses[0]->advanceTo(stop + milliseconds(50));
    const std::vector<TimeNs> emcy = startsOf(rig, "081#5082110000000000", stop);
    CHECK(rig.fakes[0]->state() == c.after);
    CHECK(rig.fakes[0]->nmt() == MRQP_FW_NMT_STATE_OPERATIONAL);  // the CiA 402 reaction only
    if (c.timeout_ms == 0) {
      CHECK(emcy.empty());
      continue;
    }
    REQUIRE(emcy.size() == 1u);
    CHECK(emcy[0] > last_rpdo + milliseconds(c.timeout_ms) - 100000);
    CHECK(emcy[0] < last_rpdo + milliseconds(c.timeout_ms) + 100000);
  }
}
