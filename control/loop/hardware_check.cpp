// Resolving the hardware section against the models, and the bus budget (see hardware_check.hpp).
#include "loop/hardware_check.hpp"

#include <mrqp/drivers/arm_driver.hpp>
#include <mrqp/drivers/bus_budget.hpp>

#include <algorithm>
#include <cmath>
#include <map>
#include <set>

#include "scene/scene_yaml.hpp"
#include "scene/yaml_reader.hpp"

namespace mrqp::loop {

namespace {

[[noreturn]] void fail(const scene::Source& s, const std::string& field, const std::string& message) {
  throw scene::SceneError(s.file + ":" + std::to_string(s.line) + ": " + field + ": " + message);
}

std::string robotField(std::size_t r, const std::string& rest) {
  return "hardware.robots[" + std::to_string(r) + "]" + (rest.empty() ? "" : "." + rest);
}

int busIndex(const HardwareSpec& spec, const std::string& name, const scene::Source& at,
             const std::string& field) {
  for (std::size_t i = 0; i < spec.buses.size(); ++i) {
    if (spec.buses[i].name == name) {
      return static_cast<int>(i);
    }
  }
  fail(at, field, "unknown bus '" + name + "' (not in hardware.buses)");
}

}  // namespace

ResolvedHardware resolveHardware(const HardwareSpec& spec, const problem::MultiRobotProblem& problem,
                                 double dt) {
  ResolvedHardware out;
  out.heartbeat_timeout_s = spec.heartbeat_timeout_s;
  out.feedback_missing_cycles = spec.feedback_missing_cycles;
  out.frame_loss_window = spec.frame_loss_window;
  out.frame_loss_limit = spec.frame_loss_limit;
  out.controller_heartbeat = spec.controller_heartbeat;
  out.recovery = spec.recovery;
  out.safe_exit = spec.safe_exit;
  if (const int hb = spec.controller_heartbeat.node; hb != 0) {
    for (std::size_t r = 0; r < spec.robots.size(); ++r) {
      for (const Cia402Group& g : spec.robots[r].cia402) {
        if (hb >= g.first_node && hb < g.first_node + static_cast<int>(g.joints.size())) {
          fail(spec.controller_heartbeat.source, "hardware.controller_heartbeat.node",
               "node " + std::to_string(hb) + " is a CiA 402 drive of '" + spec.robots[r].entity +
                   "' on bus '" + g.bus + "'");
        }
      }
    }
  }
  for (const BusDecl& b : spec.buses) {
    ResolvedBus rb;
    rb.decl = b;
    out.buses.push_back(rb);
  }
  // (bus, node) → where it was first used
  std::map<std::pair<int, int>, int> nodes;
  auto claimNode = [&](int bus, int node, const scene::Source& at, const std::string& field) {
    const auto [it, inserted] = nodes.emplace(std::make_pair(bus, node), at.line);
    if (!inserted) {
      fail(at, field,
           "node id " + std::to_string(node) + " on bus '" + spec.buses[static_cast<std::size_t>(bus)].name +
               "' is already used (line " + std::to_string(it->second) + ")");
    }
  };
  std::set<std::pair<int, int>> boards;  // (bus, hand board)
  auto claimBus = [&](int bus, int robot, const scene::Source& at, const std::string& field) {
    ResolvedBus& rb = out.buses[static_cast<std::size_t>(bus)];
    if (rb.robot >= 0 && rb.robot != robot) {
      fail(at, field,
           "bus '" + rb.decl.name + "' already carries robot '" +
               out.robots[static_cast<std::size_t>(rb.robot)].name +
               "' (one robot per bus: its drives share one SYNC)");
    }
    rb.robot = robot;
  };

  for (std::size_t r = 0; r < spec.robots.size(); ++r) {
    const RobotHardware& rh = spec.robots[r];
    ResolvedRobot rr;
    rr.name = rh.entity;
    rr.entity = problem.entityIndex(rh.entity);
    rr.divisor = rh.divisor;
    rr.safe_stop = rh.safe_stop;
    rr.hold_damping = rh.hold_damping;
    rr.state = rh.state;
    rr.interpolating_drives = rh.interpolating_drives;
    rr.rpdo_timeout_s = rh.rpdo_timeout_s;
    if (rr.entity < 0) {
      fail(rh.source, robotField(r, "entity"), "unknown entity '" + rh.entity + "'");
    }
    const problem::Entity& e = problem.entity(rr.entity);
    std::vector<int> assigned(static_cast<std::size_t>(e.nv()), -1);
    const int robot_index = static_cast<int>(out.robots.size());
    out.robots.push_back(rr);
    ResolvedRobot& rob = out.robots.back();

    auto joint = [&](const std::string& name, const scene::Source& at, const std::string& field) {
      const int k = e.jointIndex(name);
      if (k < 0) {
        fail(at, field, "entity '" + rh.entity + "' has no joint '" + name + "'");
      }
      if (!e.actuated()[static_cast<std::size_t>(k)]) {
        fail(at, field, "joint '" + name + "' of '" + rh.entity + "' is not actuated in the scene");
      }
      if (assigned[static_cast<std::size_t>(k)] >= 0) {
        fail(at, field,
             "joint '" + name + "' already has a drive (line " +
                 std::to_string(assigned[static_cast<std::size_t>(k)]) + ")");
      }
      assigned[static_cast<std::size_t>(k)] = at.line;
      return k;
    };

    for (std::size_t g = 0; g < rh.cia402.size(); ++g) {
      const Cia402Group& grp = rh.cia402[g];
      const std::string field = robotField(r, "cia402[" + std::to_string(g) + "]");
      const int bus = busIndex(spec, grp.bus, grp.source, field + ".bus");
      claimBus(bus, robot_index, grp.source, field + ".bus");
      for (std::size_t j = 0; j < grp.joints.size(); ++j) {
        ResolvedDrive d;
        d.joint = joint(grp.joints[j], grp.source, field + ".joints[" + std::to_string(j) + "]");
        d.q_index = e.qIndexOfV(d.joint);
        d.joint_name = grp.joints[j];
        d.bus = bus;
        d.node = grp.first_node + static_cast<int>(j);
        d.mode = grp.mode;
        d.rated_torque = grp.rated_torque;
        d.identity = grp.identity;
        claimNode(bus, d.node, grp.source, field + ".joints[" + std::to_string(j) + "]");
        rob.drives.push_back(d);
      }
    }
    if (rh.rpdo_timeout_s > 0.0) {
      // The drives' RPDO1 deadline: there must be drives, and a deadline longer than the robot's
      // cycle (one RPDO per cycle), else a drive times out between two setpoints.
      const double cycle = dt * rh.divisor;
      if (rob.drives.empty()) {
        fail(rh.rpdo_timeout_source, robotField(r, "rpdo_timeout"),
             "'" + rh.entity + "' has no CiA 402 drives to write 0x1400:05 to");
      }
      if (rh.rpdo_timeout_s <= cycle) {
        fail(rh.rpdo_timeout_source, robotField(r, "rpdo_timeout"),
             "must exceed the robot's cycle of " + scene::formatNumber(cycle) +
                 " s (one RPDO per cycle), got " + scene::formatNumber(rh.rpdo_timeout_s));
      }
    }
    std::size_t mit_groups = 0, fd_groups = 0;
    for (std::size_t g = 0; g < rh.impedance.size(); ++g) {
      const ImpedanceGroup& grp = rh.impedance[g];
      const bool mit = grp.kind == "mit";
      const std::string field =
          robotField(r, grp.kind + "[" + std::to_string(mit ? mit_groups++ : fd_groups++) + "]");
      const int bus = busIndex(spec, grp.bus, grp.source, field + ".bus");
      claimBus(bus, robot_index, grp.source, field + ".bus");
      const BusDecl& bd = spec.buses[static_cast<std::size_t>(bus)];
      if (!mit && bd.data_bitrate == 0) {
        fail(grp.source, field + ".bus",
             "a hand board sends CAN FD frames: bus '" + grp.bus + "' has no data_bitrate");
      }
      if (!mit && !boards.emplace(bus, grp.first_id).second) {
        fail(grp.source, field + ".board",
             "board " + std::to_string(grp.first_id) + " on bus '" + grp.bus + "' is already used");
      }
      for (std::size_t j = 0; j < grp.joints.size(); ++j) {
        ResolvedDrive d;
        d.joint = joint(grp.joints[j], grp.source, field + ".joints[" + std::to_string(j) + "]");
        d.q_index = e.qIndexOfV(d.joint);
        d.joint_name = grp.joints[j];
        d.bus = bus;
        d.node = mit ? grp.first_id + static_cast<int>(j) : grp.first_id;
        d.kind = mit ? ActuatorKind::Mit : ActuatorKind::FdBoard;
        d.mode = DriveMode::Csp;
        d.group = static_cast<int>(g);
        d.kp = grp.kp;
        d.kd = grp.kd;
        if (mit) claimNode(bus, d.node, grp.source, field + ".joints[" + std::to_string(j) + "]");
        rob.impedance.push_back(d);
      }
    }
    auto sensors = [&](const std::vector<SensorDecl>& decls, const char* key,
                       std::vector<ResolvedSensor>& into) {
      for (std::size_t i = 0; i < decls.size(); ++i) {
        const SensorDecl& s = decls[i];
        const std::string field = robotField(r, std::string(key) + "[" + std::to_string(i) + "]");
        ResolvedSensor rs;
        rs.frame = e.frameIndex(s.frame);
        rs.frame_name = s.frame;
        if (rs.frame < 0) {
          fail(s.source, field + ".frame", "entity '" + rh.entity + "' has no frame '" + s.frame + "'");
        }
        rs.bus = busIndex(spec, s.bus, s.source, field + ".bus");
        claimBus(rs.bus, robot_index, s.source, field + ".bus");
        claimNode(rs.bus, s.node, s.source, field + ".node");
        rs.node = s.node;
        into.push_back(rs);
      }
    };
    sensors(rh.ft_sensors, "ft_sensors", rob.ft_sensors);
    sensors(rh.imus, "imus", rob.imus);
    if (!rh.imus.empty() && !e.floatingBase()) {
      fail(rh.imus.front().source, robotField(r, "imus"),
           "'" + rh.entity + "' has no floating base to estimate");
    }
    for (std::size_t i = 0; i < rob.imus.size(); ++i) {
      if (spec.buses[static_cast<std::size_t>(rob.imus[i].bus)].data_bitrate == 0) {
        fail(rh.imus[i].source, robotField(r, "imus[" + std::to_string(i) + "].bus"),
             "an IMU sends CAN FD frames: bus '" + rh.imus[i].bus + "' has no data_bitrate");
      }
    }
    for (int k = e.jointOffset(); k < e.nv(); ++k) {
      if (e.actuated()[static_cast<std::size_t>(k)] && assigned[static_cast<std::size_t>(k)] < 0) {
        fail(rh.source, robotField(r, ""),
             "actuated joint '" + std::string(e.jointName(k - e.jointOffset())) + "' of '" + rh.entity +
                 "' has no drive");
      }
    }
  }

  // MIT motors answer on identifier 0x000, CANopen's NMT: nothing else may share their bus.
  for (std::size_t r = 0; r < out.robots.size(); ++r) {
    const ResolvedRobot& rob = out.robots[r];
    for (const ResolvedDrive& m : rob.impedance) {
      if (m.kind != ActuatorKind::Mit) continue;
      bool shared = false;
      for (const ResolvedDrive& d : rob.drives) shared = shared || d.bus == m.bus;
      for (const ResolvedDrive& d : rob.impedance)
        shared = shared || (d.bus == m.bus && d.kind != ActuatorKind::Mit);
      for (const ResolvedSensor& x : rob.ft_sensors) shared = shared || x.bus == m.bus;
      for (const ResolvedSensor& x : rob.imus) shared = shared || x.bus == m.bus;
      if (shared) {
        const RobotHardware& rh = spec.robots[r];
        const auto grp = std::find_if(rh.impedance.begin(), rh.impedance.end(),
                                      [](const ImpedanceGroup& g) { return g.kind == "mit"; });
        fail(grp->source, robotField(r, "mit"),
             "MIT motors need a bus of their own: their replies use identifier 0x000 (CANopen's NMT), "
             "and bus '" +
                 out.buses[static_cast<std::size_t>(m.bus)].decl.name + "' carries other devices");
      }
    }
  }

  // The bus budget of every bus at the cycle rate of the robot it carries.
  for (std::size_t b = 0; b < out.buses.size(); ++b) {
    ResolvedBus& rb = out.buses[b];
    if (rb.robot < 0) {
      fail(rb.decl.source, "hardware.buses[" + std::to_string(b) + "]",
           "bus '" + rb.decl.name + "' carries nothing");
    }
    const ResolvedRobot& rob = out.robots[static_cast<std::size_t>(rb.robot)];
    drivers::BusSpec bs;
    bs.name = rb.decl.name;
    bs.nominal_bps = rb.decl.bitrate;
    bs.data_bps = rb.decl.data_bitrate;
    bs.cycle_hz = 1.0 / (dt * rob.divisor);
    rb.cycle_hz = bs.cycle_hz;
    drivers::BusBudget budget(bs);
    std::uint32_t drives = 0, mit = 0, ft = 0, imu = 0;
    for (const ResolvedDrive& d : rob.drives) drives += d.bus == static_cast<int>(b) ? 1u : 0u;
    std::vector<std::uint32_t> board_joints;  // per fd group on this bus
    int group = -1;
    for (const ResolvedDrive& d : rob.impedance) {
      if (d.bus != static_cast<int>(b)) continue;
      if (d.kind == ActuatorKind::Mit) {
        ++mit;
      } else {
        if (d.group != group) board_joints.push_back(0u);
        group = d.group;
        ++board_joints.back();
      }
    }
    for (const ResolvedSensor& s : rob.ft_sensors) ft += s.bus == static_cast<int>(b) ? 1u : 0u;
    for (const ResolvedSensor& s : rob.imus) imu += s.bus == static_cast<int>(b) ? 1u : 0u;
    if (drives > 0 || ft > 0 || imu > 0) budget.addSync();
    if (drives > 0) {
      budget.addArmDrives(drives, true);
      budget.addHeartbeats(drives, 0.1);
      // The controller's own heartbeat goes to every bus of CiA 402 drives (their 0x1016 watches it).
      if (out.controller_heartbeat.node != 0) {
        budget.addPeriodic("controller heartbeat", 1, 1, drivers::FrameFormat::Classic,
                           out.controller_heartbeat.period_s);
      }
    }
    if (mit > 0) budget.addMitMotors(mit);
    for (std::uint32_t joints : board_joints) budget.addHandBoard(joints);
    if (ft > 0) {
      if (rb.decl.data_bitrate != 0)
        budget.addFtFd(ft);
      else
        budget.addFtClassic(ft);
    }
    if (imu > 0) budget.addImuFd(imu);
    std::string message;
    if (!budget.check(&message)) {
      fail(rb.decl.source, "hardware.buses[" + std::to_string(b) + "]", message);
    }
    rb.utilisation_worst = budget.result().utilisation_worst;
    rb.report = budget.report();
  }
  return out;
}

void applyDriveIdentity(drivers::ArmDriveConfig& config, const ResolvedDrive& drive) {
  config.device_type = drive.identity.device_type;
  config.vendor_id = drive.identity.vendor_id;
  config.product_code = drive.identity.product_code;
  config.revision = drive.identity.revision;
}

void applySafetyConfig(drivers::ArmConfig& config, const ResolvedHardware& hw, const ResolvedRobot* robot) {
  if (robot != nullptr && robot->rpdo_timeout_s > 0.0) {
    config.rpdo_timeout_ms = static_cast<std::uint16_t>(std::lround(robot->rpdo_timeout_s * 1000.0));
  }
  const ControllerHeartbeatSpec& hb = hw.controller_heartbeat;
  if (hb.node != 0) {
    config.master_node = static_cast<std::uint8_t>(hb.node);
    config.master_heartbeat_ms = static_cast<std::uint16_t>(std::lround(hb.period_s * 1000.0));
    config.drive_consumer_ms = static_cast<std::uint16_t>(std::lround(hb.drive_timeout_s * 1000.0));
  }
  config.exit_stop = hw.safe_exit.stop == ExitStopKind::DisableVoltage ? drivers::ExitStop::DisableVoltage
                                                                       : drivers::ExitStop::QuickStop;
  config.exit_nmt = hw.safe_exit.nmt == ExitNmtKind::Stopped     ? drivers::ExitNmt::Stopped
                    : hw.safe_exit.nmt == ExitNmtKind::Unchanged ? drivers::ExitNmt::Unchanged
                                                                 : drivers::ExitNmt::PreOperational;
  config.recovery = drivers::RecoveryPolicy::Manual;
}

}  // namespace mrqp::loop
