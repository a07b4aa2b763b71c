// The robot I/O map (docs/loop.md): for every robot entity with hardware, each of its driven
// joints as (device, index) with its place in the entity's q and v, built once at set-up from the
// hardware section; the cycle reads and writes through it without any name lookup.
#pragma once

#include <mrqp/drivers/bus_router.hpp>
#include <mrqp/drivers/device.hpp>

#include <memory>
#include <string>
#include <vector>

#include "loop/hardware_spec.hpp"

namespace mrqp::loop {

struct JointIo {
  drivers::JointDevice* device = nullptr;
  std::size_t index = 0;       ///< joint index within the device
  int v_index = -1;            ///< in the entity's v
  int q_index = -1;            ///< in the entity's q
  bool torque = false;         ///< a torque-commanded joint (CST)
  std::string name;            ///< "ENTITY.JOINT" (logs, set-up only)
};

struct RobotIo {
  int entity = -1;
  std::string name;
  int divisor = 1;
  SafeStop safe_stop = SafeStop::Hold;
  double hold_damping = 1.0;
  std::vector<std::unique_ptr<drivers::Device>> devices;  ///< owned drivers
  std::vector<drivers::BusRouter*> routers;               ///< the buses this robot's devices use
  std::vector<JointIo> joints;
  // Per-joint cycle storage (sized at set-up).
  std::vector<double> q_cmd, v_cmd, tau_cmd;
  std::vector<double> q_meas, v_meas;
  std::vector<double> q_sent, v_sent;                     ///< the last setpoint sent, as the drive reports it
  std::vector<std::uint32_t> stale;                       ///< consecutive robot cycles without fresh feedback
  std::vector<double> miss_rate;                          ///< averaged rate of robot cycles without fresh feedback
  double tracking_error_max = 0.0;                        ///< |measured − commanded|, rad
};

}  // namespace mrqp::loop
