// mrqp drivers -- small helpers shared by the device drivers (internal header).
#pragma once

#include <cmath>

#include "mrqp/drivers/bus.hpp"
#include "mrqp/drivers/faults.hpp"
#include "mrqp/firmware_if/saturate.h"

namespace mrqp::drivers::detail {

/// Reception time of a frame: its timestamp when it has one that is not in the future, else now.
inline TimeNs rx_time(const RxFrame& rx, TimeNs now) noexcept
{
  return rx.has_timestamp && rx.timestamp <= now ? rx.timestamp : now;
}

/// Finite test on the bit pattern (immune to -ffast-math).
inline bool finite(double x) noexcept
{
  return mrqp_fw_isfinite_d(x) != 0;
}
inline bool finite_f(float x) noexcept
{
  return mrqp_fw_isfinite_f(x) != 0;
}

/// Clamps x into [lo, hi]; sets *limited when it had to.
inline double clamp(double x, double lo, double hi, bool* limited) noexcept
{
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

/// Fills a FaultReport from the driver's arrays.
inline void publish(FaultReport& r, const DeviceFaults* devices, std::size_t n_devices, const BusFaults* buses,
                    std::size_t n_buses) noexcept
{
  r.devices = devices;
  r.device_count = n_devices;
  r.buses = buses;
  r.bus_count = n_buses;
  std::uint32_t flags = 0;
  for (std::size_t i = 0; i < n_devices; ++i) {
    flags |= devices[i].flags;
  }
  for (std::size_t i = 0; i < n_buses; ++i) {
    flags |= buses[i].flags;
  }
  r.flags = flags;
}

}  // namespace mrqp::drivers::detail
