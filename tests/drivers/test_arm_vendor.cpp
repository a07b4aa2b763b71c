// The CiA 402 master against a drive as strict as a vendor's (the emulated drive with
// VendorProfile::strict(): two TPDOs, aborts for absent / read-only / out-of-range objects, the
// PDO rules, no RTR-capable TPDOs, a SYNC timeout of 1.5 x 0x1006 with EMCY 0x8100 and
// pre-operational per 0x1029, statusword bits 4 and 9, an identity to read). Each of the four
// interoperability findings is first reproduced with the master's earlier behaviour (a switch of
// ArmConfig, or the cycles a program without a safe exit runs), then shown fixed. Expected values
// come from CiA 301 / CiA 402 (abort codes, frames encoded by hand) and from the test's own
// schedule (SYNC gaps), not from the master.
#include <catch2/catch.hpp>

#include <mrqp/drivers/arm_driver.hpp>
#include <mrqp/drivers/canopen/canopen_text.hpp>

#include <string>
#include <vector>

#include "arm_rig.hpp"

using namespace mrqp::drivers;
using drvtest::ArmRig;
using mrqp::emulation::VendorProfile;

namespace {

ArmConfig config1ms() {
  ArmConfig c;
  c.cycle_period = milliseconds(1);
  c.producer_heartbeat_ms = 10;
  c.heartbeat_timeout = milliseconds(50);
  return c;
}

std::vector<std::string> withPrefix(const std::vector<std::string>& frames, const std::string& prefix) {
  std::vector<std::string> out;
  for (const auto& f : frames) {
    if (f.compare(0, prefix.size(), prefix) == 0) {
      out.push_back(f);
    }
  }
  return out;
}

/// Cycles until `done` or `max` cycles; returns the cycles run.
template <class F>
int cycleUntil(ArmRig& rig, F done, int max) {
  int k = 0;
  while (!done() && k < max) {
    rig.cycle();
    ++k;
  }
  return k;
}

/// Boots and enables; true when every drive is Operation enabled.
bool bootAndEnable(ArmRig& rig) {
  rig.boot();
  if (rig.arm->phase() != ArmPhase::Running) {
    return false;
  }
  rig.arm->requestEnable(rig.t);
  cycleUntil(
      rig, [&] { return rig.arm->allEnabled(); }, 50);
  return rig.arm->allEnabled();
}

}  // namespace

TEST_CASE("vendor: finding 1: a drive with two TPDOs aborts the write disabling TPDO3; the boot tolerates it",
          "[drivers][arm][vendor]") {
  const VendorProfile strict = VendorProfile::strict();
  REQUIRE(strict.tpdo_count == 2);
  {
    // Reproduced with the earlier master (any abort fails the boot).
    ArmConfig c = config1ms();
    c.tolerate_absent_pdos = false;
    ArmRig rig({{0, 1}}, c, 64, {}, false, 2000000, strict);
    REQUIRE(rig.arm != nullptr);
    rig.boot();
    CHECK(rig.arm->phase() == ArmPhase::Failed);
    const DeviceFaults& d = rig.arm->faults().devices[0];
    CHECK(d.sdo_abort_code == 0x06020000u);
    CHECK(d.sdo_index == 0x1802);
    CHECK(d.sdo_subindex == 1);
    CHECK(d.node == 1);
    // The abort on the wire, CiA 301: 0x80, index, sub, code little-endian.
    CHECK(withPrefix(rig.wire(), "581#80021801").size() == 1u);
    const std::string text = describeFaults(rig.arm->faults());
    CHECK_THAT(text, Catch::Matchers::Contains("boot failed"));
    CHECK_THAT(text, Catch::Matchers::Contains("SDO abort 0x06020000 (" +
                                               std::string(mrqp_fw_sdo_abort_str(0x06020000u)) +
                                               ") writing 0x1802:01 of node 1"));
  }
  {
    ArmRig rig({{0, 1}}, config1ms(), 64, {}, false, 2000000, strict);
    REQUIRE(rig.arm != nullptr);
    rig.boot();
    REQUIRE(rig.arm->phase() == ArmPhase::Running);
    const FaultReport& r = rig.cycle();
    CHECK(r.devices[0].tolerated_aborts == 2u);  // TPDO3 and TPDO4
    CHECK(r.flags == 0u);
    CHECK(rig.fakes[0]->rpdo1Configured());
    CHECK(rig.fakes[0]->tpdo1Configured());
    CHECK(rig.fakes[0]->tpdo2Configured());
    std::uint32_t v = 0;
    CHECK_FALSE(rig.fakes[0]->od(0x1802, 1, &v));  // it really has no TPDO3
    CHECK(withPrefix(rig.wire(), "581#80021801").size() == 1u);
    CHECK(withPrefix(rig.wire(), "581#80031801").size() == 1u);
  }
  {
    // One TPDO and TPDO2 not wanted: its disabling write is tolerated too.
    VendorProfile one = strict;
    one.tpdo_count = 1;
    ArmConfig c = config1ms();
    c.tpdo2 = false;
    ArmRig rig({{0, 1}}, c, 64, {}, false, 2000000, one);
    rig.boot();
    REQUIRE(rig.arm->phase() == ArmPhase::Running);
    CHECK(rig.cycle().devices[0].tolerated_aborts == 3u);
  }
  {
    // A PDO the master needs is not tolerated: TPDO2 on a one-TPDO drive fails the boot.
    VendorProfile one = strict;
    one.tpdo_count = 1;
    ArmRig rig({{0, 1}}, config1ms(), 64, {}, false, 2000000, one);
    rig.boot();
    CHECK(rig.arm->phase() == ArmPhase::Failed);
    CHECK(rig.arm->faults().devices[0].sdo_abort_code == 0x06020000u);
    CHECK(rig.arm->faults().devices[0].sdo_index == 0x1801);
  }
}

TEST_CASE("vendor: finding 4: TPDO COB-IDs are written with bit 30 = 1 (no RTR)", "[drivers][arm][vendor]") {
  const VendorProfile strict = VendorProfile::strict();
  REQUIRE(strict.rtr_check);
  {
    // Reproduced: COB-IDs with bit 30 = 0 are refused when the TPDO is enabled.
    ArmConfig c = config1ms();
    c.tpdo_rtr_allowed = true;
    ArmRig rig({{0, 3}}, c, 64, {}, false, 2000000, strict);
    rig.boot();
    CHECK(rig.arm->phase() == ArmPhase::Failed);
    const DeviceFaults& d = rig.arm->faults().devices[0];
    CHECK(d.sdo_abort_code == 0x06090030u);
    CHECK(d.sdo_index == 0x1800);
    CHECK(d.sdo_subindex == 1);
    // The write it refused: 0x00000183, expedited 4 bytes (0x23).
    CHECK(withPrefix(rig.wire(), "603#2300180183010000").size() == 1u);
  }
  {
    ArmRig rig({{0, 3}}, config1ms(), 64, {}, false, 2000000, strict);
    rig.boot();
    REQUIRE(rig.arm->phase() == ArmPhase::Running);
    std::uint32_t v = 0;
    REQUIRE(rig.fakes[0]->od(0x1800, 1, &v));
    CHECK(v == 0x40000183u);
    REQUIRE(rig.fakes[0]->od(0x1801, 1, &v));
    CHECK(v == 0x40000283u);
    CHECK(withPrefix(rig.wire(), "603#2300180183010040").size() == 1u);
  }
}

TEST_CASE("vendor: identity and device type are read and checked before the configuration",
          "[drivers][arm][vendor]") {
  const VendorProfile strict = VendorProfile::strict();
  {
    ArmConfig c = config1ms();
    ArmDriveConfig d;
    d.device_type = 0x192;  // profile 402 in the low 16 bits (default mask)
    d.vendor_id = strict.vendor_id;
    d.product_code = strict.product_code;
    d.revision = strict.revision;
    c.drives.push_back(d);
    ArmRig rig({{0, 1}}, c, 64, {}, false, 2000000, strict);
    REQUIRE(rig.arm != nullptr);
    rig.boot();
    CHECK(rig.arm->phase() == ArmPhase::Running);
    // Upload requests (0x40), CiA 301, before the first write.
    const auto m = rig.masterFrames();
    const auto reads = withPrefix(m, "601#40");
    REQUIRE(reads.size() == 4u);
    CHECK(reads[0] == "601#4000100000000000");
    CHECK(reads[1] == "601#4018100100000000");
    CHECK(reads[2] == "601#4018100200000000");
    CHECK(reads[3] == "601#4018100300000000");
    std::size_t first_read = 0, first_write = 0;
    for (std::size_t k = 0; k < m.size(); ++k) {
      if (m[k] == reads[0]) first_read = k;
      if (first_write == 0 && m[k].compare(0, 5, "601#2") == 0) first_write = k;
    }
    CHECK(first_read < first_write);
  }
  {
    ArmConfig c = config1ms();
    ArmDriveConfig d;
    d.product_code = strict.product_code + 1;
    c.drives.push_back(d);
    ArmRig rig({{0, 1}}, c, 64, {}, false, 2000000, strict);
    rig.boot();
    CHECK(rig.arm->phase() == ArmPhase::Failed);
    const DeviceFaults& f = rig.arm->faults().devices[0];
    CHECK(f.sdo_check_failed);
    CHECK(f.sdo_index == 0x1018);
    CHECK(f.sdo_subindex == 2);
    CHECK(f.sdo_check_actual == strict.product_code);
    CHECK(rig.fakes[0]->sdoWrites() == 0u);  // nothing configured on a wrong device
    CHECK_THAT(
        describeFaults(rig.arm->faults()),
        Catch::Matchers::Contains("0x1018:02 of node 1 is 0x00000402, the configuration expects 0x00000403"));
  }
  {
    ArmConfig c = config1ms();
    ArmDriveConfig d;
    d.device_type = 0x191;  // CiA 401, not a drive
    c.drives.push_back(d);
    ArmRig rig({{0, 1}}, c, 64, {}, false, 2000000, strict);
    rig.boot();
    CHECK(rig.arm->phase() == ArmPhase::Failed);
    CHECK(rig.arm->faults().devices[0].sdo_check_actual == strict.device_type);
  }
}

TEST_CASE("vendor: out-of-range writes are refused with their abort, named in the report",
          "[drivers][arm][vendor]") {
  ArmConfig c = config1ms();
  c.comm_cycle_period_us = 100;  // below the strict drive's 250 us
  ArmRig rig({{0, 2}}, c, 64, {}, false, 2000000, VendorProfile::strict());
  rig.boot();
  CHECK(rig.arm->phase() == ArmPhase::Failed);
  const DeviceFaults& d = rig.arm->faults().devices[0];
  CHECK(d.sdo_abort_code == 0x06090032u);  // value of parameter written too low
  CHECK(d.sdo_index == 0x1006);
  CHECK_THAT(
      describeFaults(rig.arm->faults()),
      Catch::Matchers::Contains("SDO abort 0x06090032 (" + std::string(mrqp_fw_sdo_abort_str(0x06090032u)) +
                                ") writing 0x1006:00 of node 2"));
  // The value written is the configured one, not the cycle period.
  CHECK(withPrefix(rig.wire(), "602#2306100064000000").size() == 1u);
}

TEST_CASE("vendor: statusword bits 4 and 9 as drives set them do not change the decoded states",
          "[drivers][arm][vendor]") {
  ArmRig rig({{0, 1}}, config1ms(), 64, {}, false, 2000000, VendorProfile::strict());
  rig.boot();
  REQUIRE(rig.arm->phase() == ArmPhase::Running);
  for (int k = 0; k < 3; ++k) rig.cycle();
  // Switch on disabled, operational: bit 6, bit 9 (remote), no bit 4 (voltage disabled).
  CHECK(rig.arm->drive(0).statusword == 0x0240);
  CHECK(rig.arm->drive(0).state == MRQP_FW_CIA402_SWITCH_ON_DISABLED);
  rig.arm->requestEnable(rig.t);
  cycleUntil(
      rig, [&] { return rig.arm->allEnabled(); }, 50);
  REQUIRE(rig.arm->allEnabled());
  CHECK(rig.arm->drive(0).statusword == 0x0237);  // 0x27 Operation enabled, bit 4, bit 9
  CHECK(rig.cycle().flags == 0u);
}

TEST_CASE(
    "vendor: finding 2: a SYNC gap makes the drive leave Operational; recovery only when asked, never in "
    "the safe state",
    "[drivers][arm][vendor]") {
  const VendorProfile strict = VendorProfile::strict();
  REQUIRE(strict.sync_timeout_factor == 1.5);
  ArmRig rig({{0, 1}, {0, 2}}, config1ms(), 64, {}, true, 2000000, strict);
  REQUIRE(bootAndEnable(rig));
  for (int k = 0; k < 5; ++k) {
    CHECK(rig.cycle().flags == 0u);
  }
  // A 3 ms gap in the cycle (two cycles lost): more than 1.5 x 0x1006 = 1.5 ms.
  rig.t += milliseconds(2);
  rig.cycle();
  for (const auto& f : rig.fakes) {
    CHECK(f->commErrors() == 1u);
    CHECK(f->nmt() == MRQP_FW_NMT_STATE_PRE_OPERATIONAL);
  }
  // EMCY 0x8100, register 0x11 (generic | communication), CiA 301, from each node.
  CHECK(withPrefix(rig.wire(), "081#0081110000000000").size() == 1u);
  CHECK(withPrefix(rig.wire(), "082#0081110000000000").size() == 1u);

  // Reproduced: without a recovery the master fails every cycle, for good.
  std::uint32_t seen = 0;
  for (int k = 0; k < 100; ++k) {
    const FaultReport& r = rig.cycle();
    CHECK(r.flags != 0u);
    seen |= r.flags;
  }
  CHECK((seen & fault::kEmcy) != 0u);
  CHECK((seen & fault::kStateMismatch) != 0u);
  CHECK((seen & fault::kFeedbackMissing) != 0u);
  CHECK(rig.arm->needsRecovery(0));
  CHECK(rig.arm->needsRecovery(1));
  CHECK_FALSE(rig.arm->ready());
  // The master saw the gap as the drives did (SYNC timed on its TX echo).
  CHECK(rig.arm->syncStats(0).over_timeout == 1u);
  CHECK(rig.arm->syncStats(0).max_interval == milliseconds(3));
  const FaultReport& now_faults = rig.arm->faults();
  CHECK(now_faults.devices[0].emcy_code == 0x8100);
  CHECK(now_faults.devices[0].nmt_state == MRQP_FW_NMT_STATE_PRE_OPERATIONAL);
  const std::string text = describeFaults(now_faults);
  CHECK_THAT(text, Catch::Matchers::Contains("EMCY 0x8100 (" + std::string(mrqp_fw_emcy_code_str(0x8100)) +
                                             ") register 0x11 from node 1"));
  CHECK_THAT(text, Catch::Matchers::Contains("NMT state pre-operational"));

  // Never while the safe state is in force.
  rig.arm->setSafeState(true);
  CHECK(rig.arm->requestRecovery(rig.t) == 0u);
  for (int k = 0; k < 20; ++k) rig.cycle();
  CHECK(rig.fakes[0]->nmt() == MRQP_FW_NMT_STATE_PRE_OPERATIONAL);

  // Asked for, outside the safe state: NMT start per node, then enable, every flag gone.
  rig.arm->setSafeState(false);
  const TimeNs asked = rig.t;
  CHECK(rig.arm->requestRecovery(rig.t) == 2u);
  CHECK(rig.arm->recovering(0));
  const int k = cycleUntil(
      rig, [&] { return rig.arm->ready() && !rig.arm->recovering(0) && !rig.arm->recovering(1); }, 100);
  CHECK(k < 100);
  CHECK(rig.arm->allEnabled());
  const auto starts = withPrefix(rig.masterFrames(asked), "000#01");
  CHECK(starts == std::vector<std::string>{"000#0101", "000#0102"});
  for (int j = 0; j < 5; ++j) rig.cycle();
  const FaultReport& after = rig.cycle();
  CHECK(after.flags == 0u);
  CHECK(after.devices[0].recoveries == 1u);
  CHECK(after.devices[0].emcy_code == 0u);  // the drive's error reset EMCY
  for (const auto& f : rig.fakes) {
    CHECK(f->nmt() == MRQP_FW_NMT_STATE_OPERATIONAL);
    CHECK(f->state() == MRQP_FW_CIA402_OPERATION_ENABLED);
    CHECK_FALSE(f->commErrorActive());
  }
}

TEST_CASE("vendor: automatic recovery where configured, held off by the safe state",
          "[drivers][arm][vendor]") {
  ArmConfig c = config1ms();
  c.recovery = RecoveryPolicy::Automatic;
  c.recovery_retry = milliseconds(20);
  ArmRig rig({{0, 1}}, c, 64, {}, true, 2000000, VendorProfile::strict());
  REQUIRE(bootAndEnable(rig));
  rig.arm->setSafeState(true);
  rig.t += milliseconds(2);
  for (int k = 0; k < 100; ++k) rig.cycle();
  CHECK(rig.fakes[0]->nmt() == MRQP_FW_NMT_STATE_PRE_OPERATIONAL);
  CHECK_FALSE(rig.arm->recovering(0));
  rig.arm->setSafeState(false);
  cycleUntil(
      rig, [&] { return rig.arm->ready(); }, 100);
  CHECK(rig.arm->ready());
  CHECK(rig.fakes[0]->nmt() == MRQP_FW_NMT_STATE_OPERATIONAL);
  CHECK(rig.arm->faults().devices[0].recoveries == 1u);
}

TEST_CASE("vendor: a drive that reboots is reconfigured, started and enabled again on request",
          "[drivers][arm][vendor]") {
  ArmRig rig({{0, 1}, {0, 2}}, config1ms(), 64, {}, true, 2000000, VendorProfile::strict());
  REQUIRE(bootAndEnable(rig));
  const unsigned writes_before = rig.fakes[1]->sdoWrites();
  rig.fakes[1]->power(false);
  for (int k = 0; k < 5; ++k) rig.cycle();
  rig.fakes[1]->power(true);
  std::uint32_t seen = 0;
  for (int k = 0; k < 30; ++k) seen |= rig.cycle().flags;
  CHECK((seen & fault::kStateMismatch) != 0u);
  CHECK(rig.arm->needsRecovery(1));
  CHECK_FALSE(rig.arm->needsRecovery(0));
  CHECK(rig.fakes[0]->state() == MRQP_FW_CIA402_OPERATION_ENABLED);  // the other drive runs on
  CHECK(rig.arm->requestRecovery(rig.t) == 1u);
  cycleUntil(
      rig, [&] { return rig.arm->ready() && !rig.arm->recovering(1); }, 200);
  CHECK(rig.arm->ready());
  CHECK(rig.fakes[1]->sdoWrites() == 2 * writes_before);  // the whole configuration again
  CHECK(rig.fakes[1]->tpdo1Configured());
  for (int k = 0; k < 5; ++k) rig.cycle();
  CHECK(rig.cycle().flags == 0u);
}

TEST_CASE("vendor: finding 3: the safe exit stops the drives and leaves them pre-operational",
          "[drivers][arm][vendor]") {
  {
    // Reproduced: a program that just stops cycling leaves the drive enabled and operational.
    ArmRig rig({{0, 1}}, config1ms(), 64, {}, false, 2000000, VendorProfile::strict());
    REQUIRE(bootAndEnable(rig));
    for (int k = 0; k < 5; ++k) rig.cycle();
    rig.flush();
    CHECK(rig.fakes[0]->state() == MRQP_FW_CIA402_OPERATION_ENABLED);
    CHECK(rig.fakes[0]->nmt() == MRQP_FW_NMT_STATE_OPERATIONAL);
    CHECK(rig.fakes[0]->lastControlword() == 0x000F);
  }
  {
    // Quick stop (0x0002), disable voltage (0x0000), NMT enter pre-operational (0x80).
    ArmRig rig({{0, 1}, {0, 2}}, config1ms(), 64, {}, false, 2000000, VendorProfile::strict());
    REQUIRE(bootAndEnable(rig));
    const TimeNs from = rig.t;
    rig.arm->requestSafeExit(rig.t);
    const int k = cycleUntil(
        rig, [&] { return rig.arm->safeExitDone(); }, 100);
    CHECK(k < 20);
    const TimeNs done = rig.t;
    for (int j = 0; j < 10; ++j) rig.cycle();
    for (const auto& f : rig.fakes) {
      CHECK(f->state() == MRQP_FW_CIA402_SWITCH_ON_DISABLED);
      CHECK(f->nmt() == MRQP_FW_NMT_STATE_PRE_OPERATIONAL);
    }
    std::vector<std::uint16_t> cws;
    for (const auto& f : withPrefix(rig.masterFrames(from), "201#")) {
      const auto cw = static_cast<std::uint16_t>(std::stoul(f.substr(4, 2), nullptr, 16));
      if (cws.empty() || cws.back() != cw) cws.push_back(cw);
    }
    CHECK(cws == std::vector<std::uint16_t>{0x02, 0x00});
    CHECK(withPrefix(rig.masterFrames(from), "000#") == std::vector<std::string>{"000#8001", "000#8002"});
    // Nothing cyclic after the exit.
    CHECK(withPrefix(rig.masterFrames(done), "080#").empty());
    CHECK(withPrefix(rig.masterFrames(done), "201#").empty());
  }
  {
    // Disable voltage and NMT stop, as configured.
    ArmConfig c = config1ms();
    c.exit_stop = ExitStop::DisableVoltage;
    c.exit_nmt = ExitNmt::Stopped;
    ArmRig rig({{0, 1}}, c, 64, {}, false, 2000000, VendorProfile::strict());
    REQUIRE(bootAndEnable(rig));
    const TimeNs from = rig.t;
    rig.arm->requestSafeExit(rig.t);
    cycleUntil(
        rig, [&] { return rig.arm->safeExitDone(); }, 100);
    REQUIRE(rig.arm->safeExitDone());
    rig.cycle();
    CHECK(rig.fakes[0]->state() == MRQP_FW_CIA402_SWITCH_ON_DISABLED);
    CHECK(rig.fakes[0]->nmt() == MRQP_FW_NMT_STATE_STOPPED);
    const auto rpdos = withPrefix(rig.masterFrames(from), "201#");
    REQUIRE_FALSE(rpdos.empty());
    for (const auto& f : rpdos) CHECK(f.substr(4, 4) == "0000");
    CHECK(withPrefix(rig.masterFrames(from), "000#") == std::vector<std::string>{"000#0201"});
  }
  {
    // Drives that left Operational with their power stage on (a SYNC gap: PDOs stopped): disable
    // voltage by SDO (0x6040 = 0x0000, expedited 2 bytes 0x2B), then the NMT command.
    ArmRig rig({{0, 1}, {0, 2}}, config1ms(), 64, {}, false, 2000000, VendorProfile::strict());
    REQUIRE(bootAndEnable(rig));
    rig.t += milliseconds(2);
    for (int k = 0; k < 20; ++k) rig.cycle();
    REQUIRE(rig.fakes[0]->nmt() == MRQP_FW_NMT_STATE_PRE_OPERATIONAL);
    REQUIRE(rig.fakes[0]->state() == MRQP_FW_CIA402_OPERATION_ENABLED);
    const TimeNs from = rig.t;
    rig.arm->requestSafeExit(rig.t);
    cycleUntil(
        rig, [&] { return rig.arm->safeExitDone(); }, 100);
    REQUIRE(rig.arm->safeExitDone());
    rig.cycle();
    const auto m = rig.masterFrames(from);
    CHECK(withPrefix(m, "601#") == std::vector<std::string>{"601#2B40600000000000"});
    CHECK(withPrefix(m, "602#") == std::vector<std::string>{"602#2B40600000000000"});
    CHECK(withPrefix(m, "000#") == std::vector<std::string>{"000#8001", "000#8002"});
    for (const auto& f : rig.fakes) {
      CHECK(f->state() == MRQP_FW_CIA402_SWITCH_ON_DISABLED);
      CHECK(f->nmt() == MRQP_FW_NMT_STATE_PRE_OPERATIONAL);
    }
    CHECK(rig.arm->faults().devices[0].corrupt_frames == 0u);  // the SDO answers were expected
  }
  {
    // After a failed boot: straight to the NMT command.
    ArmConfig c = config1ms();
    c.tpdo_rtr_allowed = true;
    ArmRig rig({{0, 1}}, c, 64, {}, false, 2000000, VendorProfile::strict());
    rig.boot();
    REQUIRE(rig.arm->phase() == ArmPhase::Failed);
    const TimeNs from = rig.t;
    rig.arm->requestSafeExit(rig.t);
    cycleUntil(
        rig, [&] { return rig.arm->safeExitDone(); }, 10);
    CHECK(rig.arm->safeExitDone());
    CHECK(withPrefix(rig.masterFrames(from), "000#") == std::vector<std::string>{"000#8001"});
  }
}

TEST_CASE("vendor: SYNC intervals and jitter as the test scheduled them", "[drivers][arm][vendor]") {
  for (const bool echo : {false, true}) {
    ArmRig rig({{0, 1}}, config1ms(), 64, {}, echo, 2000000, VendorProfile::lenient());
    rig.boot();
    REQUIRE(rig.arm->phase() == ArmPhase::Running);
    for (int k = 0; k < 10; ++k) rig.cycle();
    SyncStats s = rig.arm->syncStats(0);
    CHECK(s.intervals + 1 == s.syncs);
    CHECK(s.min_interval == milliseconds(1));
    CHECK(s.max_interval == milliseconds(1));
    CHECK(s.max_jitter == 0);
    // One cycle 400 us late, then back on time: intervals 1.4 and 0.6 ms (with echoes a SYNC is
    // timed when its echo is read, at the next cycle: one regular cycle more).
    rig.t += microseconds(400);
    rig.cycle();
    rig.t -= microseconds(400);
    rig.cycle();
    rig.cycle();
    s = rig.arm->syncStats(0);
    CHECK(s.max_interval == microseconds(1400));
    CHECK(s.min_interval == microseconds(600));
    CHECK(s.max_jitter == microseconds(400));
    CHECK(s.over_timeout == 0u);
    rig.t += microseconds(600);  // 1.6 ms > 1.5 x 1 ms
    rig.cycle();
    rig.cycle();
    CHECK(rig.arm->syncStats(0).over_timeout == 1u);
  }
}
