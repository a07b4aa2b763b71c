// The hardware section of a scene file (see hardware_yaml.hpp).
#include "loop/hardware_yaml.hpp"

#include <climits>
#include <cstdint>
#include <optional>

#include "scene/yaml_reader.hpp"

namespace mrqp::loop {

namespace {

using scene::Bound;
using scene::Map;
using scene::Reader;

std::uint32_t bitRate(const Map& m, const std::string& key, std::uint32_t fallback, bool allow_zero) {
  const YAML::Node* n = m.find(key);
  if (n == nullptr) {
    return fallback;
  }
  const int v = m.reader().integer(*n, m.at(key), allow_zero ? 0 : 10000, 20000000);
  if (v != 0 && v < 10000) {
    m.reader().fail(*n, m.at(key),
                    "expected 0 or a bit rate in [10000, 20000000], got " + scene::describe(*n));
  }
  return static_cast<std::uint32_t>(v);
}

BusDecl readBus(const Reader& r, const YAML::Node& n, const std::string& path) {
  const Map m(r, n, path, {"name", "bitrate", "data_bitrate"});
  BusDecl b;
  b.name = m.name("name");
  b.bitrate = bitRate(m, "bitrate", 1000000, false);
  b.data_bitrate = bitRate(m, "data_bitrate", 0, true);
  if (b.data_bitrate != 0 && b.data_bitrate < b.bitrate) {
    r.fail(*m.find("data_bitrate"), m.at("data_bitrate"),
           "the data-phase rate must be at least the nominal rate");
  }
  b.source = m.source();
  return b;
}

/// An unsigned 32-bit value (decimal or 0x hex) of a CANopen object; 0 when absent.
std::uint32_t u32(const Map& m, const char* key) {
  const YAML::Node* n = m.find(key);
  if (n == nullptr) return 0;
  const std::optional<long long> v = scene::toInteger(*n);
  if (!v || *v < 0 || *v > 0xFFFFFFFFLL) {
    m.reader().fail(*n, m.at(key), "expected an integer in [0, 0xFFFFFFFF], got " + scene::describe(*n));
  }
  return static_cast<std::uint32_t>(*v);
}

std::vector<std::string> jointList(const Map& m) {
  std::vector<std::string> j = m.reader().names(m.require("joints"), m.at("joints"));
  if (j.empty()) {
    m.reader().fail(m.require("joints"), m.at("joints"), "expected at least one joint");
  }
  return j;
}

Cia402Group readCia402(const Reader& r, const YAML::Node& n, const std::string& path) {
  const Map m(r, n, path,
              {"bus", "mode", "first_node", "rated_torque", "device_type", "vendor_id", "product_code",
               "revision", "joints"});
  Cia402Group g;
  g.bus = m.name("bus");
  if (const YAML::Node* mode = m.find("mode")) {
    const std::string s = r.name(*mode, m.at("mode"));
    if (s == "csp") {
      g.mode = DriveMode::Csp;
    } else if (s == "cst") {
      g.mode = DriveMode::Cst;
    } else {
      r.fail(*mode, m.at("mode"), "expected csp or cst, got \"" + s + "\"");
    }
  }
  g.first_node = m.integer("first_node", 1, 127, 1);
  g.rated_torque = m.number("rated_torque", Bound::Positive, 100.0);
  g.identity.device_type = u32(m, "device_type");
  g.identity.vendor_id = u32(m, "vendor_id");
  g.identity.product_code = u32(m, "product_code");
  g.identity.revision = u32(m, "revision");
  g.joints = jointList(m);
  if (g.first_node + static_cast<int>(g.joints.size()) - 1 > 127) {
    r.fail(m.require("joints"), m.at("joints"),
           std::to_string(g.joints.size()) + " drives from node " + std::to_string(g.first_node) +
               " go past node id 127");
  }
  g.source = m.source();
  return g;
}

ImpedanceGroup readImpedance(const Reader& r, const YAML::Node& n, const std::string& path,
                             const char* kind) {
  const bool mit = std::string(kind) == "mit";
  const Map m = mit ? Map(r, n, path, {"bus", "first_id", "joints", "kp", "kd"})
                    : Map(r, n, path, {"bus", "board", "joints"});
  ImpedanceGroup g;
  g.kind = kind;
  g.bus = m.name("bus");
  g.joints = jointList(m);
  if (mit) {
    g.first_id = m.integer("first_id", 1, 127, 1);
    // The MIT command frame's ranges (firmware_if/mit_frame.h): kp 0..500, kd 0..5.
    g.kp = m.number("kp", Bound::NonNegative, 50.0);
    g.kd = m.number("kd", Bound::NonNegative, 1.0);
    if (g.kp > 500.0) r.fail(m.require("kp"), m.at("kp"), "above 500, the MIT frame's largest stiffness");
    if (g.kd > 5.0) r.fail(m.require("kd"), m.at("kd"), "above 5, the MIT frame's largest damping");
    if (g.first_id + static_cast<int>(g.joints.size()) - 1 > 127) {
      r.fail(m.require("joints"), m.at("joints"),
             std::to_string(g.joints.size()) + " motors from id " + std::to_string(g.first_id) +
                 " go past motor id 127");
    }
  } else {
    g.first_id = m.integer("board", 0, 15, 0);
    if (g.joints.size() > 32) {
      r.fail(m.require("joints"), m.at("joints"), "a hand board has at most 32 joints");
    }
  }
  g.source = m.source();
  return g;
}

SensorDecl readSensor(const Reader& r, const YAML::Node& n, const std::string& path) {
  const Map m(r, n, path, {"frame", "bus", "node"});
  SensorDecl s;
  s.frame = m.name("frame");
  s.bus = m.name("bus");
  s.node = m.integer("node", 1, 127, 1);
  s.source = m.source();
  return s;
}

RobotHardware readRobot(const Reader& r, const YAML::Node& n, const std::string& path) {
  const Map m(r, n, path,
              {"entity", "divisor", "safe_stop", "hold_damping", "state", "interpolating_drives", "rpdo_timeout",
               "cia402", "mit", "fd", "ft_sensors", "imus"});
  RobotHardware rh;
  rh.entity = m.name("entity");
  rh.divisor = m.integer("divisor", 1, 1000, 1);
  if (const YAML::Node* s = m.find("safe_stop")) {
    const std::string v = r.name(*s, m.at("safe_stop"));
    if (v == "hold") {
      rh.safe_stop = SafeStop::Hold;
    } else if (v == "quick_stop") {
      rh.safe_stop = SafeStop::QuickStop;
    } else {
      r.fail(*s, m.at("safe_stop"), "expected hold or quick_stop, got \"" + v + "\"");
    }
  }
  rh.hold_damping = m.number("hold_damping", Bound::NonNegative, 1.0);
  if (const YAML::Node* s = m.find("state")) {
    const std::string v = r.name(*s, m.at("state"));
    if (v == "measured") {
      rh.state = JointState::Measured;
    } else if (v == "commanded") {
      rh.state = JointState::Commanded;
    } else {
      r.fail(*s, m.at("state"), "expected measured or commanded, got \"" + v + "\"");
    }
  }
  rh.interpolating_drives = m.boolean("interpolating_drives", false);
  if (const YAML::Node* t = m.find("rpdo_timeout")) {
    // 0x1400:05 holds milliseconds in 16 bits.
    rh.rpdo_timeout_s = m.number("rpdo_timeout", Bound::Positive, 0.0);
    if (rh.rpdo_timeout_s < 0.001 || rh.rpdo_timeout_s > 65.535) {
      r.fail(*t, m.at("rpdo_timeout"),
             "expected a time in [0.001, 65.535] s (0x1400:05 holds milliseconds in 16 bits), got " +
                 scene::describe(*t));
    }
    rh.rpdo_timeout_source = r.source(*t);
  }
  auto each = [&](const char* key, auto read) {
    if (const YAML::Node* l = m.find(key)) {
      const std::vector<YAML::Node> items = r.list(*l, m.at(key));
      for (std::size_t i = 0; i < items.size(); ++i) {
        read(items[i], scene::item(m.at(key), i));
      }
    }
  };
  each("cia402",
       [&](const YAML::Node& x, const std::string& p) { rh.cia402.push_back(readCia402(r, x, p)); });
  each("mit", [&](const YAML::Node& x, const std::string& p) {
    rh.impedance.push_back(readImpedance(r, x, p, "mit"));
  });
  each("fd", [&](const YAML::Node& x, const std::string& p) {
    rh.impedance.push_back(readImpedance(r, x, p, "fd"));
  });
  each("ft_sensors",
       [&](const YAML::Node& x, const std::string& p) { rh.ft_sensors.push_back(readSensor(r, x, p)); });
  each("imus", [&](const YAML::Node& x, const std::string& p) { rh.imus.push_back(readSensor(r, x, p)); });
  rh.source = m.source();
  return rh;
}

ControllerHeartbeatSpec readControllerHeartbeat(const Reader& r, const YAML::Node& n,
                                                const std::string& path) {
  const Map m(r, n, path, {"node", "period", "drive_timeout"});
  ControllerHeartbeatSpec h;
  h.node = m.integer("node", 1, 127, 1);
  h.period_s = m.number("period", Bound::Positive, 0.1);
  h.drive_timeout_s = m.number("drive_timeout", Bound::Positive, 0.3);
  // Both go to the wire in milliseconds (16 bits); the drives' consumer time must exceed the period.
  if (h.period_s < 0.001 || h.period_s > 65.535) {
    r.fail(m.require("period"), m.at("period"), "expected a period in [0.001, 65.535] s");
  }
  if (h.drive_timeout_s > 65.535) {
    r.fail(m.require("drive_timeout"), m.at("drive_timeout"), "above 65.535 s, the largest consumer time");
  }
  if (h.drive_timeout_s <= h.period_s) {
    r.fail(m.has("drive_timeout") ? m.require("drive_timeout") : n, m.at("drive_timeout"),
           "the drives' consumer time must exceed the heartbeat period");
  }
  h.source = m.source();
  return h;
}

RecoverySpec readRecovery(const Reader& r, const YAML::Node& n, const std::string& path) {
  const Map m(r, n, path, {"max_attempts", "backoff"});
  RecoverySpec s;
  s.max_attempts = m.integer("max_attempts", 0, 100, 1);
  s.backoff_s = m.number("backoff", Bound::Positive, 0.5);
  return s;
}

SafeExitSpec readSafeExit(const Reader& r, const YAML::Node& n, const std::string& path) {
  const Map m(r, n, path, {"stop", "nmt"});
  SafeExitSpec s;
  if (const YAML::Node* stop = m.find("stop")) {
    const std::string v = r.name(*stop, m.at("stop"));
    if (v == "quick_stop") {
      s.stop = ExitStopKind::QuickStop;
    } else if (v == "disable_voltage") {
      s.stop = ExitStopKind::DisableVoltage;
    } else {
      r.fail(*stop, m.at("stop"), "expected quick_stop or disable_voltage, got \"" + v + "\"");
    }
  }
  if (const YAML::Node* nmt = m.find("nmt")) {
    const std::string v = r.name(*nmt, m.at("nmt"));
    if (v == "pre_operational") {
      s.nmt = ExitNmtKind::PreOperational;
    } else if (v == "stopped") {
      s.nmt = ExitNmtKind::Stopped;
    } else if (v == "unchanged") {
      s.nmt = ExitNmtKind::Unchanged;
    } else {
      r.fail(*nmt, m.at("nmt"), "expected pre_operational, stopped or unchanged, got \"" + v + "\"");
    }
  }
  return s;
}

HardwareSpec readHardware(const Reader& r, const YAML::Node& n) {
  const Map m(r, n, "hardware",
              {"heartbeat_timeout", "feedback_missing_cycles", "frame_loss", "controller_heartbeat",
               "recovery", "safe_exit", "buses", "robots"});
  HardwareSpec h;
  h.present = true;
  h.source = m.source();
  h.heartbeat_timeout_s = m.number("heartbeat_timeout", Bound::Positive, 0.25);
  h.feedback_missing_cycles = m.integer("feedback_missing_cycles", 1, 1000, 3);
  if (const YAML::Node* c = m.find("frame_loss")) {
    const Map fl(r, *c, m.at("frame_loss"), {"window", "limit"});
    h.frame_loss_window = static_cast<double>(fl.integer("window", 1, 100000, 100));
    h.frame_loss_limit = fl.number("limit", Bound::Positive, 0.02);
    if (h.frame_loss_limit > 1.0) {
      r.fail((*c)["limit"], fl.at("limit"), "expected a fraction of robot cycles, at most 1");
    }
  }
  if (const YAML::Node* c = m.find("controller_heartbeat")) {
    h.controller_heartbeat = readControllerHeartbeat(r, *c, m.at("controller_heartbeat"));
  }
  if (const YAML::Node* c = m.find("recovery")) h.recovery = readRecovery(r, *c, m.at("recovery"));
  if (const YAML::Node* c = m.find("safe_exit")) h.safe_exit = readSafeExit(r, *c, m.at("safe_exit"));
  scene::UniqueNames bus_names(r, "bus");
  const std::vector<YAML::Node> buses = r.list(m.require("buses"), m.at("buses"));
  for (std::size_t i = 0; i < buses.size(); ++i) {
    h.buses.push_back(readBus(r, buses[i], scene::item(m.at("buses"), i)));
    bus_names.add(h.buses.back().name, buses[i], scene::item(m.at("buses"), i) + ".name");
  }
  scene::UniqueNames robot_names(r, "robot entity");
  const std::vector<YAML::Node> robots = r.list(m.require("robots"), m.at("robots"));
  for (std::size_t i = 0; i < robots.size(); ++i) {
    h.robots.push_back(readRobot(r, robots[i], scene::item(m.at("robots"), i)));
    robot_names.add(h.robots.back().entity, robots[i], scene::item(m.at("robots"), i) + ".entity");
  }
  return h;
}

}  // namespace

HardwareSpec readHardwareString(const std::string& text, const std::string& file_name_for_messages) {
  const YAML::Node doc = scene::parseYamlDocument(text, file_name_for_messages);
  const Reader r(file_name_for_messages);
  HardwareSpec h;
  if (doc.IsMap() && doc["hardware"] && !doc["hardware"].IsNull()) {
    h = readHardware(r, doc["hardware"]);
  }
  h.source.file = file_name_for_messages;
  return h;
}

HardwareSpec readHardwareFile(const std::string& path) {
  return readHardwareString(scene::readTextFile(path), path);
}

std::string readPlantSimulatorString(const std::string& text, const std::string& file_name_for_messages) {
  const YAML::Node doc = scene::parseYamlDocument(text, file_name_for_messages);
  const Reader r(file_name_for_messages);
  if (!doc.IsMap() || !doc["plant"] || doc["plant"].IsNull()) {
    return "";
  }
  const YAML::Node plant = doc["plant"];
  if (!plant.IsMap()) {
    r.fail(plant, "plant", "expected a map, got " + scene::describe(plant));
  }
  if (!plant["simulator"]) {
    return "mujoco";  // a plant section without a simulator describes the MuJoCo plant
  }
  const std::string kind = r.name(plant["simulator"], "plant.simulator");
  if (kind != "ideal" && kind != "mujoco") {
    r.fail(plant["simulator"], "plant.simulator", "expected mujoco or ideal, got \"" + kind + "\"");
  }
  return kind;
}

}  // namespace mrqp::loop
