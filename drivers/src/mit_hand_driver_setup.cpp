// mrqp drivers -- MIT-mode hand actuators: construction and budget (setup).
#include <cmath>

#include "mrqp/drivers/mit_hand_driver.hpp"
#include "router_setup.hpp"

namespace mrqp::drivers {

std::unique_ptr<MitHandDriver> MitHandDriver::create(const std::vector<BusRouter*>& buses,
                                                     const MitHandConfig& config, std::string* error) {
  auto fail = [error](const std::string& msg) {
    if (error != nullptr) {
      *error = "MIT hand driver: " + msg;
    }
    return std::unique_ptr<MitHandDriver>();
  };
  if (const std::string why = detail::checkRouters(buses); !why.empty()) {
    return fail(why);
  }
  if (config.motors.empty()) {
    return fail("no motor configured");
  }
  if (config.feedback_missing_cycles == 0u || config.enable_timeout <= 0) {
    return fail("feedback_missing_cycles and enable_timeout must be > 0");
  }
  std::vector<std::vector<bool>> used(buses.size(), std::vector<bool>(128, false));
  for (std::size_t i = 0; i < config.motors.size(); ++i) {
    const MitMotorConfig& m = config.motors[i];
    const std::string who = "motor " + std::to_string(i) + " (id " + std::to_string(m.motor_id) + ")";
    if (m.bus >= buses.size()) {
      return fail(who + ": bus index " + std::to_string(m.bus) + " but only " + std::to_string(buses.size()) +
                  " bus(es) given");
    }
    if (m.motor_id < MRQP_FW_MIT_MOTOR_ID_MIN || m.motor_id > MRQP_FW_MIT_MOTOR_ID_MAX) {
      return fail(who + ": motor id must be 1..127");
    }
    if (used[m.bus][m.motor_id]) {
      return fail(who + ": motor id used twice on bus " + std::to_string(m.bus));
    }
    used[m.bus][m.motor_id] = true;
    if (mrqp_fw_mit_ranges_valid(&m.ranges) == 0) {
      return fail(who + ": invalid ranges (each min < max, finite)");
    }
    if (std::isnan(m.position_min) || std::isnan(m.position_max) || !(m.position_min < m.position_max)) {
      return fail(who + ": position_min must be < position_max");
    }
  }
  std::unique_ptr<MitHandDriver> p(new MitHandDriver());
  p->config_ = config;
  p->buses_.resize(buses.size());
  for (BusSlot& b : p->buses_) {
    b.id_to_motor.fill(-1);
  }
  p->motors_.resize(config.motors.size());
  for (std::size_t i = 0; i < config.motors.size(); ++i) {
    p->motors_[i].cfg = config.motors[i];
    p->buses_[config.motors[i].bus].id_to_motor[config.motors[i].motor_id] = static_cast<std::int16_t>(i);
  }
  if (const std::string why = p->routers_.attach(buses, *p, p->motors_.size()); !why.empty()) {
    return fail(why);
  }
  return p;
}

void MitHandDriver::declareTraffic(std::size_t bus, BusBudget& budget) const {
  std::uint32_t n = 0;
  for (const Motor& m : motors_) {
    n += m.cfg.bus == bus ? 1u : 0u;
  }
  budget.addMitMotors(n);
}

}  // namespace mrqp::drivers
