// mrqp-stream's command line (see stream_options.hpp).
#include "stream_options.hpp"

#include <algorithm>
#include <cerrno>
#include <cstdio>
#include <cstdlib>

#include "drive_emu.hpp"

namespace mrqp::stream {

using namespace mrqp::drivers;

namespace {

/// An unsigned number (decimal or 0x hex) within [0, max]; false if it is not one.
bool parseU32(const std::string& s, unsigned long max, unsigned long* out) {
  if (s.empty() || s[0] == '-') return false;
  char* end = nullptr;
  errno = 0;
  const unsigned long v = std::strtoul(s.c_str(), &end, 0);
  if (*end != '\0' || errno != 0 || v > max) return false;
  *out = v;
  return true;
}

void usage() {
  std::fprintf(stderr,
               "usage: mrqp-stream [--interface IF|sim] [--nodes 1-7|1,2,3] [--rate HZ] [--cycles N]\n"
               "       [--config EMU.yaml] [--amplitude RAD] [--frequency HZ] [--max-error RAD]\n"
               "       [--heartbeat-ms MS] [--heartbeat-timeout-ms MS] [--sdo-timeout-ms MS] "
               "[--feedback-missing-cycles N]\n"
               "       [--expect-heartbeat-loss NODE] [--quiet] [--realtime]\n"
               "       [--recover] [--tpdo-rtr-allowed] [--comm-cycle-us US]\n"
               "       [--exit-stop quick-stop|disable] [--exit-nmt pre-operational|stopped|unchanged]\n"
               "       [--device-type N] [--vendor-id N] [--product-code N]\n"
               "--config reads nodes and scales from a mrqp-drive-emu YAML file.\n");
}

bool parseNodes(const std::string& s, std::vector<std::uint8_t>* out) {
  std::size_t pos = 0;
  while (pos < s.size()) {
    std::size_t end = s.find(',', pos);
    if (end == std::string::npos) end = s.size();
    const std::string part = s.substr(pos, end - pos);
    const auto dash = part.find('-');
    const int a = std::atoi(part.substr(0, dash).c_str());
    const int b = dash == std::string::npos ? a : std::atoi(part.substr(dash + 1).c_str());
    if (a < 1 || b > 127 || b < a) return false;
    for (int n = a; n <= b; ++n) out->push_back(static_cast<std::uint8_t>(n));
    pos = end + 1;
  }
  return !out->empty();
}

}  // namespace

int parseOptions(int argc, char** argv, Options* po) {
  Options& o = *po;
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    if (a == "--quiet" || a == "--realtime" || a == "--recover" || a == "--tpdo-rtr-allowed") {
      (a == "--quiet"      ? o.quiet
       : a == "--realtime" ? o.realtime
       : a == "--recover"  ? o.recover
                           : o.tpdo_rtr_allowed) = true;
      continue;
    }
    if (a == "--help" || a == "-h") {
      usage();
      return 0;
    }
    static const char* const kValued[] = {"--interface",
                                          "--nodes",
                                          "--rate",
                                          "--cycles",
                                          "--config",
                                          "--amplitude",
                                          "--frequency",
                                          "--max-error",
                                          "--expect-heartbeat-loss",
                                          "--sdo-timeout-ms",
                                          "--heartbeat-timeout-ms",
                                          "--heartbeat-ms",
                                          "--feedback-missing-cycles",
                                          "--comm-cycle-us",
                                          "--device-type",
                                          "--vendor-id",
                                          "--product-code",
                                          "--exit-stop",
                                          "--exit-nmt"};
    if (std::none_of(std::begin(kValued), std::end(kValued), [&](const char* k) { return a == k; })) {
      std::fprintf(stderr, "mrqp-stream: unknown option %s\n", a.c_str());
      usage();
      return 2;
    }
    if (i + 1 >= argc) {
      std::fprintf(stderr, "mrqp-stream: %s needs a value\n", a.c_str());
      return 2;
    }
    const std::string v = argv[++i];
    if (a == "--interface") {
      o.interface = v;
    } else if (a == "--nodes") {
      if (!parseNodes(v, &o.nodes)) {
        std::fprintf(stderr, "mrqp-stream: --nodes: expected e.g. 1-7 or 1,2,3 (ids 1..127)\n");
        return 2;
      }
    } else if (a == "--rate" || a == "--amplitude" || a == "--frequency" || a == "--max-error") {
      (a == "--rate"        ? o.rate
       : a == "--amplitude" ? o.amplitude
       : a == "--frequency" ? o.frequency
                            : o.max_error) = std::atof(v.c_str());
    } else if (a == "--cycles") {
      o.cycles = std::atol(v.c_str());
    } else if (a == "--config") {
      o.yaml = v;
    } else if (a == "--expect-heartbeat-loss") {
      o.expect_heartbeat_loss = std::atoi(v.c_str());
    } else if (a == "--sdo-timeout-ms" || a == "--heartbeat-timeout-ms" || a == "--heartbeat-ms" ||
               a == "--feedback-missing-cycles") {
      (a == "--sdo-timeout-ms"         ? o.sdo_timeout_ms
       : a == "--heartbeat-timeout-ms" ? o.heartbeat_timeout_ms
       : a == "--heartbeat-ms"         ? o.heartbeat_ms
                                       : o.feedback_missing_cycles) = std::atoi(v.c_str());
    } else if (a == "--comm-cycle-us") {
      unsigned long u = 0;
      if (!parseU32(v, 0xFFFFFFFFul, &u)) {
        std::fprintf(stderr, "mrqp-stream: --comm-cycle-us: expected microseconds 0..4294967295\n");
        return 2;
      }
      o.comm_cycle_us = static_cast<long>(u);
    } else if (a == "--device-type" || a == "--vendor-id" || a == "--product-code") {
      unsigned long u = 0;
      if (!parseU32(v, 0xFFFFFFFFul, &u)) {
        std::fprintf(stderr, "mrqp-stream: %s: expected a 32-bit unsigned number (0x... for hex)\n",
                     a.c_str());
        return 2;
      }
      (a == "--device-type" ? o.device_type : a == "--vendor-id" ? o.vendor_id : o.product_code) = u;
    } else if (a == "--exit-stop") {
      if (v != "quick-stop" && v != "disable") {
        std::fprintf(stderr, "mrqp-stream: --exit-stop: expected quick-stop or disable\n");
        return 2;
      }
      o.exit_stop = v == "quick-stop" ? ExitStop::QuickStop : ExitStop::DisableVoltage;
    } else {  // --exit-nmt
      if (v != "pre-operational" && v != "stopped" && v != "unchanged") {
        std::fprintf(stderr, "mrqp-stream: --exit-nmt: expected pre-operational, stopped or unchanged\n");
        return 2;
      }
      o.exit_nmt = v == "pre-operational" ? ExitNmt::PreOperational
                   : v == "stopped"       ? ExitNmt::Stopped
                                          : ExitNmt::Unchanged;
    }
  }
  if (!(o.rate > 0.0 && o.rate <= 10000.0) || o.cycles <= 0 || o.heartbeat_ms <= 0 ||
      o.heartbeat_timeout_ms <= 0 || o.sdo_timeout_ms <= 0 || o.feedback_missing_cycles <= 0) {
    std::fprintf(stderr,
                 "mrqp-stream: --rate must be 0..10000 Hz; --cycles, heartbeat times, "
                 "--feedback-missing-cycles > 0\n");
    return 2;
  }
  return -1;
}

bool armConfig(Options& o, ArmConfig* cfg, std::string* err) {
  auto drive = [&](std::uint8_t node) {
    ArmDriveConfig d;
    d.node = node;
    d.device_type = static_cast<std::uint32_t>(o.device_type);
    d.vendor_id = static_cast<std::uint32_t>(o.vendor_id);
    d.product_code = static_cast<std::uint32_t>(o.product_code);
    return d;
  };
  if (!o.yaml.empty()) {
    mrqp::drive_emu::EmuConfig emu;
    if (!mrqp::drive_emu::loadConfig(o.yaml, &emu, err)) return false;
    for (const auto& n : emu.nodes) {
      if (!o.nodes.empty() && std::find(o.nodes.begin(), o.nodes.end(), n.node) == o.nodes.end()) continue;
      ArmDriveConfig d = drive(n.node);
      d.scale = n.scale;
      cfg->drives.push_back(d);
    }
  } else {
    if (o.nodes.empty()) o.nodes = {1};
    for (std::uint8_t n : o.nodes) cfg->drives.push_back(drive(n));
  }
  cfg->cycle_period = periodOfHz(o.rate);
  cfg->producer_heartbeat_ms = static_cast<std::uint16_t>(o.heartbeat_ms);
  cfg->heartbeat_timeout = milliseconds(o.heartbeat_timeout_ms);
  cfg->sdo_timeout = milliseconds(o.sdo_timeout_ms);
  cfg->boot_timeout = std::max(cfg->boot_timeout, 50 * cfg->sdo_timeout);
  cfg->enable_timeout = std::max(cfg->enable_timeout, 10 * cfg->sdo_timeout);
  cfg->feedback_missing_cycles = static_cast<std::uint32_t>(o.feedback_missing_cycles);
  cfg->recovery = o.recover ? RecoveryPolicy::Automatic : RecoveryPolicy::Manual;
  cfg->tpdo_rtr_allowed = o.tpdo_rtr_allowed;
  cfg->comm_cycle_period_us = static_cast<std::uint32_t>(o.comm_cycle_us);
  cfg->exit_stop = o.exit_stop;
  cfg->exit_nmt = o.exit_nmt;
  cfg->exit_timeout = std::max(cfg->exit_timeout, 20 * cfg->cycle_period);
  return true;
}

}  // namespace mrqp::stream
