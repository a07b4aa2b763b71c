// The emulated hardware of a scene (see emulated_rig.hpp).
#include "loop/emulated_rig.hpp"

#include <algorithm>
#include <stdexcept>

#include "loop/actuator_scaling.hpp"

namespace mrqp::loop {

EmulatedRig::EmulatedRig(const ResolvedHardware& hw, const problem::MultiRobotProblem& problem, Plant& plant)
    : plant_(plant) {
  for (const ResolvedBus& b : hw.buses) {
    drivers::SimBusConfig bc;
    bc.nominal_bps = b.decl.bitrate;
    bc.data_bps = b.decl.data_bitrate;
    bc.max_nodes = 160;
    buses_.push_back(std::make_unique<drivers::SimBus>(bc));
    drivers::SimNodeConfig mc;
    mc.name = "controller";
    mc.fd = b.decl.data_bitrate != 0;
    mc.tx_queue = 256;
    mc.rx_queue = 1024;
    masters_.push_back(buses_.back()->addNode(mc));
  }
  for (const ResolvedRobot& r : hw.robots) {
    const problem::Entity& e = problem.entity(r.entity);
    for (const ResolvedDrive& d : r.drives) {
      drivers::SimNodeConfig nc;
      nc.name = "cia402";
      nc.fd = hw.buses[static_cast<std::size_t>(d.bus)].decl.data_bitrate !=
              0;  // an FD-capable controller on an FD bus
      drivers::SimNode* node = buses_[static_cast<std::size_t>(d.bus)]->addNode(nc);
      if (node == nullptr) {
        throw std::runtime_error("emulated rig: too many nodes on one bus");
      }
      PlantDriveOptions o;
      o.node = static_cast<std::uint8_t>(d.node);
      o.joint = plant.jointHandle(r.name, d.joint_name);
      if (o.joint < 0) {
        throw std::runtime_error("emulated rig: the " + std::string(plant.kind()) + " plant has no joint '" +
                                 d.joint_name + "' of '" + r.name + "'");
      }
      // The drive watches the controller's heartbeat when the hardware section has one (the
      // controller then writes 0x1016:1); it reacts by a fault (0x6007 = 1) and pre-operational.
      o.profile.heartbeat_consumer = true;
      o.torque_mode = d.mode == DriveMode::Cst;
      o.rated_torque = d.rated_torque;
      const double limit = e.effortLimit()(d.joint);
      o.torque_limit = limit > 0.0 ? limit : 1e9;
      drives_.push_back(
          DriveSlot{r.name + "." + d.joint_name, std::make_unique<PlantCia402Drive>(*node, plant, o)});
    }
    // MIT motors: one node per bus for all of the robot's motors there; hand boards: one node each.
    auto jointOf = [&](const ResolvedDrive& d) {
      const int h = plant.jointHandle(r.name, d.joint_name);
      if (h < 0) {
        throw std::runtime_error("emulated rig: the " + std::string(plant.kind()) + " plant has no joint '" +
                                 d.joint_name + "' of '" + r.name + "'");
      }
      return h;
    };
    auto addNode = [&](int bus, const char* name) {
      drivers::SimNodeConfig nc;
      nc.name = name;
      nc.fd = hw.buses[static_cast<std::size_t>(bus)].decl.data_bitrate != 0;
      drivers::SimNode* node = buses_[static_cast<std::size_t>(bus)]->addNode(nc);
      if (node == nullptr) throw std::runtime_error("emulated rig: too many nodes on one bus");
      return node;
    };
    for (const ResolvedDrive& d : r.impedance) {
      if (d.kind == ActuatorKind::Mit) {
        PlantActuators<emulation::EmulatedMitMotor>* on = nullptr;
        for (std::size_t i = 0; i < mit_.size(); ++i) {
          if (mit_bus_[i] == d.bus) on = mit_[i].get();
        }
        if (on == nullptr) {
          mit_.push_back(
              std::make_unique<PlantActuators<emulation::EmulatedMitMotor>>(*addNode(d.bus, "mit"), plant));
          mit_bus_.push_back(d.bus);
          on = mit_.back().get();
        }
        emulation::EmulatedMitMotor::Options o;
        o.motor_id = static_cast<std::uint8_t>(d.node);
        o.ranges = mitRanges(e, d.joint);
        const std::size_t j = on->host().addJoint(jointOf(d), e.effortLimit()(d.joint));
        mit_joints_.emplace_back(r.name + "." + d.joint_name, &on->add(o, j));
      }
    }
    for (std::size_t i = 0; i < r.impedance.size();) {
      const ResolvedDrive& first = r.impedance[i];
      if (first.kind != ActuatorKind::FdBoard) {
        ++i;
        continue;
      }
      boards_.push_back(
          std::make_unique<PlantActuators<emulation::EmulatedHandBoard>>(*addNode(first.bus, "hand"), plant));
      PlantActuators<emulation::EmulatedHandBoard>& b = *boards_.back();
      std::size_t n = 0, j0 = 0;
      std::vector<int> joints;
      for (; i + n < r.impedance.size() && r.impedance[i + n].kind == ActuatorKind::FdBoard &&
             r.impedance[i + n].group == first.group;
           ++n) {
        const ResolvedDrive& d = r.impedance[i + n];
        const std::size_t j = b.host().addJoint(jointOf(d), e.effortLimit()(d.joint));
        if (n == 0) j0 = j;
        joints.push_back(d.joint);
      }
      emulation::EmulatedHandBoard::Options o;
      o.scale = handScale(e, joints);
      o.board = static_cast<std::uint8_t>(first.node);
      o.joints = static_cast<std::uint8_t>(n);
      emulation::EmulatedHandBoard* board = &b.add(o, j0);
      for (std::size_t k = 0; k < n; ++k)
        board_joints_.emplace_back(r.name + "." + r.impedance[i + k].joint_name, board);
      i += n;
    }
    auto frameOf = [&](const ResolvedSensor& s) {
      const int f = plant.frameHandle(r.name, s.frame_name);
      if (f < 0) {
        throw std::runtime_error("emulated rig: the " + std::string(plant.kind()) + " plant has no frame '" +
                                 s.frame_name + "' of '" + r.name + "'");
      }
      return f;
    };
    for (const ResolvedSensor& s : r.ft_sensors) {
      drivers::SimNodeConfig nc;
      nc.name = "ft";
      nc.fd = hw.buses[static_cast<std::size_t>(s.bus)].decl.data_bitrate != 0;
      drivers::SimNode* node = buses_[static_cast<std::size_t>(s.bus)]->addNode(nc);
      if (node == nullptr) throw std::runtime_error("emulated rig: too many nodes on one bus");
      ft_.emplace_back(
          r.name + "." + s.frame_name,
          std::make_unique<PlantFtSensor>(*node, plant, frameOf(s), static_cast<std::uint8_t>(s.node)));
    }
    for (const ResolvedSensor& s : r.imus) {
      drivers::SimNodeConfig nc;
      nc.name = "imu";
      nc.fd = true;
      drivers::SimNode* node = buses_[static_cast<std::size_t>(s.bus)]->addNode(nc);
      if (node == nullptr) throw std::runtime_error("emulated rig: too many nodes on one bus");
      imus_.emplace_back(
          r.name + "." + s.frame_name,
          std::make_unique<PlantImu>(*node, plant, frameOf(s), static_cast<std::uint8_t>(s.node)));
    }
  }
}

emulation::EmulatedMitMotor* EmulatedRig::mitMotor(const std::string& joint) noexcept {
  for (auto& [n, m] : mit_joints_) {
    if (n == joint) return m;
  }
  return nullptr;
}

emulation::EmulatedHandBoard* EmulatedRig::handBoard(const std::string& joint) noexcept {
  for (auto& [n, b] : board_joints_) {
    if (n == joint) return b;
  }
  return nullptr;
}

PlantFtSensor* EmulatedRig::ftSensor(const std::string& name) noexcept {
  for (auto& [n, s] : ft_) {
    if (name.empty() || n == name) return s.get();
  }
  return nullptr;
}

PlantImu* EmulatedRig::imu(const std::string& name) noexcept {
  for (auto& [n, s] : imus_) {
    if (name.empty() || n == name) return s.get();
  }
  return nullptr;
}

const std::string& EmulatedRig::ftSensorName(const PlantFtSensor* sensor) const {
  for (const auto& [n, s] : ft_) {
    if (s.get() == sensor) return n;
  }
  static const std::string none;
  return none;
}

void EmulatedRig::advanceTo(drivers::TimeNs t) noexcept {
  for (auto& b : buses_) {
    b->advanceTo(t);
  }
  while (now_ < t) {
    const drivers::TimeNs step = std::min(max_step_, t - now_);
    plant_.step(static_cast<double>(step) * 1e-9);
    now_ += step;
  }
}

PlantCia402Drive* EmulatedRig::drive(const std::string& name) noexcept {
  for (DriveSlot& d : drives_) {
    if (d.name == name) return d.drive.get();
  }
  return nullptr;
}

const std::string& EmulatedRig::driveName(const PlantCia402Drive* drive) const {
  for (const DriveSlot& d : drives_) {
    if (d.drive.get() == drive) return d.name;
  }
  static const std::string none;
  return none;
}

}  // namespace mrqp::loop
