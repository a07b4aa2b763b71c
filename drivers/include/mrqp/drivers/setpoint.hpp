// mrqp drivers -- the result of handing a setpoint to a driver.
#pragma once

#include <cstdint>

namespace mrqp::drivers {

enum class SetpointResult : std::uint8_t {
  Ok = 0,
  Limited,  ///< accepted after clamping to a configured limit or the wire range (flagged)
  Refused,  ///< NaN or infinite: not stored, never sent; the previous setpoint stays (flagged)
  BadIndex  ///< no such device / joint
};

}  // namespace mrqp::drivers
