// mrqp-stream: streams a sine per joint through the ArmDriver on a SocketCAN interface at a fixed
// rate (clock_nanosleep, absolute deadlines) for N cycles, checks the feedback, prints a summary
// and exits non-zero on failure (README.md). Whatever ends it (the last cycle, SIGINT/SIGTERM, a
// failed boot or enable), the drives are left stopped: ArmDriver::requestSafeExit (quick stop or
// disable voltage, then NMT pre-operational or stop).
#include <mrqp/drivers/arm_driver.hpp>
#include <mrqp/drivers/bus_router.hpp>
#include <mrqp/drivers/canopen/canopen_text.hpp>
#include <mrqp/drivers/socketcan_bus.hpp>

#include <signal.h>
#include <time.h>

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <exception>
#include <string>
#include <vector>

#include "drive_emu.hpp"

using namespace mrqp::drivers;

namespace {

struct Options {
  std::string interface = "vcan0";
  std::vector<std::uint8_t> nodes;
  double rate = 250.0;
  long cycles = 2000;
  std::string yaml;
  double amplitude = 0.2;             ///< rad
  double frequency = 0.5;             ///< Hz
  double max_error = 0.1;             ///< rad, tracking error bound
  int expect_heartbeat_loss = 0;      ///< node whose heartbeat loss is expected (and required)
  double heartbeat_loss_after = 0.0;  ///< s after streaming starts: earliest expected stop
  int heartbeat_timeout_ms = 250;
  int sdo_timeout_ms = 100;  ///< per SDO request during boot (a slow emulated target needs more)
  int heartbeat_ms = 100;
  int feedback_missing_cycles = 5;
  bool quiet = false;
  bool recover = false;  ///< RecoveryPolicy::Automatic
  bool tpdo_rtr_allowed = false;
  long comm_cycle_us = 0;  ///< 0x1006; 0: the cycle period
  ExitStop exit_stop = ExitStop::QuickStop;
  ExitNmt exit_nmt = ExitNmt::PreOperational;
  unsigned long device_type = 0, vendor_id = 0, product_code = 0;
};

volatile sig_atomic_t g_stop = 0;
void onSignal(int) { g_stop = 1; }

/// A fault seen during the run, kept for the report after the loop (no printing in the cycle).
struct FaultEvent {
  long cycle = 0;
  std::size_t drive = 0;
  DeviceFaults faults;
};

/// An unsigned number (decimal or 0x hex) within [0, max]; false if it is not one.
bool parseU32(const std::string& s, unsigned long max, unsigned long* out) {
  if (s.empty() || s[0] == '-') {
    return false;
  }
  char* end = nullptr;
  errno = 0;
  const unsigned long v = std::strtoul(s.c_str(), &end, 0);
  if (*end != '\0' || errno != 0 || v > max) {
    return false;
  }
  *out = v;
  return true;
}

void usage() {
  std::fprintf(stderr,
               "usage: mrqp-stream [--interface IF] [--nodes 1-7|1,2,3] [--rate HZ] [--cycles N]\n"
               "       [--config EMU.yaml] [--amplitude RAD] [--frequency HZ] [--max-error RAD]\n"
               "       [--heartbeat-ms MS] [--heartbeat-timeout-ms MS] [--sdo-timeout-ms MS] "
               "[--feedback-missing-cycles N]\n"
               "       [--expect-heartbeat-loss NODE] [--quiet]\n"
               "       [--recover] [--tpdo-rtr-allowed] [--comm-cycle-us US]\n"
               "       [--exit-stop quick-stop|disable] [--exit-nmt pre-operational|stopped|unchanged]\n"
               "       [--device-type N] [--vendor-id N] [--product-code N]\n"
               "--config reads nodes and scales from a mrqp-drive-emu YAML file.\n");
}

bool parseNodes(const std::string& s, std::vector<std::uint8_t>* out) {
  std::size_t pos = 0;
  while (pos < s.size()) {
    std::size_t end = s.find(',', pos);
    if (end == std::string::npos) {
      end = s.size();
    }
    const std::string part = s.substr(pos, end - pos);
    const auto dash = part.find('-');
    const int a = std::atoi(part.substr(0, dash).c_str());
    const int b = dash == std::string::npos ? a : std::atoi(part.substr(dash + 1).c_str());
    if (a < 1 || b > 127 || b < a) {
      return false;
    }
    for (int n = a; n <= b; ++n) {
      out->push_back(static_cast<std::uint8_t>(n));
    }
    pos = end + 1;
  }
  return !out->empty();
}

void addNs(timespec* t, TimeNs ns) {
  t->tv_nsec += ns;
  while (t->tv_nsec >= 1000000000L) {
    t->tv_nsec -= 1000000000L;
    ++t->tv_sec;
  }
}

TimeNs toNs(const timespec& t) { return static_cast<TimeNs>(t.tv_sec) * 1000000000 + t.tv_nsec; }

}  // namespace

static int unwrappedMain(int argc, char** argv) {
  Options o;
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    auto value = [&]() -> std::string {
      if (i + 1 >= argc) {
        std::fprintf(stderr, "mrqp-stream: %s needs a value\n", a.c_str());
        std::exit(2);
      }
      return argv[++i];
    };
    if (a == "--interface") {
      o.interface = value();
    } else if (a == "--nodes") {
      if (!parseNodes(value(), &o.nodes)) {
        std::fprintf(stderr, "mrqp-stream: --nodes: expected e.g. 1-7 or 1,2,3 (ids 1..127)\n");
        return 2;
      }
    } else if (a == "--rate") {
      o.rate = std::atof(value().c_str());
    } else if (a == "--cycles") {
      o.cycles = std::atol(value().c_str());
    } else if (a == "--config") {
      o.yaml = value();
    } else if (a == "--amplitude") {
      o.amplitude = std::atof(value().c_str());
    } else if (a == "--frequency") {
      o.frequency = std::atof(value().c_str());
    } else if (a == "--max-error") {
      o.max_error = std::atof(value().c_str());
    } else if (a == "--expect-heartbeat-loss") {
      o.expect_heartbeat_loss = std::atoi(value().c_str());
    } else if (a == "--sdo-timeout-ms") {
      o.sdo_timeout_ms = std::atoi(value().c_str());
    } else if (a == "--heartbeat-timeout-ms") {
      o.heartbeat_timeout_ms = std::atoi(value().c_str());
    } else if (a == "--heartbeat-ms") {
      o.heartbeat_ms = std::atoi(value().c_str());
    } else if (a == "--feedback-missing-cycles") {
      o.feedback_missing_cycles = std::atoi(value().c_str());
    } else if (a == "--quiet") {
      o.quiet = true;
    } else if (a == "--recover") {
      o.recover = true;
    } else if (a == "--tpdo-rtr-allowed") {
      o.tpdo_rtr_allowed = true;
    } else if (a == "--comm-cycle-us") {
      unsigned long v = 0;
      if (!parseU32(value(), 0xFFFFFFFFul, &v)) {
        std::fprintf(stderr, "mrqp-stream: --comm-cycle-us: expected microseconds 0..4294967295\n");
        return 2;
      }
      o.comm_cycle_us = static_cast<long>(v);
    } else if (a == "--device-type" || a == "--vendor-id" || a == "--product-code") {
      unsigned long v = 0;
      if (!parseU32(value(), 0xFFFFFFFFul, &v)) {
        std::fprintf(stderr, "mrqp-stream: %s: expected a 32-bit unsigned number (0x... for hex)\n",
                     a.c_str());
        return 2;
      }
      (a == "--device-type" ? o.device_type : a == "--vendor-id" ? o.vendor_id : o.product_code) = v;
    } else if (a == "--exit-stop") {
      const std::string v = value();
      if (v == "quick-stop") {
        o.exit_stop = ExitStop::QuickStop;
      } else if (v == "disable") {
        o.exit_stop = ExitStop::DisableVoltage;
      } else {
        std::fprintf(stderr, "mrqp-stream: --exit-stop: expected quick-stop or disable\n");
        return 2;
      }
    } else if (a == "--exit-nmt") {
      const std::string v = value();
      if (v == "pre-operational") {
        o.exit_nmt = ExitNmt::PreOperational;
      } else if (v == "stopped") {
        o.exit_nmt = ExitNmt::Stopped;
      } else if (v == "unchanged") {
        o.exit_nmt = ExitNmt::Unchanged;
      } else {
        std::fprintf(stderr, "mrqp-stream: --exit-nmt: expected pre-operational, stopped or unchanged\n");
        return 2;
      }
    } else if (a == "--help" || a == "-h") {
      usage();
      return 0;
    } else {
      std::fprintf(stderr, "mrqp-stream: unknown option %s\n", a.c_str());
      usage();
      return 2;
    }
  }
  if (!(o.rate > 0.0 && o.rate <= 10000.0) || o.cycles <= 0 || o.heartbeat_ms <= 0 ||
      o.heartbeat_timeout_ms <= 0 || o.sdo_timeout_ms <= 0 || o.feedback_missing_cycles <= 0) {
    std::fprintf(stderr,
                 "mrqp-stream: --rate must be 0..10000 Hz; --cycles, heartbeat times, "
                 "--feedback-missing-cycles > 0\n");
    return 2;
  }

  ArmConfig cfg;
  if (!o.yaml.empty()) {
    mrqp::drive_emu::EmuConfig emu;
    std::string err;
    if (!mrqp::drive_emu::loadConfig(o.yaml, &emu, &err)) {
      std::fprintf(stderr, "mrqp-stream: %s\n", err.c_str());
      return 2;
    }
    for (const auto& n : emu.nodes) {
      if (!o.nodes.empty() && std::find(o.nodes.begin(), o.nodes.end(), n.node) == o.nodes.end()) {
        continue;
      }
      ArmDriveConfig d;
      d.node = n.node;
      d.scale = n.scale;
      d.device_type = static_cast<std::uint32_t>(o.device_type);
      d.vendor_id = static_cast<std::uint32_t>(o.vendor_id);
      d.product_code = static_cast<std::uint32_t>(o.product_code);
      cfg.drives.push_back(d);
    }
  } else {
    if (o.nodes.empty()) {
      o.nodes = {1};
    }
    for (std::uint8_t n : o.nodes) {
      ArmDriveConfig d;
      d.node = n;
      d.device_type = static_cast<std::uint32_t>(o.device_type);
      d.vendor_id = static_cast<std::uint32_t>(o.vendor_id);
      d.product_code = static_cast<std::uint32_t>(o.product_code);
      cfg.drives.push_back(d);
    }
  }
  cfg.cycle_period = periodOfHz(o.rate);
  cfg.producer_heartbeat_ms = static_cast<std::uint16_t>(o.heartbeat_ms);
  cfg.heartbeat_timeout = milliseconds(o.heartbeat_timeout_ms);
  cfg.sdo_timeout = milliseconds(o.sdo_timeout_ms);
  cfg.boot_timeout = std::max(cfg.boot_timeout, 50 * cfg.sdo_timeout);
  cfg.enable_timeout = std::max(cfg.enable_timeout, 10 * cfg.sdo_timeout);
  cfg.feedback_missing_cycles = static_cast<std::uint32_t>(o.feedback_missing_cycles);
  cfg.recovery = o.recover ? RecoveryPolicy::Automatic : RecoveryPolicy::Manual;
  cfg.tpdo_rtr_allowed = o.tpdo_rtr_allowed;
  cfg.comm_cycle_period_us = static_cast<std::uint32_t>(o.comm_cycle_us);
  cfg.exit_stop = o.exit_stop;
  cfg.exit_nmt = o.exit_nmt;
  cfg.exit_timeout = std::max(cfg.exit_timeout, 20 * cfg.cycle_period);

  SocketCanBus bus;
  SocketCanConfig sc;
  sc.interface = o.interface;
  sc.receive_own = true;  // the arm master takes a boot-up only after its reset's own echo
  std::string err;
  if (!bus.open(sc, &err)) {
    std::fprintf(stderr, "mrqp-stream: %s: %s\n", o.interface.c_str(), err.c_str());
    return 1;
  }
  BusRouter router(bus);
  auto arm = ArmDriver::create({&router}, cfg, &err);
  if (!arm) {
    std::fprintf(stderr, "mrqp-stream: %s\n", err.c_str());
    return 2;
  }
  const std::size_t n = arm->driveCount();
  int hb_drive = -1;
  for (std::size_t j = 0; j < n; ++j) {
    if (cfg.drives[j].node == o.expect_heartbeat_loss) {
      hb_drive = static_cast<int>(j);
    }
  }
  if (o.expect_heartbeat_loss != 0 && hb_drive < 0) {
    std::fprintf(stderr, "mrqp-stream: --expect-heartbeat-loss %d: not a streamed node\n",
                 o.expect_heartbeat_loss);
    return 2;
  }

  signal(SIGINT, onSignal);
  signal(SIGTERM, onSignal);

  // Setup done: everything below is the cycle (no allocation in the loop).
  std::vector<double> q0(n, 0.0);
  std::vector<double> sent(n, 0.0);
  std::vector<double> max_err(n, 0.0);
  std::vector<std::uint64_t> hb_lost(n, 0);
  std::vector<TimeNs> hb_lost_at(n, -1);
  std::vector<double> hb_lost_wall(n, -1.0);
  std::uint64_t overruns = 0;
  std::uint64_t fail_cycles = 0;
  std::uint32_t fail_flags = 0;
  std::uint32_t all_flags = 0;
  std::uint64_t frames_sent = 0;
  TimeNs worst_late = 0;
  std::vector<FaultEvent> events(64);  // the first faults of each kind per drive, in order
  std::size_t event_count = 0;
  std::vector<std::uint32_t> reported(n, 0);
  long cycle_no = 0;
  auto note = [&](const FaultReport& r) {  // real-time safe: copies into the preallocated events
    for (std::size_t j = 0; j < n && j < r.device_count; ++j) {
      const std::uint32_t fresh =
          r.devices[j].flags & ~reported[j] &
          (fault::kEmcy | fault::kStateMismatch | fault::kBootFailed | fault::kTimeout |
           fault::kHeartbeatLost | fault::kDeviceFault | fault::kRecovering);
      if (fresh != 0u && event_count < events.size()) {
        events[event_count++] = FaultEvent{cycle_no, j, r.devices[j]};
      }
      reported[j] |= fresh;
    }
  };

  timespec next;
  clock_gettime(CLOCK_MONOTONIC, &next);
  const TimeNs period = cfg.cycle_period;
  auto cycle_start = [&]() {
    addNs(&next, period);
    clock_nanosleep(CLOCK_MONOTONIC, TIMER_ABSTIME, &next, nullptr);
    timespec now;
    clock_gettime(CLOCK_MONOTONIC, &now);
    const TimeNs late = toNs(now) - toNs(next);
    worst_late = std::max(worst_late, late);
    if (late > period) {
      ++overruns;
    }
    return toNs(next);
  };

  // Boot and enable (at the same rate).
  TimeNs now = toNs(next);
  arm->start(now);
  long boot_cycles = 0;
  const long boot_limit = static_cast<long>(o.rate * 10.0);
  while (arm->phase() != ArmPhase::Running && arm->phase() != ArmPhase::Failed && boot_cycles < boot_limit) {
    now = cycle_start();
    router.poll(now);
    const FaultReport& r = arm->update(now);
    all_flags |= r.flags;
    note(r);
    frames_sent += arm->transmit(now);
    ++boot_cycles;
    ++cycle_no;
    if (g_stop != 0) {
      break;
    }
  }

  // The safe exit: run the cycle until the drives are stopped and left in the NMT state asked for.
  auto safe_exit = [&]() -> bool {
    arm->requestSafeExit(now);
    const long limit =
        static_cast<long>(static_cast<double>(cfg.exit_timeout) / static_cast<double>(period)) + 20;
    long k = 0;
    while (!arm->safeExitDone() && k < limit) {
      now = cycle_start();
      router.poll(now);
      (void)arm->update(now);
      frames_sent += arm->transmit(now);
      ++k;
    }
    // Let the NMT commands reach the bus before the socket closes.
    now = cycle_start();
    router.poll(now);
    (void)arm->update(now);
    std::printf("mrqp-stream: safe exit: %s after %ld cycles (%s, then %s)\n",
                arm->safeExitDone() ? "drives stopped" : "NOT completed", k,
                cfg.exit_stop == ExitStop::QuickStop ? "quick stop" : "disable voltage",
                cfg.exit_nmt == ExitNmt::PreOperational ? "NMT pre-operational"
                : cfg.exit_nmt == ExitNmt::Stopped      ? "NMT stop"
                                                        : "NMT state unchanged");
    return arm->safeExitDone();
  };
  auto print_events = [&]() {
    for (std::size_t e = 0; e < event_count; ++e) {
      std::printf("mrqp-stream: cycle %ld: drive %zu: %s\n", events[e].cycle, events[e].drive,
                  describeDeviceFaults(events[e].faults).c_str());
    }
  };
  auto print_faults = [&](const FaultReport& r) {
    const std::string text = describeFaults(r, "drive");
    if (!text.empty()) {
      std::printf("mrqp-stream: faults:\n%s", text.c_str());
    }
  };

  if (arm->phase() != ArmPhase::Running) {
    std::printf("mrqp-stream: FAIL: boot ended in phase %s after %ld cycles, flags %s\n",
                armPhaseStr(arm->phase()), boot_cycles, faultFlagsStr(all_flags).c_str());
    print_faults(arm->faults());
    print_events();
    safe_exit();
    return 1;
  }
  arm->requestEnable(now);
  long enable_cycles = 0;
  while (!arm->allEnabled() && enable_cycles < boot_limit && g_stop == 0) {
    now = cycle_start();
    router.poll(now);
    const FaultReport& r = arm->update(now);
    all_flags |= r.flags;
    note(r);
    frames_sent += arm->transmit(now);
    ++enable_cycles;
    ++cycle_no;
  }
  if (!arm->allEnabled()) {
    std::printf("mrqp-stream: FAIL: drives not enabled after %ld cycles, flags %s%s\n", enable_cycles,
                faultFlagsStr(all_flags).c_str(), g_stop != 0 ? " (signalled)" : "");
    print_faults(arm->faults());
    print_events();
    safe_exit();
    return 1;
  }
  std::printf("mrqp-stream: booted in %ld cycles, enabled in %ld cycles; streaming %ld cycles at %.1f Hz\n",
              boot_cycles, enable_cycles, o.cycles, o.rate);
  std::fflush(stdout);
  for (std::size_t j = 0; j < n; ++j) {
    q0[j] = arm->drive(j).position;
    sent[j] = q0[j];
  }

  const std::uint32_t hard = fault::kFeedbackMissing | fault::kDeviceFault | fault::kBootFailed |
                             fault::kTimeout | fault::kHeartbeatLost | fault::kStateMismatch | fault::kBusOff;
  const TimeNs stream_start = now;
  const double w = 2.0 * M_PI * o.frequency;
  long streamed = 0;
  for (long k = 0; k < o.cycles && g_stop == 0; ++k) {
    now = cycle_start();
    router.poll(now);
    const FaultReport& r = arm->update(now);
    all_flags |= r.flags;
    note(r);
    ++cycle_no;
    ++streamed;
    std::uint32_t cycle_fail = 0;
    for (std::size_t j = 0; j < n; ++j) {
      const DeviceFaults& df = r.devices[j];
      const bool hb = (df.flags & fault::kHeartbeatLost) != 0u;
      if (hb) {
        ++hb_lost[j];
        if (hb_lost_at[j] < 0) {
          hb_lost_at[j] = now - stream_start;
          timespec wall;
          clock_gettime(CLOCK_REALTIME, &wall);
          hb_lost_wall[j] = static_cast<double>(wall.tv_sec) + static_cast<double>(wall.tv_nsec) * 1e-9;
        }
      }
      const bool excused = static_cast<int>(j) == hb_drive && hb_lost_at[j] >= 0;
      if (excused) {
        continue;  // the drive whose heartbeat loss is the point of the test
      }
      cycle_fail |= df.flags & hard;
      const ArmDriveState& s = arm->drive(j);
      if (k > 0 && s.valid) {
        const double e = std::fabs(s.position - sent[j]);
        max_err[j] = std::max(max_err[j], e);
        if (e > o.max_error) {
          cycle_fail |= fault::kOutOfRange;
        }
      }
    }
    if (cycle_fail != 0u) {
      ++fail_cycles;
      fail_flags |= cycle_fail;
    }
    const double t = static_cast<double>(k) / o.rate;
    for (std::size_t j = 0; j < n; ++j) {
      const double target = q0[j] + o.amplitude * std::sin(w * t) * (1.0 - 0.1 * static_cast<double>(j % 5));
      (void)arm->setPosition(j, target);
      sent[j] = target;
    }
    frames_sent += arm->transmit(now);
  }
  const bool signalled = g_stop != 0;
  const DeviceFaults* fin_devices = arm->faults().devices;
  std::vector<DeviceFaults> fin_copy(fin_devices, fin_devices + n);  // before the exit rewrites them
  const BusFaults fin_bus = arm->faults().buses[0];
  const SyncStats sync = arm->syncStats(0);
  const bool exited = safe_exit();
  // Summary.
  std::printf(
      "mrqp-stream: summary: cycles=%ld rate=%.1fHz frames_sent=%llu overruns=%llu worst_late_us=%.1f\n",
      streamed, o.rate, static_cast<unsigned long long>(frames_sent),
      static_cast<unsigned long long>(overruns), static_cast<double>(worst_late) / 1000.0);
  std::uint64_t emcy_total = 0;
  std::uint64_t corrupt_total = 0;
  for (std::size_t j = 0; j < n; ++j) {
    const DeviceFaults& df = fin_copy[j];
    emcy_total += df.emcy_count;
    corrupt_total += df.corrupt_frames;
    std::printf(
        "mrqp-stream: node %u: max_error=%.5f rad emcy_count=%u emcy_code=0x%04x corrupt_frames=%u "
        "heartbeat_lost_cycles=%llu heartbeat_lost_at_ms=%.1f tolerated_aborts=%u recoveries=%u nmt=%s\n",
        cfg.drives[j].node, max_err[j], df.emcy_count, df.emcy_code, df.corrupt_frames,
        static_cast<unsigned long long>(hb_lost[j]),
        hb_lost_at[j] < 0 ? -1.0 : static_cast<double>(hb_lost_at[j]) / 1e6, df.tolerated_aborts,
        df.recoveries, nmtStateStr(df.nmt_state));
  }
  std::printf(
      "mrqp-stream: sync: syncs=%llu intervals=%llu period_us=%.1f min_us=%.1f max_us=%.1f "
      "max_jitter_us=%.1f "
      "mean_abs_jitter_us=%.1f over_%.1fx=%llu (%s)\n",
      static_cast<unsigned long long>(sync.syncs), static_cast<unsigned long long>(sync.intervals),
      static_cast<double>(sync.period) / 1e3, static_cast<double>(sync.min_interval) / 1e3,
      static_cast<double>(sync.max_interval) / 1e3, static_cast<double>(sync.max_jitter) / 1e3,
      sync.mean_abs_jitter_ns / 1e3, sync.timeout_factor, static_cast<unsigned long long>(sync.over_timeout),
      bus.echoesOwn() ? "timed on the TX echo" : "timed at transmit");
  print_events();
  const BusFaults& bf = fin_bus;
  std::printf(
      "mrqp-stream: counters: emcy=%llu corrupt_frames=%llu unknown_frames=%llu rejected_frames=%llu "
      "bus_error_events=%llu tx_queue_full=%llu\n",
      static_cast<unsigned long long>(emcy_total), static_cast<unsigned long long>(corrupt_total),
      static_cast<unsigned long long>(bf.unknown_total), static_cast<unsigned long long>(bf.rejected_total),
      static_cast<unsigned long long>(bf.error_events_total),
      static_cast<unsigned long long>(bf.tx_queue_full_total));
  std::printf("mrqp-stream: flags seen: %s\n", faultFlagsStr(all_flags).c_str());
  bool ok = fail_cycles == 0 && exited && !signalled;
  if (signalled) {
    std::printf("mrqp-stream: FAIL: stopped by a signal after %ld of %ld cycles\n", streamed, o.cycles);
  }
  if (!ok) {
    std::printf("mrqp-stream: FAIL: %llu cycle(s) failed: %s\n", static_cast<unsigned long long>(fail_cycles),
                faultFlagsStr(fail_flags).c_str());
  }
  if (hb_drive >= 0) {
    if (hb_lost_at[static_cast<std::size_t>(hb_drive)] < 0) {
      std::printf("mrqp-stream: FAIL: heartbeat loss of node %d expected, not detected\n",
                  o.expect_heartbeat_loss);
      ok = false;
    } else {
      const auto hj = static_cast<std::size_t>(hb_drive);
      std::printf(
          "mrqp-stream: heartbeat loss of node %d detected at %.1f ms of streaming, wall %.6f, timeout %d "
          "ms\n",
          o.expect_heartbeat_loss, static_cast<double>(hb_lost_at[hj]) / 1e6, hb_lost_wall[hj],
          o.heartbeat_timeout_ms);
    }
  }
  std::printf("mrqp-stream: %s\n", ok ? "PASS" : "FAIL");
  return ok ? 0 : 1;
}

// Any exception becomes one error line and exit status 1 (docs/robustness.md).
int main(int argc, char** argv) {
  try {
    return unwrappedMain(argc, argv);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "%s: %s\n", "mrqp-stream", e.what());
  } catch (...) {
    std::fprintf(stderr, "%s: unknown error\n", "mrqp-stream");
  }
  return 1;
}
