// mrqp drivers -- hand controller boards on CAN FD: construction and budget (setup).
#include "mrqp/drivers/fd_hand_driver.hpp"
#include "router_setup.hpp"

namespace mrqp::drivers {

std::unique_ptr<FdHandDriver> FdHandDriver::create(const std::vector<BusRouter*>& buses,
                                                   const FdHandConfig& config, std::string* error) {
  auto fail = [error](const std::string& msg) {
    if (error != nullptr) {
      *error = "FD hand driver: " + msg;
    }
    return std::unique_ptr<FdHandDriver>();
  };
  if (const std::string why = detail::checkRouters(buses); !why.empty()) {
    return fail(why);
  }
  if (config.boards.empty()) {
    return fail("no board configured");
  }
  if (config.enabled_mode != MRQP_FW_HAND_MODE_POSITION && config.enabled_mode != MRQP_FW_HAND_MODE_TORQUE) {
    return fail("enabled_mode must be POSITION (1) or TORQUE (2)");
  }
  if (config.feedback_missing_cycles == 0u || config.enable_timeout <= 0) {
    return fail("feedback_missing_cycles and enable_timeout must be > 0");
  }
  std::vector<std::vector<bool>> used(buses.size(), std::vector<bool>(16, false));
  for (std::size_t i = 0; i < config.boards.size(); ++i) {
    const HandBoardConfig& b = config.boards[i];
    const std::string who = "board " + std::to_string(i) + " (id " + std::to_string(b.board) + ")";
    if (b.bus >= buses.size()) {
      return fail(who + ": bus index " + std::to_string(b.bus) + " but only " + std::to_string(buses.size()) +
                  " bus(es) given");
    }
    if (!buses[b.bus]->bus().fdEnabled()) {
      return fail(who + ": bus " + std::to_string(b.bus) + " (" + buses[b.bus]->bus().name() +
                  ") is not CAN FD enabled");
    }
    if (b.board > MRQP_FW_HAND_BOARD_MAX) {
      return fail(who + ": board id must be 0..15");
    }
    if (used[b.bus][b.board]) {
      return fail(who + ": board id used twice on bus " + std::to_string(b.bus));
    }
    used[b.bus][b.board] = true;
    if (b.joints == 0u || b.joints > MRQP_FW_HAND_MAX_JOINTS) {
      return fail(who + ": joints must be 1..32");
    }
    if (mrqp_fw_hand_scale_valid(&b.scale) == 0) {
      return fail(who + ": invalid scale (each LSB finite and > 0)");
    }
  }
  std::unique_ptr<FdHandDriver> p(new FdHandDriver());
  p->config_ = config;
  p->buses_.resize(buses.size());
  for (BusSlot& s : p->buses_) {
    s.board_to_index.fill(-1);
  }
  p->boards_.resize(config.boards.size());
  for (std::size_t i = 0; i < config.boards.size(); ++i) {
    Board& b = p->boards_[i];
    b.cfg = config.boards[i];
    b.chunks = mrqp_fw_hand_frames_needed(b.cfg.joints);
    p->joint_count_ += b.cfg.joints;
    p->buses_[b.cfg.bus].board_to_index[b.cfg.board] = static_cast<std::int16_t>(i);
  }
  if (const std::string why = p->routers_.attach(buses, *p, p->boards_.size()); !why.empty()) {
    return fail(why);
  }
  return p;
}

void FdHandDriver::declareTraffic(std::size_t bus, BusBudget& budget) const {
  for (const Board& b : boards_) {
    if (b.cfg.bus == bus) {
      budget.addHandBoard(b.cfg.joints);
    }
  }
}

}  // namespace mrqp::drivers
