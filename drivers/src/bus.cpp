// mrqp drivers -- the bus interface.
#include "mrqp/drivers/bus.hpp"

namespace mrqp::drivers {

Bus::~Bus() = default;

const char* busStateStr(BusState state) noexcept {
  switch (state) {
    case BusState::ErrorActive:
      return "error active";
    case BusState::ErrorWarning:
      return "error warning";
    case BusState::ErrorPassive:
      return "error passive";
    case BusState::BusOff:
      return "bus-off";
  }
  return "unknown";
}

}  // namespace mrqp::drivers
