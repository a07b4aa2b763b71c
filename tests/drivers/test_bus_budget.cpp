// Bus-load budgets against the figures of docs/protocol.md computed by hand, the refusal
// message, the table of docs/drivers.md, and the simulated bus as a second implementation.
#include <catch2/catch.hpp>

#include <mrqp/drivers/arm_driver.hpp>
#include <mrqp/drivers/budget_table.hpp>
#include <mrqp/drivers/bus_budget.hpp>
#include <mrqp/drivers/sim_bus.hpp>

#include <fstream>
#include <memory>
#include <sstream>
#include <string>
#include <vector>

#include "fake_cia402_drive.hpp"

using namespace mrqp::drivers;
using Catch::Matchers::Contains;

namespace {

BusSpec classic1m(double hz, double limit = 0.8) {
  BusSpec s;
  s.name = "arm0";
  s.cycle_hz = hz;
  s.limit = limit;
  return s;
}

}  // namespace

TEST_CASE("drivers: a 7-joint arm with a force/torque sensor at 1 kHz needs 2544..3090 bit times per ms",
          "[drivers][budget]") {
  // docs/protocol.md: 47 + 7 x (111 + 111 + 103) + 2 x 111 = 2544 bits without stuffing,
  // 55 + 7 x (135 + 135 + 125) + 2 x 135 = 3090 with worst-case stuffing.
  BusBudget b(classic1m(1000.0));
  b.addSync();
  b.addArmDrives(7, true);
  b.addFtClassic(1);
  const BudgetResult r = b.result();
  CHECK(r.valid);
  CHECK(r.frames_per_cycle == Approx(24.0));
  CHECK(r.nominal_bits_min == Approx(2544.0));
  CHECK(r.nominal_bits_worst == Approx(3090.0));
  CHECK(r.time_worst_ns == Approx(3090e3));
  CHECK(r.utilisation_min == Approx(2.544));
  CHECK(r.utilisation_worst == Approx(3.090));
  CHECK(!r.fits);
  std::string msg;
  CHECK(!b.check(&msg));
  CHECK_THAT(msg, Contains("309.0 % of the bus"));
  CHECK_THAT(msg, Contains("the limit is 80.0 %: over by 229.0 percentage points"));
  CHECK_THAT(msg, Contains("2290.0 us too much per cycle"));
  CHECK_THAT(msg, Contains("3.86 times"));
  CHECK_THAT(msg, Contains("bus 'arm0' (classic 1 Mbit/s, 1000 Hz)"));
  // SYNC + RPDO1 + TPDO1 alone (no TPDO2, no sensor): 1601 .. 1945 bits.
  BusBudget lean(classic1m(1000.0));
  lean.addSync();
  lean.addArmDrives(7, false);
  CHECK(lean.result().nominal_bits_min == Approx(1601.0));
  CHECK(lean.result().nominal_bits_worst == Approx(1945.0));
}

TEST_CASE("drivers: two arm joints fit a classic bus at 1 kHz within 70 %, three do not",
          "[drivers][budget]") {
  // 55 + 2 x 270 = 595 bits: 59.5 %.
  BusBudget two(classic1m(1000.0, 0.7));
  two.addSync();
  two.addArmDrives(2, false);
  std::string msg;
  CHECK(two.check(&msg));
  CHECK(two.result().utilisation_worst == Approx(0.595));
  CHECK_THAT(msg, Contains("within the 70.0 % limit"));
  // The limit is configurable: at 59 % the same bus is refused by 0.5 points (5 us).
  BusBudget strict(classic1m(1000.0, 0.59));
  strict.addSync();
  strict.addArmDrives(2, false);
  CHECK(!strict.check(&msg));
  CHECK_THAT(msg, Contains("over by 0.5 percentage points (5.0 us too much per cycle"));
  // 55 + 3 x 270 = 865 bits.
  BusBudget three(classic1m(1000.0, 0.7));
  three.addSync();
  three.addArmDrives(3, false);
  CHECK(three.result().nominal_bits_worst == Approx(865.0));
  CHECK(!three.check(nullptr));
}

TEST_CASE("drivers: a 20-joint MIT hand at 1 kHz is 4.1..5.0 classic buses, on CAN FD 56..68 % of one",
          "[drivers][budget]") {
  BusBudget mit(classic1m(1000.0));
  mit.addMitMotors(20);
  // command 8 bytes (111..135) + reply 6 bytes (95..115) = 206..250 bits per joint.
  CHECK(mit.result().nominal_bits_min == Approx(20 * 206.0));
  CHECK(mit.result().nominal_bits_worst == Approx(20 * 250.0));
  CHECK(mit.result().frames_per_cycle == Approx(40.0));

  BusSpec fd = classic1m(1000.0);
  fd.data_bps = 5000000;
  BusBudget board(fd);
  board.addHandBoard(20);
  // 11 + 9 joints: commands of 62 and 52 bytes and feedback of 64 and 54 bytes, all 64-byte
  // frames: 4 x 139.8 .. 4 x 169.6 us.
  REQUIRE(board.lines().size() == 4u);
  for (const BudgetLine& l : board.lines()) {
    CHECK(l.len == 64u);
    CHECK(l.ns_min == Approx(139800.0));
    CHECK(l.ns_worst == Approx(169600.0));
  }
  CHECK(board.result().utilisation_min == Approx(0.5592));
  CHECK(board.result().utilisation_worst == Approx(0.6784));
  CHECK(board.check(nullptr));
  // 8 Mbit/s data phase: 30 us + 549 x 125 ns = 98.625 us .. 34 us + 678 x 125 ns = 118.75 us.
  fd.data_bps = 8000000;
  BusBudget fast(fd);
  fast.addHandBoard(20);
  CHECK(fast.result().time_min_ns == Approx(4 * 98625.0));
  CHECK(fast.result().time_worst_ns == Approx(4 * 118750.0));
}

TEST_CASE("drivers: force/torque frames: the FD frame takes 88.6..105.6 us instead of 2 x 111..135",
          "[drivers][budget]") {
  BusSpec fd = classic1m(1000.0);
  fd.data_bps = 5000000;
  BusBudget b(fd);
  b.addFtFd(1);
  CHECK(b.result().time_min_ns == Approx(88600.0));
  CHECK(b.result().time_worst_ns == Approx(105600.0));
  BusBudget c(classic1m(1000.0));
  c.addFtClassic(1);
  CHECK(c.result().time_min_ns == Approx(222000.0));
  CHECK(c.result().time_worst_ns == Approx(270000.0));
}

TEST_CASE("drivers: periodic frames are averaged over the cycles, invalid budgets are refused",
          "[drivers][budget]") {
  BusBudget b(classic1m(1000.0));
  b.addHeartbeats(10, 0.1);  // 10 heartbeats every 100 ms: 0.1 per 1 ms cycle
  CHECK(b.result().frames_per_cycle == Approx(0.1));
  CHECK(b.result().nominal_bits_worst == Approx(6.5));
  BusBudget bad(classic1m(1000.0));
  bad.addFtFd(1);  // FD frames on a classic bus
  std::string msg;
  CHECK(!bad.check(&msg));
  CHECK_THAT(msg, Contains("CAN FD frames on a classic bus"));
  BusBudget nine(classic1m(1000.0));
  nine.addCyclic("too long", 1, 9, FrameFormat::Classic);
  CHECK(!nine.result().valid);
  CHECK(busSpecLabel(BusSpec{"x", 1000000, 5000000, 1.0, 0.8}) == "CAN FD 1/5 Mbit/s");
  CHECK(busSpecLabel(BusSpec{"x", 500000, 0, 1.0, 0.8}) == "classic 0.5 Mbit/s");
  const std::string report = b.report();
  CHECK_THAT(report, Contains("heartbeat (every 100 ms)"));
  CHECK_THAT(report, Contains("-> fits"));
}

TEST_CASE("drivers: bus plans for 7 drives + 20 hand joints + 2 F/T sensors", "[drivers][budget]") {
  const RobotTraffic robot;
  const BusKind classic{"classic 1 Mbit/s", 1000000, 0};
  const BusKind fd{"CAN FD 1/5 Mbit/s", 1000000, 5000000};
  // Per drive (worst case): 135 + 135 + 125 = 395 us; SYNC 55; F/T pair 270; MIT joint 250.
  // 1 kHz, 800 us allowed: 55 + 2 x 395 = 845 > 800 -> one drive per bus; 3 MIT joints per bus.
  BusPlan p = planBuses(robot, classic, 1000.0, 0.8);
  CHECK(p.feasible);
  CHECK(p.max_drives_per_bus == 1u);
  CHECK(p.max_mit_per_bus == 3u);
  CHECK(p.arm_buses == 7u);
  CHECK(p.hand_buses == 7u);
  // 500 Hz, 1600 us: 55 + 4 x 395 = 1635 > 1600 -> 3 drives per bus; 6 MIT joints.
  p = planBuses(robot, classic, 500.0, 0.8);
  CHECK(p.max_drives_per_bus == 3u);
  CHECK(p.arm_buses == 3u);
  CHECK(p.hand_buses == 4u);
  // 250 Hz, 3200 us: 55 + 7 x 395 + 270 = 3090 fits, + 270 more does not -> 2 arm buses.
  p = planBuses(robot, classic, 250.0, 0.8);
  CHECK(p.arm_buses == 2u);
  CHECK(p.hand_buses == 2u);
  // CAN FD: the 20-joint board (678.4 us) fits one bus even at 1 kHz.
  p = planBuses(robot, fd, 1000.0, 0.8);
  CHECK(p.hand_buses == 1u);
  CHECK(p.arm_buses == 7u);
  p = planBuses(robot, fd, 250.0, 0.8);
  CHECK(p.arm_buses + p.hand_buses == 2u);
  for (const PlannedBus& b : p.buses) {
    CHECK(b.utilisation_worst <= 0.8);
  }
  // Without TPDO2 (270 us per drive): 2 drives per bus at 1 kHz.
  RobotTraffic lean = robot;
  lean.arm_tpdo2 = false;
  CHECK(planBuses(lean, classic, 1000.0, 0.8).max_drives_per_bus == 2u);
}

TEST_CASE("drivers: docs/drivers.md carries the generated budget tables", "[drivers][budget]") {
  const std::string table = referenceBudgetTables();
  CHECK_THAT(table, Contains("| 1000 Hz | classic 1 Mbit/s | 1 | 7: "));
  CHECK_THAT(table, Contains("| **14** |"));
  std::ifstream in(std::string(MRQP_TEST_DATA_DIR) + "/../../docs/drivers.md");
  REQUIRE(in.good());
  std::stringstream ss;
  ss << in.rdbuf();
  const std::string doc = ss.str();
  INFO("regenerate with: mrqp-bus-budget (build/drivers/mrqp-bus-budget) and paste into docs/drivers.md");
  CHECK(doc.find(table) != std::string::npos);
}

TEST_CASE("drivers: the simulated bus carries exactly the budgeted worst-case time per cycle",
          "[drivers][budget][simbus]") {
  // Second implementation: the arm driver with 7 fake drives at 250 Hz on the simulated bus
  // (worst-case stuffing). In steady state the wire is busy 55 + 7 x 395 = 2820 us per cycle,
  // which is what the budget declares for this driver (heartbeats off).
  SimBus bus;
  SimNodeConfig mc;
  mc.rx_queue = 1024;
  SimNode* master = bus.addNode(mc);
  std::vector<std::unique_ptr<drvtest::FakeCia402Drive>> fakes;
  ArmConfig cfg;
  cfg.cycle_period = milliseconds(4);
  cfg.producer_heartbeat_ms = 0;
  for (std::uint8_t n = 1; n <= 7; ++n) {
    drvtest::FakeDriveOptions o;
    o.node = n;
    fakes.push_back(std::make_unique<drvtest::FakeCia402Drive>(*bus.addNode(SimNodeConfig{}), o));
    ArmDriveConfig d;
    d.node = n;
    cfg.drives.push_back(d);
  }
  BusRouter router(*master);
  std::string err;
  auto arm = ArmDriver::create({&router}, cfg, &err);
  REQUIRE(arm != nullptr);
  BusBudget budget(BusSpec{"arm", 1000000, 0, 250.0, 0.8});
  arm->declareTraffic(0, budget);
  CHECK(budget.result().time_worst_ns == Approx(2820e3));
  CHECK(budget.check(nullptr));

  arm->start(0);
  TimeNs t = 0;
  for (int k = 0; k < 100 && arm->phase() != ArmPhase::Running; ++k, t += cfg.cycle_period) {
    bus.advanceTo(t);
    router.poll(t);
    arm->update(t);
    arm->transmit(t);
  }
  REQUIRE(arm->phase() == ArmPhase::Running);
  for (int k = 0; k < 3; ++k, t += cfg.cycle_period) {  // let the TPDOs start
    bus.advanceTo(t);
    router.poll(t);
    arm->update(t);
    arm->transmit(t);
  }
  bus.advanceTo(t);  // the last warm-up cycle's frames are on the wire
  const TimeNs busy0 = bus.stats().busy_ns;
  const int cycles = 50;
  for (int k = 0; k < cycles; ++k, t += cfg.cycle_period) {
    bus.advanceTo(t);
    router.poll(t);
    arm->update(t);
    arm->transmit(t);
  }
  bus.advanceTo(t);
  const double per_cycle = static_cast<double>(bus.stats().busy_ns - busy0) / cycles;
  CHECK(per_cycle == Approx(budget.result().time_worst_ns));
}
