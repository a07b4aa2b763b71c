// The emulated CiA 402 drive's vendor profile, switch by switch (vendor_profile.hpp): SDO answers
// to hand-encoded CiA 301 requests (expedited download 0x23/0x2F, upload 0x40; answers 0x60, 0x4x
// or abort 0x80 with the code little-endian), the SYNC timeout with EMCY 0x8100 and each
// behaviour of 0x1029:01, against the lenient profile that keeps the old behaviour.
#include <catch2/catch.hpp>

#include <mrqp/emulation/emulated_cia402_drive.hpp>

#include <string>
#include <vector>

#include "sim_trace.hpp"

using mrqp::drivers::microseconds;
using mrqp::drivers::milliseconds;
using mrqp::drivers::TimeNs;
using mrqp::emulation::EmulatedCia402Drive;
using mrqp::emulation::VendorProfile;

namespace {

/// The drive alone: its frames recorded as text, a drive on node 1 booted at 2 ms.
class Bench final : private EmulatedCia402Drive::Host {
 public:
  explicit Bench(const VendorProfile& p) : drive_(*this, options(p)) { drive_.advance(milliseconds(2)); }

  /// An expedited write of `size` bytes; returns the answer.
  std::string write(std::uint16_t index, std::uint8_t sub, unsigned size, std::uint32_t v) {
    const auto cs = static_cast<std::uint8_t>(0x23u | ((4u - size) << 2));
    return request(drvtest::makeFrame(
        0x601, {cs, static_cast<std::uint8_t>(index & 0xFFu), static_cast<std::uint8_t>(index >> 8), sub,
                static_cast<std::uint8_t>(v & 0xFFu), static_cast<std::uint8_t>((v >> 8) & 0xFFu),
                static_cast<std::uint8_t>((v >> 16) & 0xFFu), static_cast<std::uint8_t>(v >> 24)}));
  }
  std::string read(std::uint16_t index, std::uint8_t sub) {
    return request(drvtest::makeFrame(0x601, {0x40, static_cast<std::uint8_t>(index & 0xFFu),
                                              static_cast<std::uint8_t>(index >> 8), sub, 0, 0, 0, 0}));
  }
  void nmt(std::uint8_t cmd) { (void)drive_.onFrame(drvtest::makeFrame(0x000, {cmd, 1}), t); }
  void sync() { (void)drive_.onFrame(drvtest::makeFrame(0x080, {}), t); }
  /// Moves time to `to`, running the drive's events; returns the frames it sent meanwhile.
  std::vector<std::string> advanceTo(TimeNs to) {
    out.clear();
    while (drive_.nextEvent() <= to) {
      t = drive_.nextEvent();
      drive_.advance(t);
    }
    t = to;
    drive_.advance(t);
    return out;
  }

  EmulatedCia402Drive& drive() { return drive_; }
  std::vector<std::string> out;
  TimeNs t = milliseconds(2);

 private:
  static EmulatedCia402Drive::Options options(const VendorProfile& p) {
    EmulatedCia402Drive::Options o;
    o.node = 1;
    o.profile = p;
    return o;
  }
  std::string request(const mrqp_fw_frame& f) {
    out.clear();
    (void)drive_.onFrame(f, t);
    return out.empty() ? std::string("none") : out.back();
  }
  void emit(const mrqp_fw_frame& frame, TimeNs) noexcept override { out.push_back(drvtest::frameStr(frame)); }
  EmulatedCia402Drive::Feedback onSync(const EmulatedCia402Drive&, bool, TimeNs) noexcept override {
    return EmulatedCia402Drive::Feedback{};
  }

  EmulatedCia402Drive drive_;
};

}  // namespace

TEST_CASE("vendor profile: TPDO count, absent and read-only objects", "[drivers][emulation][vendor]") {
  Bench lenient(VendorProfile::lenient());
  Bench strict(VendorProfile::strict());
  // TPDO3 exists only on the lenient drive (four TPDOs).
  CHECK(lenient.write(0x1802, 1, 4, 0xC0000381u) == "581#6002180100000000");
  CHECK(strict.write(0x1802, 1, 4, 0xC0000381u) == "581#8002180100000206");
  CHECK(strict.write(0x1A02, 0, 1, 0) == "581#80021A0000000206");
  VendorProfile three = VendorProfile::strict();
  three.tpdo_count = 3;
  CHECK(Bench(three).write(0x1802, 1, 4, 0xC0000381u) == "581#6002180100000000");

  // An absent object: 0x06020000; an absent sub-index of an existing one: 0x06090011.
  CHECK(strict.write(0x2000, 0, 4, 1) == "581#8000200000000206");
  CHECK(strict.write(0x1017, 5, 2, 1) == "581#8017100511000906");
  VendorProfile quiet = VendorProfile::strict();
  quiet.abort_absent = false;
  CHECK(Bench(quiet).write(0x2000, 0, 4, 1) == "581#6000200000000000");

  // Read-only: device type 0x1000; identity as configured.
  CHECK(strict.write(0x1000, 0, 4, 0) == "581#8000100002000106");
  CHECK(strict.read(0x1000, 0) == "581#4300100092010200");
  CHECK(strict.read(0x1018, 1) == "581#431810019C020000");
  VendorProfile ro = VendorProfile::strict();
  ro.abort_read_only = false;
  Bench ignores(ro);
  CHECK(ignores.write(0x1000, 0, 4, 0) == "581#6000100000000000");
  CHECK(ignores.read(0x1000, 0) == "581#4300100092010200");  // acknowledged, not stored
}

TEST_CASE("vendor profile: range checks, RTR bit, PDO rules", "[drivers][emulation][vendor]") {
  Bench lenient(VendorProfile::lenient());
  Bench strict(VendorProfile::strict());
  // 0x1006 below 250 us: value too low (0x06090032); the lenient drive takes it.
  CHECK(strict.write(0x1006, 0, 4, 100) == "581#8006100032000906");
  CHECK(lenient.write(0x1006, 0, 4, 100) == "581#6006100000000000");
  CHECK(strict.write(0x1006, 0, 4, 1000) == "581#6006100000000000");
  // 0x1017 below 10 ms.
  CHECK(strict.write(0x1017, 0, 2, 5) == "581#8017100032000906");
  // Reserved transmission type 0xF5 (PDO disabled first).
  CHECK(strict.write(0x1800, 1, 4, 0xC0000181u) == "581#6000180100000000");
  CHECK(strict.write(0x1800, 2, 1, 0xF5) == "581#8000180230000906");
  CHECK(lenient.write(0x1800, 1, 4, 0x80000181u) == "581#6000180100000000");
  CHECK(lenient.write(0x1800, 2, 1, 0xF5) == "581#6000180200000000");
  // 0x1029:01 beyond 2: value too high.
  CHECK(strict.write(0x1029, 1, 1, 3) == "581#8029100131000906");
  // Enabling a TPDO with bit 30 = 0 is refused; with bit 30 = 1 accepted.
  CHECK(strict.write(0x1800, 1, 4, 0x00000181u) == "581#8000180130000906");
  CHECK(strict.write(0x1800, 1, 4, 0x40000181u) == "581#6000180100000000");
  CHECK(lenient.write(0x1801, 1, 4, 0x00000281u) == "581#6001180100000000");
  // PDO rules: mapping while the PDO is enabled (0x1800 enabled above) -> 0x06040043; off: accepted.
  CHECK(strict.write(0x1A00, 0, 1, 0) == "581#80001A0043000406");
  VendorProfile loose = VendorProfile::strict();
  loose.pdo_rules = false;
  Bench b(loose);
  CHECK(b.write(0x1A00, 0, 1, 0) == "581#60001A0000000000");
}

TEST_CASE("vendor profile: SYNC timeout, EMCY 0x8100 and the behaviour of 0x1029",
          "[drivers][emulation][vendor]") {
  for (const unsigned behaviour : {0u, 1u, 2u}) {
    VendorProfile p = VendorProfile::strict();
    p.comm_error_behaviour = static_cast<std::uint8_t>(behaviour);
    Bench b(p);
    REQUIRE(b.write(0x1006, 0, 4, 1000) == "581#6006100000000000");  // 1 ms
    b.nmt(0x01);
    REQUIRE(b.drive().nmt() == MRQP_FW_NMT_STATE_OPERATIONAL);
    // No SYNC yet: nothing is watched.
    CHECK(b.advanceTo(b.t + milliseconds(10)).empty());
    b.sync();
    // 1.5 ms after the SYNC: still fine; a little later: the communication error.
    CHECK(b.advanceTo(b.t + microseconds(1500)).empty());
    const auto frames = b.advanceTo(b.t + microseconds(10));
    CHECK(frames == std::vector<std::string>{"081#0081110000000000"});
    CHECK(b.drive().commErrors() == 1u);
    const mrqp_fw_nmt_state expected = behaviour == 0   ? MRQP_FW_NMT_STATE_PRE_OPERATIONAL
                                       : behaviour == 1 ? MRQP_FW_NMT_STATE_OPERATIONAL
                                                        : MRQP_FW_NMT_STATE_STOPPED;
    CHECK(b.drive().nmt() == expected);
    CHECK(b.drive().state() != MRQP_FW_CIA402_FAULT);
    // Once: no second EMCY while no SYNC comes.
    CHECK(b.advanceTo(b.t + milliseconds(20)).empty());
    // Operational again and SYNC back: the error reset EMCY.
    b.nmt(0x01);
    b.out.clear();
    b.sync();
    CHECK(b.out == std::vector<std::string>{"081#0000000000000000"});
    CHECK_FALSE(b.drive().commErrorActive());
  }
  {
    // The power stage faults too, where configured.
    VendorProfile p = VendorProfile::strict();
    p.comm_error_fault = true;
    Bench b(p);
    REQUIRE(b.write(0x1006, 0, 4, 1000) == "581#6006100000000000");
    b.nmt(0x01);
    b.sync();
    (void)b.advanceTo(b.t + milliseconds(2));
    CHECK(b.drive().state() == MRQP_FW_CIA402_FAULT_REACTION_ACTIVE);
    CHECK(b.drive().errorCode() == 0x8100);
  }
  {
    // The lenient drive never times out.
    Bench b(VendorProfile::lenient());
    REQUIRE(b.write(0x1006, 0, 4, 1000) == "581#6006100000000000");
    b.nmt(0x01);
    b.sync();
    CHECK(b.advanceTo(b.t + milliseconds(50)).empty());
    CHECK(b.drive().nmt() == MRQP_FW_NMT_STATE_OPERATIONAL);
  }
}
