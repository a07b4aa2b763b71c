// YAML configuration of mrqp-drive-emu (see README.md for the format), read with the checker of
// every YAML file of mrqp (control/scene/yaml_reader.hpp): errors are "FILE:LINE: FIELD: message".
#include <algorithm>
#include <climits>
#include <cmath>
#include <cstdlib>
#include <exception>
#include <map>
#include <set>
#include <sstream>

#include "drive_emu.hpp"
#include "scene/yaml_reader.hpp"

namespace mrqp::drive_emu {

namespace {

using scene::Bound;
using scene::Map;
using scene::Reader;

TimeNs seconds_to_ns(double s) { return static_cast<TimeNs>(std::llround(s * 1e9)); }

void read_faults(const Reader& r, const YAML::Node& f, const std::string& path, NodeFaults* out) {
  const Map m(r, f, path, {"stop_heartbeat_at", "emcy_at", "emcy_code", "saturate_at"});
  if (m.has("stop_heartbeat_at")) {
    out->heartbeat_stop_at = seconds_to_ns(m.number("stop_heartbeat_at", Bound::NonNegative, 0.0));
  }
  if (m.has("emcy_at")) {
    out->emcy_at = seconds_to_ns(m.number("emcy_at", Bound::NonNegative, 0.0));
  }
  out->emcy_code = static_cast<std::uint16_t>(m.integer("emcy_code", 1, 0xFFFF, out->emcy_code));
  if (m.has("saturate_at")) {
    out->saturate_at = seconds_to_ns(m.number("saturate_at", Bound::NonNegative, 0.0));
  }
}

void read_joint(const Map& m, JointModel* j) {
  j->inertia = m.number("inertia", Bound::Positive, j->inertia);
  j->damping = m.number("damping", Bound::NonNegative, j->damping);
  j->torque_limit = m.number("torque_limit", Bound::Positive, j->torque_limit);
  j->kp = m.number("kp", Bound::NonNegative, j->kp);
  j->kd = m.number("kd", Bound::NonNegative, j->kd);
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

std::uint32_t rated_mNm(double n_m) { return static_cast<std::uint32_t>(std::llround(n_m * 1000.0)); }

EmuConfig read_config(const Reader& r, const YAML::Node& root) {
  EmuConfig c;
  const Map top(r, root, "",
                {"interface", "step_ms", "boot_delay_ms", "duration", "increments_per_rev", "rated_torque",
                 "joint", "nodes", "faults"});
  if (top.has("interface")) {
    c.interface = top.name("interface");
  }
  c.step = static_cast<TimeNs>(std::llround(top.number("step_ms", Bound::Positive, 0.5) * 1e6));
  c.boot_delay =
      static_cast<TimeNs>(std::llround(top.number("boot_delay_ms", Bound::NonNegative, 2.0) * 1e6));
  c.duration_s = top.number("duration", Bound::NonNegative, 0.0);
  const int ipr = top.integer("increments_per_rev", 1, INT_MAX, 524288);
  const double rated = top.number("rated_torque", Bound::Positive, 1.0);

  JointModel def;
  if (const YAML::Node* j = top.find("joint")) {
    read_joint(Map(r, *j, top.at("joint"), {"inertia", "damping", "torque_limit", "kp", "kd"}), &def);
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
    e.scale.rated_torque_mNm = rated_mNm(rated);
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
      e.scale.rated_torque_mNm = rated_mNm(m.number("rated_torque", Bound::Positive, rated));
      read_joint(m, &e.joint);
      e.joint.initial_position = m.number("initial_position", Bound::Any, 0.0);
      if (const YAML::Node* f = m.find("faults")) {
        read_faults(r, *f, m.at("faults"), &e.faults);
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

bool validate_config(const EmuConfig& c, const std::string& origin, std::string* error) {
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

bool load_config(const std::string& path, EmuConfig* out, std::string* error) {
  try {
    const Reader r(path);
    const YAML::Node root = scene::parseYamlDocument(scene::readTextFile(path), path);
    const EmuConfig c = read_config(r, root);
    if (!validate_config(c, path, error)) {
      return false;
    }
    *out = c;
    return true;
  } catch (const std::exception& e) {
    if (error != nullptr) {
      *error = e.what();
    }
    return false;
  }
}

bool apply_fault_switch(const std::string& kind, const std::string& arg, EmuConfig* c, std::string* error) {
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
