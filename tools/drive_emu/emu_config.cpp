// YAML configuration of mrqp-drive-emu (see README.md for the format), read with the checker of
// every YAML file of mrqp (control/scene/yaml_reader.hpp): errors are "FILE:LINE: FIELD: message".
// Every value is checked for its type, finiteness and range (drive_emu.hpp, limits::) where it is
// read, so nothing read can overflow a conversion (seconds to nanoseconds, N m to u32 mN m).
#include <algorithm>
#include <climits>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <exception>
#include <map>
#include <optional>
#include <set>
#include <sstream>

#include "drive_emu.hpp"
#include "scene/yaml_reader.hpp"

namespace mrqp::drive_emu {

namespace {

using scene::Bound;
using scene::Map;
using scene::Reader;

TimeNs secondsToNs(double s) { return static_cast<TimeNs>(std::llround(s * 1e9)); }

/// A limit as written in the docs (up to 10 significant digits, e.g. 4294967.295).
std::string limitStr(double v) {
  std::ostringstream o;
  o.precision(10);
  o << v;
  return o.str();
}

/// A finite number within [lo, hi] (`lo_open`: lo itself excluded); `fallback` when absent.
double ranged(const Map& m, const char* key, double lo, double hi, double fallback, bool lo_open = false) {
  const YAML::Node* n = m.find(key);
  if (n == nullptr) {
    return fallback;
  }
  const double v = m.reader().number(*n, m.at(key), Bound::Any);
  if (v > hi || v < lo || (lo_open && v == lo)) {
    m.reader().fail(*n, m.at(key),
                    std::string("expected a number in ") + (lo_open ? "(" : "[") + limitStr(lo) + ", " +
                        limitStr(hi) + "], got " + scene::describe(*n));
  }
  return v;
}

/// An unsigned 32-bit integer (decimal or 0x hex) within [lo, hi]; `fallback` when absent.
std::uint32_t u32(const Map& m, const char* key, std::uint32_t lo, std::uint32_t hi, std::uint32_t fallback) {
  const YAML::Node* n = m.find(key);
  if (n == nullptr) {
    return fallback;
  }
  const std::optional<long long> v = scene::toInteger(*n);
  if (!v || *v < static_cast<long long>(lo) || *v > static_cast<long long>(hi)) {
    m.reader().fail(*n, m.at(key),
                    "expected an integer in [" + std::to_string(lo) + ", " + std::to_string(hi) + "], got " +
                        scene::describe(*n));
  }
  return static_cast<std::uint32_t>(*v);
}

/// A time in seconds from the emulator's start, [0, kTimeSMax].
TimeNs atTime(const Map& m, const char* key, TimeNs fallback) {
  return m.has(key) ? secondsToNs(ranged(m, key, 0.0, limits::kTimeSMax, 0.0)) : fallback;
}

void readFaults(const Reader& r, const YAML::Node& f, const std::string& path, NodeFaults* out) {
  const Map m(r, f, path, {"stop_heartbeat_at", "emcy_at", "emcy_code", "saturate_at"});
  out->heartbeat_stop_at = atTime(m, "stop_heartbeat_at", out->heartbeat_stop_at);
  out->emcy_at = atTime(m, "emcy_at", out->emcy_at);
  out->emcy_code = static_cast<std::uint16_t>(m.integer("emcy_code", 1, 0xFFFF, out->emcy_code));
  out->saturate_at = atTime(m, "saturate_at", out->saturate_at);
}

void readJoint(const Map& m, JointModel* j) {
  j->inertia = ranged(m, "inertia", 0.0, limits::kPhysicalMax, j->inertia, true);
  j->damping = ranged(m, "damping", 0.0, limits::kPhysicalMax, j->damping);
  j->torque_limit = ranged(m, "torque_limit", 0.0, limits::kPhysicalMax, j->torque_limit, true);
  j->kp = ranged(m, "kp", 0.0, limits::kGainMax, j->kp);
  j->kd = ranged(m, "kd", 0.0, limits::kGainMax, j->kd);
}

/// Rated torque in N m -> 0x6076 units (mN m, u32): (0.001, 4294967.295] N m.
std::uint32_t ratedTorque(const Map& m, double fallback_nm) {
  const double nm = ranged(m, "rated_torque", limits::kRatedTorqueMin, limits::kRatedTorqueMax, fallback_nm);
  return static_cast<std::uint32_t>(std::llround(nm * 1000.0));
}

using mrqp::emulation::VendorProfile;

/// `profile`: a name (lenient, strict) or a map of switches on top of `base` (lenient by default).
VendorProfile readProfile(const Reader& r, const YAML::Node& n, const std::string& path) {
  if (n.IsScalar()) {
    const std::string name = r.name(n, path);
    if (name == "lenient") {
      return VendorProfile::lenient();
    }
    if (name == "strict") {
      return VendorProfile::strict();
    }
    r.fail(n, path, "expected lenient, strict or a map of switches, got " + scene::describe(n));
  }
  const Map m(r, n, path,
              {"base",
               "tpdo_count",
               "abort_absent",
               "abort_read_only",
               "range_checks",
               "min_cycle_us",
               "min_heartbeat_ms",
               "pdo_rules",
               "rtr_check",
               "sync_timeout_factor",
               "comm_error_behaviour",
               "comm_error_fault",
               "statusword_bits",
               "heartbeat_consumer",
               "rpdo_timeout_ms",
               "abort_connection_option",
               "device_type",
               "vendor_id",
               "product_code",
               "revision",
               "serial"});
  if (const YAML::Node* b = m.find("base"); b != nullptr && !b->IsScalar()) {
    r.fail(*b, m.at("base"), "expected lenient or strict, got " + scene::describe(*b));
  }
  VendorProfile p =
      m.has("base") ? readProfile(r, m.require("base"), m.at("base")) : VendorProfile::lenient();
  p.tpdo_count = static_cast<std::uint8_t>(m.integer("tpdo_count", 1, 4, p.tpdo_count));
  p.abort_absent = m.boolean("abort_absent", p.abort_absent);
  p.abort_read_only = m.boolean("abort_read_only", p.abort_read_only);
  p.range_checks = m.boolean("range_checks", p.range_checks);
  p.min_cycle_us = u32(m, "min_cycle_us", 0, 1000000, p.min_cycle_us);
  p.min_heartbeat_ms = static_cast<std::uint16_t>(u32(m, "min_heartbeat_ms", 0, 0xFFFF, p.min_heartbeat_ms));
  p.pdo_rules = m.boolean("pdo_rules", p.pdo_rules);
  p.rtr_check = m.boolean("rtr_check", p.rtr_check);
  if (m.has("sync_timeout_factor")) {
    p.sync_timeout_factor = ranged(m, "sync_timeout_factor", 0.0, 100.0, p.sync_timeout_factor);
    if (p.sync_timeout_factor > 0.0 && p.sync_timeout_factor < 1.0) {
      r.fail(m.require("sync_timeout_factor"), m.at("sync_timeout_factor"),
             "expected 0 (no SYNC timeout) or a factor in [1, 100], got " +
                 scene::describe(m.require("sync_timeout_factor")));
    }
  }
  p.comm_error_behaviour =
      static_cast<std::uint8_t>(m.integer("comm_error_behaviour", 0, 2, p.comm_error_behaviour));
  p.comm_error_fault = m.boolean("comm_error_fault", p.comm_error_fault);
  p.statusword_bits = m.boolean("statusword_bits", p.statusword_bits);
  p.heartbeat_consumer = m.boolean("heartbeat_consumer", p.heartbeat_consumer);
  p.rpdo_timeout_ms = static_cast<std::uint16_t>(u32(m, "rpdo_timeout_ms", 0, 0xFFFF, p.rpdo_timeout_ms));
  p.abort_connection_option =
      static_cast<std::uint8_t>(m.integer("abort_connection_option", 0, 3, p.abort_connection_option));
  p.device_type = u32(m, "device_type", 0, 0xFFFFFFFFu, p.device_type);
  p.vendor_id = u32(m, "vendor_id", 0, 0xFFFFFFFFu, p.vendor_id);
  p.product_code = u32(m, "product_code", 0, 0xFFFFFFFFu, p.product_code);
  p.revision = u32(m, "revision", 0, 0xFFFFFFFFu, p.revision);
  p.serial = u32(m, "serial", 0, 0xFFFFFFFFu, p.serial);
  return p;
}

/// A fraction of the frames sent, in [0, 1] (0 when absent).
double fraction(const Map& m, const char* key) {
  const double v = m.number(key, Bound::NonNegative, 0.0);
  if (v > 1.0) {
    m.reader().fail(*m.find(key), m.at(key),
                    "expected a fraction in [0, 1], got " + scene::describe(*m.find(key)));
  }
  return v;
}

EmuConfig readConfig(const Reader& r, const YAML::Node& root) {
  EmuConfig c;
  const Map top(r, root, "",
                {"interface", "step_ms", "boot_delay_ms", "duration", "increments_per_rev", "rated_torque",
                 "joint", "nodes", "faults", "profile"});
  if (top.has("interface")) {
    c.interface = top.name("interface");
  }
  c.step = static_cast<TimeNs>(
      std::llround(ranged(top, "step_ms", limits::kStepMsMin, limits::kStepMsMax, 0.5) * 1e6));
  c.boot_delay = static_cast<TimeNs>(
      std::llround(ranged(top, "boot_delay_ms", 0.0, limits::kBootDelayMsMax, 2.0) * 1e6));
  c.duration_s = ranged(top, "duration", 0.0, limits::kTimeSMax, 0.0);
  const int ipr = top.integer("increments_per_rev", 1, INT_MAX, 524288);
  const std::uint32_t rated = ratedTorque(top, 1.0);
  if (const YAML::Node* p = top.find("profile")) {
    c.profile = readProfile(r, *p, top.at("profile"));
  }

  JointModel def;
  if (const YAML::Node* j = top.find("joint")) {
    readJoint(Map(r, *j, top.at("joint"), {"inertia", "damping", "torque_limit", "kp", "kd"}), &def);
  }

  const std::string nodes_path = top.at("nodes");
  const std::vector<YAML::Node> nodes = r.list(top.require("nodes"), nodes_path);
  if (nodes.empty()) {
    r.fail(top.require("nodes"), nodes_path, "at least one node is needed");
  }
  std::map<int, int> first_line;  // node id -> line
  for (std::size_t i = 0; i < nodes.size(); ++i) {
    const YAML::Node& n = nodes[i];
    const std::string path = scene::item(nodes_path, i);
    EmuNode e;
    e.joint = def;
    e.scale.increments_per_rev = static_cast<std::uint32_t>(ipr);
    e.scale.rated_torque_mNm = rated;
    YAML::Node id_node = n;
    std::string id_path = path;
    if (n.IsMap()) {
      const Map m(r, n, path,
                  {"node", "increments_per_rev", "rated_torque", "inertia", "damping", "torque_limit", "kp",
                   "kd", "initial_position", "faults"});
      id_node = m.require("node");
      id_path = m.at("node");
      e.scale.increments_per_rev =
          static_cast<std::uint32_t>(m.integer("increments_per_rev", 1, INT_MAX, ipr));
      e.scale.rated_torque_mNm = ratedTorque(m, rated / 1000.0);
      readJoint(m, &e.joint);
      e.joint.initial_position =
          ranged(m, "initial_position", -limits::kPositionMax, limits::kPositionMax, 0.0);
      if (const YAML::Node* f = m.find("faults")) {
        readFaults(r, *f, m.at("faults"), &e.faults);
      }
    } else if (!n.IsScalar()) {
      r.fail(n, path, "expected a node id or a map, got " + scene::describe(n));
    }
    const int id = r.integer(id_node, id_path, 1, 127);
    const auto [it, inserted] = first_line.emplace(id, scene::lineOf(id_node));
    if (!inserted) {
      r.fail(id_node, id_path,
             "node id " + std::to_string(id) + " appears twice (first at line " + std::to_string(it->second) +
                 ")");
    }
    e.node = static_cast<std::uint8_t>(id);
    c.nodes.push_back(e);
  }

  if (const YAML::Node* f = top.find("faults")) {
    const Map m(r, *f, top.at("faults"), {"drop_fraction", "corrupt_fraction", "seed"});
    c.drop_fraction = fraction(m, "drop_fraction");
    c.corrupt_fraction = fraction(m, "corrupt_fraction");
    c.seed = static_cast<std::uint32_t>(m.integer("seed", 0, INT_MAX, 1));
  }
  return c;
}

}  // namespace

bool validateConfig(const EmuConfig& c, const std::string& origin, std::string* error) {
  auto fail = [&](const std::string& field, const std::string& what) {
    if (error != nullptr) {
      *error = origin + ": " + field + ": " + what;
    }
    return false;
  };
  if (c.nodes.empty()) {
    return fail("nodes", "at least one node is needed");
  }
  std::set<unsigned> seen;
  for (std::size_t i = 0; i < c.nodes.size(); ++i) {
    const EmuNode& n = c.nodes[i];
    const std::string w = "nodes[" + std::to_string(i) + "].";
    if (n.node < 1 || n.node > 127) {
      return fail(w + "node", "must be 1..127");
    }
    if (!seen.insert(n.node).second) {
      return fail(w + "node", "node id " + std::to_string(n.node) + " appears twice");
    }
    if (n.scale.increments_per_rev == 0u) {
      return fail(w + "increments_per_rev", "must be > 0");
    }
    if (n.scale.rated_torque_mNm == 0u) {
      return fail(w + "rated_torque", "must be > 0");
    }
    if (!(n.joint.inertia > 0.0) || !std::isfinite(n.joint.inertia)) {
      return fail(w + "inertia", "must be > 0");
    }
    if (!(n.joint.damping >= 0.0) || !std::isfinite(n.joint.damping)) {
      return fail(w + "damping", "must be >= 0");
    }
    if (!(n.joint.torque_limit > 0.0) || !std::isfinite(n.joint.torque_limit)) {
      return fail(w + "torque_limit", "must be > 0");
    }
    if (!(n.joint.kp >= 0.0 && n.joint.kp <= limits::kGainMax) ||
        !(n.joint.kd >= 0.0 && n.joint.kd <= limits::kGainMax)) {
      return fail(w + "kp/kd", "must be in [0, 1e9]");
    }
    if (!(n.joint.inertia <= limits::kPhysicalMax) || !(n.joint.damping <= limits::kPhysicalMax) ||
        !(n.joint.torque_limit <= limits::kPhysicalMax)) {
      return fail(w + "inertia/damping/torque_limit", "must be at most 1e6");
    }
    if (!(std::fabs(n.joint.initial_position) <= limits::kPositionMax)) {
      return fail(w + "initial_position", "must be in [-1000, 1000] rad");
    }
    const TimeNs t_max = secondsToNs(limits::kTimeSMax);
    for (const TimeNs t : {n.faults.heartbeat_stop_at, n.faults.emcy_at, n.faults.saturate_at}) {
      if (t != kNever && (t < 0 || t > t_max)) {
        return fail(w + "faults", "fault times must be in [0, 1e6] s");
      }
    }
  }
  if (c.step < std::llround(limits::kStepMsMin * 1e6) || c.step > std::llround(limits::kStepMsMax * 1e6)) {
    return fail("step_ms", "must be in [0.01, 100] ms");
  }
  if (c.boot_delay < 0 || c.boot_delay > std::llround(limits::kBootDelayMsMax * 1e6)) {
    return fail("boot_delay_ms", "must be in [0, 60000] ms");
  }
  if (!(c.duration_s >= 0.0 && c.duration_s <= limits::kTimeSMax)) {
    return fail("duration", "must be in [0, 1e6] s");
  }
  if (c.profile.tpdo_count < 1u || c.profile.tpdo_count > 4u || c.profile.comm_error_behaviour > 2u ||
      c.profile.abort_connection_option > 3u ||
      !(c.profile.sync_timeout_factor == 0.0 ||
        (c.profile.sync_timeout_factor >= 1.0 && c.profile.sync_timeout_factor <= 100.0))) {
    return fail(
        "profile",
        "tpdo_count 1..4, comm_error_behaviour 0..2, abort_connection_option 0..3, sync_timeout_factor 0 "
        "or [1, 100]");
  }
  if (!(c.drop_fraction >= 0.0 && c.drop_fraction <= 1.0)) {
    return fail("faults.drop_fraction", "must be 0..1");
  }
  if (!(c.corrupt_fraction >= 0.0 && c.corrupt_fraction <= 1.0)) {
    return fail("faults.corrupt_fraction", "must be 0..1");
  }
  return true;
}

bool loadConfig(const std::string& path, EmuConfig* out, std::string* error) {
  try {
    const Reader r(path);
    const YAML::Node root = scene::parseYamlDocument(scene::readTextFile(path), path);
    const EmuConfig c = readConfig(r, root);
    if (!validateConfig(c, path, error)) {
      return false;
    }
    *out = c;
    return true;
  } catch (const std::exception& e) {
    if (error != nullptr) {
      *error = e.what();
    }
    return false;
  } catch (...) {
    if (error != nullptr) {
      *error = path + ": unreadable configuration";
    }
    return false;
  }
}

std::string describeConfig(const EmuConfig& c) {
  std::ostringstream o;
  o << "interface " << c.interface << ", physics step " << static_cast<double>(c.step) / 1e6
    << " ms, boot delay " << static_cast<double>(c.boot_delay) / 1e6 << " ms, duration "
    << (c.duration_s > 0.0 ? scene::formatNumber(c.duration_s) + " s" : std::string("until SIGINT/SIGTERM"))
    << ", frames dropped " << c.drop_fraction << ", corrupted " << c.corrupt_fraction << " (seed " << c.seed
    << ")\n";
  const VendorProfile& p = c.profile;
  o << "profile: " << static_cast<unsigned>(p.tpdo_count) << " TPDO(s); aborts: absent "
    << (p.abort_absent ? "yes" : "no") << ", read-only " << (p.abort_read_only ? "yes" : "no") << ", range "
    << (p.range_checks ? "yes" : "no") << "; PDO rules " << (p.pdo_rules ? "yes" : "no") << "; RTR check "
    << (p.rtr_check ? "yes" : "no") << "; SYNC timeout "
    << (p.sync_timeout_factor > 0.0 ? scene::formatNumber(p.sync_timeout_factor) + " x 0x1006"
                                    : std::string("off"))
    << " (0x1029:01 = " << static_cast<unsigned>(p.comm_error_behaviour)
    << (p.comm_error_fault ? ", power stage faults" : "") << "); statusword bits 4/9 "
    << (p.statusword_bits ? "as drives set them" : "bit 4 always") << "; heartbeat consumer (0x1016) "
    << (p.heartbeat_consumer ? "watched" : "not watched") << "; RPDO timeout (0x1400:05) "
    << (p.rpdo_timeout_ms != 0u ? std::to_string(p.rpdo_timeout_ms) + " ms" : std::string("off"))
    << "; 0x6007 = " << static_cast<unsigned>(p.abort_connection_option);
  char ids[96];
  std::snprintf(ids, sizeof ids, "; device type 0x%08X, vendor 0x%08X, product 0x%08X, revision 0x%08X\n",
                p.device_type, p.vendor_id, p.product_code, p.revision);
  o << ids;
  for (const EmuNode& n : c.nodes) {
    o << "node " << static_cast<unsigned>(n.node) << ": " << n.scale.increments_per_rev
      << " increments/rev, rated " << static_cast<double>(n.scale.rated_torque_mNm) / 1000.0
      << " N m, inertia " << n.joint.inertia << ", damping " << n.joint.damping << ", torque limit "
      << n.joint.torque_limit << ", kp " << n.joint.kp << ", kd " << n.joint.kd << ", initial position "
      << n.joint.initial_position << " rad";
    auto when = [](TimeNs t) { return scene::formatNumber(static_cast<double>(t) / 1e9) + " s"; };
    if (n.faults.heartbeat_stop_at != kNever) {
      o << ", heartbeat stops at " << when(n.faults.heartbeat_stop_at);
    }
    if (n.faults.emcy_at != kNever) {
      char code[16];
      std::snprintf(code, sizeof code, "0x%04X", static_cast<unsigned>(n.faults.emcy_code));
      o << ", EMCY " << code << " at " << when(n.faults.emcy_at);
    }
    if (n.faults.saturate_at != kNever) {
      o << ", torque saturates at " << when(n.faults.saturate_at);
    }
    o << "\n";
  }
  return o.str();
}

bool applyFaultSwitch(const std::string& kind, const std::string& arg, EmuConfig* c, std::string* error) {
  // arg: N@T or N@T:code (T in seconds)
  const auto at = arg.find('@');
  auto fail = [&](const std::string& what) {
    if (error != nullptr) {
      *error = "--" + kind + " " + arg + ": " + what;
    }
    return false;
  };
  if (at == std::string::npos) {
    return fail("expected NODE@SECONDS");
  }
  char* end = nullptr;
  const long node = std::strtol(arg.c_str(), &end, 10);
  if (end != arg.c_str() + at || node < 1 || node > 127) {
    return fail("bad node id");
  }
  const std::string rest = arg.substr(at + 1);
  const double t = std::strtod(rest.c_str(), &end);
  if (end == rest.c_str() || !(t >= 0.0 && t <= limits::kTimeSMax)) {
    return fail("bad time: expected seconds in [0, 1e6]");
  }
  unsigned long code = 0;
  if (*end == ':') {
    code = std::strtoul(end + 1, &end, 0);
    if (code == 0 || code > 0xFFFF) {
      return fail("bad EMCY code");
    }
  }
  if (*end != '\0') {
    return fail("trailing characters");
  }
  for (EmuNode& n : c->nodes) {
    if (n.node != node) {
      continue;
    }
    const TimeNs tn = static_cast<TimeNs>(std::llround(t * 1e9));
    if (kind == "stop-heartbeat") {
      n.faults.heartbeat_stop_at = tn;
    } else if (kind == "emcy") {
      n.faults.emcy_at = tn;
      if (code != 0) {
        n.faults.emcy_code = static_cast<std::uint16_t>(code);
      }
    } else if (kind == "saturate") {
      n.faults.saturate_at = tn;
    } else {
      return fail("unknown fault switch");
    }
    return true;
  }
  return fail("node " + std::to_string(node) + " is not emulated");
}

}  // namespace mrqp::drive_emu
