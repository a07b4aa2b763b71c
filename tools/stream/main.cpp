// mrqp-stream: streams a sine per joint through the ArmDriver on a SocketCAN interface at a fixed
// rate (clock_nanosleep, absolute deadlines) for N cycles, checks the feedback, prints a summary
// and exits non-zero on failure (README.md).
#include <mrqp/drivers/arm_driver.hpp>
#include <mrqp/drivers/bus_router.hpp>
#include <mrqp/drivers/socketcan_bus.hpp>

#include <time.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
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
};

void usage() {
  std::fprintf(stderr,
               "usage: mrqp-stream [--interface IF] [--nodes 1-7|1,2,3] [--rate HZ] [--cycles N]\n"
               "       [--config EMU.yaml] [--amplitude RAD] [--frequency HZ] [--max-error RAD]\n"
               "       [--heartbeat-ms MS] [--heartbeat-timeout-ms MS] [--sdo-timeout-ms MS] "
               "[--feedback-missing-cycles N]\n"
               "       [--expect-heartbeat-loss NODE] [--quiet]\n"
               "--config reads nodes and scales from a mrqp-drive-emu YAML file.\n");
}

bool parse_nodes(const std::string& s, std::vector<std::uint8_t>* out) {
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

void add_ns(timespec* t, TimeNs ns) {
  t->tv_nsec += ns;
  while (t->tv_nsec >= 1000000000L) {
    t->tv_nsec -= 1000000000L;
    ++t->tv_sec;
  }
}

TimeNs to_ns(const timespec& t) { return static_cast<TimeNs>(t.tv_sec) * 1000000000 + t.tv_nsec; }

}  // namespace

int main(int argc, char** argv) {
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
      if (!parse_nodes(value(), &o.nodes)) {
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
    if (!mrqp::drive_emu::load_config(o.yaml, &emu, &err)) {
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
      cfg.drives.push_back(d);
    }
  } else {
    if (o.nodes.empty()) {
      o.nodes = {1};
    }
    for (std::uint8_t n : o.nodes) {
      ArmDriveConfig d;
      d.node = n;
      cfg.drives.push_back(d);
    }
  }
  cfg.cycle_period = period_of_hz(o.rate);
  cfg.producer_heartbeat_ms = static_cast<std::uint16_t>(o.heartbeat_ms);
  cfg.heartbeat_timeout = milliseconds(o.heartbeat_timeout_ms);
  cfg.sdo_timeout = milliseconds(o.sdo_timeout_ms);
  cfg.boot_timeout = std::max(cfg.boot_timeout, 50 * cfg.sdo_timeout);
  cfg.enable_timeout = std::max(cfg.enable_timeout, 10 * cfg.sdo_timeout);
  cfg.feedback_missing_cycles = static_cast<std::uint32_t>(o.feedback_missing_cycles);

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
  const std::size_t n = arm->drive_count();
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

  timespec next;
  clock_gettime(CLOCK_MONOTONIC, &next);
  const TimeNs period = cfg.cycle_period;
  auto cycle_start = [&]() {
    add_ns(&next, period);
    clock_nanosleep(CLOCK_MONOTONIC, TIMER_ABSTIME, &next, nullptr);
    timespec now;
    clock_gettime(CLOCK_MONOTONIC, &now);
    const TimeNs late = to_ns(now) - to_ns(next);
    worst_late = std::max(worst_late, late);
    if (late > period) {
      ++overruns;
    }
    return to_ns(next);
  };

  // Boot and enable (at the same rate).
  TimeNs now = to_ns(next);
  arm->start(now);
  long boot_cycles = 0;
  const long boot_limit = static_cast<long>(o.rate * 10.0);
  while (arm->phase() != ArmPhase::Running && arm->phase() != ArmPhase::Failed && boot_cycles < boot_limit) {
    now = cycle_start();
    router.poll(now);
    all_flags |= arm->update(now).flags;
    frames_sent += arm->transmit(now);
    ++boot_cycles;
  }
  if (arm->phase() != ArmPhase::Running) {
    std::printf("mrqp-stream: FAIL: boot ended in phase %s after %ld cycles, flags %s\n",
                arm_phase_str(arm->phase()), boot_cycles, fault_flags_str(all_flags).c_str());
    return 1;
  }
  arm->request_enable(now);
  long enable_cycles = 0;
  while (!arm->all_enabled() && enable_cycles < boot_limit) {
    now = cycle_start();
    router.poll(now);
    all_flags |= arm->update(now).flags;
    frames_sent += arm->transmit(now);
    ++enable_cycles;
  }
  if (!arm->all_enabled()) {
    std::printf("mrqp-stream: FAIL: drives not enabled after %ld cycles, flags %s\n", enable_cycles,
                fault_flags_str(all_flags).c_str());
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
  for (long k = 0; k < o.cycles; ++k) {
    now = cycle_start();
    router.poll(now);
    const FaultReport& r = arm->update(now);
    all_flags |= r.flags;
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
      (void)arm->set_position(j, target);
      sent[j] = target;
    }
    frames_sent += arm->transmit(now);
  }
  // Summary.
  const FaultReport& fin = arm->faults();
  std::printf(
      "mrqp-stream: summary: cycles=%ld rate=%.1fHz frames_sent=%llu overruns=%llu worst_late_us=%.1f\n",
      o.cycles, o.rate, static_cast<unsigned long long>(frames_sent),
      static_cast<unsigned long long>(overruns), static_cast<double>(worst_late) / 1000.0);
  std::uint64_t emcy_total = 0;
  std::uint64_t corrupt_total = 0;
  for (std::size_t j = 0; j < n; ++j) {
    const DeviceFaults& df = fin.devices[j];
    emcy_total += df.emcy_count;
    corrupt_total += df.corrupt_frames;
    std::printf(
        "mrqp-stream: node %u: max_error=%.5f rad emcy_count=%u emcy_code=0x%04x corrupt_frames=%u "
        "heartbeat_lost_cycles=%llu heartbeat_lost_at_ms=%.1f\n",
        cfg.drives[j].node, max_err[j], df.emcy_count, df.emcy_code, df.corrupt_frames,
        static_cast<unsigned long long>(hb_lost[j]),
        hb_lost_at[j] < 0 ? -1.0 : static_cast<double>(hb_lost_at[j]) / 1e6);
  }
  const BusFaults& bf = fin.buses[0];
  std::printf(
      "mrqp-stream: counters: emcy=%llu corrupt_frames=%llu unknown_frames=%llu rejected_frames=%llu "
      "bus_error_events=%llu tx_queue_full=%llu\n",
      static_cast<unsigned long long>(emcy_total), static_cast<unsigned long long>(corrupt_total),
      static_cast<unsigned long long>(bf.unknown_total), static_cast<unsigned long long>(bf.rejected_total),
      static_cast<unsigned long long>(bf.error_events_total),
      static_cast<unsigned long long>(bf.tx_queue_full_total));
  std::printf("mrqp-stream: flags seen: %s\n", fault_flags_str(all_flags).c_str());
  bool ok = fail_cycles == 0;
  if (!ok) {
    std::printf("mrqp-stream: FAIL: %llu cycle(s) failed: %s\n", static_cast<unsigned long long>(fail_cycles),
                fault_flags_str(fail_flags).c_str());
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
