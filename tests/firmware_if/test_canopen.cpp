// CANopen COB-IDs, NMT, heartbeat, SYNC, EMCY.
#include <catch2/catch.hpp>

#include "test_util.hpp"

#include <string>

using namespace fwtest;

TEST_CASE("COB-IDs of the predefined connection set", "[firmware_if][canopen]") {
  CHECK(mrqp_fw_cob_id(MRQP_FW_COB_KIND_NMT, 0) == 0x000u);
  CHECK(mrqp_fw_cob_id(MRQP_FW_COB_KIND_SYNC, 0) == 0x080u);
  struct Row {
    mrqp_fw_cob kind;
    std::uint32_t base;
  };
  const Row rows[] = {
      {MRQP_FW_COB_KIND_EMCY, 0x080},   {MRQP_FW_COB_KIND_TPDO1, 0x180},  {MRQP_FW_COB_KIND_RPDO1, 0x200},
      {MRQP_FW_COB_KIND_TPDO2, 0x280},  {MRQP_FW_COB_KIND_RPDO2, 0x300},  {MRQP_FW_COB_KIND_TPDO3, 0x380},
      {MRQP_FW_COB_KIND_RPDO3, 0x400},  {MRQP_FW_COB_KIND_TPDO4, 0x480},  {MRQP_FW_COB_KIND_RPDO4, 0x500},
      {MRQP_FW_COB_KIND_SDO_TX, 0x580}, {MRQP_FW_COB_KIND_SDO_RX, 0x600}, {MRQP_FW_COB_KIND_HEARTBEAT, 0x700},
  };
  for (const Row& r : rows) {
    for (unsigned node : {1u, 5u, 64u, 127u}) {
      const std::uint32_t id = mrqp_fw_cob_id(r.kind, node);
      CHECK(id == r.base + node);
      std::uint8_t n = 0;
      CHECK(mrqp_fw_cob_decode(id, &n) == r.kind);
      CHECK(n == node);
    }
    CHECK(mrqp_fw_cob_id(r.kind, 0) == 0xFFFFFFFFu);
    CHECK(mrqp_fw_cob_id(r.kind, 128) == 0xFFFFFFFFu);
  }
  for (unsigned n = 1; n <= 4; ++n) {
    CHECK(mrqp_fw_cob_tpdo(n, 7) == 0x180u + 0x100u * (n - 1) + 7);
    CHECK(mrqp_fw_cob_rpdo(n, 7) == 0x200u + 0x100u * (n - 1) + 7);
  }
  CHECK(mrqp_fw_cob_tpdo(5, 7) == 0xFFFFFFFFu);
  CHECK(mrqp_fw_cob_rpdo(0, 7) == 0xFFFFFFFFu);
  CHECK(mrqp_fw_cob_tpdo(1, 0) == 0xFFFFFFFFu);

  // Every 11-bit identifier decodes to a kind that re-encodes to itself, or to UNKNOWN.
  int known = 0;
  for (std::uint32_t id = 0; id <= 0x7FF; ++id) {
    std::uint8_t node = 0xAA;
    const mrqp_fw_cob kind = mrqp_fw_cob_decode(id, &node);
    if (kind == MRQP_FW_COB_KIND_UNKNOWN) {
      CHECK(node == 0);
      continue;
    }
    ++known;
    REQUIRE(mrqp_fw_cob_id(kind, node) == id);
  }
  CHECK(known == 2 + 12 * 127);
  CHECK(mrqp_fw_cob_decode(0x800, nullptr) == MRQP_FW_COB_KIND_UNKNOWN);
  CHECK(mrqp_fw_cob_decode(0x780 + 3, nullptr) == MRQP_FW_COB_KIND_UNKNOWN);
}

TEST_CASE("NMT frames, byte-exact and validated", "[firmware_if][nmt]") {
  mrqp_fw_frame f{};
  REQUIRE(mrqp_fw_nmt_pack(MRQP_FW_NMT_START, 5, &f) == MRQP_FW_PACK_OK);
  CHECK(f.id == 0x000u);
  CHECK(payload(f) == Bytes{0x01, 0x05});
  REQUIRE(mrqp_fw_nmt_pack(MRQP_FW_NMT_RESET_COMM, 0, &f) == MRQP_FW_PACK_OK);
  CHECK(payload(f) == Bytes{0x82, 0x00});

  const mrqp_fw_nmt_cmd cmds[] = {MRQP_FW_NMT_START, MRQP_FW_NMT_STOP, MRQP_FW_NMT_ENTER_PREOP,
                                  MRQP_FW_NMT_RESET_NODE, MRQP_FW_NMT_RESET_COMM};
  const std::uint8_t bytes[] = {0x01, 0x02, 0x80, 0x81, 0x82};
  for (int i = 0; i < 5; ++i) {
    for (unsigned node : {0u, 1u, 127u}) {
      REQUIRE(mrqp_fw_nmt_pack(cmds[i], node, &f) == MRQP_FW_PACK_OK);
      CHECK(f.data[0] == bytes[i]);
      mrqp_fw_nmt_cmd c{};
      std::uint8_t n = 0xFF;
      REQUIRE(mrqp_fw_nmt_unpack(&f, &c, &n) == MRQP_FW_OK);
      CHECK(c == cmds[i]);
      CHECK(n == node);
    }
  }
  CHECK(mrqp_fw_nmt_pack(MRQP_FW_NMT_START, 128, &f) == MRQP_FW_PACK_ERR_ARG);
  CHECK(isCleared(f));
  CHECK(mrqp_fw_nmt_pack(static_cast<mrqp_fw_nmt_cmd>(0x03), 1, &f) == MRQP_FW_PACK_ERR_ARG);
  CHECK(mrqp_fw_nmt_pack(MRQP_FW_NMT_START, 1, nullptr) == MRQP_FW_PACK_ERR_ARG);

  mrqp_fw_nmt_cmd c{};
  std::uint8_t n = 0;
  mrqp_fw_frame bad = makeFrame(0x000, {0x03, 0x01});
  CHECK(mrqp_fw_nmt_unpack(&bad, &c, &n) == MRQP_FW_ERR_COMMAND);
  bad = makeFrame(0x000, {0x01, 0x80});
  CHECK(mrqp_fw_nmt_unpack(&bad, &c, &n) == MRQP_FW_ERR_RANGE);
  bad = makeFrame(0x000, {0x01});
  CHECK(mrqp_fw_nmt_unpack(&bad, &c, &n) == MRQP_FW_ERR_LENGTH);
  bad = makeFrame(0x001, {0x01, 0x01});
  CHECK(mrqp_fw_nmt_unpack(&bad, &c, &n) == MRQP_FW_ERR_ID);
  bad = makeFrame(0x000, {0x01, 0x01}, MRQP_FW_FRAME_FD);
  CHECK(mrqp_fw_nmt_unpack(&bad, &c, &n) == MRQP_FW_ERR_FORMAT);

  CHECK(mrqp_fw_nmt_addresses(0, 9));
  CHECK(mrqp_fw_nmt_addresses(9, 9));
  CHECK_FALSE(mrqp_fw_nmt_addresses(8, 9));
}

TEST_CASE("NMT slave state machine (CiA 301 figure)", "[firmware_if][nmt]") {
  using S = mrqp_fw_nmt_state;
  const S pre = MRQP_FW_NMT_STATE_PRE_OPERATIONAL;
  const S op = MRQP_FW_NMT_STATE_OPERATIONAL;
  const S stop = MRQP_FW_NMT_STATE_STOPPED;
  const S init = MRQP_FW_NMT_STATE_BOOTUP;
  struct Row {
    S from;
    mrqp_fw_nmt_cmd cmd;
    S to;
  };
  const Row table[] = {
      {pre, MRQP_FW_NMT_START, op},         {pre, MRQP_FW_NMT_STOP, stop},
      {pre, MRQP_FW_NMT_ENTER_PREOP, pre},  {op, MRQP_FW_NMT_STOP, stop},
      {op, MRQP_FW_NMT_ENTER_PREOP, pre},   {op, MRQP_FW_NMT_START, op},
      {stop, MRQP_FW_NMT_START, op},        {stop, MRQP_FW_NMT_ENTER_PREOP, pre},
      {stop, MRQP_FW_NMT_STOP, stop},       {op, MRQP_FW_NMT_RESET_NODE, init},
      {stop, MRQP_FW_NMT_RESET_COMM, init}, {pre, MRQP_FW_NMT_RESET_NODE, init},
      {init, MRQP_FW_NMT_START, init},      {init, MRQP_FW_NMT_RESET_COMM, init},
  };
  for (const Row& r : table) {
    CHECK(mrqp_fw_nmt_next_state(r.from, r.cmd) == r.to);
  }
  CHECK(mrqp_fw_nmt_boot_complete(init) == pre);
  CHECK(mrqp_fw_nmt_boot_complete(op) == op);
}

TEST_CASE("heartbeat and boot-up frames", "[firmware_if][nmt]") {
  mrqp_fw_frame f{};
  REQUIRE(mrqp_fw_heartbeat_pack(0x12, MRQP_FW_NMT_STATE_OPERATIONAL, &f) == MRQP_FW_PACK_OK);
  CHECK(f.id == 0x712u);
  CHECK(payload(f) == Bytes{0x05});
  REQUIRE(mrqp_fw_heartbeat_pack(1, MRQP_FW_NMT_STATE_BOOTUP, &f) == MRQP_FW_PACK_OK);
  CHECK(f.id == 0x701u);
  CHECK(payload(f) == Bytes{0x00});
  for (auto s : {MRQP_FW_NMT_STATE_BOOTUP, MRQP_FW_NMT_STATE_STOPPED, MRQP_FW_NMT_STATE_OPERATIONAL,
                 MRQP_FW_NMT_STATE_PRE_OPERATIONAL}) {
    REQUIRE(mrqp_fw_heartbeat_pack(127, s, &f) == MRQP_FW_PACK_OK);
    std::uint8_t node = 0;
    mrqp_fw_nmt_state st{};
    REQUIRE(mrqp_fw_heartbeat_unpack(&f, &node, &st) == MRQP_FW_OK);
    CHECK(node == 127);
    CHECK(st == s);
  }
  CHECK(mrqp_fw_heartbeat_pack(0, MRQP_FW_NMT_STATE_OPERATIONAL, &f) == MRQP_FW_PACK_ERR_ARG);
  CHECK(isCleared(f));
  CHECK(mrqp_fw_heartbeat_pack(1, outOfRangeEnum<mrqp_fw_nmt_state>(0x85), &f) == MRQP_FW_PACK_ERR_ARG);

  std::uint8_t node = 0;
  mrqp_fw_nmt_state st{};
  mrqp_fw_frame bad = makeFrame(0x705, {0x85});  // node-guarding toggle bit: not a heartbeat
  CHECK(mrqp_fw_heartbeat_unpack(&bad, &node, &st) == MRQP_FW_ERR_COMMAND);
  bad = makeFrame(0x700, {0x05});
  CHECK(mrqp_fw_heartbeat_unpack(&bad, &node, &st) == MRQP_FW_ERR_ID);
  bad = makeFrame(0x605, {0x05});
  CHECK(mrqp_fw_heartbeat_unpack(&bad, &node, &st) == MRQP_FW_ERR_ID);
  bad = makeFrame(0x705, {0x05, 0x00});
  CHECK(mrqp_fw_heartbeat_unpack(&bad, &node, &st) == MRQP_FW_ERR_LENGTH);
}

TEST_CASE("SYNC with and without counter", "[firmware_if][sync]") {
  mrqp_fw_frame f{};
  REQUIRE(mrqp_fw_sync_pack(0, &f) == MRQP_FW_PACK_OK);
  CHECK(f.id == 0x080u);
  CHECK(f.len == 0);
  std::uint8_t c = 99;
  REQUIRE(mrqp_fw_sync_unpack(&f, &c) == MRQP_FW_OK);
  CHECK(c == 0);
  for (unsigned k : {1u, 2u, 240u}) {
    REQUIRE(mrqp_fw_sync_pack(k, &f) == MRQP_FW_PACK_OK);
    CHECK(payload(f) == Bytes{static_cast<std::uint8_t>(k)});
    REQUIRE(mrqp_fw_sync_unpack(&f, &c) == MRQP_FW_OK);
    CHECK(c == k);
  }
  CHECK(mrqp_fw_sync_pack(241, &f) == MRQP_FW_PACK_ERR_ARG);
  mrqp_fw_frame bad = makeFrame(0x080, {0});
  CHECK(mrqp_fw_sync_unpack(&bad, &c) == MRQP_FW_ERR_RANGE);
  bad = makeFrame(0x080, {241});
  CHECK(mrqp_fw_sync_unpack(&bad, &c) == MRQP_FW_ERR_RANGE);
  bad = makeFrame(0x080, {1, 2});
  CHECK(mrqp_fw_sync_unpack(&bad, &c) == MRQP_FW_ERR_LENGTH);
  bad = makeFrame(0x081, {});
  CHECK(mrqp_fw_sync_unpack(&bad, &c) == MRQP_FW_ERR_ID);

  CHECK(mrqp_fw_sync_counter_next(1, 3) == 2);
  CHECK(mrqp_fw_sync_counter_next(3, 3) == 1);
  CHECK(mrqp_fw_sync_counter_next(0, 3) == 1);
  CHECK(mrqp_fw_sync_counter_next(240, 240) == 1);
  CHECK(mrqp_fw_sync_counter_next(5, 1) == 0);
}

TEST_CASE("EMCY frames, byte-exact and validated", "[firmware_if][emcy]") {
  mrqp_fw_emcy e{};
  e.error_code = MRQP_FW_EMCY_CONTINUOUS_OVER_CURRENT;
  e.error_register = MRQP_FW_ERRREG_GENERIC | MRQP_FW_ERRREG_CURRENT;
  for (std::uint8_t i = 0; i < 5; ++i) {
    e.manufacturer[i] = static_cast<std::uint8_t>(i + 1);
  }
  mrqp_fw_frame f{};
  REQUIRE(mrqp_fw_emcy_pack(2, &e, &f) == MRQP_FW_PACK_OK);
  CHECK(f.id == 0x082u);
  CHECK(payload(f) == Bytes{0x10, 0x23, 0x03, 0x01, 0x02, 0x03, 0x04, 0x05});

  std::uint8_t node = 0;
  mrqp_fw_emcy d{};
  REQUIRE(mrqp_fw_emcy_unpack(&f, &node, &d) == MRQP_FW_OK);
  CHECK(node == 2);
  CHECK(d.error_code == 0x2310);
  CHECK(d.error_register == 0x03);
  CHECK(d.manufacturer[4] == 0x05);

  e.error_code = 0xFFFF;
  e.error_register = 0xBF;
  REQUIRE(mrqp_fw_emcy_pack(127, &e, &f) == MRQP_FW_PACK_OK);
  REQUIRE(mrqp_fw_emcy_unpack(&f, &node, &d) == MRQP_FW_OK);
  CHECK(node == 127);
  CHECK(d.error_code == 0xFFFF);

  CHECK(mrqp_fw_emcy_pack(0, &e, &f) == MRQP_FW_PACK_ERR_ARG);
  CHECK(isCleared(f));
  mrqp_fw_frame bad = makeFrame(0x080, {0, 0, 0, 0, 0, 0, 0, 0});  // that is SYNC
  CHECK(mrqp_fw_emcy_unpack(&bad, &node, &d) == MRQP_FW_ERR_ID);
  bad = makeFrame(0x081, {0, 0, 0, 0, 0, 0, 0});
  CHECK(mrqp_fw_emcy_unpack(&bad, &node, &d) == MRQP_FW_ERR_LENGTH);
  bad = makeFrame(0x081, {0x00, 0x10, 0x41, 0, 0, 0, 0, 0});  // reserved error-register bit 6
  CHECK(mrqp_fw_emcy_unpack(&bad, &node, &d) == MRQP_FW_ERR_FORMAT);

  CHECK(std::string(mrqp_fw_emcy_code_str(0x8611)) == "following error");
  CHECK(std::string(mrqp_fw_emcy_code_str(0x0000)) == "error reset or no error");
  CHECK(std::string(mrqp_fw_emcy_code_str(0x2399)) == "current");
  CHECK(std::string(mrqp_fw_emcy_code_str(0xFF42)) == "device specific");
  CHECK(std::string(mrqp_fw_emcy_code_str(0xA000)) == "unknown emergency code");
}
