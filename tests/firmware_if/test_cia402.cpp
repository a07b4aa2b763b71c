// CiA 402 power state machine, checked against tables transcribed from the standard
// (IEC 61800-7-201 / CiA 402-2: statusword coding, device control commands, transitions 0..16).
#include <catch2/catch.hpp>

#include "test_util.hpp"

#include <string>

using St = mrqp_fw_cia402_state;
using Cmd = mrqp_fw_cia402_cmd;

namespace {

const St NRTSO = MRQP_FW_CIA402_NOT_READY_TO_SWITCH_ON;
const St SOD = MRQP_FW_CIA402_SWITCH_ON_DISABLED;
const St RTSO = MRQP_FW_CIA402_READY_TO_SWITCH_ON;
const St SO = MRQP_FW_CIA402_SWITCHED_ON;
const St OE = MRQP_FW_CIA402_OPERATION_ENABLED;
const St QSA = MRQP_FW_CIA402_QUICK_STOP_ACTIVE;
const St FRA = MRQP_FW_CIA402_FAULT_REACTION_ACTIVE;
const St FLT = MRQP_FW_CIA402_FAULT;
const St UNK = MRQP_FW_CIA402_UNKNOWN;

const St all_states[] = {NRTSO, SOD, RTSO, SO, OE, QSA, FRA, FLT};

// Statusword coding as printed in the standard (mask, value).
struct Coding {
  St state;
  std::uint16_t mask;
  std::uint16_t value;
};
const Coding coding[] = {
    {NRTSO, 0x004F, 0x0000}, {SOD, 0x004F, 0x0040}, {RTSO, 0x006F, 0x0021}, {SO, 0x006F, 0x0023},
    {OE, 0x006F, 0x0027},    {QSA, 0x006F, 0x0007}, {FRA, 0x004F, 0x000F},  {FLT, 0x004F, 0x0008},
};

}  // namespace

TEST_CASE("statusword decoding matches the standard's bit masks for all 65536 words",
          "[firmware_if][cia402]") {
  for (std::uint32_t sw = 0; sw <= 0xFFFF; ++sw) {
    St expected = UNK;
    int matches = 0;
    for (const Coding& c : coding) {
      if ((sw & c.mask) == c.value) {
        expected = c.state;
        ++matches;
      }
    }
    REQUIRE(matches <= 1);  // the codings are disjoint
    REQUIRE(mrqp_fw_cia402_decode_statusword(static_cast<std::uint16_t>(sw)) == expected);
  }
  // Typical words seen on real drives.
  CHECK(mrqp_fw_cia402_decode_statusword(0x0250) == SOD);
  CHECK(mrqp_fw_cia402_decode_statusword(0x0231) == RTSO);
  CHECK(mrqp_fw_cia402_decode_statusword(0x0233) == SO);
  CHECK(mrqp_fw_cia402_decode_statusword(0x1637) == OE);
  CHECK(mrqp_fw_cia402_decode_statusword(0x0217) == QSA);
  CHECK(mrqp_fw_cia402_decode_statusword(0x0218) == FLT);
}

TEST_CASE("drive-side statusword encodes each state and keeps the other bits", "[firmware_if][cia402]") {
  for (St s : all_states) {
    CHECK(mrqp_fw_cia402_decode_statusword(mrqp_fw_cia402_statusword(s, 0)) == s);
    const std::uint16_t sw = mrqp_fw_cia402_statusword(s, 0xFFFF);
    CHECK(mrqp_fw_cia402_decode_statusword(sw) == s);
    CHECK((sw & 0xFF90u) == 0xFF90u);  // warning, remote, target reached, ... untouched
    CHECK(std::string(mrqp_fw_cia402_state_str(s)) != "unknown");
  }
  CHECK(mrqp_fw_cia402_statusword(OE, MRQP_FW_SW_VOLTAGE_ENABLED) == 0x0037);
  CHECK(mrqp_fw_cia402_statusword(UNK, 0x1234) == 0x1234);
  CHECK(std::string(mrqp_fw_cia402_state_str(UNK)) == "unknown");
}

TEST_CASE("controlword command decoding for all bit patterns 3..0", "[firmware_if][cia402]") {
  // bits: eo qs ev so (3..0), from the device control command table.
  for (unsigned bits = 0; bits < 16; ++bits) {
    const bool so = (bits & 1u) != 0;
    const bool ev = (bits & 2u) != 0;
    const bool qs = (bits & 4u) != 0;
    const bool eo = (bits & 8u) != 0;
    Cmd expected;
    if (!ev) {
      expected = MRQP_FW_CIA402_CMD_DISABLE_VOLTAGE;  // x x 0 x
    } else if (!qs) {
      expected = MRQP_FW_CIA402_CMD_QUICK_STOP;  // x 0 1 x
    } else if (!so) {
      expected = MRQP_FW_CIA402_CMD_SHUTDOWN;  // x 1 1 0
    } else if (!eo) {
      expected = MRQP_FW_CIA402_CMD_SWITCH_ON;  // 0 1 1 1
    } else {
      expected = MRQP_FW_CIA402_CMD_ENABLE_OPERATION;  // 1 1 1 1
    }
    CHECK(mrqp_fw_cia402_decode_command(static_cast<std::uint16_t>(bits)) == expected);
    CHECK(mrqp_fw_cia402_decode_command(static_cast<std::uint16_t>(bits | 0xFF70u)) == expected);
  }
  CHECK(mrqp_fw_cia402_controlword(MRQP_FW_CIA402_CMD_SHUTDOWN) == 0x0006);
  CHECK(mrqp_fw_cia402_controlword(MRQP_FW_CIA402_CMD_SWITCH_ON) == 0x0007);
  CHECK(mrqp_fw_cia402_controlword(MRQP_FW_CIA402_CMD_ENABLE_OPERATION) == 0x000F);
  CHECK(mrqp_fw_cia402_controlword(MRQP_FW_CIA402_CMD_DISABLE_VOLTAGE) == 0x0000);
  CHECK(mrqp_fw_cia402_controlword(MRQP_FW_CIA402_CMD_QUICK_STOP) == 0x0002);
  CHECK(mrqp_fw_cia402_controlword(MRQP_FW_CIA402_CMD_FAULT_RESET) == 0x0080);
}

TEST_CASE("drive transitions follow the CiA 402 state machine table", "[firmware_if][cia402]") {
  // One row per (state, command) pair of the standard; commands given as several controlwords
  // that differ only in don't-care bits.
  struct Row {
    St from;
    std::uint16_t cw;
    St to;
    unsigned transition;
  };
  const Row table[] = {
      // Switch on disabled: only Shutdown leaves (2).
      {SOD, 0x0006, RTSO, 2},
      {SOD, 0x000E, RTSO, 2},
      {SOD, 0x0007, SOD, 0},
      {SOD, 0x000F, SOD, 0},
      {SOD, 0x0000, SOD, 0},
      {SOD, 0x0002, SOD, 0},
      // Ready to switch on: Switch on (3), Switch on + enable operation (3+4), Disable voltage / Quick stop (7).
      {RTSO, 0x0007, SO, 3},
      {RTSO, 0x000F, OE, 34},
      {RTSO, 0x0000, SOD, 7},
      {RTSO, 0x0001, SOD, 7},
      {RTSO, 0x0008, SOD, 7},
      {RTSO, 0x0002, SOD, 7},
      {RTSO, 0x000B, SOD, 7},
      {RTSO, 0x0006, RTSO, 0},
      // Switched on: Enable operation (4), Shutdown (6), Disable voltage / Quick stop (10).
      {SO, 0x000F, OE, 4},
      {SO, 0x0006, RTSO, 6},
      {SO, 0x000E, RTSO, 6},
      {SO, 0x0000, SOD, 10},
      {SO, 0x0002, SOD, 10},
      {SO, 0x0003, SOD, 10},
      {SO, 0x0007, SO, 0},
      // Operation enabled: Disable operation (5), Shutdown (8), Disable voltage (9), Quick stop (11).
      {OE, 0x0007, SO, 5},
      {OE, 0x0006, RTSO, 8},
      {OE, 0x000E, RTSO, 8},
      {OE, 0x0000, SOD, 9},
      {OE, 0x0005, SOD, 9},
      {OE, 0x000D, SOD, 9},
      {OE, 0x0002, QSA, 11},
      {OE, 0x000B, QSA, 11},
      {OE, 0x000F, OE, 0},
      {OE, 0x010F, OE, 0},  // halt bit is not a state command
      // Quick stop active: Disable voltage (12), Enable operation (16); others stay.
      {QSA, 0x0000, SOD, 12},
      {QSA, 0x000F, OE, 16},
      {QSA, 0x0002, QSA, 0},
      {QSA, 0x0006, QSA, 0},
      {QSA, 0x0007, QSA, 0},
      // Not ready to switch on and Fault reaction active ignore the controlword.
      {NRTSO, 0x0006, NRTSO, 0},
      {NRTSO, 0x000F, NRTSO, 0},
      {NRTSO, 0x0080, NRTSO, 0},
      {FRA, 0x0080, FRA, 0},
      {FRA, 0x0000, FRA, 0},
      {FRA, 0x000F, FRA, 0},
      // Fault: only the fault-reset edge (15); other commands are ignored.
      {FLT, 0x0080, SOD, 15},
      {FLT, 0x008F, SOD, 15},
      {FLT, 0x000F, FLT, 0},
      {FLT, 0x0006, FLT, 0},
      {FLT, 0x0000, FLT, 0},
      {UNK, 0x000F, UNK, 0},
  };
  for (const Row& r : table) {
    unsigned t = 999;
    INFO("from " << mrqp_fw_cia402_state_str(r.from) << " cw 0x" << std::hex << r.cw);
    CHECK(mrqp_fw_cia402_drive_next(r.from, r.cw, 0x0000, &t) == r.to);
    CHECK(t == r.transition);
  }
  CHECK(mrqp_fw_cia402_drive_next(OE, 0x0002, 0, nullptr) == QSA);
}

TEST_CASE("fault reset needs a rising edge; bit 7 is ignored outside Fault", "[firmware_if][cia402]") {
  unsigned t = 0;
  CHECK(mrqp_fw_cia402_drive_next(FLT, 0x0080, 0x0080, &t) == FLT);  // held high: no edge
  CHECK(t == 0);
  CHECK(mrqp_fw_cia402_drive_next(FLT, 0x0080, 0x0006, &t) == SOD);
  CHECK(t == 15);
  CHECK(mrqp_fw_cia402_drive_next(OE, 0x008F, 0x000F, &t) == OE);
  CHECK(mrqp_fw_cia402_drive_next(SOD, 0x0086, 0x0080, &t) == RTSO);
}

TEST_CASE("automatic transitions 1, 12, 13, 14", "[firmware_if][cia402]") {
  unsigned t = 0;
  CHECK(mrqp_fw_cia402_drive_event(NRTSO, MRQP_FW_CIA402_EV_INIT_COMPLETE, &t) == SOD);
  CHECK(t == 1);
  CHECK(mrqp_fw_cia402_drive_event(OE, MRQP_FW_CIA402_EV_INIT_COMPLETE, &t) == OE);
  CHECK(t == 0);
  for (St s : {NRTSO, SOD, RTSO, SO, OE, QSA}) {
    CHECK(mrqp_fw_cia402_drive_event(s, MRQP_FW_CIA402_EV_FAULT, &t) == FRA);
    CHECK(t == 13);
  }
  CHECK(mrqp_fw_cia402_drive_event(FRA, MRQP_FW_CIA402_EV_FAULT, &t) == FRA);
  CHECK(mrqp_fw_cia402_drive_event(FLT, MRQP_FW_CIA402_EV_FAULT, &t) == FLT);
  CHECK(mrqp_fw_cia402_drive_event(FRA, MRQP_FW_CIA402_EV_FAULT_REACTION_DONE, &t) == FLT);
  CHECK(t == 14);
  CHECK(mrqp_fw_cia402_drive_event(QSA, MRQP_FW_CIA402_EV_QUICK_STOP_DONE, &t) == SOD);
  CHECK(t == 12);
  CHECK(mrqp_fw_cia402_drive_event(OE, MRQP_FW_CIA402_EV_QUICK_STOP_DONE, &t) == OE);
}

TEST_CASE("master helper drives an emulated drive to every target from every state",
          "[firmware_if][cia402]") {
  const St targets[] = {SOD, RTSO, SO, OE};
  for (St start : all_states) {
    for (St target : targets) {
      St drive = start;
      std::uint16_t prev = start == FLT ? 0x0080 : 0x0000;  // worst case: fault reset already high
      int steps = 0;
      while (mrqp_fw_cia402_decode_statusword(mrqp_fw_cia402_statusword(drive, 0)) != target) {
        // The drive's own automatic transitions happen between cycles.
        if (drive == NRTSO) {
          drive = mrqp_fw_cia402_drive_event(drive, MRQP_FW_CIA402_EV_INIT_COMPLETE, nullptr);
        } else if (drive == FRA) {
          drive = mrqp_fw_cia402_drive_event(drive, MRQP_FW_CIA402_EV_FAULT_REACTION_DONE, nullptr);
        }
        const St seen = mrqp_fw_cia402_decode_statusword(mrqp_fw_cia402_statusword(drive, 0x0200));
        const std::uint16_t cw = mrqp_fw_cia402_master_controlword(seen, target, prev);
        CHECK((cw & ~MRQP_FW_CW_COMMAND_BITS) == 0);
        drive = mrqp_fw_cia402_drive_next(drive, cw, prev, nullptr);
        prev = cw;
        ++steps;
        INFO("start " << mrqp_fw_cia402_state_str(start) << " target " << mrqp_fw_cia402_state_str(target));
        REQUIRE(steps <= 7);
      }
    }
  }
  // Quick stop target: from Operation enabled one quick stop command.
  CHECK(mrqp_fw_cia402_master_controlword(OE, QSA, 0x000F) == 0x0002);
  // Fault: drop bit 7 first, then raise it.
  CHECK(mrqp_fw_cia402_master_controlword(FLT, OE, 0x0080) == 0x0000);
  CHECK(mrqp_fw_cia402_master_controlword(FLT, OE, 0x0000) == 0x0080);
  // Unknown statusword: the safe command.
  CHECK(mrqp_fw_cia402_master_controlword(UNK, OE, 0x000F) == 0x0000);
}

TEST_CASE("modes of operation of this contract", "[firmware_if][cia402]") {
  CHECK(MRQP_FW_MODE_CSP == 8);
  CHECK(MRQP_FW_MODE_CST == 10);
  CHECK(mrqp_fw_cia402_mode_supported(MRQP_FW_MODE_CSP));
  CHECK(mrqp_fw_cia402_mode_supported(MRQP_FW_MODE_CST));
  CHECK_FALSE(mrqp_fw_cia402_mode_supported(MRQP_FW_MODE_CSV));
  CHECK_FALSE(mrqp_fw_cia402_mode_supported(MRQP_FW_MODE_PROFILE_POSITION));
  CHECK(MRQP_FW_OBJ_CONTROLWORD == 0x6040u);
  CHECK(MRQP_FW_OBJ_STATUSWORD == 0x6041u);
  CHECK(MRQP_FW_OBJ_MODES_OF_OPERATION == 0x6060u);
  CHECK(MRQP_FW_OBJ_MODES_OF_OPERATION_DISPLAY == 0x6061u);
  CHECK(MRQP_FW_OBJ_POSITION_ACTUAL == 0x6064u);
  CHECK(MRQP_FW_OBJ_VELOCITY_ACTUAL == 0x606Cu);
  CHECK(MRQP_FW_OBJ_TORQUE_ACTUAL == 0x6077u);
  CHECK(MRQP_FW_OBJ_TARGET_POSITION == 0x607Au);
  CHECK(MRQP_FW_OBJ_TARGET_TORQUE == 0x6071u);
}
