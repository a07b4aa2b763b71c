// mrqp-bus-budget: prints the bus-budget tables of docs/drivers.md (markdown) for the reference
// robot (7 arm drives, 20 hand joints, 2 force/torque sensors) at 250/500/1000 Hz on classic
// 1 Mbit/s and CAN FD 1/5 Mbit/s buses with an 80 % limit.
//
//   mrqp-bus-budget                 the reference tables
//   mrqp-bus-budget DRIVES JOINTS FT [LIMIT_PERCENT]   another robot
#include <cstdio>
#include <cstdlib>
#include <string>

#include "mrqp/drivers/budget_table.hpp"

int main(int argc, char** argv) {
  if (argc == 1) {
    std::fputs(mrqp::drivers::referenceBudgetTables().c_str(), stdout);
    return 0;
  }
  if (argc != 4 && argc != 5) {
    std::fprintf(stderr, "usage: %s [DRIVES JOINTS FT [LIMIT_PERCENT]]\n", argv[0]);
    return 2;
  }
  mrqp::drivers::RobotTraffic robot;
  robot.arm_drives = static_cast<std::uint32_t>(std::strtoul(argv[1], nullptr, 10));
  robot.hand_joints = static_cast<std::uint32_t>(std::strtoul(argv[2], nullptr, 10));
  robot.ft_sensors = static_cast<std::uint32_t>(std::strtoul(argv[3], nullptr, 10));
  const double limit = argc == 5 ? std::strtod(argv[4], nullptr) / 100.0 : 0.8;
  if (!(limit > 0.0 && limit <= 1.0)) {
    std::fprintf(stderr, "%s: LIMIT_PERCENT must be in (0, 100]\n", argv[0]);
    return 2;
  }
  const std::string table = mrqp::drivers::budgetTableMarkdown(
      robot, {{"classic 1 Mbit/s", 1000000u, 0u}, {"CAN FD 1/5 Mbit/s", 1000000u, 5000000u}},
      {250.0, 500.0, 1000.0}, limit);
  std::fputs(table.c_str(), stdout);
  return 0;
}
