// mrqp drivers -- inertial measurement units: construction and budget (setup).
#include "mrqp/drivers/imu_driver.hpp"
#include "router_setup.hpp"

namespace mrqp::drivers {

std::unique_ptr<ImuDriver> ImuDriver::create(const std::vector<BusRouter*>& buses, const ImuConfig& config,
                                             std::string* error) {
  auto fail = [error](const std::string& msg) {
    if (error != nullptr) {
      *error = "IMU driver: " + msg;
    }
    return std::unique_ptr<ImuDriver>();
  };
  if (const std::string why = detail::checkRouters(buses); !why.empty()) {
    return fail(why);
  }
  if (config.imus.empty()) {
    return fail("no IMU configured");
  }
  if (config.feedback_missing_cycles == 0u) {
    return fail("feedback_missing_cycles must be > 0");
  }
  std::vector<std::vector<bool>> used(buses.size(), std::vector<bool>(128, false));
  for (std::size_t i = 0; i < config.imus.size(); ++i) {
    const ImuSensorConfig& s = config.imus[i];
    const std::string who = "IMU " + std::to_string(i) + " (node " + std::to_string(s.node) + ")";
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
    if (mrqp_fw_imu_scale_valid(&s.scale) == 0) {
      return fail(who + ": invalid scale (counts per unit finite and > 0)");
    }
    if (!buses[s.bus]->bus().fdEnabled()) {
      return fail(who + ": bus " + std::to_string(s.bus) + " (" + buses[s.bus]->bus().name() +
                  ") is not CAN FD enabled (the IMU frame is CAN FD)");
    }
    if (!(s.rate_limit > 0.0) || !(s.force_limit > 0.0)) {
      return fail(who + ": rate_limit and force_limit must be > 0");
    }
  }
  std::unique_ptr<ImuDriver> p(new ImuDriver());
  p->config_ = config;
  p->buses_.resize(buses.size());
  for (BusSlot& b : p->buses_) {
    b.node_to_imu.fill(-1);
  }
  p->imus_.resize(config.imus.size());
  for (std::size_t i = 0; i < config.imus.size(); ++i) {
    p->imus_[i].cfg = config.imus[i];
    p->buses_[config.imus[i].bus].node_to_imu[config.imus[i].node] = static_cast<std::int16_t>(i);
    p->buses_[config.imus[i].bus].has_imus = true;
  }
  if (const std::string why = p->routers_.attach(buses, *p, p->imus_.size()); !why.empty()) {
    return fail(why);
  }
  return p;
}

void ImuDriver::declareTraffic(std::size_t bus, BusBudget& budget) const {
  std::uint32_t n = 0;
  for (const Imu& m : imus_) {
    n += m.cfg.bus == bus ? 1u : 0u;
  }
  if (config_.produce_sync && n > 0u) {
    budget.addSync();
  }
  budget.addImuFd(n);
}

}  // namespace mrqp::drivers
