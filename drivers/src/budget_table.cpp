// mrqp drivers -- bus plans and the budget table (tooling; allocates).
#include "mrqp/drivers/budget_table.hpp"

#include <algorithm>
#include <cstdio>

#include "mrqp/drivers/bus_budget.hpp"

namespace mrqp::drivers {

namespace {

std::string pct(double u) {
  char buf[32];
  std::snprintf(buf, sizeof(buf), "%.1f %%", 100.0 * u);
  return buf;
}

BusSpec specOf(const BusKind& kind, double cycle_hz, double limit) {
  BusSpec s;
  s.name = kind.label;
  s.nominal_bps = kind.nominal_bps;
  s.data_bps = kind.data_bps;
  s.cycle_hz = cycle_hz;
  s.limit = limit;
  return s;
}

double armLoad(const RobotTraffic& robot, const BusKind& kind, double hz, double limit, std::uint32_t drives,
               std::uint32_t ft) {
  BusBudget b(specOf(kind, hz, limit));
  if (drives + ft > 0u) {
    b.addSync();
  }
  b.addArmDrives(drives, robot.arm_tpdo2);
  if (robot.heartbeat_period_s > 0.0) {
    b.addHeartbeats(drives, robot.heartbeat_period_s);
  }
  if (kind.data_bps > 0u) {
    b.addFtFd(ft);
  } else {
    b.addFtClassic(ft);
  }
  return b.result().utilisation_worst;
}

double handLoad(const BusKind& kind, double hz, double limit, std::uint32_t mit,
                const std::vector<std::uint32_t>& boards) {
  BusBudget b(specOf(kind, hz, limit));
  b.addMitMotors(mit);
  for (std::uint32_t joints : boards) {
    b.addHandBoard(joints);
  }
  return b.result().utilisation_worst;
}

bool fits(double u, double limit) { return u <= limit + 1e-12; }

struct ArmBus {
  std::uint32_t drives = 0;
  std::uint32_t ft = 0;
};

struct HandBus {
  std::uint32_t mit = 0;
  std::vector<std::uint32_t> boards;
};

std::string armContent(std::uint32_t drives, std::uint32_t ft) {
  std::string s;
  if (drives > 0u) {
    s += std::to_string(drives) + (drives == 1u ? " drive" : " drives");
  }
  if (ft > 0u) {
    s += (s.empty() ? "" : " + ") + std::to_string(ft) + " F/T";
  }
  return s;
}

std::string handContent(const HandBus& h) {
  if (h.mit > 0u) {
    return std::to_string(h.mit) + " MIT";
  }
  std::string s;
  for (std::uint32_t j : h.boards) {
    s += (s.empty() ? "" : " + ") + std::string("board of ") + std::to_string(j) + " joints";
  }
  return s;
}

}  // namespace

BusPlan planBuses(const RobotTraffic& robot, const BusKind& kind, double cycle_hz, double limit) {
  BusPlan plan;
  const bool fd = kind.data_bps > 0u;

  for (std::uint32_t k = 1; k <= 127u; ++k) {
    if (!fits(armLoad(robot, kind, cycle_hz, limit, k, 0), limit)) {
      break;
    }
    plan.max_drives_per_bus = k;
  }
  if (!fd) {
    for (std::uint32_t k = 1; k <= 127u; ++k) {
      if (!fits(handLoad(kind, cycle_hz, limit, k, {}), limit)) {
        break;
      }
      plan.max_mit_per_bus = k;
    }
  }

  // Arm buses: drives first, then the force/torque sensors, first fit.
  std::vector<ArmBus> arm;
  auto place_arm = [&](bool drive) {
    for (ArmBus& b : arm) {
      const std::uint32_t d = b.drives + (drive ? 1u : 0u);
      const std::uint32_t f = b.ft + (drive ? 0u : 1u);
      if (fits(armLoad(robot, kind, cycle_hz, limit, d, f), limit)) {
        b.drives = d;
        b.ft = f;
        return true;
      }
    }
    ArmBus b;
    (drive ? b.drives : b.ft) = 1u;
    if (!fits(armLoad(robot, kind, cycle_hz, limit, b.drives, b.ft), limit)) {
      return false;
    }
    arm.push_back(b);
    return true;
  };
  for (std::uint32_t i = 0; i < robot.arm_drives && plan.feasible; ++i) {
    if (!place_arm(true)) {
      plan.feasible = false;
      plan.error = "one arm drive alone exceeds a bus";
    }
  }
  for (std::uint32_t i = 0; i < robot.ft_sensors && plan.feasible; ++i) {
    if (!place_arm(false)) {
      plan.feasible = false;
      plan.error = "one force/torque sensor alone exceeds a bus";
    }
  }

  // Hand buses.
  std::vector<HandBus> hand;
  if (plan.feasible && robot.hand_joints > 0u) {
    if (!fd) {
      for (std::uint32_t i = 0; i < robot.hand_joints && plan.feasible; ++i) {
        bool placed = false;
        for (HandBus& b : hand) {
          if (fits(handLoad(kind, cycle_hz, limit, b.mit + 1u, {}), limit)) {
            ++b.mit;
            placed = true;
            break;
          }
        }
        if (!placed) {
          if (!fits(handLoad(kind, cycle_hz, limit, 1u, {}), limit)) {
            plan.feasible = false;
            plan.error = "one MIT motor alone exceeds a bus";
          } else {
            HandBus b;
            b.mit = 1u;
            hand.push_back(b);
          }
        }
      }
    } else {
      // The fewest boards such that each one fits a bus on its own.
      std::vector<std::uint32_t> boards;
      for (std::uint32_t n = 1; n <= robot.hand_joints; ++n) {
        boards.clear();
        bool ok = true;
        for (std::uint32_t i = 0; i < n; ++i) {
          const std::uint32_t j = robot.hand_joints / n + (i < robot.hand_joints % n ? 1u : 0u);
          boards.push_back(j);
          if (j > 32u || !fits(handLoad(kind, cycle_hz, limit, 0u, {j}), limit)) {
            ok = false;
          }
        }
        if (ok) {
          break;
        }
        if (n == robot.hand_joints) {
          plan.feasible = false;
          plan.error = "one hand joint alone exceeds a bus";
        }
      }
      if (plan.feasible) {
        for (std::uint32_t j : boards) {
          bool placed = false;
          for (HandBus& b : hand) {
            std::vector<std::uint32_t> with = b.boards;
            with.push_back(j);
            if (fits(handLoad(kind, cycle_hz, limit, 0u, with), limit)) {
              b.boards = with;
              placed = true;
              break;
            }
          }
          if (!placed) {
            HandBus b;
            b.boards.push_back(j);
            hand.push_back(b);
          }
        }
      }
    }
  }

  for (const ArmBus& b : arm) {
    PlannedBus p;
    p.arm_drives = b.drives;
    p.ft_sensors = b.ft;
    p.utilisation_worst = armLoad(robot, kind, cycle_hz, limit, b.drives, b.ft);
    p.content = armContent(b.drives, b.ft);
    plan.fullest = std::max(plan.fullest, p.utilisation_worst);
    plan.buses.push_back(p);
  }
  for (const HandBus& b : hand) {
    PlannedBus p;
    p.hand = true;
    p.mit_motors = b.mit;
    p.hand_boards = static_cast<std::uint32_t>(b.boards.size());
    for (std::uint32_t j : b.boards) {
      p.hand_joints += j;
    }
    p.utilisation_worst = handLoad(kind, cycle_hz, limit, b.mit, b.boards);
    p.content = handContent(b);
    plan.fullest = std::max(plan.fullest, p.utilisation_worst);
    plan.buses.push_back(p);
  }
  plan.arm_buses = arm.size();
  plan.hand_buses = hand.size();
  return plan;
}

std::string budgetTableMarkdown(const RobotTraffic& robot, const std::vector<BusKind>& kinds,
                                const std::vector<double>& rates_hz, double limit) {
  std::string out =
      "| cycle | bus | max drives per bus | arm buses (drives + F/T: worst-case load) | hand buses "
      "(worst-case "
      "load) | buses |\n|---|---|---|---|---|---|\n";
  for (double hz : rates_hz) {
    for (const BusKind& kind : kinds) {
      const BusPlan plan = planBuses(robot, kind, hz, limit);
      char rate[32];
      std::snprintf(rate, sizeof(rate), "%g Hz", hz);
      out += "| " + std::string(rate) + " | " + kind.label + " | ";
      if (!plan.feasible) {
        out += "— | does not fit: " + plan.error + " | | — |\n";
        continue;
      }
      out += std::to_string(plan.max_drives_per_bus) + " | ";
      std::string arm;
      std::string hand;
      for (const PlannedBus& b : plan.buses) {
        std::string& cell = b.hand ? hand : arm;
        cell += (cell.empty() ? "" : "; ") + b.content + " (" + pct(b.utilisation_worst) + ")";
      }
      out += std::to_string(plan.arm_buses) + ": " + arm + " | " + std::to_string(plan.hand_buses) + ": " +
             hand + " | **" + std::to_string(plan.arm_buses + plan.hand_buses) + "** |\n";
    }
  }
  return out;
}

std::string referenceBudgetTables() {
  const std::vector<BusKind> kinds = {{"classic 1 Mbit/s", 1000000u, 0u},
                                      {"CAN FD 1/5 Mbit/s", 1000000u, 5000000u}};
  const std::vector<double> rates = {250.0, 500.0, 1000.0};
  RobotTraffic robot;
  std::string out = "With TPDO2 (velocity, error code and mode feedback every cycle):\n\n";
  out += budgetTableMarkdown(robot, kinds, rates, 0.8);
  robot.arm_tpdo2 = false;
  out += "\nWithout TPDO2 (statusword, position and torque only):\n\n";
  out += budgetTableMarkdown(robot, kinds, rates, 0.8);
  return out;
}

}  // namespace mrqp::drivers
