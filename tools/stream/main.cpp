// mrqp-stream: streams a sine per joint through the ArmDriver on a SocketCAN interface at a fixed
// rate for N cycles (or on the simulated bus with emulated drives, `--interface sim`), checks the
// feedback, prints a summary and exits non-zero on failure (README.md). A short program over the loop layer (control/loop): absolute deadlines
// (DeadlineClock), the devices' boot and safe exit (DeviceSet, bootDevices / exitDevices, as the
// controller boots and stops its devices), the real-time set-up (--realtime, setupRealtime).
// Whatever ends it (the last cycle, SIGINT/SIGTERM, a failed boot or enable), the drives are left
// stopped: ArmDriver::requestSafeExit (quick stop or disable voltage, then NMT pre-operational or
// stop).
#include <mrqp/drivers/arm_driver.hpp>
#include <mrqp/drivers/bus_router.hpp>
#include <mrqp/drivers/canopen/canopen_text.hpp>

#include <signal.h>

#include <cmath>
#include <cstdio>
#include <exception>
#include <string>
#include <vector>

#include "loop/device_set.hpp"
#include "loop/realtime.hpp"
#include "stream_bus.hpp"
#include "stream_monitor.hpp"
#include "stream_options.hpp"

using namespace mrqp::drivers;
using mrqp::stream::Options;
using mrqp::stream::StreamMonitor;

namespace {

volatile sig_atomic_t g_stop = 0;
void onSignal(int) { g_stop = 1; }

const char* exitText(const ArmConfig& cfg) {
  return cfg.exit_nmt == ExitNmt::PreOperational ? "NMT pre-operational"
         : cfg.exit_nmt == ExitNmt::Stopped      ? "NMT stop"
                                                 : "NMT state unchanged";
}

}  // namespace

static int unwrappedMain(int argc, char** argv) {
  Options o;
  if (const int status = mrqp::stream::parseOptions(argc, argv, &o); status >= 0) return status;
  ArmConfig cfg;
  std::string err;
  if (!mrqp::stream::armConfig(o, &cfg, &err)) {
    std::fprintf(stderr, "mrqp-stream: %s\n", err.c_str());
    return 2;
  }
  mrqp::stream::StreamBus bus(cfg.cycle_period);  // SocketCAN, or the simulated bus with emulated drives
  if (!bus.open(o, &err)) {
    std::fprintf(stderr, "mrqp-stream: %s: %s\n", o.interface.c_str(), err.c_str());
    return o.interface == "sim" ? 2 : 1;
  }
  BusRouter router(bus.bus());
  auto arm = ArmDriver::create({&router}, cfg, &err);
  if (!arm) {
    std::fprintf(stderr, "mrqp-stream: %s\n", err.c_str());
    return 2;
  }
  const std::size_t n = arm->driveCount();
  int hb_drive = -1;
  for (std::size_t j = 0; j < n; ++j) {
    if (cfg.drives[j].node == o.expect_heartbeat_loss) hb_drive = static_cast<int>(j);
  }
  if (o.expect_heartbeat_loss != 0 && hb_drive < 0) {
    std::fprintf(stderr, "mrqp-stream: --expect-heartbeat-loss %d: not a streamed node\n",
                 o.expect_heartbeat_loss);
    return 2;
  }
  if (o.realtime) {
    for (const std::string& m : mrqp::loop::setupRealtime().messages)
      std::printf("mrqp-stream: realtime: %s\n", m.c_str());
  }
  signal(SIGINT, onSignal);
  signal(SIGTERM, onSignal);

  // Set-up done: everything below runs at the cycle rate (no allocation in the streaming cycle).
  StreamMonitor mon(n, o.max_error, hb_drive);
  mrqp::loop::DeviceSet devices({&router}, {arm.get()});
  const TimeNs period = cfg.cycle_period;
  TimeNs now = bus.start();
  auto next = [&]() {  // after each boot / exit cycle: its faults, then the next deadline
    mon.note(arm->faults());
    mon.nextCycle();
    return bus.next();
  };
  // Boot and enable at the streaming rate (up to 20 s); `now` ends on the next cycle's deadline.
  const auto boot = mrqp::loop::bootDevices(devices, now, period, 20.0, next, [] { return g_stop != 0; });
  const long boot_cycles = devices.enableRequestedAfter() < 0 ? boot.cycles : devices.enableRequestedAfter();
  const long enable_cycles = boot.cycles - boot_cycles;

  auto safe_exit = [&]() -> bool {
    const double timeout_s = static_cast<double>(cfg.exit_timeout + 20 * period) * 1e-9;
    const auto ex = mrqp::loop::exitDevices(devices, now, period, timeout_s, [&]() { return bus.next(); });
    std::printf("mrqp-stream: safe exit: %s after %ld cycles (%s, then %s)\n",
                ex.done ? "drives stopped" : "NOT completed", ex.cycles,
                cfg.exit_stop == ExitStop::QuickStop ? "quick stop" : "disable voltage", exitText(cfg));
    return ex.done;
  };
  auto fail_boot = [&](const std::string& what) {
    std::printf("mrqp-stream: FAIL: %s\n", what.c_str());
    const std::string text = describeFaults(arm->faults(), "drive");
    if (!text.empty()) std::printf("mrqp-stream: faults:\n%s", text.c_str());
    mon.printEvents();
    safe_exit();
    return 1;
  };
  if (arm->phase() != ArmPhase::Running) {
    return fail_boot("boot ended in phase " + std::string(armPhaseStr(arm->phase())) + " after " +
                     std::to_string(boot_cycles) + " cycles, flags " + faultFlagsStr(mon.allFlags()));
  }
  if (!boot.done) {
    return fail_boot("drives not enabled after " + std::to_string(enable_cycles) + " cycles, flags " +
                     faultFlagsStr(mon.allFlags()) + (g_stop != 0 ? " (signalled)" : ""));
  }
  std::printf("mrqp-stream: booted in %ld cycles, enabled in %ld cycles; streaming %ld cycles at %.1f Hz\n",
              boot_cycles, enable_cycles, o.cycles, o.rate);
  std::fflush(stdout);
  std::vector<double> q0(n, 0.0);
  for (std::size_t j = 0; j < n; ++j) {
    q0[j] = arm->drive(j).position;
    mon.sent(j, q0[j]);
  }

  const TimeNs stream_start = now;
  const double w = 2.0 * M_PI * o.frequency;
  std::uint64_t frames_sent = 0;
  long streamed = 0;
  for (long k = 0; k < o.cycles && g_stop == 0; ++k) {
    if (k > 0) now = bus.next();  // the first cycle is the deadline the boot ended on
    mon.phases().begin();
    router.poll(now);
    const FaultReport& r = arm->update(now);
    mon.note(r);
    mon.nextCycle();
    ++streamed;
    mon.check(k, now - stream_start, r, *arm);
    mon.phases().lap(StreamMonitor::kRead);
    const double t = static_cast<double>(k) / o.rate;
    for (std::size_t j = 0; j < n; ++j) {
      const double target = q0[j] + o.amplitude * std::sin(w * t) * (1.0 - 0.1 * static_cast<double>(j % 5));
      (void)arm->setPosition(j, target);
      mon.sent(j, target);
    }
    frames_sent += arm->transmit(now);
    mon.phases().lap(StreamMonitor::kWrite);
  }
  const bool signalled = g_stop != 0;
  const std::vector<DeviceFaults> fin(arm->faults().devices, arm->faults().devices + n);  // before the exit
  const BusFaults bf = arm->faults().buses[0];
  const SyncStats sync = arm->syncStats(0);
  now = bus.next();
  const bool exited = safe_exit();

  std::printf(
      "mrqp-stream: summary: cycles=%ld rate=%.1fHz frames_sent=%llu overruns=%llu worst_late_us=%.1f\n",
      streamed, o.rate, static_cast<unsigned long long>(frames_sent),
      static_cast<unsigned long long>(bus.overruns()), static_cast<double>(bus.worstLateness()) / 1000.0);
  mon.printDrives(cfg, fin);
  std::uint64_t emcy_total = 0, corrupt_total = 0;
  for (const DeviceFaults& df : fin) {
    emcy_total += df.emcy_count;
    corrupt_total += df.corrupt_frames;
  }
  std::printf(
      "mrqp-stream: sync: syncs=%llu intervals=%llu period_us=%.1f min_us=%.1f max_us=%.1f "
      "max_jitter_us=%.1f "
      "mean_abs_jitter_us=%.1f over_%.1fx=%llu (%s)\n",
      static_cast<unsigned long long>(sync.syncs), static_cast<unsigned long long>(sync.intervals),
      static_cast<double>(sync.period) / 1e3, static_cast<double>(sync.min_interval) / 1e3,
      static_cast<double>(sync.max_interval) / 1e3, static_cast<double>(sync.max_jitter) / 1e3,
      sync.mean_abs_jitter_ns / 1e3, sync.timeout_factor, static_cast<unsigned long long>(sync.over_timeout),
      bus.bus().echoesOwn() ? "timed on the TX echo" : "timed at transmit");
  mon.printEvents();
  mon.printPhases();
  std::printf(
      "mrqp-stream: counters: emcy=%llu corrupt_frames=%llu unknown_frames=%llu rejected_frames=%llu "
      "bus_error_events=%llu tx_queue_full=%llu\n",
      static_cast<unsigned long long>(emcy_total), static_cast<unsigned long long>(corrupt_total),
      static_cast<unsigned long long>(bf.unknown_total), static_cast<unsigned long long>(bf.rejected_total),
      static_cast<unsigned long long>(bf.error_events_total),
      static_cast<unsigned long long>(bf.tx_queue_full_total));
  std::printf("mrqp-stream: flags seen: %s\n", faultFlagsStr(mon.allFlags()).c_str());
  bool ok = mon.failedCycles() == 0 && exited && !signalled;
  if (signalled)
    std::printf("mrqp-stream: FAIL: stopped by a signal after %ld of %ld cycles\n", streamed, o.cycles);
  if (!ok) {
    std::printf("mrqp-stream: FAIL: %llu cycle(s) failed: %s\n",
                static_cast<unsigned long long>(mon.failedCycles()), faultFlagsStr(mon.failFlags()).c_str());
  }
  if (hb_drive >= 0) {
    const auto hj = static_cast<std::size_t>(hb_drive);
    if (!mon.heartbeatLost(hj)) {
      std::printf("mrqp-stream: FAIL: heartbeat loss of node %d expected, not detected\n",
                  o.expect_heartbeat_loss);
      ok = false;
    } else {
      mon.printHeartbeatLoss(hj, o.expect_heartbeat_loss, o.heartbeat_timeout_ms);
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
