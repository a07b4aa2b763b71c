// SDO frames (expedited and segmented) and the client transfer helper against an emulated server.
#include <catch2/catch.hpp>

#include "test_util.hpp"

#include <algorithm>
#include <string>

using namespace fwtest;

TEST_CASE("expedited SDO frames, byte-exact", "[firmware_if][sdo]") {
  mrqp_fw_frame f{};
  const std::uint8_t mode = MRQP_FW_MODE_CSP;
  REQUIRE(mrqp_fw_sdo_pack_download_req(3, MRQP_FW_OBJ_MODES_OF_OPERATION, 0, &mode, 1, &f) ==
          MRQP_FW_PACK_OK);
  CHECK(f.id == 0x603u);
  CHECK(payload(f) == Bytes{0x2F, 0x60, 0x60, 0x00, 0x08, 0x00, 0x00, 0x00});

  REQUIRE(mrqp_fw_sdo_pack_download_u32(3, MRQP_FW_OBJ_PRODUCER_HEARTBEAT, 0, 100, 2, &f) == MRQP_FW_PACK_OK);
  CHECK(payload(f) == Bytes{0x2B, 0x17, 0x10, 0x00, 0x64, 0x00, 0x00, 0x00});
  REQUIRE(mrqp_fw_sdo_pack_download_u32(3, 0x1400, 1, 0x80000203u, 4, &f) == MRQP_FW_PACK_OK);
  CHECK(payload(f) == Bytes{0x23, 0x00, 0x14, 0x01, 0x03, 0x02, 0x00, 0x80});
  const std::uint8_t three[3] = {0xAA, 0xBB, 0xCC};
  REQUIRE(mrqp_fw_sdo_pack_download_req(3, 0x2000, 7, three, 3, &f) == MRQP_FW_PACK_OK);
  CHECK(payload(f) == Bytes{0x27, 0x00, 0x20, 0x07, 0xAA, 0xBB, 0xCC, 0x00});

  REQUIRE(mrqp_fw_sdo_pack_download_resp(3, MRQP_FW_OBJ_MODES_OF_OPERATION, 0, &f) == MRQP_FW_PACK_OK);
  CHECK(f.id == 0x583u);
  CHECK(payload(f) == Bytes{0x60, 0x60, 0x60, 0x00, 0x00, 0x00, 0x00, 0x00});

  REQUIRE(mrqp_fw_sdo_pack_upload_req(3, MRQP_FW_OBJ_STATUSWORD, 0, &f) == MRQP_FW_PACK_OK);
  CHECK(f.id == 0x603u);
  CHECK(payload(f) == Bytes{0x40, 0x41, 0x60, 0x00, 0x00, 0x00, 0x00, 0x00});

  const std::uint8_t sw[2] = {0x37, 0x02};
  REQUIRE(mrqp_fw_sdo_pack_upload_resp(3, MRQP_FW_OBJ_STATUSWORD, 0, sw, 2, &f) == MRQP_FW_PACK_OK);
  CHECK(f.id == 0x583u);
  CHECK(payload(f) == Bytes{0x4B, 0x41, 0x60, 0x00, 0x37, 0x02, 0x00, 0x00});

  REQUIRE(mrqp_fw_sdo_pack_abort(3, 1, 0x2000, 0, MRQP_FW_SDO_ABORT_NO_OBJECT, &f) == MRQP_FW_PACK_OK);
  CHECK(f.id == 0x583u);
  CHECK(payload(f) == Bytes{0x80, 0x00, 0x20, 0x00, 0x00, 0x00, 0x02, 0x06});
  REQUIRE(mrqp_fw_sdo_pack_abort(3, 0, 0x2000, 0, MRQP_FW_SDO_ABORT_TIMEOUT, &f) == MRQP_FW_PACK_OK);
  CHECK(f.id == 0x603u);

  CHECK(mrqp_fw_sdo_pack_download_req(3, 0x2000, 0, three, 5, &f) == MRQP_FW_PACK_ERR_ARG);
  CHECK(isCleared(f));
  CHECK(mrqp_fw_sdo_pack_download_req(3, 0x2000, 0, three, 0, &f) == MRQP_FW_PACK_ERR_ARG);
  CHECK(mrqp_fw_sdo_pack_download_req(0, 0x2000, 0, three, 1, &f) == MRQP_FW_PACK_ERR_ARG);
  CHECK(mrqp_fw_sdo_pack_download_u32(3, 0x2000, 0, 1, 3, &f) == MRQP_FW_PACK_ERR_ARG);
  CHECK(mrqp_fw_sdo_pack_upload_req(128, 0x2000, 0, &f) == MRQP_FW_PACK_ERR_ARG);
}

TEST_CASE("segmented SDO frames, byte-exact", "[firmware_if][sdo]") {
  mrqp_fw_frame f{};
  REQUIRE(mrqp_fw_sdo_pack_download_init_segmented(4, 0x1008, 0, 20, &f) == MRQP_FW_PACK_OK);
  CHECK(f.id == 0x604u);
  CHECK(payload(f) == Bytes{0x21, 0x08, 0x10, 0x00, 0x14, 0x00, 0x00, 0x00});
  REQUIRE(mrqp_fw_sdo_pack_upload_resp_segmented(4, 0x1008, 0, 20, &f) == MRQP_FW_PACK_OK);
  CHECK(f.id == 0x584u);
  CHECK(payload(f) == Bytes{0x41, 0x08, 0x10, 0x00, 0x14, 0x00, 0x00, 0x00});

  const std::uint8_t d[7] = {'m', 'r', 'q', 'p', '-', 'a', 'x'};
  REQUIRE(mrqp_fw_sdo_pack_segment(4, 0, 0, d, 7, 0, &f) == MRQP_FW_PACK_OK);
  CHECK(payload(f) == Bytes{0x00, 'm', 'r', 'q', 'p', '-', 'a', 'x'});
  // toggle 1, 3 bytes (n = 4 unused), last: 000 1 100 1
  REQUIRE(mrqp_fw_sdo_pack_segment(4, 1, 1, d, 3, 1, &f) == MRQP_FW_PACK_OK);
  CHECK(f.id == 0x584u);
  CHECK(payload(f) == Bytes{0x19, 'm', 'r', 'q', 0x00, 0x00, 0x00, 0x00});
  REQUIRE(mrqp_fw_sdo_pack_segment(4, 0, 0, nullptr, 0, 1, &f) == MRQP_FW_PACK_OK);
  CHECK(f.data[0] == 0x0F);

  REQUIRE(mrqp_fw_sdo_pack_download_seg_resp(4, 1, &f) == MRQP_FW_PACK_OK);
  CHECK(payload(f) == Bytes{0x30, 0, 0, 0, 0, 0, 0, 0});
  REQUIRE(mrqp_fw_sdo_pack_upload_seg_req(4, 0, &f) == MRQP_FW_PACK_OK);
  CHECK(payload(f) == Bytes{0x60, 0, 0, 0, 0, 0, 0, 0});
  REQUIRE(mrqp_fw_sdo_pack_upload_seg_req(4, 1, &f) == MRQP_FW_PACK_OK);
  CHECK(f.data[0] == 0x70);

  CHECK(mrqp_fw_sdo_pack_segment(4, 0, 2, d, 1, 0, &f) == MRQP_FW_PACK_ERR_ARG);
  CHECK(mrqp_fw_sdo_pack_segment(4, 0, 0, d, 8, 0, &f) == MRQP_FW_PACK_ERR_ARG);
  CHECK(mrqp_fw_sdo_pack_segment(4, 0, 0, nullptr, 1, 0, &f) == MRQP_FW_PACK_ERR_ARG);
  CHECK(mrqp_fw_sdo_pack_upload_seg_req(4, 2, &f) == MRQP_FW_PACK_ERR_ARG);
}

TEST_CASE("SDO unpack decodes every frame kind and rejects bad ones", "[firmware_if][sdo]") {
  mrqp_fw_sdo_msg m{};
  mrqp_fw_frame f = makeFrame(0x603, {0x2F, 0x60, 0x60, 0x00, 0x08, 0x00, 0x00, 0x00});
  REQUIRE(mrqp_fw_sdo_unpack(&f, &m) == MRQP_FW_OK);
  CHECK(m.kind == MRQP_FW_SDO_DOWNLOAD_INIT_REQ);
  CHECK(m.node == 3);
  CHECK(m.from_server == 0);
  CHECK(m.index == 0x6060);
  CHECK(m.subindex == 0);
  CHECK(m.expedited == 1);
  CHECK(m.size_indicated == 1);
  CHECK(m.n == 1);
  CHECK(m.data[0] == 8);

  f = makeFrame(0x583, {0x4B, 0x41, 0x60, 0x00, 0x37, 0x02, 0x00, 0x00});
  REQUIRE(mrqp_fw_sdo_unpack(&f, &m) == MRQP_FW_OK);
  CHECK(m.kind == MRQP_FW_SDO_UPLOAD_INIT_RESP);
  CHECK(m.from_server == 1);
  CHECK(m.n == 2);
  CHECK(m.data[0] == 0x37);
  CHECK(m.data[1] == 0x02);

  // Expedited without size indication: 4 bytes.
  f = makeFrame(0x583, {0x42, 0x00, 0x10, 0x00, 1, 2, 3, 4});
  REQUIRE(mrqp_fw_sdo_unpack(&f, &m) == MRQP_FW_OK);
  CHECK(m.expedited == 1);
  CHECK(m.size_indicated == 0);
  CHECK(m.n == 4);

  f = makeFrame(0x583, {0x41, 0x08, 0x10, 0x00, 0x14, 0x00, 0x00, 0x00});
  REQUIRE(mrqp_fw_sdo_unpack(&f, &m) == MRQP_FW_OK);
  CHECK(m.kind == MRQP_FW_SDO_UPLOAD_INIT_RESP);
  CHECK(m.expedited == 0);
  CHECK(m.size == 20);

  f = makeFrame(0x583, {0x19, 'a', 'b', 'c', 0, 0, 0, 0});
  REQUIRE(mrqp_fw_sdo_unpack(&f, &m) == MRQP_FW_OK);
  CHECK(m.kind == MRQP_FW_SDO_UPLOAD_SEG_RESP);
  CHECK(m.toggle == 1);
  CHECK(m.n == 3);
  CHECK(m.last == 1);
  CHECK(m.data[2] == 'c');

  f = makeFrame(0x603, {0x70, 0, 0, 0, 0, 0, 0, 0});
  REQUIRE(mrqp_fw_sdo_unpack(&f, &m) == MRQP_FW_OK);
  CHECK(m.kind == MRQP_FW_SDO_UPLOAD_SEG_REQ);
  CHECK(m.toggle == 1);

  f = makeFrame(0x583, {0x30, 0, 0, 0, 0, 0, 0, 0});
  REQUIRE(mrqp_fw_sdo_unpack(&f, &m) == MRQP_FW_OK);
  CHECK(m.kind == MRQP_FW_SDO_DOWNLOAD_SEG_RESP);
  CHECK(m.toggle == 1);

  f = makeFrame(0x583, {0x60, 0x17, 0x10, 0x00, 0, 0, 0, 0});
  REQUIRE(mrqp_fw_sdo_unpack(&f, &m) == MRQP_FW_OK);
  CHECK(m.kind == MRQP_FW_SDO_DOWNLOAD_INIT_RESP);
  CHECK(m.index == 0x1017);

  f = makeFrame(0x603, {0x40, 0x41, 0x60, 0x00, 0, 0, 0, 0});
  REQUIRE(mrqp_fw_sdo_unpack(&f, &m) == MRQP_FW_OK);
  CHECK(m.kind == MRQP_FW_SDO_UPLOAD_INIT_REQ);

  f = makeFrame(0x583, {0x80, 0x00, 0x20, 0x00, 0x00, 0x00, 0x02, 0x06});
  REQUIRE(mrqp_fw_sdo_unpack(&f, &m) == MRQP_FW_OK);
  CHECK(m.kind == MRQP_FW_SDO_ABORT);
  CHECK(m.abort_code == MRQP_FW_SDO_ABORT_NO_OBJECT);

  // Block transfer and cs 7 are not supported.
  for (unsigned cs : {5u, 6u, 7u}) {
    f = makeFrame(0x603, {static_cast<std::uint8_t>(cs << 5u), 0, 0, 0, 0, 0, 0, 0});
    CHECK(mrqp_fw_sdo_unpack(&f, &m) == MRQP_FW_ERR_COMMAND);
    f.id = 0x583;
    CHECK(mrqp_fw_sdo_unpack(&f, &m) == MRQP_FW_ERR_COMMAND);
  }
  f = makeFrame(0x603, {0x40, 0x41, 0x60, 0x00, 0, 0, 0});
  CHECK(mrqp_fw_sdo_unpack(&f, &m) == MRQP_FW_ERR_LENGTH);
  f = makeFrame(0x703, {0x40, 0x41, 0x60, 0x00, 0, 0, 0, 0});
  CHECK(mrqp_fw_sdo_unpack(&f, &m) == MRQP_FW_ERR_ID);
  f = makeFrame(0x600, {0x40, 0x41, 0x60, 0x00, 0, 0, 0, 0});
  CHECK(mrqp_fw_sdo_unpack(&f, &m) == MRQP_FW_ERR_ID);
  f = makeFrame(0x603, {0x40, 0x41, 0x60, 0x00, 0, 0, 0, 0}, MRQP_FW_FRAME_FD);
  CHECK(mrqp_fw_sdo_unpack(&f, &m) == MRQP_FW_ERR_FORMAT);
}

TEST_CASE("SDO abort codes have their CiA 301 names", "[firmware_if][sdo]") {
  CHECK(std::string(mrqp_fw_sdo_abort_str(0x05030000u)) == "toggle bit not alternated");
  CHECK(std::string(mrqp_fw_sdo_abort_str(0x06020000u)) == "object does not exist in the object dictionary");
  CHECK(std::string(mrqp_fw_sdo_abort_str(0x06090011u)) == "sub-index does not exist");
  CHECK(std::string(mrqp_fw_sdo_abort_str(0x08000022u)).find("present device state") != std::string::npos);
  CHECK(std::string(mrqp_fw_sdo_abort_str(0x12345678u)) == "unknown SDO abort code");
  const std::uint32_t all[] = {MRQP_FW_SDO_ABORT_TOGGLE,
                               MRQP_FW_SDO_ABORT_TIMEOUT,
                               MRQP_FW_SDO_ABORT_COMMAND,
                               MRQP_FW_SDO_ABORT_BLOCK_SIZE,
                               MRQP_FW_SDO_ABORT_SEQUENCE,
                               MRQP_FW_SDO_ABORT_CRC,
                               MRQP_FW_SDO_ABORT_OUT_OF_MEMORY,
                               MRQP_FW_SDO_ABORT_UNSUPPORTED_ACCESS,
                               MRQP_FW_SDO_ABORT_WRITE_ONLY,
                               MRQP_FW_SDO_ABORT_READ_ONLY,
                               MRQP_FW_SDO_ABORT_NO_OBJECT,
                               MRQP_FW_SDO_ABORT_NOT_MAPPABLE,
                               MRQP_FW_SDO_ABORT_PDO_LENGTH,
                               MRQP_FW_SDO_ABORT_PARAM_INCOMPATIBLE,
                               MRQP_FW_SDO_ABORT_INTERNAL_INCOMPATIBLE,
                               MRQP_FW_SDO_ABORT_HARDWARE,
                               MRQP_FW_SDO_ABORT_TYPE_LENGTH,
                               MRQP_FW_SDO_ABORT_TYPE_LENGTH_HIGH,
                               MRQP_FW_SDO_ABORT_TYPE_LENGTH_LOW,
                               MRQP_FW_SDO_ABORT_NO_SUBINDEX,
                               MRQP_FW_SDO_ABORT_INVALID_VALUE,
                               MRQP_FW_SDO_ABORT_VALUE_HIGH,
                               MRQP_FW_SDO_ABORT_VALUE_LOW,
                               MRQP_FW_SDO_ABORT_MAX_LESS_MIN,
                               MRQP_FW_SDO_ABORT_NO_RESOURCE,
                               MRQP_FW_SDO_ABORT_GENERAL,
                               MRQP_FW_SDO_ABORT_STORE,
                               MRQP_FW_SDO_ABORT_STORE_LOCAL,
                               MRQP_FW_SDO_ABORT_STORE_STATE,
                               MRQP_FW_SDO_ABORT_NO_DICTIONARY,
                               MRQP_FW_SDO_ABORT_NO_DATA};
  for (std::uint32_t code : all) {
    CHECK(std::string(mrqp_fw_sdo_abort_str(code)) != "unknown SDO abort code");
  }
}

namespace {

// A minimal SDO server (emulated drive firmware) with one object 0x2000:01, built only from the
// pack/unpack functions. Faults can be injected.
struct TestServer {
  std::uint8_t node = 9;
  Bytes value;
  Bytes written;
  std::uint32_t announced = 0;
  unsigned toggle = 0;
  std::size_t pos = 0;
  bool wrong_toggle = false;
  bool abort_reads = false;

  // Returns true and fills `resp` if the server answers.
  bool handle(const mrqp_fw_frame& req, mrqp_fw_frame& resp) {
    mrqp_fw_sdo_msg m{};
    if (mrqp_fw_sdo_unpack(&req, &m) != MRQP_FW_OK || m.from_server || m.node != node) {
      return false;
    }
    switch (m.kind) {
      case MRQP_FW_SDO_UPLOAD_INIT_REQ:
        if (abort_reads || m.index != 0x2000 || m.subindex != 1) {
          mrqp_fw_sdo_pack_abort(node, 1, m.index, m.subindex, MRQP_FW_SDO_ABORT_NO_OBJECT, &resp);
          return true;
        }
        pos = 0;
        toggle = 0;
        if (value.size() <= 4 && !value.empty()) {
          mrqp_fw_sdo_pack_upload_resp(node, m.index, m.subindex, value.data(),
                                       static_cast<unsigned>(value.size()), &resp);
        } else {
          mrqp_fw_sdo_pack_upload_resp_segmented(node, m.index, m.subindex,
                                                 static_cast<std::uint32_t>(value.size()), &resp);
        }
        return true;
      case MRQP_FW_SDO_UPLOAD_SEG_REQ: {
        const std::size_t n = std::min<std::size_t>(7, value.size() - pos);
        const bool last = pos + n == value.size();
        const unsigned t = wrong_toggle ? (m.toggle ^ 1u) : m.toggle;
        mrqp_fw_sdo_pack_segment(node, 1, t, value.data() + pos, static_cast<unsigned>(n), last, &resp);
        pos += n;
        return true;
      }
      case MRQP_FW_SDO_DOWNLOAD_INIT_REQ:
        written.clear();
        if (m.expedited) {
          written.assign(m.data, m.data + m.n);
        }
        announced = m.size;
        mrqp_fw_sdo_pack_download_resp(node, m.index, m.subindex, &resp);
        return true;
      case MRQP_FW_SDO_DOWNLOAD_SEG_REQ:
        written.insert(written.end(), m.data, m.data + m.n);
        mrqp_fw_sdo_pack_download_seg_resp(node, wrong_toggle ? (m.toggle ^ 1u) : m.toggle, &resp);
        return true;
      default:
        return false;
    }
  }
};

// Runs the client against the server until the client stops sending. Returns the last step.
mrqp_fw_sdo_step run(mrqp_fw_sdo_client& c, TestServer& s, mrqp_fw_sdo_step step, mrqp_fw_frame& out,
                     int* frames = nullptr) {
  int count = 0;
  while (step == MRQP_FW_SDO_STEP_SEND) {
    ++count;
    mrqp_fw_frame resp{};
    REQUIRE(s.handle(out, resp));
    step = mrqp_fw_sdo_client_on_frame(&c, &resp, &out);
    REQUIRE(count < 100);
  }
  if (frames != nullptr) {
    *frames = count;
  }
  return step;
}

}  // namespace

TEST_CASE("SDO client reads and writes any size through the emulated server", "[firmware_if][sdo]") {
  for (std::size_t size = 1; size <= 30; ++size) {
    TestServer s;
    for (std::size_t i = 0; i < size; ++i) {
      s.value.push_back(static_cast<std::uint8_t>(0x30 + i));
    }
    mrqp_fw_sdo_client c{};
    mrqp_fw_frame out{};
    std::uint8_t buf[64] = {};
    int frames = 0;
    mrqp_fw_sdo_step step = mrqp_fw_sdo_client_start_upload(&c, s.node, 0x2000, 1, buf, sizeof(buf), &out);
    REQUIRE(step == MRQP_FW_SDO_STEP_SEND);
    step = run(c, s, step, out, &frames);
    REQUIRE(step == MRQP_FW_SDO_STEP_DONE);
    CHECK(isCleared(out));
    REQUIRE(c.count == size);
    CHECK(Bytes(buf, buf + size) == s.value);
    // expedited: 1 request; segmented: initiate + ceil(size / 7) segments
    CHECK(frames == (size <= 4 ? 1 : 1 + static_cast<int>((size + 6) / 7)));

    mrqp_fw_sdo_client w{};
    step = mrqp_fw_sdo_client_start_download(&w, s.node, 0x2000, 1, s.value.data(),
                                             static_cast<std::uint32_t>(size), &out);
    REQUIRE(step == MRQP_FW_SDO_STEP_SEND);
    step = run(w, s, step, out, &frames);
    REQUIRE(step == MRQP_FW_SDO_STEP_DONE);
    CHECK(s.written == s.value);
    CHECK(frames == (size <= 4 ? 1 : 1 + static_cast<int>((size + 6) / 7)));
    if (size > 4) {
      CHECK(s.announced == size);
    }
  }
}

TEST_CASE("SDO client aborts on protocol errors and reports server aborts", "[firmware_if][sdo]") {
  TestServer s;
  s.value = Bytes(20, 0x55);
  mrqp_fw_frame out{};
  std::uint8_t buf[64] = {};

  SECTION("wrong toggle from the server") {
    s.wrong_toggle = true;
    mrqp_fw_sdo_client c{};
    mrqp_fw_sdo_step step = mrqp_fw_sdo_client_start_upload(&c, s.node, 0x2000, 1, buf, sizeof(buf), &out);
    step = run(c, s, step, out);
    CHECK(step == MRQP_FW_SDO_STEP_ABORT_SEND);
    CHECK(c.abort_code == MRQP_FW_SDO_ABORT_TOGGLE);
    CHECK(out.id == 0x609u);
    CHECK(payload(out) == Bytes{0x80, 0x00, 0x20, 0x01, 0x00, 0x00, 0x03, 0x05});
    CHECK(c.state == MRQP_FW_SDO_CLIENT_IDLE);
  }
  SECTION("wrong toggle on a segmented download") {
    s.wrong_toggle = true;
    mrqp_fw_sdo_client c{};
    mrqp_fw_sdo_step step =
        mrqp_fw_sdo_client_start_download(&c, s.node, 0x2000, 1, s.value.data(), 20, &out);
    step = run(c, s, step, out);
    CHECK(step == MRQP_FW_SDO_STEP_ABORT_SEND);
    CHECK(c.abort_code == MRQP_FW_SDO_ABORT_TOGGLE);
  }
  SECTION("buffer too small") {
    mrqp_fw_sdo_client c{};
    mrqp_fw_sdo_step step = mrqp_fw_sdo_client_start_upload(&c, s.node, 0x2000, 1, buf, 10, &out);
    step = run(c, s, step, out);
    CHECK(step == MRQP_FW_SDO_STEP_ABORT_SEND);
    CHECK(c.abort_code == MRQP_FW_SDO_ABORT_OUT_OF_MEMORY);
  }
  SECTION("server abort") {
    s.abort_reads = true;
    mrqp_fw_sdo_client c{};
    mrqp_fw_sdo_step step = mrqp_fw_sdo_client_start_upload(&c, s.node, 0x2000, 1, buf, sizeof(buf), &out);
    step = run(c, s, step, out);
    CHECK(step == MRQP_FW_SDO_STEP_ABORTED);
    CHECK(c.abort_code == MRQP_FW_SDO_ABORT_NO_OBJECT);
    CHECK(isCleared(out));
  }
  SECTION("timeout, foreign frames, misuse") {
    mrqp_fw_sdo_client c{};
    mrqp_fw_sdo_step step = mrqp_fw_sdo_client_start_upload(&c, s.node, 0x2000, 1, buf, sizeof(buf), &out);
    REQUIRE(step == MRQP_FW_SDO_STEP_SEND);
    // Busy: a second start is refused.
    mrqp_fw_frame other{};
    CHECK(mrqp_fw_sdo_client_start_upload(&c, s.node, 0x2000, 1, buf, sizeof(buf), &other) ==
          MRQP_FW_SDO_STEP_ERROR);
    // A frame from another node or a PDO is ignored.
    mrqp_fw_frame foreign = makeFrame(0x585, {0x4F, 0x00, 0x20, 0x01, 1, 0, 0, 0});
    CHECK(mrqp_fw_sdo_client_on_frame(&c, &foreign, &other) == MRQP_FW_SDO_STEP_IGNORED);
    foreign = makeFrame(0x189, {0, 0, 0, 0, 0, 0, 0, 0});
    CHECK(mrqp_fw_sdo_client_on_frame(&c, &foreign, &other) == MRQP_FW_SDO_STEP_IGNORED);
    // A response for another object: abort.
    mrqp_fw_frame wrong = makeFrame(0x589, {0x4F, 0x01, 0x20, 0x01, 1, 0, 0, 0});
    CHECK(mrqp_fw_sdo_client_on_frame(&c, &wrong, &other) == MRQP_FW_SDO_STEP_ABORT_SEND);
    CHECK(c.abort_code == MRQP_FW_SDO_ABORT_GENERAL);
    // Idle now: timeouts and frames are errors / ignored.
    CHECK(mrqp_fw_sdo_client_timeout(&c, &other) == MRQP_FW_SDO_STEP_ERROR);
    CHECK(mrqp_fw_sdo_client_on_frame(&c, &wrong, &other) == MRQP_FW_SDO_STEP_IGNORED);
    // Timeout while waiting.
    step = mrqp_fw_sdo_client_start_upload(&c, s.node, 0x2000, 1, buf, sizeof(buf), &out);
    REQUIRE(step == MRQP_FW_SDO_STEP_SEND);
    CHECK(mrqp_fw_sdo_client_timeout(&c, &out) == MRQP_FW_SDO_STEP_ABORT_SEND);
    CHECK(c.abort_code == MRQP_FW_SDO_ABORT_TIMEOUT);
    CHECK(payload(out) == Bytes{0x80, 0x00, 0x20, 0x01, 0x00, 0x00, 0x04, 0x05});
    // Unknown command specifier from the server.
    step = mrqp_fw_sdo_client_start_upload(&c, s.node, 0x2000, 1, buf, sizeof(buf), &out);
    mrqp_fw_frame block = makeFrame(0x589, {0xC0, 0, 0, 0, 0, 0, 0, 0});
    CHECK(mrqp_fw_sdo_client_on_frame(&c, &block, &out) == MRQP_FW_SDO_STEP_ABORT_SEND);
    CHECK(c.abort_code == MRQP_FW_SDO_ABORT_COMMAND);
    // Invalid starts.
    CHECK(mrqp_fw_sdo_client_start_upload(&c, 0, 0x2000, 1, buf, sizeof(buf), &out) ==
          MRQP_FW_SDO_STEP_ERROR);
    CHECK(mrqp_fw_sdo_client_start_upload(&c, 9, 0x2000, 1, buf, 0, &out) == MRQP_FW_SDO_STEP_ERROR);
    CHECK(mrqp_fw_sdo_client_start_download(&c, 9, 0x2000, 1, buf, 0, &out) == MRQP_FW_SDO_STEP_ERROR);
  }
}
