// mrqp drivers -- force/torque sensors: construction and budget (setup).
#include "mrqp/drivers/ft_sensor_driver.hpp"
#include "router_setup.hpp"

namespace mrqp::drivers {

std::unique_ptr<FtSensorDriver> FtSensorDriver::create(const std::vector<BusRouter*>& buses,
                                                       const FtConfig& config, std::string* error) {
  auto fail = [error](const std::string& msg) {
    if (error != nullptr) {
      *error = "F/T sensor driver: " + msg;
    }
    return std::unique_ptr<FtSensorDriver>();
  };
  if (const std::string why = detail::checkRouters(buses); !why.empty()) {
    return fail(why);
  }
  if (config.sensors.empty()) {
    return fail("no sensor configured");
  }
  if (config.feedback_missing_cycles == 0u || config.tare_timeout <= 0) {
    return fail("feedback_missing_cycles and tare_timeout must be > 0");
  }
  std::vector<std::vector<bool>> used(buses.size(), std::vector<bool>(128, false));
  for (std::size_t i = 0; i < config.sensors.size(); ++i) {
    const FtSensorConfig& s = config.sensors[i];
    const std::string who = "sensor " + std::to_string(i) + " (node " + std::to_string(s.node) + ")";
    if (s.bus >= buses.size()) {
      return fail(who + ": bus index " + std::to_string(s.bus) + " but only " + std::to_string(buses.size()) +
                  " bus(es) given");
    }
    if (s.node < 1u || s.node > 127u) {
      return fail(who + ": node id must be 1..127");
    }
    if (used[s.bus][s.node]) {
      return fail(who + ": node id used twice on bus " + std::to_string(s.bus));
    }
    used[s.bus][s.node] = true;
    if (mrqp_fw_ft_scale_valid(&s.scale) == 0) {
      return fail(who + ": invalid scale (counts per unit finite and > 0)");
    }
    if (s.variant == FtVariant::Fd && !buses[s.bus]->bus().fdEnabled()) {
      return fail(who + ": FD variant on bus " + std::to_string(s.bus) + " (" + buses[s.bus]->bus().name() +
                  ") which is not CAN FD enabled");
    }
    if (!(s.force_limit > 0.0) || !(s.moment_limit > 0.0)) {
      return fail(who + ": force_limit and moment_limit must be > 0");
    }
  }
  std::unique_ptr<FtSensorDriver> p(new FtSensorDriver());
  p->config_ = config;
  p->buses_.resize(buses.size());
  for (BusSlot& b : p->buses_) {
    b.node_to_sensor.fill(-1);
  }
  p->sensors_.resize(config.sensors.size());
  for (std::size_t i = 0; i < config.sensors.size(); ++i) {
    p->sensors_[i].cfg = config.sensors[i];
    p->buses_[config.sensors[i].bus].node_to_sensor[config.sensors[i].node] = static_cast<std::int16_t>(i);
    p->buses_[config.sensors[i].bus].has_sensors = true;
  }
  if (const std::string why = p->routers_.attach(buses, *p, p->sensors_.size()); !why.empty()) {
    return fail(why);
  }
  return p;
}

void FtSensorDriver::declareTraffic(std::size_t bus, BusBudget& budget) const {
  std::uint32_t classic = 0;
  std::uint32_t fd = 0;
  for (const Sensor& s : sensors_) {
    if (s.cfg.bus == bus) {
      (s.cfg.variant == FtVariant::Fd ? fd : classic) += 1u;
    }
  }
  if (config_.produce_sync && classic + fd > 0u) {
    budget.addSync();
  }
  budget.addFtClassic(classic);
  budget.addFtFd(fd);
}

}  // namespace mrqp::drivers
