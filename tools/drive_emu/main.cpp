// mrqp-drive-emu: emulated CiA 402 drives on a SocketCAN interface (README.md). The configuration
// and the command line are validated before the bus is opened; --check validates, prints what
// would be emulated and exits. Any failure is one error line and a non-zero exit.
#include <mrqp/drivers/socketcan_bus.hpp>

#include <poll.h>
#include <signal.h>
#include <time.h>

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <exception>
#include <string>

#include "drive_emu.hpp"

using namespace mrqp::drive_emu;
using mrqp::drivers::monotonicNow;

namespace {

volatile sig_atomic_t g_stop = 0;
void onSignal(int) { g_stop = 1; }

class BusSink final : public FrameSink {
 public:
  explicit BusSink(mrqp::drivers::SocketCanBus& bus) : bus_(bus) {}
  void emit(const mrqp_fw_frame& frame, TimeNs) noexcept override {
    if (bus_.send(frame) != mrqp::drivers::SendResult::Ok) {
      ++failed;
    }
  }
  unsigned long failed = 0;

 private:
  mrqp::drivers::SocketCanBus& bus_;
};

void usage() {
  std::fprintf(stderr,
               "usage: mrqp-drive-emu --config FILE.yaml [--check] [--interface IF] [--duration S]\n"
               "       [--stop-heartbeat N@T] [--emcy N@T[:code]] [--saturate N@T]\n"
               "       [--drop FRACTION] [--corrupt FRACTION] [--seed N] [--profile lenient|strict]\n"
               "  T in seconds from the start of the emulator. --check: validate, print what would be\n"
               "  emulated, exit 0.\n");
}

/// The whole of `s` as a finite number; false otherwise.
bool parseDouble(const std::string& s, double* out) {
  char* end = nullptr;
  const double v = std::strtod(s.c_str(), &end);
  if (s.empty() || *end != '\0' || !std::isfinite(v)) {
    return false;
  }
  *out = v;
  return true;
}

int run(int argc, char** argv);

}  // namespace

int main(int argc, char** argv) {
  try {
    return run(argc, argv);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "mrqp-drive-emu: %s\n", e.what());
  } catch (...) {
    std::fprintf(stderr, "mrqp-drive-emu: unexpected error\n");
  }
  return 2;
}

namespace {

int run(int argc, char** argv) {
  std::string config_path;
  std::string interface;
  double duration = -1.0;
  double drop = -1.0;
  double corrupt = -1.0;
  long seed = -1;
  bool check = false;
  std::string profile;
  std::vector<std::pair<std::string, std::string>> switches;
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    auto value = [&]() -> std::string {
      if (i + 1 >= argc) {
        std::fprintf(stderr, "mrqp-drive-emu: %s needs a value\n", a.c_str());
        std::exit(2);
      }
      return argv[++i];
    };
    if (a == "--config") {
      config_path = value();
    } else if (a == "--interface") {
      interface = value();
    } else if (a == "--duration" || a == "--drop" || a == "--corrupt" || a == "--seed") {
      const std::string v = value();
      double x = 0.0;
      if (!parseDouble(v, &x) || x < 0.0) {
        std::fprintf(stderr, "mrqp-drive-emu: %s: expected a number >= 0, got '%s'\n", a.c_str(), v.c_str());
        return 2;
      }
      if (a == "--seed") {
        if (x > 2147483647.0 || x != std::floor(x)) {
          std::fprintf(stderr, "mrqp-drive-emu: --seed: expected an integer 0..2147483647, got '%s'\n",
                       v.c_str());
          return 2;
        }
        seed = static_cast<long>(x);
      } else {
        (a == "--duration" ? duration : a == "--drop" ? drop : corrupt) = x;
      }
    } else if (a == "--check") {
      check = true;
    } else if (a == "--profile") {
      profile = value();
      if (profile != "lenient" && profile != "strict") {
        std::fprintf(stderr, "mrqp-drive-emu: --profile: expected lenient or strict, got '%s'\n",
                     profile.c_str());
        return 2;
      }
    } else if (a == "--stop-heartbeat" || a == "--emcy" || a == "--saturate") {
      switches.emplace_back(a.substr(2), value());
    } else if (a == "--help" || a == "-h") {
      usage();
      return 0;
    } else {
      std::fprintf(stderr, "mrqp-drive-emu: unknown option %s\n", a.c_str());
      usage();
      return 2;
    }
  }
  if (config_path.empty()) {
    usage();
    return 2;
  }
  EmuConfig cfg;
  std::string err;
  if (!loadConfig(config_path, &cfg, &err)) {
    std::fprintf(stderr, "mrqp-drive-emu: %s\n", err.c_str());
    return 2;
  }
  if (!interface.empty()) {
    cfg.interface = interface;
  }
  if (duration >= 0.0) {
    cfg.duration_s = duration;
  }
  if (drop >= 0.0) {
    cfg.drop_fraction = drop;
  }
  if (corrupt >= 0.0) {
    cfg.corrupt_fraction = corrupt;
  }
  if (seed >= 0) {
    cfg.seed = static_cast<std::uint32_t>(seed);
  }
  if (!profile.empty()) {
    cfg.profile = profile == "strict" ? mrqp::emulation::VendorProfile::strict()
                                      : mrqp::emulation::VendorProfile::lenient();
  }
  for (const auto& s : switches) {
    if (!applyFaultSwitch(s.first, s.second, &cfg, &err)) {
      std::fprintf(stderr, "mrqp-drive-emu: %s\n", err.c_str());
      return 2;
    }
  }
  if (!validateConfig(cfg, "command line", &err)) {
    std::fprintf(stderr, "mrqp-drive-emu: %s\n", err.c_str());
    return 2;
  }
  if (check) {
    std::printf("mrqp-drive-emu: %s: OK, %zu node(s)\n%s", config_path.c_str(), cfg.nodes.size(),
                describeConfig(cfg).c_str());
    return 0;
  }

  mrqp::drivers::SocketCanBus bus;
  mrqp::drivers::SocketCanConfig sc;
  sc.interface = cfg.interface;
  sc.error_frames = false;
  if (!bus.open(sc, &err)) {
    std::fprintf(stderr, "mrqp-drive-emu: %s: %s\n", cfg.interface.c_str(), err.c_str());
    return 1;
  }
  signal(SIGINT, onSignal);
  signal(SIGTERM, onSignal);
  BusSink sink(bus);
  DriveEmulator emu(cfg, sink);
  const TimeNs t0 = monotonicNow();
  const TimeNs end = cfg.duration_s > 0.0 ? t0 + static_cast<TimeNs>(cfg.duration_s * 1e9) : kNever;
  std::printf("mrqp-drive-emu: %zu node(s) on %s\n", cfg.nodes.size(), cfg.interface.c_str());
  std::fflush(stdout);
  while (g_stop == 0) {
    const TimeNs now = monotonicNow();
    if (now >= end) {
      break;
    }
    emu.advance(now - t0);
    mrqp::drivers::RxFrame rx;
    while (bus.receive(rx) == mrqp::drivers::ReceiveResult::Frame) {
      const TimeNs t = monotonicNow() - t0;
      emu.advance(t);
      emu.onFrame(rx.frame, t);
    }
    const TimeNs wait_ns = emu.nextEvent() - (monotonicNow() - t0);
    if (wait_ns > 0) {
      pollfd p{bus.nativeHandle(), POLLIN, 0};
      const int ms = static_cast<int>(std::min<TimeNs>(wait_ns / 1000000 + 1, 100));
      (void)::poll(&p, 1, ms);
    }
  }
  const EmuStats& st = emu.stats();
  std::printf(
      "mrqp-drive-emu: done: sent=%llu dropped=%llu corrupted=%llu syncs=%llu rpdos=%llu send_failed=%lu\n",
      static_cast<unsigned long long>(st.sent), static_cast<unsigned long long>(st.dropped),
      static_cast<unsigned long long>(st.corrupted), static_cast<unsigned long long>(st.syncs),
      static_cast<unsigned long long>(st.rpdos), sink.failed);
  for (std::size_t i = 0; i < emu.size(); ++i) {
    std::printf("  node %u: nmt=0x%02x cia402=%d (%s) position=%.4f rad comm_errors=%u%s\n",
                cfg.nodes[i].node, static_cast<unsigned>(emu.nmt(i)), static_cast<int>(emu.state(i)),
                mrqp_fw_cia402_state_str(emu.state(i)), emu.position(i), emu.commErrors(i),
                emu.state(i) == MRQP_FW_CIA402_OPERATION_ENABLED ? " LEFT ENABLED" : "");
  }
  return 0;
}

}  // namespace
