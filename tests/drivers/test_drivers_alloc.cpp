// The cyclic path of every driver allocates nothing: 10,000+ control cycles of a whole robot
// (7 arm drives and a force/torque sensor on one bus, MIT hand motors on a classic bus, a hand
// board on a CAN FD bus, fake devices and the simulated buses included) with the global
// allocator replaced by a counting one. Built only without sanitizers (they replace it too).
#include <catch2/catch.hpp>

#include <mrqp/drivers/drivers.hpp>

#include <atomic>
#include <cmath>
#include <cstdlib>
#include <memory>
#include <new>
#include <string>
#include <vector>

#include "emulated_node.hpp"
#include "fake_cia402_drive.hpp"
#include "fake_devices.hpp"

extern "C" void* __libc_malloc(std::size_t);
extern "C" void* __libc_calloc(std::size_t, std::size_t);
extern "C" void* __libc_realloc(void*, std::size_t);
extern "C" void* __libc_memalign(std::size_t, std::size_t);
extern "C" void __libc_free(void*);

namespace {
std::atomic<long> g_count{0};
}

// Counting replacements of the C allocator, forwarding to glibc's own implementation.
extern "C" void* malloc(std::size_t n) {
  g_count.fetch_add(1, std::memory_order_relaxed);
  return __libc_malloc(n);
}
extern "C" void* calloc(std::size_t n, std::size_t size) {
  g_count.fetch_add(1, std::memory_order_relaxed);
  return __libc_calloc(n, size);
}
extern "C" void* realloc(void* p, std::size_t n) {
  g_count.fetch_add(1, std::memory_order_relaxed);
  return __libc_realloc(p, n);
}
extern "C" void free(void* p) { __libc_free(p); }

// ... and of the C++ allocation functions.
void* operator new(std::size_t n) {
  g_count.fetch_add(1, std::memory_order_relaxed);
  void* p = __libc_malloc(n == 0 ? 1 : n);
  if (p == nullptr) {
    throw std::bad_alloc();
  }
  return p;
}
void* operator new[](std::size_t n) { return ::operator new(n); }
void* operator new(std::size_t n, std::align_val_t a) {
  g_count.fetch_add(1, std::memory_order_relaxed);
  void* p = __libc_memalign(static_cast<std::size_t>(a), n == 0 ? 1 : n);
  if (p == nullptr) {
    throw std::bad_alloc();
  }
  return p;
}
void* operator new[](std::size_t n, std::align_val_t a) { return ::operator new(n, a); }
void operator delete(void* p) noexcept { __libc_free(p); }
void operator delete[](void* p) noexcept { __libc_free(p); }
void operator delete(void* p, std::size_t) noexcept { __libc_free(p); }
void operator delete[](void* p, std::size_t) noexcept { __libc_free(p); }
void operator delete(void* p, std::align_val_t) noexcept { __libc_free(p); }
void operator delete[](void* p, std::align_val_t) noexcept { __libc_free(p); }
void operator delete(void* p, std::size_t, std::align_val_t) noexcept { __libc_free(p); }
void operator delete[](void* p, std::size_t, std::align_val_t) noexcept { __libc_free(p); }

using namespace mrqp::drivers;

TEST_CASE("drivers: the counting allocator is in effect", "[drivers][realtime]") {
  const long before = g_count.load();
  auto p = std::make_unique<int>(3);
  void* q = std::malloc(8);
  std::free(q);
  CHECK(g_count.load() - before == 2);
}

TEST_CASE("drivers: 10,000 cycles of the whole robot allocate nothing", "[drivers][realtime]") {
  const TimeNs period = milliseconds(4);  // 250 Hz: 7 drives + a sensor fit one classic bus

  // Arm bus: 7 drives (CSP), a classic force/torque sensor.
  SimBus arm_bus;
  SimNodeConfig mc;
  mc.rx_queue = 1024;
  SimNode* arm_master = arm_bus.addNode(mc);
  std::vector<std::unique_ptr<drvtest::FakeCia402Drive>> drives;
  ArmConfig ac;
  ac.cycle_period = period;
  ac.producer_heartbeat_ms = 20;
  ac.master_node = 0x7F;
  ac.master_heartbeat_ms = 20;
  ac.drive_consumer_ms = 60;
  for (std::uint8_t n = 1; n <= 7; ++n) {
    drvtest::FakeDriveOptions o;
    o.node = n;
    o.initial_position = 100 * n;
    drives.push_back(std::make_unique<drvtest::FakeCia402Drive>(*arm_bus.addNode(SimNodeConfig{}), o));
    ArmDriveConfig d;
    d.node = n;
    d.position_min = -3.0;
    d.position_max = 3.0;
    ac.drives.push_back(d);
  }
  drvtest::FakeFtSensor ft_fake(*arm_bus.addNode(SimNodeConfig{}), 0x30, false);
  ft_fake.setWrench({1.0, 2.0, 3.0, 0.1, 0.2, 0.3});
  BusRouter arm_router(*arm_master);

  // MIT hand bus: 3 motors.
  SimBus mit_bus;
  SimNode* mit_master = mit_bus.addNode(mc);
  drvtest::FakeMitMotors mit_fake(*mit_bus.addNode(SimNodeConfig{}));
  MitHandConfig hc;
  for (std::uint8_t id = 1; id <= 3; ++id) {
    mit_fake.add(id);
    MitMotorConfig m;
    m.motor_id = id;
    hc.motors.push_back(m);
  }
  BusRouter mit_router(*mit_master);

  // CAN FD hand bus: a 20-joint board.
  SimBusConfig fdc;
  fdc.data_bps = 5000000;
  SimBus fd_bus(fdc);
  SimNodeConfig fdm = mc;
  fdm.fd = true;
  SimNode* fd_master = fd_bus.addNode(fdm);
  SimNodeConfig fdn;
  fdn.fd = true;
  drvtest::FakeHandBoard board_fake(*fd_bus.addNode(fdn), 0, 20);
  FdHandConfig bc;
  HandBoardConfig hb;
  hb.board = 0;
  hb.joints = 20;
  bc.boards.push_back(hb);
  // ... and an IMU (24-byte FD frames) sampling on this driver's SYNC.
  drvtest::FakeImu imu_fake(*fd_bus.addNode(fdn), 0x40);
  imu_fake.sample().angular_velocity[2] = 0.5;
  ImuConfig ic;
  ic.produce_sync = true;
  ImuSensorConfig is;
  is.node = 0x40;
  ic.imus.push_back(is);
  BusRouter fd_router(*fd_master);

  FtConfig fc;
  FtSensorConfig fs;
  fs.node = 0x30;
  fc.sensors.push_back(fs);

  std::string err;
  auto arm = ArmDriver::create({&arm_router}, ac, &err);
  REQUIRE(arm != nullptr);
  auto ft = FtSensorDriver::create({&arm_router}, fc, &err);
  REQUIRE(ft != nullptr);
  auto mit = MitHandDriver::create({&mit_router}, hc, &err);
  REQUIRE(mit != nullptr);
  auto hand = FdHandDriver::create({&fd_router}, bc, &err);
  REQUIRE(hand != nullptr);
  auto imu = ImuDriver::create({&fd_router}, ic, &err);
  REQUIRE(imu != nullptr);

  // The start-up checks (allocate, outside the cycle).
  BusBudget budget(BusSpec{"arm", 1000000, 0, 250.0, 0.8});
  arm->declareTraffic(0, budget);
  ft->declareTraffic(0, budget);
  std::string msg;
  REQUIRE(budget.check(&msg));

  const int kCycles = 10500;
  long allocations = 0;
  std::uint64_t cycles_with_faults = 0;
  std::uint32_t all_flags = 0;
  double sink = 0.0;
  TimeNs t = 0;
  bool ft_started = false;
  arm->start(t);
  imu->start(t);
  for (int k = 0; k < kCycles; ++k, t += period) {
    const long before = g_count.load(std::memory_order_relaxed);

    arm_bus.advanceTo(t);
    mit_bus.advanceTo(t);
    fd_bus.advanceTo(t);
    arm_router.poll(t);
    mit_router.poll(t);
    fd_router.poll(t);
    const FaultReport& ra = arm->update(t);
    const FaultReport& rf = ft->update(t);
    const FaultReport& rm = mit->update(t);
    const FaultReport& rh = hand->update(t);
    const FaultReport& ri = imu->update(t);
    const std::uint32_t flags = ra.flags | rf.flags | rm.flags | rh.flags | ri.flags;
    all_flags |= flags;
    cycles_with_faults += flags != 0u ? 1u : 0u;

    if (!ft_started && arm->phase() == ArmPhase::Running) {
      ft->start(t);  // the sensor samples on the arm driver's SYNC, from its first transmit on
      ft_started = true;
    }
    if (k == 60) {
      arm->requestEnable(t);
      mit->requestEnable(t);
      hand->requestEnable(t);
    }
    if (k == 200) {
      ft->requestTare(0, true, t);
    }
    const double phase = 2.0 * M_PI * static_cast<double>(k) / 500.0;
    if (arm->allEnabled()) {
      for (std::size_t i = 0; i < arm->driveCount(); ++i) {
        const double target = 0.5 * std::sin(phase + static_cast<double>(i));
        // Every 1000th cycle a NaN arrives from the "controller": refused, never sent.
        (void)arm->setPosition(i, k % 1000 == 999 && i == 3 ? std::nan("") : target);
        sink += arm->drive(i).position;
      }
    }
    if (mit->allOn()) {
      for (std::size_t i = 0; i < mit->motorCount(); ++i) {
        const mrqp_fw_mit_cmd c{static_cast<float>(0.2 * std::sin(phase)), 0.0f, 20.0f, 0.5f, 0.0f};
        (void)mit->setCommand(i, c);
        sink += mit->motor(i).position;
      }
    }
    if (hand->allEnabled()) {
      for (std::size_t j = 0; j < 20; ++j) {
        (void)hand->setJoint(0, j, static_cast<float>(0.3 * std::cos(phase)), 0.0f, 0.0f);
        sink += hand->joint(0, j).position;
      }
    }
    sink += ft->sensor(0).wrench[2];
    sink += static_cast<const ImuDevice&>(*imu).imu(0).angular_velocity[2];
    if (k == 5000) {
      arm->requestDisable(t);  // and back: the whole state machine runs inside the window
    }
    if (k == 5100) {
      arm->requestEnable(t);
    }

    arm->transmit(t);
    ft->transmit(t);
    mit->transmit(t);
    hand->transmit(t);
    imu->transmit(t);

    allocations += g_count.load(std::memory_order_relaxed) - before;
  }
  CHECK(allocations == 0);
  // The run did what it should: booted, enabled, moved, and only the injected NaN were flagged.
  CHECK(arm->phase() == ArmPhase::Running);
  CHECK(arm->allEnabled());
  CHECK(mit->allOn());
  CHECK(hand->allEnabled());
  CHECK(imu->ready());
  CHECK(imu->state(0).angular_velocity[2] == Approx(0.5));
  CHECK(!ft->tarePending(0));
  CHECK(arm->faults().devices[3].refused_setpoints == 10u);
  CHECK((all_flags & ~fault::kSetpointRefused) == 0u);
  CHECK(cycles_with_faults == 10u);
  CHECK(std::isfinite(sink));
  CHECK(drives[3]->position() != 0);
}

TEST_CASE("drivers: the emulated firmware and its drivers allocate nothing in the cycle",
          "[drivers][realtime]") {
  using mrqp::emulation::EmulatedFtSensor;
  using mrqp::emulation::EmulatedHandBoard;
  using mrqp::emulation::EmulatedImu;
  using mrqp::emulation::EmulatedMitMotor;
  const TimeNs period = milliseconds(1);
  SimNodeConfig mc;
  mc.rx_queue = 1024;
  mc.echo_own = true;

  // MIT bus: 3 motors on one node; classic bus: an F/T sensor; FD bus: a hand board and an IMU.
  SimBus mit_bus;
  SimNode* mit_master = mit_bus.addNode(mc);
  SimNode& mit_node = *mit_bus.addNode(SimNodeConfig{});
  drvtest::IdealJointHost mit_host(mit_node, false);
  drvtest::EmulatedNode<EmulatedMitMotor> mit_emu(mit_node);
  std::vector<std::unique_ptr<EmulatedMitMotor>> motors;
  MitHandConfig hc;
  for (std::uint8_t id = 1; id <= 3; ++id) {
    EmulatedMitMotor::Options o;
    o.motor_id = id;
    o.joint = id;
    motors.push_back(std::make_unique<EmulatedMitMotor>(mit_host, o));
    mit_emu.add(*motors.back());
    MitMotorConfig m;
    m.motor_id = id;
    hc.motors.push_back(m);
  }
  BusRouter mit_router(*mit_master);

  SimBus ft_bus;
  SimNode* ft_master = ft_bus.addNode(mc);
  SimNode& ft_node = *ft_bus.addNode(SimNodeConfig{});
  drvtest::ConstantFtHost ft_host(ft_node);
  ft_host.value = {{1.0, 2.0, 3.0, 0.1, 0.2, 0.3}};
  drvtest::EmulatedNode<EmulatedFtSensor> ft_emu(ft_node);
  EmulatedFtSensor::Options fo;
  fo.node = 0x30;
  EmulatedFtSensor ft_dev(ft_host, fo);
  ft_emu.add(ft_dev);
  BusRouter ft_router(*ft_master);

  SimBusConfig fdc;
  fdc.data_bps = 5000000;
  SimBus fd_bus(fdc);
  SimNodeConfig fdm = mc;
  fdm.fd = true;
  SimNode* fd_master = fd_bus.addNode(fdm);
  SimNodeConfig fdn;
  fdn.fd = true;
  SimNode& board_node = *fd_bus.addNode(fdn);
  drvtest::IdealJointHost board_host(board_node, true);
  drvtest::EmulatedNode<EmulatedHandBoard> board_emu(board_node);
  EmulatedHandBoard::Options bo;
  bo.joints = 20;
  bo.command_timeout = milliseconds(20);
  EmulatedHandBoard board(board_host, bo);
  board_emu.add(board);
  SimNode& imu_node = *fd_bus.addNode(fdn);
  drvtest::ConstantImuHost imu_host(imu_node);
  drvtest::EmulatedNode<EmulatedImu> imu_emu(imu_node);
  EmulatedImu::Options io;
  io.node = 0x40;
  EmulatedImu imu_dev(imu_host, io);
  imu_emu.add(imu_dev);
  BusRouter fd_router(*fd_master);

  std::string err;
  auto mit = MitHandDriver::create({&mit_router}, hc, &err);
  REQUIRE(mit != nullptr);
  FtConfig fc;
  fc.produce_sync = true;
  FtSensorConfig fs;
  fs.node = 0x30;
  fc.sensors.push_back(fs);
  auto ft = FtSensorDriver::create({&ft_router}, fc, &err);
  REQUIRE(ft != nullptr);
  FdHandConfig bc;
  HandBoardConfig hb;
  hb.joints = 20;
  bc.boards.push_back(hb);
  auto hand = FdHandDriver::create({&fd_router}, bc, &err);
  REQUIRE(hand != nullptr);
  ImuConfig ic;
  ic.produce_sync = true;
  ImuSensorConfig is;
  is.node = 0x40;
  ic.imus.push_back(is);
  auto imu = ImuDriver::create({&fd_router}, ic, &err);
  REQUIRE(imu != nullptr);
  std::vector<Device*> devices{mit.get(), ft.get(), hand.get(), imu.get()};

  long allocations = 0;
  std::uint32_t all_flags = 0;
  TimeNs t = 0;
  for (Device* d : devices) {
    d->start(t);
  }
  for (int k = 0; k < 3000; ++k, t += period) {
    const long before = g_count.load(std::memory_order_relaxed);
    mit_bus.advanceTo(t);
    ft_bus.advanceTo(t);
    fd_bus.advanceTo(t);
    mit_router.poll(t);
    ft_router.poll(t);
    fd_router.poll(t);
    for (Device* d : devices) {
      all_flags |= d->update(t).flags;
    }
    if (k == 10) {
      for (Device* d : devices) {
        d->requestEnable(t);
      }
    }
    const double phase = 2.0 * M_PI * static_cast<double>(k) / 500.0;
    for (JointDevice* j : {static_cast<JointDevice*>(mit.get()), static_cast<JointDevice*>(hand.get())}) {
      for (std::size_t i = 0; i < j->jointCount(); ++i) {
        JointCommand c;
        c.position = 0.3 * std::sin(phase + static_cast<double>(i));
        c.stiffness = 20.0;
        c.damping = 0.5;
        (void)j->setJoint(i, c);
      }
    }
    if (k == 1500) {
      motors[1]->corruptReplies(1);
      imu_dev.corruptSamples(1);
    }
    for (Device* d : devices) {
      d->transmit(t);
    }
    allocations += g_count.load(std::memory_order_relaxed) - before;
  }
  CHECK(allocations == 0);
  for (Device* d : devices) {
    CHECK(d->ready());
  }
  // Only the injected corruption: one MIT reply and one IMU sample dropped (a gap in its sequence).
  CHECK((all_flags & ~(fault::kCorruptFrame | fault::kSampleLost)) == 0u);
  CHECK(mit->faults().devices[1].corrupt_frames == 1u);
  CHECK(imu->faults().devices[0].corrupt_frames == 1u);
  CHECK(imu->faults().devices[0].lost_samples == 1u);
  CHECK(board_host.servo[7].enabled);
  CHECK(mit_host.servo[2].kp == Approx(20.0).margin(0.2));
}

TEST_CASE("drivers: recovery and safe exit of strict drives allocate nothing", "[drivers][realtime]") {
  // Two strict drives (vendor_profile.hpp) with a SYNC timeout; the master with TX echo. Boot and
  // enable outside the count, then counted: a SYNC gap (EMCY 0x8100, pre-operational), 50 failing
  // cycles, the recovery, a reboot and its reconfiguration, the safe exit.
  const TimeNs period = milliseconds(1);
  SimBus bus;
  SimNodeConfig mc;
  mc.rx_queue = 1024;
  mc.echo_own = true;
  SimNode* master = bus.addNode(mc);
  std::vector<std::unique_ptr<drvtest::FakeCia402Drive>> drives;
  ArmConfig ac;
  ac.cycle_period = period;
  ac.producer_heartbeat_ms = 10;
  ac.heartbeat_timeout = milliseconds(50);
  for (std::uint8_t n = 1; n <= 2; ++n) {
    drvtest::FakeDriveOptions o;
    o.node = n;
    o.profile = mrqp::emulation::VendorProfile::strict();
    drives.push_back(std::make_unique<drvtest::FakeCia402Drive>(*bus.addNode(SimNodeConfig{}), o));
    ArmDriveConfig d;
    d.node = n;
    d.device_type = 0x192;
    ac.drives.push_back(d);
  }
  BusRouter router(*master);
  std::string err;
  auto arm = ArmDriver::create({&router}, ac, &err);
  REQUIRE(arm != nullptr);
  TimeNs t = 0;
  auto cycle = [&]() {
    bus.advanceTo(t);
    router.poll(t);
    const std::uint32_t flags = arm->update(t).flags;
    arm->transmit(t);
    t += period;
    return flags;
  };
  arm->start(t);
  for (int k = 0; k < 200 && arm->phase() != ArmPhase::Running; ++k) cycle();
  REQUIRE(arm->phase() == ArmPhase::Running);
  arm->requestEnable(t);
  for (int k = 0; k < 50 && !arm->ready(); ++k) cycle();
  REQUIRE(arm->ready());

  bool recovered = false, rebooted_back = false, exited = false;
  const long before = g_count.load();
  t += 2 * period;  // the SYNC gap
  for (int k = 0; k < 50; ++k) cycle();
  const std::size_t started = arm->requestRecovery(t);
  for (int k = 0; k < 100 && !recovered; ++k) {
    cycle();
    recovered = arm->ready();
  }
  drives[1]->power(false);
  for (int k = 0; k < 5; ++k) cycle();
  drives[1]->power(true);
  for (int k = 0; k < 30; ++k) cycle();
  (void)arm->requestRecovery(t);
  for (int k = 0; k < 200 && !rebooted_back; ++k) {
    cycle();
    rebooted_back = arm->ready();
  }
  arm->requestSafeExit(t);
  for (int k = 0; k < 100 && !exited; ++k) {
    cycle();
    exited = arm->safeExitDone();
  }
  const long allocations = g_count.load() - before;
  CHECK(allocations == 0);
  CHECK(started == 2u);
  CHECK(recovered);
  CHECK(rebooted_back);
  CHECK(exited);
  bus.advanceTo(t);  // the NMT commands on the wire
  CHECK(drives[0]->nmt() == MRQP_FW_NMT_STATE_PRE_OPERATIONAL);
  CHECK(drives[1]->nmt() == MRQP_FW_NMT_STATE_PRE_OPERATIONAL);
}
