// The CiA 402 master against fake drives on the simulated bus: exact boot and cyclic frame
// sequences (encoded here by hand from CiA 301/402), the enable/disable controlword sequences,
// EMCY decoding, heartbeat-loss detection time, missing feedback, corrupted frames, NaN setpoints.
#include <catch2/catch.hpp>

#include <mrqp/drivers/arm_driver.hpp>

#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include "arm_rig.hpp"

using namespace mrqp::drivers;
using drvtest::ArmRig;
using drvtest::frameStr;
using drvtest::makeFrame;

namespace {

// Expedited SDO download request, CiA 301: byte 0 = 001 0 nn 1 1 with nn = 4 - size.
std::string sdoWrite(unsigned node, unsigned index, unsigned sub, unsigned size, std::uint32_t value) {
  char buf[64];
  const unsigned cs = 0x23u | ((4u - size) << 2);
  std::snprintf(buf, sizeof(buf), "%03X#%02X%02X%02X%02X%02X%02X%02X%02X", 0x600 + node, cs, index & 0xFFu,
                index >> 8, sub, value & 0xFFu, (value >> 8) & 0xFFu, size > 2 ? (value >> 16) & 0xFFu : 0u,
                size > 2 ? (value >> 24) & 0xFFu : 0u);
  return buf;
}

// Download response: 0x60, index, sub, zeros.
std::string sdoAck(unsigned node, unsigned index, unsigned sub) {
  char buf[64];
  std::snprintf(buf, sizeof(buf), "%03X#60%02X%02X%02X00000000", 0x580 + node, index & 0xFFu, index >> 8,
                sub);
  return buf;
}

struct Write {
  unsigned index, sub, size;
  std::uint32_t value;
};

// The boot configuration of node n (period 1 ms, heartbeat 100 ms, TPDO2 on, CSP), by hand:
// CiA 301 PDO procedure (disable, transmission type, clear mapping, entries, count, enable),
// mapping entries = index << 16 | sub << 8 | bits (docs/protocol.md); TPDO COB-IDs with bit 31
// (0x80000000: disabled) while configured and bit 30 (0x40000000: no RTR) always.
std::vector<Write> bootWrites(unsigned n, bool consumer = false) {
  std::vector<Write> w = {{0x1017, 0, 2, 100}};
  if (consumer) {
    w.push_back({0x1016, 1, 4, (0x7Fu << 16) | 30u});
  }
  const std::vector<Write> rest = {
      {0x1006, 0, 4, 1000},
      {0x1400, 1, 4, 0x80000200u + n},
      {0x1400, 2, 1, 1},
      {0x1600, 0, 1, 0},
      {0x1600, 1, 4, 0x60400010u},
      {0x1600, 2, 4, 0x607A0020u},
      {0x1600, 3, 4, 0x60710010u},
      {0x1600, 0, 1, 3},
      {0x1400, 1, 4, 0x200u + n},
      {0x1800, 1, 4, 0xC0000180u + n},
      {0x1800, 2, 1, 1},
      {0x1A00, 0, 1, 0},
      {0x1A00, 1, 4, 0x60410010u},
      {0x1A00, 2, 4, 0x60640020u},
      {0x1A00, 3, 4, 0x60770010u},
      {0x1A00, 0, 1, 3},
      {0x1800, 1, 4, 0x40000180u + n},
      {0x1801, 1, 4, 0xC0000280u + n},
      {0x1801, 2, 1, 1},
      {0x1A01, 0, 1, 0},
      {0x1A01, 1, 4, 0x606C0020u},
      {0x1A01, 2, 4, 0x603F0010u},
      {0x1A01, 3, 4, 0x60610008u},
      {0x1A01, 0, 1, 3},
      {0x1801, 1, 4, 0x40000280u + n},
      {0x1802, 1, 4, 0xC0000380u + n},
      {0x1803, 1, 4, 0xC0000480u + n},
      {0x6060, 0, 1, 8},
  };
  w.insert(w.end(), rest.begin(), rest.end());
  return w;
}

std::string rpdo(unsigned node, std::uint16_t cw, std::int32_t pos, std::int16_t torque) {
  char buf[64];
  const auto p = static_cast<std::uint32_t>(pos);
  const auto t = static_cast<std::uint16_t>(torque);
  std::snprintf(buf, sizeof(buf), "%03X#%02X%02X%02X%02X%02X%02X%02X%02X", 0x200 + node, cw & 0xFFu, cw >> 8,
                p & 0xFFu, (p >> 8) & 0xFFu, (p >> 16) & 0xFFu, p >> 24, t & 0xFFu, t >> 8);
  return buf;
}

std::vector<std::string> only(const std::vector<std::string>& frames, unsigned id) {
  char prefix[8];
  std::snprintf(prefix, sizeof(prefix), "%03X#", id);
  std::vector<std::string> out;
  for (const auto& f : frames) {
    if (f.compare(0, 4, prefix) == 0) {
      out.push_back(f);
    }
  }
  return out;
}

std::uint16_t cwOf(const std::string& rpdo_text) {
  return static_cast<std::uint16_t>(std::stoul(rpdo_text.substr(4, 2), nullptr, 16) |
                                    (std::stoul(rpdo_text.substr(6, 2), nullptr, 16) << 8));
}

ArmConfig baseConfig() {
  ArmConfig c;
  c.cycle_period = milliseconds(1);
  return c;
}

}  // namespace

TEST_CASE("drivers: boot: exact master frame sequence (NMT reset, SDO configuration, NMT start, PDOs)",
          "[drivers][arm]") {
  ArmRig rig({{0, 1}, {0, 2}}, baseConfig());
  REQUIRE(rig.arm != nullptr);
  const int cycles = rig.boot();
  REQUIRE(rig.arm->phase() == ArmPhase::Running);
  for (int k = 0; k < 3; ++k) {
    rig.cycle();
  }
  std::vector<std::string> expected = {"000#8101", "000#8102"};
  const auto w1 = bootWrites(1);
  const auto w2 = bootWrites(2);
  REQUIRE(w1.size() == 29u);
  for (std::size_t k = 0; k < w1.size(); ++k) {
    expected.push_back(sdoWrite(1, w1[k].index, w1[k].sub, w1[k].size, w1[k].value));
    expected.push_back(sdoWrite(2, w2[k].index, w2[k].sub, w2[k].size, w2[k].value));
  }
  expected.push_back("000#0101");
  expected.push_back("000#0102");
  for (int k = 0; k < 3; ++k) {
    expected.push_back(rpdo(1, 0, 0, 0));
    expected.push_back(rpdo(2, 0, 0, 0));
    expected.push_back("080#");
  }
  CHECK(rig.masterFrames() == expected);
  // 3 cycles until both boot-up messages (2 ms after the resets), 29 SDO round trips (one per
  // cycle and drive), the start cycle.
  CHECK(cycles == 3 + 29 + 1);

  // The whole wire during configuration: request 1, request 2, answer 1, answer 2 per cycle.
  const auto all = rig.wire();
  std::vector<std::string> sdo;
  for (const auto& f : all) {
    if (f[0] == '5' || f[0] == '6') {
      sdo.push_back(f);
    }
  }
  std::vector<std::string> sdo_expected;
  for (std::size_t k = 0; k < w1.size(); ++k) {
    sdo_expected.push_back(sdoWrite(1, w1[k].index, w1[k].sub, w1[k].size, w1[k].value));
    sdo_expected.push_back(sdoWrite(2, w2[k].index, w2[k].sub, w2[k].size, w2[k].value));
    sdo_expected.push_back(sdoAck(1, w1[k].index, w1[k].sub));
    sdo_expected.push_back(sdoAck(2, w2[k].index, w2[k].sub));
  }
  CHECK(sdo == sdo_expected);
  CHECK(only(all, 0x701) == std::vector<std::string>{"701#00"});  // boot-up after the reset
  CHECK(only(all, 0x702) == std::vector<std::string>{"702#00"});

  // The drives ended configured as written (their own checks refuse a wrong order).
  for (const auto& f : rig.fakes) {
    CHECK(f->nmt() == MRQP_FW_NMT_STATE_OPERATIONAL);
    CHECK(f->rpdo1Configured());
    CHECK(f->tpdo1Configured());
    CHECK(f->tpdo2Configured());
    std::uint32_t v = 0;
    REQUIRE(f->od(0x6060, 0, &v));
    CHECK(v == 8u);
    REQUIRE(f->od(0x1802, 1, &v));
    CHECK((v & 0x80000000u) != 0u);
    CHECK(f->sdoWrites() == 29u);
  }
  CHECK(rig.arm->faults().flags == 0u);
}

TEST_CASE("drivers: boot with a master heartbeat: consumer time written, heartbeat every period",
          "[drivers][arm]") {
  ArmConfig c = baseConfig();
  c.master_node = 0x7F;
  c.master_heartbeat_ms = 10;
  c.drive_consumer_ms = 30;
  ArmRig rig({{0, 3}}, c);
  REQUIRE(rig.arm != nullptr);
  rig.boot();
  REQUIRE(rig.arm->phase() == ArmPhase::Running);
  while (rig.t < milliseconds(100)) {
    rig.cycle();
  }
  const auto master = rig.masterFrames();
  const auto w = bootWrites(3, true);
  std::vector<std::string> sdo;
  for (const auto& f : master) {
    if (f[0] == '6') {
      sdo.push_back(f);
    }
  }
  REQUIRE(sdo.size() == w.size());
  for (std::size_t k = 0; k < w.size(); ++k) {
    CHECK(sdo[k] == sdoWrite(3, w[k].index, w[k].sub, w[k].size, w[k].value));
  }
  // Heartbeats at 0, 10, 20, ... 90 ms: 10 of them before 100 ms.
  CHECK(only(master, 0x77F).size() == 10u);
  std::vector<TimeNs> starts;
  for (const auto& e : rig.logs[0]->events) {
    if (e.frame.id == 0x77F) {
      starts.push_back(e.start);
    }
  }
  REQUIRE(starts.size() == 10u);
  CHECK(starts[0] == microseconds(75));  // right after the NMT reset (2 bytes: 75 bit times)
  for (std::size_t i = 0; i < starts.size(); ++i) {
    CHECK(starts[i] / milliseconds(1) == static_cast<TimeNs>(10 * i));  // sent in the cycles 0, 10, 20 ms...
  }
}

TEST_CASE("drivers: per-cycle traffic: RPDO per drive, one SYNC, then TPDO1/TPDO2 by priority",
          "[drivers][arm]") {
  ArmRig rig({{0, 1}, {0, 2}}, baseConfig(), 64, {1000, -2000});
  REQUIRE(rig.arm != nullptr);
  rig.boot();
  for (int k = 0; k < 3; ++k) {
    rig.cycle();
  }
  const TimeNs t0 = rig.t;
  rig.cycle();
  rig.buses[0]->advanceTo(rig.t);
  // Hand-encoded: disabled (cw 0), hold the measured position; statusword 0x0050 = switch on
  // disabled + voltage enabled; TPDO2: velocity 0, error 0, mode 8.
  const std::vector<std::string> expected = {
      rpdo(1, 0, 1000, 0),  rpdo(2, 0, -2000, 0), "080#", "181#5000E80300000000", "182#500030F8FFFF0000",
      "281#00000000000008", "282#00000000000008",
  };
  CHECK(rig.logs[0]->framesBetween(t0, rig.t) == expected);
  // Timing: 135 + 135 us of RPDOs, SYNC 55 us, answers 20 us after the SYNC.
  std::vector<TimeNs> starts;
  for (const auto& e : rig.logs[0]->events) {
    if (e.start >= t0) {
      starts.push_back(e.start - t0);
    }
  }
  REQUIRE(starts.size() == 7u);
  CHECK(starts[0] == 0);
  CHECK(starts[1] == microseconds(135));
  CHECK(starts[2] == microseconds(270));
  CHECK(starts[3] == microseconds(345));
  CHECK(starts[4] == microseconds(480));
  const ArmDriveState& d1 = rig.arm->drive(1);
  CHECK(d1.valid);
  CHECK(d1.position_inc == -2000);
  CHECK(d1.position == Approx(-2000.0 * 2.0 * M_PI / 524288.0));
  CHECK(d1.state == MRQP_FW_CIA402_SWITCH_ON_DISABLED);
  CHECK(d1.mode_display == 8);
  CHECK(d1.nmt_state == MRQP_FW_NMT_STATE_BOOTUP);  // only the boot-up message so far (heartbeat 100 ms)
}

TEST_CASE("drivers: SYNC with a counter wraps at the configured overflow", "[drivers][arm]") {
  ArmConfig c = baseConfig();
  c.sync_counter_overflow = 3;
  ArmRig rig({{0, 1}}, c);
  REQUIRE(rig.arm != nullptr);
  rig.boot();
  for (int k = 0; k < 5; ++k) {
    rig.cycle();
  }
  rig.buses[0]->advanceTo(rig.t);
  CHECK(only(rig.wire(), 0x080) ==
        std::vector<std::string>{"080#01", "080#02", "080#03", "080#01", "080#02"});
}

TEST_CASE("drivers: enable and disable follow the CiA 402 controlword sequence, setpoints after enabling",
          "[drivers][arm]") {
  ArmConfig c = baseConfig();
  ArmDriveConfig limits;
  limits.position_max = 1.0;
  c.drives = {limits};
  ArmRig rig({{0, 1}, {0, 2}}, c, 64, {1000, -2000});
  REQUIRE(rig.arm != nullptr);
  rig.boot();
  rig.cycle();
  rig.cycle();
  const TimeNs t_enable = rig.t;
  rig.hook = [](ArmRig& r) {
    r.arm->requestEnable(r.t);
    r.hook = nullptr;
  };
  int cycles = 0;
  do {
    rig.cycle();
    ++cycles;
  } while (!rig.arm->allEnabled() && cycles < 20);
  CHECK(cycles == 4);  // shutdown, switch on, enable operation, then reported enabled
  auto rpdos = only(rig.masterFrames(t_enable), 0x201);
  REQUIRE(rpdos.size() >= 4u);
  CHECK(cwOf(rpdos[0]) == 0x0006);
  CHECK(cwOf(rpdos[1]) == 0x0007);
  CHECK(cwOf(rpdos[2]) == 0x000F);
  CHECK(cwOf(rpdos[3]) == 0x000F);
  // Until a setpoint is given the drive holds its measured position.
  CHECK(rpdos[3] == rpdo(1, 0x000F, 1000, 0));
  CHECK(rig.fakes[0]->state() == MRQP_FW_CIA402_OPERATION_ENABLED);

  // A setpoint: 0.5 rad = round(0.5 x 2^19 / 2 pi) increments.
  const auto inc = static_cast<std::int32_t>(std::llround(0.5 * 524288.0 / (2.0 * M_PI)));
  CHECK(inc == 41722);
  TimeNs t_sp = rig.t;
  rig.hook = [](ArmRig& r) { CHECK(r.arm->setPosition(0, 0.5) == SetpointResult::Ok); };
  rig.cycle();
  rig.cycle();
  rpdos = only(rig.masterFrames(t_sp), 0x201);
  CHECK(rpdos[0] == rpdo(1, 0x000F, inc, 0));
  CHECK(rig.fakes[0]->targetPosition() == inc);
  CHECK(rig.arm->drive(0).position == Approx(0.5).margin(1.2e-5));

  // NaN and infinity are refused and never sent: the previous setpoint stays on the wire.
  t_sp = rig.t;
  rig.hook = [](ArmRig& r) {
    CHECK(r.arm->setPosition(0, std::nan("")) == SetpointResult::Refused);
    CHECK(r.arm->setTorque(1, INFINITY) == SetpointResult::Refused);
  };
  const FaultReport& rep0 = rig.cycle();
  CHECK(rep0.flags == 0u);
  rig.hook = nullptr;
  const FaultReport& rep = rig.cycle();
  CHECK(rep.has(fault::kSetpointRefused));
  CHECK((rep.devices[0].flags & fault::kSetpointRefused) != 0u);
  CHECK(rep.devices[0].refused_setpoints == 1u);
  CHECK(rep.devices[1].refused_setpoints == 1u);
  rpdos = only(rig.masterFrames(t_sp), 0x201);
  CHECK(rpdos[0] == rpdo(1, 0x000F, inc, 0));
  const FaultReport& rep2 = rig.cycle();
  CHECK(!rep2.has(fault::kSetpointRefused));  // an event: only in the cycle after it happened

  // Beyond position_max (1 rad): clamped and flagged.
  t_sp = rig.t;
  rig.hook = [](ArmRig& r) {
    CHECK(r.arm->setPosition(0, 2.0) == SetpointResult::Limited);
    r.hook = nullptr;
  };
  rig.cycle();
  const FaultReport& rep3 = rig.cycle();
  CHECK((rep3.devices[0].flags & fault::kSetpointLimited) != 0u);
  rpdos = only(rig.masterFrames(t_sp), 0x201);
  CHECK(rpdos[0] == rpdo(1, 0x000F, static_cast<std::int32_t>(std::llround(524288.0 / (2.0 * M_PI))), 0));

  // Disable: Disable voltage (transition 9) straight to Switch on disabled.
  const TimeNs t_dis = rig.t;
  rig.hook = [](ArmRig& r) {
    r.arm->requestDisable(r.t);
    r.hook = nullptr;
  };
  cycles = 0;
  do {
    rig.cycle();
    ++cycles;
  } while (!rig.arm->allDisabled() && cycles < 20);
  CHECK(cycles == 2);
  rpdos = only(rig.masterFrames(t_dis), 0x201);
  CHECK(cwOf(rpdos[0]) == 0x0000);
  CHECK(rig.fakes[0]->state() == MRQP_FW_CIA402_SWITCH_ON_DISABLED);
  CHECK(rig.fakes[1]->state() == MRQP_FW_CIA402_SWITCH_ON_DISABLED);
  (void)t_enable;
}

TEST_CASE("drivers: EMCY: code and register decoded, fault held until re-enabled, error reset clears it",
          "[drivers][arm]") {
  ArmRig rig({{0, 1}, {0, 2}}, baseConfig());
  REQUIRE(rig.arm != nullptr);
  rig.boot();
  rig.hook = [](ArmRig& r) {
    r.arm->requestEnable(r.t);
    r.hook = nullptr;
  };
  for (int k = 0; k < 6; ++k) {
    rig.cycle();
  }
  REQUIRE(rig.arm->allEnabled());
  rig.fakes[1]->injectFault(0x2310, 0x03);  // continuous over-current, generic + current
  const FaultReport& r1 = rig.cycle();
  CHECK(r1.has(fault::kEmcy));
  CHECK(r1.devices[1].emcy_code == 0x2310);
  CHECK(r1.devices[1].emcy_register == 0x03);
  CHECK(r1.devices[1].emcy_count == 1u);
  CHECK(r1.devices[0].flags == 0u);
  CHECK_THAT(describeFaults(r1), Catch::Matchers::Contains("device 1: EMCY"));
  CHECK_THAT(describeFaults(r1),
             Catch::Matchers::Contains("EMCY 0x2310 (" + std::string(mrqp_fw_emcy_code_str(0x2310)) +
                                       ") register 0x03 from node 2"));
  // Fault reaction active, then Fault: reported as a device fault and not reset automatically.
  for (int k = 0; k < 5; ++k) {
    rig.cycle();
  }
  const FaultReport& r2 = rig.arm->faults();
  CHECK((r2.devices[1].flags & fault::kDeviceFault) != 0u);
  CHECK(rig.arm->drive(1).state == MRQP_FW_CIA402_FAULT);
  CHECK(rig.fakes[1]->state() == MRQP_FW_CIA402_FAULT);
  CHECK(rig.fakes[1]->lastControlword() == 0x0000);
  CHECK(rig.arm->drive(0).state == MRQP_FW_CIA402_OPERATION_ENABLED);
  // Enabling again: fault reset (rising edge of bit 7), then the enabling sequence; the drive
  // announces "error reset" (EMCY 0x0000) which clears the EMCY flag.
  const TimeNs t0 = rig.t;
  rig.hook = [](ArmRig& r) {
    r.arm->requestEnable(r.t);
    r.hook = nullptr;
  };
  for (int k = 0; k < 8; ++k) {
    rig.cycle();
  }
  CHECK(rig.arm->allEnabled());
  const auto rpdos = only(rig.masterFrames(t0), 0x202);
  REQUIRE(rpdos.size() >= 4u);
  CHECK(cwOf(rpdos[0]) == 0x0080);
  CHECK(cwOf(rpdos[1]) == 0x0006);
  CHECK(cwOf(rpdos[2]) == 0x0007);
  CHECK(cwOf(rpdos[3]) == 0x000F);
  const FaultReport& r3 = rig.arm->faults();
  CHECK(r3.devices[1].emcy_code == 0x0000);
  CHECK(r3.devices[1].emcy_count == 2u);
  CHECK(!r3.has(fault::kEmcy));
  CHECK(r3.flags == 0u);
}

TEST_CASE("drivers: heartbeat loss is detected at the first cycle after the consumer time",
          "[drivers][arm]") {
  ArmConfig c = baseConfig();
  c.producer_heartbeat_ms = 10;
  c.heartbeat_timeout = milliseconds(25);
  ArmRig rig({{0, 1}, {0, 2}}, c);
  REQUIRE(rig.arm != nullptr);
  rig.boot();
  while (rig.t < milliseconds(200)) {
    const FaultReport& r = rig.cycle();
    REQUIRE(r.flags == 0u);
  }
  REQUIRE(rig.arm->drive(1).nmt_state == MRQP_FW_NMT_STATE_OPERATIONAL);
  // Power off drive 2 right after a cycle's transmit (its frames of that cycle are lost).
  const TimeNs off = rig.t;
  const std::size_t off_cycle_k = 0;
  (void)off_cycle_k;
  rig.buses[0]->advanceTo(off - microseconds(500));
  rig.fakes[1]->power(false);
  TimeNs last_hb_end = 0;
  for (const auto& e : rig.logs[0]->events) {
    if (e.frame.id == 0x702 && e.outcome == WireOutcome::Delivered) {
      last_hb_end = e.end;
    }
  }
  REQUIRE(last_hb_end > 0);
  // Detection: the first cycle time t with t - last heartbeat > 25 ms.
  const TimeNs period = c.cycle_period;
  const TimeNs expected = ((last_hb_end + milliseconds(25)) / period + 1) * period;
  TimeNs detected = -1;
  TimeNs missing_at = -1;
  int cycles_after_off = 0;
  while (rig.t < off + milliseconds(60) && detected < 0) {
    const FaultReport& r = rig.cycle();
    ++cycles_after_off;
    if ((r.devices[1].flags & fault::kFeedbackMissing) != 0u && missing_at < 0) {
      missing_at = rig.last;
    }
    if ((r.devices[1].flags & fault::kHeartbeatLost) != 0u) {
      detected = rig.last;
    }
    CHECK((r.devices[0].flags & (fault::kHeartbeatLost | fault::kFeedbackMissing)) == 0u);
  }
  CHECK(detected == expected);
  CHECK(detected - last_hb_end > milliseconds(25));
  CHECK(detected - period - last_hb_end <= milliseconds(25));
  // Feedback missing first: the drive lost the RPDOs/SYNC of the cycle before `off`... 3 cycles.
  CHECK(missing_at >= 0);
  CHECK(missing_at < detected);
}

TEST_CASE("drivers: feedback missing for N cycles is flagged at exactly the N-th cycle", "[drivers][arm]") {
  ArmConfig c = baseConfig();
  c.feedback_missing_cycles = 3;
  ArmRig rig({{0, 1}, {0, 2}}, c);
  REQUIRE(rig.arm != nullptr);
  rig.boot();
  for (int k = 0; k < 3; ++k) {
    rig.cycle();
  }
  rig.fakes[0]->setPdoSilent(true);  // from the SYNC of the last cycle on
  const FaultReport& r1 = rig.cycle();
  CHECK(r1.devices[0].missed_cycles == 1u);
  CHECK(!r1.has(fault::kFeedbackMissing));
  CHECK(!rig.arm->drive(0).fresh);
  CHECK(rig.arm->drive(1).fresh);
  const FaultReport& r2 = rig.cycle();
  CHECK(r2.devices[0].missed_cycles == 2u);
  CHECK(!r2.has(fault::kFeedbackMissing));
  const FaultReport& r3 = rig.cycle();
  CHECK(r3.devices[0].missed_cycles == 3u);
  CHECK((r3.devices[0].flags & fault::kFeedbackMissing) != 0u);
  CHECK(r3.devices[1].flags == 0u);
  rig.fakes[0]->setPdoSilent(false);
  rig.cycle();
  const FaultReport& r4 = rig.cycle();
  CHECK(r4.devices[0].missed_cycles == 0u);
  CHECK(!r4.has(fault::kFeedbackMissing));
}

TEST_CASE("drivers: corrupted and unknown frames are counted and dropped", "[drivers][arm]") {
  ArmConfig c = baseConfig();
  c.cycle_period = milliseconds(5);  // room for the injected frames after the cyclic traffic
  ArmRig rig({{0, 1}, {0, 2}}, c, 64, {1000, 0});
  REQUIRE(rig.arm != nullptr);
  SimNode* injector = rig.buses[0]->addNode(SimNodeConfig{});
  rig.boot();
  for (int k = 0; k < 3; ++k) {
    rig.cycle();
  }
  REQUIRE(rig.arm->faults().flags == 0u);
  const TimeNs quiet = rig.last + microseconds(1500);  // after this cycle's traffic
  const mrqp_fw_frame bad[] = {
      makeFrame(0x181, {0x50, 0x00, 0x99, 0x99, 0x00, 0x00, 0x00}),  // TPDO1 with DLC 7
      makeFrame(0x081, {0x10, 0x23, 0x40, 0, 0, 0, 0, 0}),           // EMCY: reserved bit 6
      makeFrame(0x701, {0x42}),                                      // heartbeat: no such state
      makeFrame(0x581, {0x60, 0x17, 0x10, 0, 0, 0, 0, 0}),           // SDO answer, nothing asked
      makeFrame(0x282, {0, 0, 0, 0, 0, 0, 0, 0}),                    // TPDO2 with DLC 8
      makeFrame(0x3F0, {1, 2, 3}),                                   // nobody's identifier
      makeFrame(0x183, {0x27, 0, 0, 0, 0, 0, 0, 0}),                 // node 3 is not configured
  };
  for (const mrqp_fw_frame& f : bad) {
    REQUIRE(injector->sendAt(f, quiet) == SendResult::Ok);
  }
  const FaultReport& r = rig.cycle();
  CHECK(r.devices[0].corrupt_frames == 4u);
  CHECK(r.devices[1].corrupt_frames == 1u);
  CHECK((r.devices[0].flags & fault::kCorruptFrame) != 0u);
  CHECK(r.buses[0].rejected_frames == 5u);
  CHECK(r.buses[0].unknown_frames == 2u);
  CHECK((r.buses[0].flags & fault::kUnknownFrame) != 0u);
  CHECK(r.has(fault::kCorruptFrame));
  CHECK(r.devices[0].emcy_count == 0u);
  // The malformed TPDO1 did not touch the state: the position is still the drive's 1000.
  CHECK(rig.arm->drive(0).position_inc == 1000);
  CHECK(rig.arm->drive(0).nmt_state != 0x42);
  const FaultReport& r2 = rig.cycle();
  CHECK(r2.flags == 0u);  // events are reported once
  CHECK(r2.buses[0].unknown_total == 2u);
}

TEST_CASE("drivers: an SDO abort fails the boot and names the object", "[drivers][arm]") {
  ArmRig rig({{0, 1}, {0, 2}}, baseConfig());
  REQUIRE(rig.arm != nullptr);
  rig.fakes[1]->abortOnWrite(0x6060, 0, MRQP_FW_SDO_ABORT_INVALID_VALUE);
  rig.boot();
  CHECK(rig.arm->phase() == ArmPhase::Failed);
  const FaultReport& r = rig.cycle();
  CHECK((r.devices[1].flags & fault::kBootFailed) != 0u);
  CHECK(r.devices[1].sdo_abort_code == 0x06090030u);
  CHECK(r.devices[1].sdo_index == 0x6060);
  CHECK(r.devices[1].sdo_subindex == 0);
  CHECK((r.devices[0].flags & fault::kBootFailed) == 0u);
  CHECK(only(rig.masterFrames(), 0x000).size() == 2u);  // no start
  CHECK(rig.fakes[0]->nmt() == MRQP_FW_NMT_STATE_PRE_OPERATIONAL);
}

TEST_CASE("drivers: a drive that never boots times out, a drive that stops answering SDO times out",
          "[drivers][arm]") {
  ArmConfig c = baseConfig();
  c.boot_timeout = milliseconds(50);
  ArmRig rig({{0, 1}, {0, 2}}, c);
  REQUIRE(rig.arm != nullptr);
  rig.fakes[1]->power(false);
  const int cycles = rig.boot();
  CHECK(rig.arm->phase() == ArmPhase::Failed);
  CHECK(cycles == 52);  // the first cycle after 50 ms (update at 51 ms)
  const FaultReport& r = rig.arm->faults();
  CHECK((r.devices[1].flags & (fault::kTimeout | fault::kBootFailed)) ==
        (fault::kTimeout | fault::kBootFailed));
  CHECK(r.devices[0].flags == 0u);

  ArmConfig c2 = baseConfig();
  c2.sdo_timeout = milliseconds(5);
  ArmRig rig2({{0, 1}, {0, 2}}, c2);
  REQUIRE(rig2.arm != nullptr);
  rig2.arm->start(0);
  for (int k = 0; k < 6; ++k) {
    rig2.cycle();
  }
  REQUIRE(rig2.arm->phase() == ArmPhase::Configuring);
  rig2.fakes[0]->power(false);
  for (int k = 0; k < 10; ++k) {
    rig2.cycle();
  }
  CHECK(rig2.arm->phase() == ArmPhase::Failed);
  CHECK(rig2.arm->faults().devices[0].sdo_abort_code == MRQP_FW_SDO_ABORT_TIMEOUT);
  // The client's abort went out (0x80, abort code 0x05040000).
  const auto master = rig2.wire();
  bool abort_seen = false;
  for (const auto& f : master) {
    abort_seen = abort_seen || (f.compare(0, 6, "601#80") == 0 && f.substr(12) == "00000405");
  }
  CHECK(abort_seen);
}

TEST_CASE("drivers: several buses: each gets its drives' RPDOs and its own SYNC", "[drivers][arm]") {
  // The same node ids on two buses are two different drives.
  ArmRig rig({{0, 1}, {0, 2}, {1, 1}, {1, 2}}, baseConfig(), 64, {10, 20, 30, 40});
  REQUIRE(rig.arm != nullptr);
  rig.boot();
  REQUIRE(rig.arm->phase() == ArmPhase::Running);
  for (int k = 0; k < 2; ++k) {
    rig.cycle();
  }
  const TimeNs t0 = rig.t;
  rig.cycle();
  for (auto& b : rig.buses) {
    b->advanceTo(rig.t);
  }
  CHECK(rig.logs[0]->framesBetween(t0, rig.t) ==
        std::vector<std::string>{rpdo(1, 0, 10, 0), rpdo(2, 0, 20, 0), "080#", "181#50000A0000000000",
                                 "182#5000140000000000", "281#00000000000008", "282#00000000000008"});
  CHECK(rig.logs[1]->framesBetween(t0, rig.t) ==
        std::vector<std::string>{rpdo(1, 0, 30, 0), rpdo(2, 0, 40, 0), "080#", "181#50001E0000000000",
                                 "182#5000280000000000", "281#00000000000008", "282#00000000000008"});
  rig.cycle();
  CHECK(rig.arm->drive(2).position_inc == 30);
  CHECK(rig.arm->drive(3).position_inc == 40);
  CHECK(rig.arm->faults().bus_count == 2u);
  BusBudget b0(BusSpec{"arm0", 1000000, 0, 1000.0, 0.8});
  rig.arm->declareTraffic(0, b0);
  // SYNC + 2 x (RPDO1, TPDO1, TPDO2) + 2 heartbeats every 100 ms (0.01 per 1 ms cycle each).
  CHECK(b0.result().frames_per_cycle == Approx(1 + 2 * 3 + 2 * 0.01));
}

TEST_CASE("drivers: bus-off and error-passive states reach the fault report", "[drivers][arm]") {
  ArmRig rig({{0, 1}}, baseConfig());
  REQUIRE(rig.arm != nullptr);
  rig.boot();
  rig.cycle();
  REQUIRE(rig.arm->faults().flags == 0u);
  rig.masters[0]->injectTxErrors(32);
  bool passive = false;
  bool off = false;
  bool error_frames = false;
  for (int k = 0; k < 10; ++k) {
    const FaultReport& r = rig.cycle();
    passive = passive || r.buses[0].state == BusState::ErrorPassive;
    off = off || (r.buses[0].flags & fault::kBusOff) != 0u;
    error_frames = error_frames || (r.buses[0].flags & fault::kBusErrorFrames) != 0u;
    if (off) {
      CHECK(r.buses[0].state == BusState::BusOff);
      CHECK(r.buses[0].tec == 256);
      break;
    }
  }
  CHECK(error_frames);
  CHECK(off);
  // The master recovers after 128 x 11 bit times of idle bus and traffic resumes.
  for (int k = 0; k < 10; ++k) {
    rig.cycle();
  }
  const FaultReport& r = rig.arm->faults();
  CHECK(r.buses[0].state == BusState::ErrorActive);
  (void)passive;
}

TEST_CASE("drivers: a full transmit queue is counted, one-shot frames are retried next cycle",
          "[drivers][arm]") {
  ArmRig rig({{0, 1}, {0, 2}, {0, 3}}, baseConfig(), 2);
  REQUIRE(rig.arm != nullptr);
  rig.arm->start(0);
  const FaultReport& r0 = rig.cycle();
  (void)r0;
  const FaultReport& r1 = rig.cycle();
  CHECK(r1.buses[0].tx_queue_full == 1u);  // the third NMT reset did not fit, retried
  CHECK((r1.devices[2].flags & fault::kTxQueueFull) != 0u);
  rig.boot();
  CHECK(rig.arm->phase() == ArmPhase::Running);
  for (const auto& f : rig.fakes) {
    CHECK(f->nmt() == MRQP_FW_NMT_STATE_OPERATIONAL);
  }
  // Running: 3 RPDOs + SYNC do not fit a queue of 2: counted every cycle, and without the SYNC
  // the feedback goes missing.
  for (int k = 0; k < 4; ++k) {
    rig.cycle();
  }
  const FaultReport& r = rig.arm->faults();
  CHECK(r.buses[0].tx_queue_full == 2u);
  CHECK(r.has(fault::kTxQueueFull));
  CHECK(r.has(fault::kFeedbackMissing));
}

TEST_CASE("drivers: invalid configurations are refused with a message naming the field", "[drivers][arm]") {
  SimBus bus;
  SimNode* m = bus.addNode(SimNodeConfig{});
  BusRouter router(*m);
  std::string err;
  ArmConfig c;
  CHECK(ArmDriver::create({&router}, c, &err) == nullptr);
  CHECK(err == "arm driver: no drive configured");
  ArmDriveConfig d;
  d.node = 0;
  c.drives = {d};
  CHECK(ArmDriver::create({&router}, c, &err) == nullptr);
  CHECK_THAT(err, Catch::Matchers::Contains("drive 0 (node 0): node id must be 1..127"));
  d.node = 5;
  c.drives = {d, d};
  CHECK(ArmDriver::create({&router}, c, &err) == nullptr);
  CHECK_THAT(err, Catch::Matchers::Contains("drive 1 (node 5): node id used twice on bus 0"));
  d.mode = 3;
  c.drives = {d};
  CHECK(ArmDriver::create({&router}, c, &err) == nullptr);
  CHECK_THAT(err, Catch::Matchers::Contains("neither CSP (8) nor CST (10)"));
  d.mode = MRQP_FW_MODE_CST;
  d.bus = 1;
  c.drives = {d};
  CHECK(ArmDriver::create({&router}, c, &err) == nullptr);
  CHECK_THAT(err, Catch::Matchers::Contains("bus index 1 but only 1 bus(es) given"));
  d.bus = 0;
  c.drives = {d};
  c.heartbeat_timeout = milliseconds(100);
  CHECK(ArmDriver::create({&router}, c, &err) == nullptr);
  CHECK_THAT(err, Catch::Matchers::Contains("must be longer than the producer heartbeat time (100 ms)"));
  c.heartbeat_timeout = milliseconds(300);
  auto ok = ArmDriver::create({&router}, c, &err);
  CHECK(ok != nullptr);
}

TEST_CASE("drivers: CST: the target torque is sent, the position is held", "[drivers][arm]") {
  ArmConfig c = baseConfig();
  ArmDriveConfig d;
  d.mode = MRQP_FW_MODE_CST;
  d.scale.rated_torque_mNm = 2000;  // 1000 per mille = 2 N m
  d.torque_limit = 1.5;
  c.drives = {d};
  ArmRig rig({{0, 4}}, c, 64, {777});
  REQUIRE(rig.arm != nullptr);
  rig.boot();
  rig.hook = [](ArmRig& r) {
    r.arm->requestEnable(r.t);
    r.hook = nullptr;
  };
  for (int k = 0; k < 6; ++k) {
    rig.cycle();
  }
  REQUIRE(rig.arm->allEnabled());
  const TimeNs t0 = rig.t;
  rig.hook = [](ArmRig& r) {
    CHECK(r.arm->setTorque(0, 0.5) == SetpointResult::Ok);
    CHECK(r.arm->setPosition(0, 3.0) == SetpointResult::Ok);  // ignored in CST
  };
  rig.cycle();
  rig.cycle();
  const auto rpdos = only(rig.masterFrames(t0), 0x204);
  // 0.5 N m / 2 N m = 250 per mille.
  CHECK(rpdos[0] == rpdo(4, 0x000F, 777, 250));
  CHECK(rig.fakes[0]->targetTorque() == 250);
  CHECK(rig.arm->drive(0).torque == Approx(0.5));
  rig.hook = [](ArmRig& r) { CHECK(r.arm->setTorque(0, -9.0) == SetpointResult::Limited); };
  rig.cycle();
  rig.cycle();
  CHECK(rig.fakes[0]->targetTorque() == -750);
}

TEST_CASE("drivers: feedback outside the configured range is flagged every cycle it lasts",
          "[drivers][arm]") {
  ArmConfig c = baseConfig();
  ArmDriveConfig d;
  d.position_max = 0.01;  // rad; the drive sits at 1000 increments = 0.01198 rad
  c.drives = {d};
  ArmRig rig({{0, 1}, {0, 2}}, c, 64, {1000, 1000});
  REQUIRE(rig.arm != nullptr);
  rig.boot();
  rig.cycle();
  const FaultReport& r = rig.cycle();
  CHECK((r.devices[0].flags & fault::kOutOfRange) != 0u);
  CHECK(r.devices[0].out_of_range >= 1u);
  CHECK((r.devices[1].flags & fault::kOutOfRange) == 0u);
  CHECK(rig.arm->drive(0).position == Approx(1000.0 * 2.0 * M_PI / 524288.0));  // still reported
}

TEST_CASE("drivers: a mode display other than the configured mode is a state mismatch", "[drivers][arm]") {
  ArmRig rig({{0, 1}}, baseConfig());
  REQUIRE(rig.arm != nullptr);
  rig.fakes[0]->forceModeDisplay(MRQP_FW_MODE_CST);
  rig.boot();
  rig.hook = [](ArmRig& r) {
    r.arm->requestEnable(r.t);
    r.hook = nullptr;
  };
  for (int k = 0; k < 6; ++k) {
    rig.cycle();
  }
  REQUIRE(rig.arm->allEnabled());
  CHECK((rig.arm->faults().devices[0].flags & fault::kStateMismatch) != 0u);
  CHECK(rig.arm->drive(0).mode_display == MRQP_FW_MODE_CST);
}
