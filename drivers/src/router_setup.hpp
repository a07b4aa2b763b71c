// mrqp drivers -- set-up steps shared by the device drivers' create() (internal header; set-up
// code, never called from the cycle).
#pragma once

#include <string>
#include <vector>

#include "mrqp/drivers/bus_router.hpp"

namespace mrqp::drivers::detail {

/// Why a driver cannot use this list of routers ("no bus given", "bus 2 is null", "bus 1 given
/// twice"), or an empty string when it can.
inline std::string checkRouters(const std::vector<BusRouter*>& buses) {
  if (buses.empty()) {
    return "no bus given";
  }
  for (std::size_t i = 0; i < buses.size(); ++i) {
    if (buses[i] == nullptr) {
      return "bus " + std::to_string(i) + " is null";
    }
    for (std::size_t k = 0; k < i; ++k) {
      if (buses[k] == buses[i]) {
        return "bus " + std::to_string(i) + " given twice";
      }
    }
  }
  return {};
}

}  // namespace mrqp::drivers::detail
