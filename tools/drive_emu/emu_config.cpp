// YAML configuration of mrqp-drive-emu (see README.md for the format).
#include <yaml-cpp/yaml.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <exception>
#include <set>
#include <sstream>

#include "drive_emu.hpp"

namespace mrqp::drive_emu {

namespace {

struct Fail {
  std::string field;
  std::string what;
};

template <typename T>
T get(const YAML::Node& map, const char* key, const std::string& where, T fallback)
{
  const YAML::Node n = map[key];
  if (!n) {
    return fallback;
  }
  try {
    return n.as<T>();
  } catch (const std::exception&) {
    throw Fail{where + key, "not a valid value (line " + std::to_string(n.Mark().line + 1) + ")"};
  }
}

TimeNs seconds_to_ns(double s) { return static_cast<TimeNs>(std::llround(s * 1e9)); }

void read_faults(const YAML::Node& f, const std::string& where, NodeFaults* out)
{
  if (!f) {
    return;
  }
  if (!f.IsMap()) {
    throw Fail{where, "must be a map"};
  }
  const double hb = get<double>(f, "stop_heartbeat_at", where, -1.0);
  if (f["stop_heartbeat_at"]) {
    if (!(hb >= 0.0)) {
      throw Fail{where + "stop_heartbeat_at", "must be >= 0 (seconds)"};
    }
    out->heartbeat_stop_at = seconds_to_ns(hb);
  }
  if (f["emcy_at"]) {
    const double t = get<double>(f, "emcy_at", where, -1.0);
    if (!(t >= 0.0)) {
      throw Fail{where + "emcy_at", "must be >= 0 (seconds)"};
    }
    out->emcy_at = seconds_to_ns(t);
  }
  const unsigned code = get<unsigned>(f, "emcy_code", where, out->emcy_code);
  if (code == 0u || code > 0xFFFFu) {
    throw Fail{where + "emcy_code", "must be 1..0xFFFF"};
  }
  out->emcy_code = static_cast<std::uint16_t>(code);
  if (f["saturate_at"]) {
    const double t = get<double>(f, "saturate_at", where, -1.0);
    if (!(t >= 0.0)) {
      throw Fail{where + "saturate_at", "must be >= 0 (seconds)"};
    }
    out->saturate_at = seconds_to_ns(t);
  }
}

}  // namespace

bool validate_config(const EmuConfig& c, const std::string& origin, std::string* error)
{
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
    if (!(n.joint.kp >= 0.0) || !(n.joint.kd >= 0.0)) {
      return fail(w + "kp/kd", "must be >= 0");
    }
  }
  if (c.step <= 0) {
    return fail("step", "must be > 0");
  }
  if (!(c.drop_fraction >= 0.0 && c.drop_fraction <= 1.0)) {
    return fail("faults.drop_fraction", "must be 0..1");
  }
  if (!(c.corrupt_fraction >= 0.0 && c.corrupt_fraction <= 1.0)) {
    return fail("faults.corrupt_fraction", "must be 0..1");
  }
  return true;
}

bool load_config(const std::string& path, EmuConfig* out, std::string* error)
{
  YAML::Node root;
  try {
    root = YAML::LoadFile(path);
  } catch (const std::exception& e) {
    if (error != nullptr) {
      *error = path + ": " + e.what();
    }
    return false;
  }
  EmuConfig c;
  try {
    if (!root.IsMap()) {
      throw Fail{"(top level)", "must be a map"};
    }
    c.interface = get<std::string>(root, "interface", "", c.interface);
    const double step_ms = get<double>(root, "step_ms", "", 0.5);
    if (!(step_ms > 0.0)) {
      throw Fail{"step_ms", "must be > 0"};
    }
    c.step = static_cast<TimeNs>(std::llround(step_ms * 1e6));
    c.boot_delay = static_cast<TimeNs>(std::llround(get<double>(root, "boot_delay_ms", "", 2.0) * 1e6));
    c.duration_s = get<double>(root, "duration", "", 0.0);
    const unsigned ipr = get<unsigned>(root, "increments_per_rev", "", 524288u);
    const double rated = get<double>(root, "rated_torque", "", 1.0);
    if (!(rated > 0.0)) {
      throw Fail{"rated_torque", "must be > 0 (N m)"};
    }
    const YAML::Node nodes = root["nodes"];
    if (!nodes || !nodes.IsSequence()) {
      throw Fail{"nodes", "missing, or not a list"};
    }
    JointModel def;
    if (root["joint"]) {
      const YAML::Node j = root["joint"];
      def.inertia = get<double>(j, "inertia", "joint.", def.inertia);
      def.damping = get<double>(j, "damping", "joint.", def.damping);
      def.torque_limit = get<double>(j, "torque_limit", "joint.", def.torque_limit);
      def.kp = get<double>(j, "kp", "joint.", def.kp);
      def.kd = get<double>(j, "kd", "joint.", def.kd);
    }
    for (std::size_t i = 0; i < nodes.size(); ++i) {
      const YAML::Node n = nodes[i];
      const std::string w = "nodes[" + std::to_string(i) + "].";
      EmuNode e;
      e.joint = def;
      if (n.IsScalar()) {
        try {
          e.node = static_cast<std::uint8_t>(std::clamp(n.as<int>(), 0, 255));
        } catch (const std::exception&) {
          throw Fail{"nodes[" + std::to_string(i) + "]", "not a node id"};
        }
        e.scale.increments_per_rev = ipr;
        e.scale.rated_torque_mNm = static_cast<std::uint32_t>(std::llround(rated * 1000.0));
        c.nodes.push_back(e);
        continue;
      }
      if (!n.IsMap()) {
        throw Fail{"nodes[" + std::to_string(i) + "]", "must be a node id or a map"};
      }
      if (!n["node"]) {
        throw Fail{w + "node", "missing"};
      }
      const int id = get<int>(n, "node", w, 0);
      e.node = static_cast<std::uint8_t>(id < 0 || id > 255 ? 0 : id);
      e.scale.increments_per_rev = get<unsigned>(n, "increments_per_rev", w, ipr);
      const double r = get<double>(n, "rated_torque", w, rated);
      if (!(r > 0.0)) {
        throw Fail{w + "rated_torque", "must be > 0 (N m)"};
      }
      e.scale.rated_torque_mNm = static_cast<std::uint32_t>(std::llround(r * 1000.0));
      e.joint.inertia = get<double>(n, "inertia", w, def.inertia);
      e.joint.damping = get<double>(n, "damping", w, def.damping);
      e.joint.torque_limit = get<double>(n, "torque_limit", w, def.torque_limit);
      e.joint.kp = get<double>(n, "kp", w, def.kp);
      e.joint.kd = get<double>(n, "kd", w, def.kd);
      e.joint.initial_position = get<double>(n, "initial_position", w, 0.0);
      read_faults(n["faults"], w + "faults.", &e.faults);
      c.nodes.push_back(e);
    }
    const YAML::Node f = root["faults"];
    if (f) {
      if (!f.IsMap()) {
        throw Fail{"faults", "must be a map"};
      }
      c.drop_fraction = get<double>(f, "drop_fraction", "faults.", 0.0);
      c.corrupt_fraction = get<double>(f, "corrupt_fraction", "faults.", 0.0);
      c.seed = get<unsigned>(f, "seed", "faults.", 1u);
    }
  } catch (const Fail& e) {
    if (error != nullptr) {
      *error = path + ": " + e.field + ": " + e.what;
    }
    return false;
  }
  if (!validate_config(c, path, error)) {
    return false;
  }
  *out = c;
  return true;
}

bool apply_fault_switch(const std::string& kind, const std::string& arg, EmuConfig* c, std::string* error)
{
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
  if (end == rest.c_str() || !(t >= 0.0)) {
    return fail("bad time");
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
