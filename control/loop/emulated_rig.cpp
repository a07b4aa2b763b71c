// The emulated hardware of a scene (see emulated_rig.hpp).
#include "loop/emulated_rig.hpp"

#include <algorithm>
#include <stdexcept>

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
    masters_.push_back(buses_.back()->add_node(mc));
  }
  for (const ResolvedRobot& r : hw.robots) {
    const problem::Entity& e = problem.entity(r.entity);
    for (const ResolvedDrive& d : r.drives) {
      drivers::SimNodeConfig nc;
      nc.name = "cia402";
      nc.fd = hw.buses[static_cast<std::size_t>(d.bus)].decl.data_bitrate !=
              0;  // an FD-capable controller on an FD bus
      drivers::SimNode* node = buses_[static_cast<std::size_t>(d.bus)]->add_node(nc);
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
      o.torque_mode = d.mode == DriveMode::Cst;
      o.rated_torque = d.rated_torque;
      const double limit = e.effortLimit()(d.joint);
      o.torque_limit = limit > 0.0 ? limit : 1e9;
      drives_.push_back(
          DriveSlot{r.name + "." + d.joint_name, std::make_unique<PlantCia402Drive>(*node, plant, o)});
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
      drivers::SimNode* node = buses_[static_cast<std::size_t>(s.bus)]->add_node(nc);
      if (node == nullptr) throw std::runtime_error("emulated rig: too many nodes on one bus");
      ft_.emplace_back(
          r.name + "." + s.frame_name,
          std::make_unique<PlantFtSensor>(*node, plant, frameOf(s), static_cast<std::uint8_t>(s.node)));
    }
    for (const ResolvedSensor& s : r.imus) {
      drivers::SimNodeConfig nc;
      nc.name = "imu";
      nc.fd = true;
      drivers::SimNode* node = buses_[static_cast<std::size_t>(s.bus)]->add_node(nc);
      if (node == nullptr) throw std::runtime_error("emulated rig: too many nodes on one bus");
      imus_.emplace_back(
          r.name + "." + s.frame_name,
          std::make_unique<PlantImu>(*node, plant, frameOf(s), static_cast<std::uint8_t>(s.node)));
    }
  }
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
    b->advance_to(t);
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
