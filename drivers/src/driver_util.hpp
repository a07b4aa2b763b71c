// mrqp drivers -- small helpers shared by the device drivers (internal header).
#pragma once

#include <cmath>

#include "mrqp/drivers/bus.hpp"
#include "mrqp/firmware_if/saturate.h"

namespace mrqp::drivers::detail {

/// Reception time of a frame: its timestamp when it has one that is not in the future, else now.
inline TimeNs rxTime(const RxFrame& rx, TimeNs now) noexcept {
  return rx.has_timestamp && rx.timestamp <= now ? rx.timestamp : now;
}

/// Finite test on the bit pattern (immune to -ffast-math).
inline bool finite(double x) noexcept { return mrqp_fw_isfinite_d(x) != 0; }
inline bool finiteF(float x) noexcept { return mrqp_fw_isfinite_f(x) != 0; }

/// Clamps x into [lo, hi]; sets *limited when it had to.
inline double clamp(double x, double lo, double hi, bool* limited) noexcept {
  if (x < lo) {
    *limited = true;
    return lo;
  }
  if (x > hi) {
    *limited = true;
    return hi;
  }
  return x;
}

}  // namespace mrqp::drivers::detail
