// mrqp drivers -- per-cycle bus fault flags from a router's counters and its bus's status.
#pragma once

#include <cstdint>

#include "mrqp/drivers/bus_router.hpp"
#include "mrqp/drivers/faults.hpp"

namespace mrqp::drivers {

/// Turns cumulative counters (router statistics, Bus::status()) into this-cycle BusFaults:
/// error frames, error passive / bus-off state, unknown and rejected frames, transmit-queue-full
/// and receive-overflow counts since the previous update. Several drivers sharing a bus each
/// keep their own BusHealth. Real-time safe.
class BusHealth {
 public:
  /// Starts counting from the router's current counters.
  void reset(const BusRouter& router) noexcept;
  /// Computes this cycle's BusFaults.
  const BusFaults& update(const BusRouter& router) noexcept;
  const BusFaults& faults() const noexcept { return faults_; }

 private:
  BusFaults faults_{};
  std::uint64_t base_error_events_ = 0;
  std::uint64_t base_unknown_ = 0;
  std::uint64_t base_rejected_ = 0;
  std::uint64_t base_tx_queue_full_ = 0;
  std::uint64_t base_rx_overflow_ = 0;
};

}  // namespace mrqp::drivers
