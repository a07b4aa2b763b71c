// The boot-up race of the arm master's reset: a drive that powers up just before the master
// resets it sends its power-up boot-up message right before (or while) the NMT reset goes out.
// That boot-up does not answer the reset: the drive reboots on receiving the reset and sends a
// second boot-up ~2 ms later. A master that takes the first one configures a rebooting drive
// (SDO writes lost, the second boot-up seen as a reboot). The answer to the reset must come after
// the reset was on the bus: after its TX echo (bus with echoes), or at least after the reset was
// handed to the bus (bus without echoes).
#include <catch2/catch.hpp>

#include <mrqp/drivers/arm_driver.hpp>

#include <string>
#include <vector>

#include "arm_rig.hpp"

using namespace mrqp::drivers;

namespace {

/// Start times of the frames `text_prefix` on bus 0 of the rig ("701#00": boot-up of node 1).
std::vector<TimeNs> timesOf(drvtest::ArmRig& r, const std::string& prefix) {
  r.flush();
  std::vector<TimeNs> out;
  for (const WireEvent& e : r.logs[0]->events) {
    if (e.outcome == WireOutcome::Delivered && drvtest::frameStr(e.frame).rfind(prefix, 0) == 0) {
      out.push_back(e.start);
    }
  }
  return out;
}

/// Cycles until Running / Failed; ORs every report's flags into *flags.
void bootThrough(drvtest::ArmRig& r, std::uint32_t* flags) {
  for (int k = 0; k < 400 && r.arm->phase() != ArmPhase::Running && r.arm->phase() != ArmPhase::Failed; ++k) {
    *flags |= r.cycle().flags;
  }
  for (int k = 0; k < 20; ++k) {
    *flags |= r.cycle().flags;
  }
}

}  // namespace

TEST_CASE("drivers: arm boot race: a power-up boot-up on the wire as the reset goes out (TX echo)",
          "[drivers][arm][race]") {
  ArmConfig c;
  c.cycle_period = milliseconds(1);
  // The drive powers up at 0 and sends its boot-up at 2 ms; the master starts at 2 ms, after
  // that cycle's poll: the boot-up is on the wire when the reset is queued, the reset follows it.
  drvtest::ArmRig r({{0, 1}}, c, 64, {}, true);
  REQUIRE(r.arm != nullptr);
  r.cycle();
  r.cycle();
  r.hook = [](drvtest::ArmRig& rr) {
    rr.arm->start(rr.t);
    rr.hook = nullptr;
  };
  r.cycle();
  const std::vector<TimeNs> resets = timesOf(r, "000#8101");
  const std::vector<TimeNs> early = timesOf(r, "701#00");
  REQUIRE(resets.size() == 1u);
  REQUIRE(early.size() == 1u);
  REQUIRE(early[0] < resets[0]);                      // the power-up boot-up went first...
  REQUIRE(resets[0] - early[0] < microseconds(200));  // ... just before the reset

  std::uint32_t flags = 0;
  bootThrough(r, &flags);
  const std::vector<TimeNs> bootups = timesOf(r, "701#00");
  const std::vector<TimeNs> sdo = timesOf(r, "601#");
  REQUIRE(bootups.size() == 2u);  // power-up, then the answer to the reset
  REQUIRE(!sdo.empty());
  CHECK(sdo[0] > bootups[1]);  // configured only once the reset was answered
  CHECK(r.arm->phase() == ArmPhase::Running);
  CHECK((flags & (fault::kStateMismatch | fault::kBootFailed)) == 0u);
}

TEST_CASE("drivers: arm boot race: a boot-up received before the reset was sent (no echo)",
          "[drivers][arm][race]") {
  ArmConfig c;
  c.cycle_period = milliseconds(1);
  // Boot-up at 1.9 ms after power-up; the caller starts the master at 2 ms before polling the
  // bus (start() then the cycle), so the boot-up is read after start() but was received before
  // the reset was even queued.
  drvtest::ArmRig r({{0, 1}}, c, 64, {}, false, microseconds(1900));
  REQUIRE(r.arm != nullptr);
  r.cycle();
  r.cycle();
  r.arm->start(r.t);
  std::uint32_t flags = 0;
  bootThrough(r, &flags);
  const std::vector<TimeNs> bootups = timesOf(r, "701#00");
  const std::vector<TimeNs> resets = timesOf(r, "000#8101");
  const std::vector<TimeNs> sdo = timesOf(r, "601#");
  REQUIRE(bootups.size() == 2u);
  REQUIRE(resets.size() == 1u);
  REQUIRE(bootups[0] < resets[0]);
  REQUIRE(!sdo.empty());
  CHECK(sdo[0] > bootups[1]);
  CHECK(r.arm->phase() == ArmPhase::Running);
  CHECK((flags & (fault::kStateMismatch | fault::kBootFailed)) == 0u);
}

TEST_CASE("drivers: SimBus TX echo: own frames in wire order, routed to on_own_frame only",
          "[drivers][arm][race]") {
  SimBus bus;
  SimNodeConfig mc;
  mc.echo_own = true;
  SimNode* master = bus.addNode(mc);
  SimNode* other = bus.addNode(SimNodeConfig{});
  CHECK(master->echoesOwn());
  CHECK_FALSE(other->echoesOwn());
  // The other node's frame (lower priority id) waits behind the master's: wire order is master
  // first, and the master receives its echo before the other frame.
  REQUIRE(master->send(drvtest::makeFrame(0x000, {0x81, 0x01})) == SendResult::Ok);
  REQUIRE(other->send(drvtest::makeFrame(0x701, {0x00})) == SendResult::Ok);
  bus.advanceTo(milliseconds(1));
  RxFrame rx{};
  REQUIRE(master->receive(rx) == ReceiveResult::Frame);
  CHECK(rx.own);
  CHECK(rx.frame.id == 0x000u);
  const TimeNs echo_t = rx.timestamp;
  REQUIRE(master->receive(rx) == ReceiveResult::Frame);
  CHECK_FALSE(rx.own);
  CHECK(rx.frame.id == 0x701u);
  CHECK(rx.timestamp > echo_t);
  CHECK(master->receive(rx) == ReceiveResult::Empty);
  REQUIRE(other->receive(rx) == ReceiveResult::Frame);  // the other node has no echo
  CHECK(rx.frame.id == 0x000u);
  CHECK(other->receive(rx) == ReceiveResult::Empty);

  // Routed: the echo goes to onOwnFrame of every handler, never to onFrame, never unknown.
  struct Handler final : FrameHandler {
    Claim onFrame(const BusRouter&, const RxFrame&, TimeNs) noexcept override {
      ++frames;
      return Claim::NotMine;
    }
    void onOwnFrame(const BusRouter&, const RxFrame&, TimeNs) noexcept override { ++own; }
    int frames = 0;
    int own = 0;
  } h;
  BusRouter router(*master);
  REQUIRE(router.addHandler(h));
  REQUIRE(master->send(drvtest::makeFrame(0x080, {})) == SendResult::Ok);
  bus.advanceTo(milliseconds(2));
  router.poll(milliseconds(2));
  CHECK(h.own == 1);
  CHECK(h.frames == 0);
  CHECK(router.stats().echoes == 1u);
  CHECK(router.stats().unknown == 0u);
  router.removeHandler(h);
}
