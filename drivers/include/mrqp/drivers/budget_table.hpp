// mrqp drivers -- how many buses a robot needs: bus plans and the markdown table of docs/drivers.md.
//
// planBuses() places a robot's devices on buses of one kind at one cycle rate, first fit, each
// bus within the utilisation limit (worst-case stuffing): arm drives and force/torque sensors on
// CANopen "arm" buses (one SYNC per bus, drive heartbeats averaged), hand actuators on their own
// "hand" buses (MIT motors on a classic bus: their replies use identifier 0x000, the NMT
// identifier of a CANopen bus; on a CAN FD bus the hand controller board with all joints, split
// into several boards only if one board cannot fit a bus). Setup / tooling only (allocates).
#pragma once

#include <cstdint>
#include <string>
#include <vector>

namespace mrqp::drivers {

struct RobotTraffic {
  std::uint32_t arm_drives = 7;
  std::uint32_t hand_joints = 20;
  std::uint32_t ft_sensors = 2;
  bool arm_tpdo2 = true;            ///< velocity / error code / mode feedback every cycle
  double heartbeat_period_s = 0.1;  ///< drive heartbeat producer time
};

struct BusKind {
  std::string label;  ///< e.g. "classic 1 Mbit/s"
  std::uint32_t nominal_bps = 1000000;
  std::uint32_t data_bps = 0;  ///< > 0: CAN FD
};

struct PlannedBus {
  bool hand = false;  ///< a hand bus (else an arm bus)
  std::uint32_t arm_drives = 0;
  std::uint32_t ft_sensors = 0;
  std::uint32_t mit_motors = 0;
  std::uint32_t hand_joints = 0;  ///< joints of hand boards on this bus
  std::uint32_t hand_boards = 0;
  double utilisation_worst = 0.0;
  std::string content;  ///< "7 drives + 1 F/T"
};

struct BusPlan {
  bool feasible = true;
  std::string error;  ///< why not (a single device exceeds a bus)
  std::vector<PlannedBus> buses;
  std::size_t arm_buses = 0;
  std::size_t hand_buses = 0;
  std::uint32_t max_drives_per_bus = 0;  ///< arm drives alone on one bus (with SYNC)
  std::uint32_t max_mit_per_bus = 0;     ///< MIT motors on one classic bus (0 on FD)
  double fullest = 0.0;                  ///< largest worst-case utilisation
};

BusPlan planBuses(const RobotTraffic& robot, const BusKind& kind, double cycle_hz, double limit);

/// The table of docs/drivers.md: one row per (rate, bus kind).
std::string budgetTableMarkdown(const RobotTraffic& robot, const std::vector<BusKind>& kinds,
                                const std::vector<double>& rates_hz, double limit);
/// The project's reference table: 7 arm drives + 20 hand joints + 2 F/T sensors at 250, 500 and
/// 1000 Hz on classic 1 Mbit/s and CAN FD 1/5 Mbit/s, 80 % limit, with and without TPDO2.
std::string referenceBudgetTables();

}  // namespace mrqp::drivers
