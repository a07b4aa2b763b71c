// The robot I/O map built from the resolved hardware section (see robot_io.hpp): the drivers of
// one robot on its buses and each driven joint and sensor as (device, index).
#include "loop/robot_io.hpp"

#include <mrqp/drivers/arm_driver.hpp>
#include <mrqp/drivers/fd_hand_driver.hpp>
#include <mrqp/drivers/ft_sensor_driver.hpp>
#include <mrqp/drivers/imu_driver.hpp>
#include <mrqp/drivers/mit_hand_driver.hpp>

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "loop/actuator_scaling.hpp"

namespace mrqp::loop {

namespace {

/// What set-up needs of one robot: its hardware, its entity, its buses in the order of the
/// hardware section (index of a bus among the robot's own = the driver's bus index).
struct RobotBuses {
  const ResolvedHardware& hw;
  const ResolvedRobot& rr;
  const problem::Entity& e;
  std::vector<int> bus_of_router;

  std::size_t routerIndex(int bus) const {
    return static_cast<std::size_t>(std::find(bus_of_router.begin(), bus_of_router.end(), bus) -
                                    bus_of_router.begin());
  }
  /// A bus with CiA 402 drives has their SYNC; a bus without needs one from its sensors.
  bool hasDrives(int bus) const {
    return std::any_of(rr.drives.begin(), rr.drives.end(),
                       [bus](const ResolvedDrive& d) { return d.bus == bus; });
  }
};

void addJoint(RobotIo& r, drivers::JointDevice* dev, std::size_t index, const ResolvedDrive& d,
              JointKind kind) {
  JointIo j;
  j.device = dev;
  j.index = index;
  j.v_index = d.joint;
  j.q_index = d.q_index;
  j.kind = kind;
  j.torque = kind == JointKind::Torque;
  j.name = r.name + "." + d.joint_name;
  r.joints.push_back(j);
}

void addArm(RobotIo& r, const RobotBuses& rb, double dt) {
  if (rb.rr.drives.empty()) return;
  drivers::ArmConfig ac;
  ac.cycle_period = static_cast<drivers::TimeNs>(std::llround(dt * rb.rr.divisor * 1e9));
  ac.heartbeat_timeout = static_cast<drivers::TimeNs>(std::llround(rb.hw.heartbeat_timeout_s * 1e9));
  ac.feedback_missing_cycles = static_cast<std::uint32_t>(rb.hw.feedback_missing_cycles);
  applySafetyConfig(ac, rb.hw, &rb.rr);  // controller heartbeat, safe exit, RPDO timeout
  for (const ResolvedDrive& d : rb.rr.drives) {
    drivers::ArmDriveConfig dc;
    dc.bus = rb.routerIndex(d.bus);
    dc.node = static_cast<std::uint8_t>(d.node);
    dc.scale.rated_torque_mNm = static_cast<std::uint32_t>(std::lround(d.rated_torque * 1000.0));
    dc.mode = d.mode == DriveMode::Csp ? MRQP_FW_MODE_CSP : MRQP_FW_MODE_CST;
    const double lim = rb.e.effortLimit()(d.joint);
    if (lim > 0.0) dc.torque_limit = lim;
    applyDriveIdentity(dc, d);  // checked at boot (hardware.robots[].cia402[].vendor_id...)
    ac.drives.push_back(dc);
  }
  std::string err;
  std::unique_ptr<drivers::ArmDriver> arm = drivers::ArmDriver::create(r.routers, ac, &err);
  if (!arm) throw std::runtime_error("controller: " + r.name + ": " + err);
  for (std::size_t i = 0; i < rb.rr.drives.size(); ++i) {
    const ResolvedDrive& d = rb.rr.drives[i];
    addJoint(r, arm.get(), i, d, d.mode == DriveMode::Cst ? JointKind::Torque : JointKind::Position);
  }
  r.devices.push_back(std::move(arm));
}

void addMit(RobotIo& r, const RobotBuses& rb) {
  drivers::MitHandConfig mc;
  mc.feedback_missing_cycles = static_cast<std::uint32_t>(rb.hw.feedback_missing_cycles);
  std::vector<const ResolvedDrive*> joints;
  for (const ResolvedDrive& d : rb.rr.impedance) {
    if (d.kind != ActuatorKind::Mit) continue;
    drivers::MitMotorConfig c;
    c.bus = rb.routerIndex(d.bus);
    c.motor_id = static_cast<std::uint8_t>(d.node);
    c.default_kp = static_cast<float>(d.kp);
    c.default_kd = static_cast<float>(d.kd);
    c.quick_stop_kd = static_cast<float>(d.kd);
    c.ranges = mitRanges(rb.e, d.joint);
    mc.motors.push_back(c);
    joints.push_back(&d);
  }
  if (joints.empty()) return;
  std::string err;
  std::unique_ptr<drivers::MitHandDriver> mit = drivers::MitHandDriver::create(r.routers, mc, &err);
  if (!mit) throw std::runtime_error("controller: " + r.name + ": MIT motors: " + err);
  for (std::size_t i = 0; i < joints.size(); ++i) addJoint(r, mit.get(), i, *joints[i], JointKind::Impedance);
  r.devices.push_back(std::move(mit));
}

void addFd(RobotIo& r, const RobotBuses& rb) {
  drivers::FdHandConfig fc;
  fc.feedback_missing_cycles = static_cast<std::uint32_t>(rb.hw.feedback_missing_cycles);
  std::vector<const ResolvedDrive*> joints;
  int group = -1;
  for (const ResolvedDrive& d : rb.rr.impedance) {
    if (d.kind != ActuatorKind::FdBoard) continue;
    if (d.group != group) {  // an fd group is one board, its joints in the board's order
      group = d.group;
      drivers::HandBoardConfig c;
      c.bus = rb.routerIndex(d.bus);
      c.board = static_cast<std::uint8_t>(d.node);
      c.joints = 0;
      fc.boards.push_back(c);
    }
    ++fc.boards.back().joints;
    joints.push_back(&d);
  }
  if (joints.empty()) return;
  std::size_t first = 0;
  for (drivers::HandBoardConfig& b : fc.boards) {
    std::vector<int> v;
    for (std::size_t k = 0; k < b.joints; ++k) v.push_back(joints[first + k]->joint);
    b.scale = handScale(rb.e, v);
    first += b.joints;
  }
  std::string err;
  std::unique_ptr<drivers::FdHandDriver> fd = drivers::FdHandDriver::create(r.routers, fc, &err);
  if (!fd) throw std::runtime_error("controller: " + r.name + ": FD hand boards: " + err);
  for (std::size_t i = 0; i < joints.size(); ++i) addJoint(r, fd.get(), i, *joints[i], JointKind::Impedance);
  r.devices.push_back(std::move(fd));
}

/// F/T sensors and IMUs alike: one driver for all of a robot's sensors of the kind, a SYNC of its
/// own on a bus without drives.
template <class Driver, class Config, class SensorConfig>
void addSensors(RobotIo& r, const RobotBuses& rb, const std::vector<ResolvedSensor>& decls,
                std::vector<SensorConfig> Config::*list, const char* what, std::vector<SensorIo>& into) {
  if (decls.empty()) return;
  Config c;
  c.feedback_missing_cycles = static_cast<std::uint32_t>(rb.hw.feedback_missing_cycles);
  for (const ResolvedSensor& s : decls) {
    SensorConfig sc;
    sc.bus = rb.routerIndex(s.bus);
    sc.node = static_cast<std::uint8_t>(s.node);
    (c.*list).push_back(sc);
    c.produce_sync = c.produce_sync || !rb.hasDrives(s.bus);
  }
  std::string err;
  std::unique_ptr<Driver> driver = Driver::create(r.routers, c, &err);
  if (!driver) throw std::runtime_error("controller: " + r.name + ": " + what + ": " + err);
  for (std::size_t i = 0; i < decls.size(); ++i) {
    into.push_back(SensorIo{driver.get(), i, decls[i].frame, r.name + "." + decls[i].frame_name, 0});
  }
  r.devices.push_back(std::move(driver));
}

}  // namespace

RobotIo makeRobotIo(const ResolvedHardware& hw, std::size_t robot, const problem::Entity& entity,
                    const std::vector<drivers::BusRouter*>& routers, double dt) {
  const ResolvedRobot& rr = hw.robots[robot];
  RobotIo r;
  r.entity = rr.entity;
  r.name = rr.name;
  r.divisor = rr.divisor;
  r.safe_stop = rr.safe_stop;
  r.hold_damping = rr.hold_damping;
  RobotBuses rb{hw, rr, entity, {}};
  for (std::size_t b = 0; b < hw.buses.size(); ++b) {
    if (hw.buses[b].robot == static_cast<int>(robot)) {
      rb.bus_of_router.push_back(static_cast<int>(b));
      r.routers.push_back(routers[b]);
    }
  }
  addArm(r, rb, dt);
  addMit(r, rb);
  addFd(r, rb);
  addSensors<drivers::FtSensorDriver>(r, rb, rr.ft_sensors, &drivers::FtConfig::sensors, "F/T sensors",
                                      r.ft_sensors);
  addSensors<drivers::ImuDriver>(r, rb, rr.imus, &drivers::ImuConfig::imus, "IMUs", r.imus);
  r.wrench.assign(r.ft_sensors.size(), std::array<double, 6>{});
  r.imu.assign(r.imus.size(), drivers::ImuFeedback{});
  const std::size_t n = r.joints.size();
  r.q_cmd.assign(n, 0.0);
  r.v_cmd.assign(n, 0.0);
  r.tau_cmd.assign(n, 0.0);
  r.q_meas.assign(n, 0.0);
  r.v_meas.assign(n, 0.0);
  r.stale.assign(n, 0);
  r.q_sent.assign(n, 0.0);
  r.v_sent.assign(n, 0.0);
  r.v_sent_before.assign(n, 0.0);
  r.miss_rate.assign(n, 0.0);
  return r;
}

}  // namespace mrqp::loop
